// A viewer of the station's live view built from Foxglove's own libraries: the WebSocket
// protocol client (@foxglove/ws-protocol, over `ws`), the ROS 2 .msg parser (@foxglove/rosmsg)
// and CDR decoder (@foxglove/rosmsg2-serialization), which decode each message with nothing but
// the schema the server advertised.
//
//   node view_client.mjs ws://127.0.0.1:8765 --topics /tf,/pomdar/markers/hand_model=1 \
//       [--count N] [--timeout-ms MS]
//
// Prints JSON lines on stdout: one {"kind":"advertise",...} per advertised channel, then one
// {"kind":"message","topic":...,"message":{...}} per received message of the given topics
// (log times as decimal strings of nanoseconds; 64-bit integers in messages as numbers where
// exact, else strings; byte and number arrays as arrays).
// Exits 0 once every topic has its N messages (TOPIC=N, else --count, default 1), 1 (naming the topics short) when the
// timeout (default 10000 ms) passes first, 2 on a usage or connection error.

import wsProtocol from "@foxglove/ws-protocol";
import rosmsg from "@foxglove/rosmsg";
import rosmsg2 from "@foxglove/rosmsg2-serialization";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;
const { parse } = rosmsg;
const { MessageReader } = rosmsg2;

/// The WebSocket subprotocol of the Foxglove SDK's server (the ws-protocol spec, schemas inline).
const SUBPROTOCOL = "foxglove.sdk.v1";

function usage(text) {
  process.stderr.write(`view_client.mjs: ${text}\n`);
  process.stderr.write(
    "usage: node view_client.mjs ws://HOST:PORT --topics T1[=N],T2[=N] [--count N] [--timeout-ms MS]\n",
  );
  process.exit(2);
}

function parseArgs(argv) {
  const args = { url: undefined, topics: [], count: 1, timeoutMs: 10000 };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    const value = () => {
      if (i + 1 >= argv.length) usage(`${a} needs a value`);
      return argv[++i];
    };
    if (a === "--topics") args.topics = value().split(",").filter((t) => t.length > 0);
    else if (a === "--count") args.count = Number(value());
    else if (a === "--timeout-ms") args.timeoutMs = Number(value());
    else if (a.startsWith("--")) usage(`unknown option ${a}`);
    else if (args.url === undefined) args.url = a;
    else usage(`unexpected argument ${a}`);
  }
  if (args.url === undefined) usage("no server URL");
  if (args.topics.length === 0) usage("no --topics");
  if (!(args.count >= 1) || !(args.timeoutMs > 0)) usage("--count and --timeout-ms must be positive");
  args.wanted = new Map(
    args.topics.map((t) => {
      const at = t.lastIndexOf("=");
      if (at < 0) return [t, args.count];
      const n = Number(t.slice(at + 1));
      if (!(n >= 1)) usage(`bad count in ${t}`);
      return [t.slice(0, at), n];
    }),
  );
  return args;
}

/// A decoded value as plain JSON: bigints as numbers when exact (else decimal strings), typed
/// arrays as arrays.
function plain(value) {
  if (typeof value === "bigint") {
    return Number.isSafeInteger(Number(value)) ? Number(value) : value.toString();
  }
  if (ArrayBuffer.isView(value)) return Array.from(value, plain);
  if (Array.isArray(value)) return value.map(plain);
  if (value !== null && typeof value === "object") {
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, plain(v)]));
  }
  return value;
}

function print(line) {
  process.stdout.write(`${JSON.stringify(line)}\n`);
}

const args = parseArgs(process.argv.slice(2));
const wanted = args.wanted;
const received = new Map([...wanted.keys()].map((t) => [t, 0]));
/// subscription id -> { topic, reader, schemaName }
const subscriptions = new Map();

const ws = new WebSocket(args.url, [SUBPROTOCOL]);
const client = new FoxgloveClient({ ws });

let done = false;

function finish(code, note) {
  if (done) return;
  done = true;
  if (note !== undefined) process.stderr.write(`view_client.mjs: ${note}\n`);
  clearTimeout(timer);
  ws.close();
  // Let stdout drain before leaving.
  process.stdout.write("", () => process.exit(code));
}

const timer = setTimeout(() => {
  const short = [...received]
    .filter(([t, n]) => n < wanted.get(t))
    .map(([t, n]) => `${t} (${n} of ${wanted.get(t)})`);
  finish(1, `timed out after ${args.timeoutMs} ms; short of messages: ${short.join(", ")}`);
}, args.timeoutMs);

client.on("error", (error) => finish(2, `connection error: ${error?.message ?? error}`));
client.on("close", () => finish(2, "the server closed the connection"));

client.on("advertise", (channels) => {
  for (const channel of channels) {
    print({
      kind: "advertise",
      topic: channel.topic,
      encoding: channel.encoding,
      schemaName: channel.schemaName,
      schemaEncoding: channel.schemaEncoding,
    });
    if (!wanted.has(channel.topic)) continue;
    if (channel.encoding !== "cdr" || channel.schemaEncoding !== "ros2msg") {
      finish(1, `${channel.topic}: encoding ${channel.encoding}, schema ${channel.schemaEncoding}`);
      return;
    }
    const reader = new MessageReader(parse(channel.schema, { ros2: true }));
    const id = client.subscribe(channel.id);
    subscriptions.set(id, { topic: channel.topic, reader, schemaName: channel.schemaName });
  }
});

client.on("message", ({ subscriptionId, timestamp, data }) => {
  const sub = subscriptions.get(subscriptionId);
  if (sub === undefined) return;
  let message;
  try {
    message = sub.reader.readMessage(data);
  } catch (error) {
    finish(1, `${sub.topic}: cannot decode with the advertised schema: ${error.message}`);
    return;
  }
  print({
    kind: "message",
    topic: sub.topic,
    schemaName: sub.schemaName,
    logTimeNs: timestamp.toString(),
    trailingBytes: sub.reader.lastReadHadTrailingBytes(),
    message: plain(message),
  });
  received.set(sub.topic, received.get(sub.topic) + 1);
  if ([...received].every(([t, n]) => n >= wanted.get(t))) finish(0);
});
