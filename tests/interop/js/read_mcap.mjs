// A reader of the station's MCAP logs built from Foxglove's own libraries: the MCAP reader
// (@mcap/core, with @mcap/support's zstd/lz4 decompressors, what the Foxglove app loads), the ROS
// 2 .msg parser (@foxglove/rosmsg) and CDR decoder (@foxglove/rosmsg2-serialization), decoding each
// message with nothing but the schema stored in the file.
//
//   node read_mcap.mjs FILE.mcap [--topics T1,T2]
//
// Prints JSON lines on stdout: one {"kind":"channel",...} per channel (topic, encodings, schema
// name, message count from the file's statistics), then one {"kind":"message",...} per message
// in log-time order (log and publish times as decimal strings of nanoseconds; 64-bit integers
// in messages as numbers where exact, else strings; byte and number arrays as arrays). Exits 1 naming the topic and log time of the first message it cannot
// decode, 2 on a usage error or an unreadable file.

import { open } from "node:fs/promises";

import { McapIndexedReader } from "@mcap/core";
import { loadDecompressHandlers } from "@mcap/support";
import rosmsg from "@foxglove/rosmsg";
import rosmsg2 from "@foxglove/rosmsg2-serialization";

const { parse } = rosmsg;
const { MessageReader } = rosmsg2;

function usage(text) {
  process.stderr.write(`read_mcap.mjs: ${text}\nusage: node read_mcap.mjs FILE.mcap [--topics T1,T2]\n`);
  process.exit(2);
}

function parseArgs(argv) {
  const args = { file: undefined, topics: undefined };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (a === "--topics") {
      if (i + 1 >= argv.length) usage("--topics needs a value");
      args.topics = argv[++i].split(",").filter((t) => t.length > 0);
    } else if (a.startsWith("--")) usage(`unknown option ${a}`);
    else if (args.file === undefined) args.file = a;
    else usage(`unexpected argument ${a}`);
  }
  if (args.file === undefined) usage("no file");
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

/// The decoder of a channel's messages, from its schema alone.
function decoderFor(channel, schema) {
  if (channel.messageEncoding === "cdr" && schema?.encoding === "ros2msg") {
    const reader = new MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: true }));
    return (data) => reader.readMessage(data);
  }
  if (channel.messageEncoding === "json") {
    return (data) => JSON.parse(new TextDecoder().decode(data));
  }
  return undefined;
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  let handle;
  try {
    handle = await open(args.file, "r");
  } catch (error) {
    process.stderr.write(`read_mcap.mjs: cannot open ${args.file}: ${error.message}\n`);
    process.exit(2);
  }
  const readable = {
    size: async () => BigInt((await handle.stat()).size),
    read: async (offset, size) => {
      const buffer = new Uint8Array(Number(size));
      const { bytesRead } = await handle.read(buffer, 0, Number(size), Number(offset));
      if (bytesRead !== Number(size)) throw new Error(`short read at ${offset}`);
      return buffer;
    },
  };
  const reader = await McapIndexedReader.Initialize({
    readable,
    decompressHandlers: await loadDecompressHandlers(),
  });
  const counts = reader.statistics?.channelMessageCounts ?? new Map();
  const decoders = new Map();
  for (const [id, channel] of [...reader.channelsById].sort(([a], [b]) => a - b)) {
    const schema = reader.schemasById.get(channel.schemaId);
    print({
      kind: "channel",
      topic: channel.topic,
      messageEncoding: channel.messageEncoding,
      schemaName: schema?.name ?? null,
      schemaEncoding: schema?.encoding ?? null,
      messageCount: plain(counts.get(id) ?? null),
    });
    decoders.set(id, { topic: channel.topic, decode: decoderFor(channel, schema) });
  }
  for await (const record of reader.readMessages({ topics: args.topics, validateCrcs: true })) {
    const { topic, decode } = decoders.get(record.channelId);
    const at = `${topic} message at log time ${record.logTime}`;
    if (decode === undefined) {
      process.stderr.write(`read_mcap.mjs: no decoder for ${at}\n`);
      process.exit(1);
    }
    let message;
    try {
      message = decode(record.data);
    } catch (error) {
      process.stderr.write(`read_mcap.mjs: cannot decode ${at}: ${error.message}\n`);
      process.exit(1);
    }
    print({
      kind: "message",
      topic,
      logTimeNs: record.logTime.toString(),
      publishTimeNs: record.publishTime.toString(),
      sequence: record.sequence,
      message: plain(message),
    });
  }
  await handle.close();
}

await main();
