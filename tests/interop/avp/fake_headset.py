"""A stand-in Apple Vision Pro for the interop suite: the hand-tracking app's gRPC service
(generated with grpcio-tools from handtracking.proto beside this file), streaming a scripted
right hand, computing on its own, with numpy, the keypoints and wrist pose the station must
publish for it.

Protocol (JSON lines on stdout; commands on stdin):
  -> {"event": "listening", "port": P}            serving on 127.0.0.1:P
  -> {"event": "client", "head": [...16]}          a client called StreamHandUpdates (its request's head)
  <- go                                            start streaming
  phase 1: 27-joint updates (with the forearm) at 50 Hz, malformed ones among them; then the
           headset goes away (server stopped) for 1 s and comes back on the same port
  phase 2: 25-joint updates (an older app) at 50 Hz to the reconnected client
  -> {"event": "report", "expected": [...], "malformed": {kind: n}, "requests": n}
  <- quit (or end of input)                        stop and exit
"""

import argparse
import json
import math
import os
import sys
import threading
import time
from concurrent import futures

import grpc
import numpy as np
from grpc_tools import protoc

HERE = os.path.dirname(os.path.abspath(__file__))

# ARKit's axes to ROS's: x_ros = -z, y_ros = -x, z_ros = y (module docs of avp_frame.rs).
C = np.array([[0.0, 0.0, -1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
# The lab's 21 wrist-and-finger points among the 25 joints (metacarpals 5, 10, 15, 20 dropped).
LAB21 = [0, 1, 2, 3, 4, 6, 7, 8, 9, 11, 12, 13, 14, 16, 17, 18, 19, 21, 22, 23, 24]
FOREARM_ARM = 26


def compile_proto(out_dir):
    os.makedirs(out_dir, exist_ok=True)
    code = protoc.main(["protoc", f"-I{HERE}", f"--python_out={out_dir}", f"--grpc_python_out={out_dir}",
                        os.path.join(HERE, "handtracking.proto")])
    if code != 0:
        raise SystemExit(f"protoc failed ({code})")
    sys.path.insert(0, out_dir)
    import handtracking_pb2  # noqa: E402  (generated just now)
    return handtracking_pb2


def emit(doc):
    print(json.dumps(doc), flush=True)


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def skeleton_local(t, with_forearm):
    """Joint positions relative to the wrist (hand-local axes: fingers along -z, thumb toward +x,
    palm normal -y), for a hand that opens, pinches (thumb tip on the index tip) and opens again."""
    pinch = 0.5 - 0.5 * math.cos(2.0 * math.pi * t / 2.0)  # 0 open .. 1 pinched, period 2 s
    joints = np.zeros((27 if with_forearm else 25, 3))
    bases = {1: (0.025, -0.01, -0.03), 5: (0.022, 0.0, -0.02), 10: (0.005, 0.0, -0.022),
             15: (-0.012, 0.0, -0.021), 20: (-0.027, 0.0, -0.019)}
    # Fingers: metacarpal, knuckle, two intermediates, tip; curl bends toward -y.
    for first, lengths in [(5, (0.07, 0.045, 0.025, 0.022)), (10, (0.068, 0.05, 0.03, 0.024)),
                           (15, (0.065, 0.047, 0.028, 0.022)), (20, (0.06, 0.038, 0.02, 0.02))]:
        curl = 0.15 + (0.9 * pinch if first == 5 else 0.3 * pinch)
        p = np.array(bases[first])
        joints[first] = p
        heading = 0.0
        for k, length in enumerate(lengths):
            heading += curl if k > 0 else 0.0
            p = p + length * np.array([0.0, -math.sin(heading), -math.cos(heading)])
            joints[first + 1 + k] = p
    # Thumb: knuckle, two intermediates, tip; the tip goes from beside the palm to the index tip.
    knuckle = np.array(bases[1])
    open_tip = knuckle + np.array([0.05, -0.02, -0.06])
    tip = (1.0 - pinch) * open_tip + pinch * (joints[9] + np.array([0.004, -0.004, 0.0]))
    joints[1] = knuckle
    joints[2] = knuckle + 0.35 * (tip - knuckle) + np.array([0.01, 0.0, 0.0])
    joints[3] = knuckle + 0.7 * (tip - knuckle) + np.array([0.005, 0.0, 0.0])
    joints[4] = tip
    if with_forearm:
        joints[25] = (0.0, 0.0, 0.0)
        joints[26] = (0.0, 0.01, 0.25)  # toward the elbow
    return joints


def wrist_at(t):
    """The wrist in ARKit's world: in front of the user at chest height, moving and turning."""
    position = np.array([0.1 + 0.05 * math.sin(1.3 * t), 1.1 + 0.03 * math.cos(0.9 * t),
                         -0.45 + 0.04 * math.sin(0.7 * t)])
    rotation = rot_y(0.6 * math.sin(0.8 * t)) @ rot_x(-0.4 + 0.2 * math.cos(1.1 * t))
    return rotation, position


def f32(a):
    return np.asarray(a, dtype=np.float32).astype(np.float64)


def fill(matrix, rotation, position):
    rows = np.eye(4)
    rows[:3, :3] = rotation
    rows[:3, 3] = position
    for r in range(4):
        for c in range(4):
            setattr(matrix, f"m{r}{c}", float(np.float32(rows[r, c])))


def quaternion(m):
    """(x, y, z, w) of a rotation matrix (Shepperd's method)."""
    trace = np.trace(m)
    if trace > 0.0:
        s = 2.0 * math.sqrt(trace + 1.0)
        return [(m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, 0.25 * s]
    i = int(np.argmax(np.diag(m)))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2.0 * math.sqrt(1.0 + m[i, i] - m[j, j] - m[k, k])
    q = [0.0, 0.0, 0.0, 0.0]
    q[i] = 0.25 * s
    q[j] = (m[j, i] + m[i, j]) / s
    q[k] = (m[k, i] + m[i, k]) / s
    q[3] = (m[k, j] - m[j, k]) / s
    return q


def scripted_update(pb, t, with_forearm):
    """One update and the keypoints (22, ROS) and wrist pose the station must publish for it."""
    rotation, position = wrist_at(t)
    rotation, position = f32(rotation), f32(position)
    joints = f32(skeleton_local(t, with_forearm))
    update = pb.HandUpdate()
    fill(update.right_hand.wristMatrix, rotation, position)
    for p in joints:
        fill(update.right_hand.skeleton.jointMatrices.add(), np.eye(3), p)
    fill(update.Head, np.eye(3), [0.0, 1.6, 0.0])
    world = (rotation @ joints.T).T + position
    points = [world[FOREARM_ARM if with_forearm else 0]] + [world[k] for k in LAB21]
    expected = {
        "keypoints": [list(C @ p) for p in points],
        "wrist": {"p": list(C @ position), "q": quaternion(C @ rotation @ C.T)},
    }
    return update, expected


def malformed(pb, kind, t):
    """An update (or raw bytes) the station must refuse, of the named kind."""
    update, _ = scripted_update(pb, t, True)
    hand = update.right_hand
    if kind == "undecodable":
        return b"\x0a\xff\xff\xff"  # field 1, length 2^28-ish: truncated
    if kind == "wrist_not_rigid":
        fill(hand.wristMatrix, np.zeros((3, 3)), [0.0, 0.0, 0.0])  # an untracked hand
    elif kind == "non_finite":
        hand.skeleton.jointMatrices[7].m13 = float("nan")
    elif kind == "joint_count":
        del hand.skeleton.jointMatrices[24:]
    elif kind == "no_hand":
        update.left_hand.CopyFrom(hand)
        update.ClearField("right_hand")
    elif kind == "benchmark_reply":
        update.Head.m00 = 777.0
    return update


class Headset:
    def __init__(self, pb, port):
        self.pb = pb
        self.port = port
        self.go = threading.Event()
        self.quit = threading.Event()
        self.phase1_done = threading.Event()
        self.phase2_done = threading.Event()
        self.requests = 0
        self.expected = []
        self.malformed = {}
        self.server = None

    def start(self):
        serialize = lambda m: m if isinstance(m, bytes) else m.SerializeToString()  # noqa: E731
        handler = grpc.method_handlers_generic_handler("handtracking.HandTrackingService", {
            "StreamHandUpdates": grpc.unary_stream_rpc_method_handler(
                self.stream, request_deserializer=self.pb.HandUpdate.FromString,
                response_serializer=serialize),
        })
        self.server = grpc.server(futures.ThreadPoolExecutor(max_workers=4))
        self.server.add_generic_rpc_handlers((handler,))
        self.port = self.server.add_insecure_port(f"127.0.0.1:{self.port}")
        self.server.start()
        return self.port

    def stream(self, request, context):
        self.requests += 1
        head = request.Head
        emit({"event": "client", "head": [getattr(head, f"m{r}{c}") for r in range(4) for c in range(4)]})
        context.send_initial_metadata(())  # the stream is open before its first update
        if self.requests == 1:
            yield from self.phase(1, with_forearm=True, count=60, bad_every=7)
            self.phase1_done.set()
        else:
            yield from self.phase(2, with_forearm=False, count=40, bad_every=0)
            self.phase2_done.set()
        while not self.quit.is_set() and context.is_active():
            time.sleep(0.05)

    def phase(self, number, with_forearm, count, bad_every):
        if number == 1:
            self.go.wait()
        kinds = ["undecodable", "wrist_not_rigid", "non_finite", "joint_count", "no_hand",
                 "benchmark_reply", "duplicate"]
        previous = None
        for i in range(count):
            t = 0.02 * i + (10.0 if number == 2 else 0.0)
            if bad_every and i % bad_every == bad_every - 1 and kinds:
                kind = kinds.pop(0)
                self.malformed[kind] = self.malformed.get(kind, 0) + 1
                yield previous if kind == "duplicate" else malformed(self.pb, kind, t)
                time.sleep(0.02)
                continue
            update, expected = scripted_update(self.pb, t, with_forearm)
            self.expected.append(expected)
            previous = update
            yield update
            time.sleep(0.02)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--generated", required=True, help="directory for the generated Python")
    args = parser.parse_args()
    pb = compile_proto(args.generated)
    headset = Headset(pb, 0)
    port = headset.start()
    emit({"event": "listening", "port": port})

    def commands():
        for line in sys.stdin:
            if line.strip() == "go":
                headset.go.set()
            elif line.strip() == "quit":
                break
        headset.go.set()
        headset.quit.set()

    threading.Thread(target=commands, daemon=True).start()
    headset.phase1_done.wait()
    time.sleep(0.3)
    headset.server.stop(None)  # the headset goes away
    emit({"event": "away"})
    time.sleep(1.0)
    headset.start()  # and comes back on the same port
    emit({"event": "back"})
    while not headset.phase2_done.wait(0.1):
        if headset.quit.is_set():
            break
    emit({"event": "report", "expected": headset.expected, "malformed": headset.malformed,
          "requests": headset.requests})
    headset.quit.wait()
    headset.server.stop(None)


if __name__ == "__main__":
    main()
