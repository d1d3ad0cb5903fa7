"""A ROS 2 peer on Eclipse Cyclone DDS: plays the glove to the station and listens to its outputs.

Usage: cyclone_peer.py PLAN.json

The plan (written by tests/tests/suite/interop_cyclonedds.rs) gives the domain id, the ROS topic names,
the QoS the station expects (`{"reliability": "reliable" | "best_effort", "depth": N}` for the
glove inputs, the command outputs and the status), the pacing and the glove frames (keypoint rows
and wrist poses). The message types are written here from the ROS 2 interface definitions, with
ROS 2 naming on the wire: topic `rt/<name>`, type `<pkg>::msg::dds_::<Type>_`.

The peer
1. joins the domain on loopback only and waits until every writer and reader is matched, then
   for the station's first status message (proof that the station has discovered this peer);
2. publishes each frame (wrist pose, then keypoints) with the send time as the DDS source
   timestamp and the wrist header stamp, paced at `period_s`;
3. once it has received the joint target of the last frame, prints `{"kind": "done", ...}`;
4. keeps receiving until its stdin closes (the test stops the station first), then prints
   `{"kind": "report", ...}`: every message it sent and received, as plain JSON with the ROS
   field names.
On failure it prints `{"kind": "error", "message": ...}` and exits with status 2.
"""

import json
import sys
import threading
import time
from dataclasses import dataclass, fields, is_dataclass

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import Domain, DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl import types as t
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

# Loopback only, no multicast: discovery by unicast to the participant ports on 127.0.0.1.
LOOPBACK = (
    "<CycloneDDS><Domain><General><Interfaces><NetworkInterface name='lo'/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast></General><Discovery>"
    "<ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>32</MaxAutoParticipantIndex>"
    "<Peers><Peer address='127.0.0.1'/></Peers></Discovery></Domain></CycloneDDS>"
)
MATCH_TIMEOUT_S = 15.0
OUTPUT_TIMEOUT_S = 10.0


@dataclass
class Time(IdlStruct, typename="builtin_interfaces::msg::dds_::Time_"):
    sec: t.int32
    nanosec: t.uint32


@dataclass
class Header(IdlStruct, typename="std_msgs::msg::dds_::Header_"):
    stamp: Time
    frame_id: str


@dataclass
class String(IdlStruct, typename="std_msgs::msg::dds_::String_"):
    data: str


@dataclass
class MultiArrayDimension(IdlStruct, typename="std_msgs::msg::dds_::MultiArrayDimension_"):
    label: str
    size: t.uint32
    stride: t.uint32


@dataclass
class MultiArrayLayout(IdlStruct, typename="std_msgs::msg::dds_::MultiArrayLayout_"):
    dim: t.sequence[MultiArrayDimension]
    data_offset: t.uint32


@dataclass
class Float32MultiArray(IdlStruct, typename="std_msgs::msg::dds_::Float32MultiArray_"):
    layout: MultiArrayLayout
    data: t.sequence[t.float32]


@dataclass
class Point(IdlStruct, typename="geometry_msgs::msg::dds_::Point_"):
    x: t.float64
    y: t.float64
    z: t.float64


@dataclass
class Quaternion(IdlStruct, typename="geometry_msgs::msg::dds_::Quaternion_"):
    x: t.float64
    y: t.float64
    z: t.float64
    w: t.float64


@dataclass
class Pose(IdlStruct, typename="geometry_msgs::msg::dds_::Pose_"):
    position: Point
    orientation: Quaternion


@dataclass
class PoseStamped(IdlStruct, typename="geometry_msgs::msg::dds_::PoseStamped_"):
    header: Header
    pose: Pose


@dataclass
class JointState(IdlStruct, typename="sensor_msgs::msg::dds_::JointState_"):
    header: Header
    name: t.sequence[str]
    position: t.sequence[t.float64]
    velocity: t.sequence[t.float64]
    effort: t.sequence[t.float64]


def plain(value):
    """A message as JSON-ready dicts and lists, keyed by the ROS field names."""
    if is_dataclass(value):
        return {f.name: plain(getattr(value, f.name)) for f in fields(value)}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    return value


def qos(spec):
    if spec["reliability"] == "reliable":
        reliability = Policy.Reliability.Reliable(max_blocking_time=duration(seconds=1))
    else:
        reliability = Policy.Reliability.BestEffort
    return Qos(reliability, Policy.History.KeepLast(spec["depth"]), Policy.Durability.Volatile)


def stamp(ns):
    return Time(sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000)


def stamp_ns(time_dict):
    return time_dict["sec"] * 1_000_000_000 + time_dict["nanosec"]


def keypoints(rows):
    layout = MultiArrayLayout(
        dim=[
            MultiArrayDimension(label="dim_0", size=len(rows), stride=3 * len(rows)),
            MultiArrayDimension(label="dim_1", size=3, stride=3),
        ],
        data_offset=0,
    )
    return Float32MultiArray(layout=layout, data=[v for row in rows for v in row])


def wrist(pose, frame_id, ns):
    return PoseStamped(
        header=Header(stamp=stamp(ns), frame_id=frame_id),
        pose=Pose(position=Point(*pose["position"]), orientation=Quaternion(*pose["orientation"])),
    )


class Failure(Exception):
    pass


def wait_for(condition, timeout_s, what, poll=None):
    deadline = time.monotonic() + timeout_s
    while not condition():
        if time.monotonic() > deadline:
            raise Failure(f"{what} within {timeout_s} s")
        if poll:
            poll()
        time.sleep(0.005)


def matched(entity):
    if isinstance(entity, DataWriter):
        return entity.get_publication_matched_status().current_count > 0
    return entity.get_subscription_matched_status().current_count > 0


def incompatible_qos(entity):
    if isinstance(entity, DataWriter):
        return entity.get_offered_incompatible_qos_status().total_count
    return entity.get_requested_incompatible_qos_status().total_count


def run(plan):
    started = time.monotonic()
    domain = Domain(plan["domain_id"], LOOPBACK)  # keep: the participant joins this domain
    participant = DomainParticipant(plan["domain_id"])
    topics = plan["topics"]

    def topic(name, data_type):
        return Topic(participant, "rt" + topics[name], data_type)

    input_qos, output_qos = qos(plan["input_qos"]), qos(plan["output_qos"])
    writers = {
        "keypoints": DataWriter(participant, topic("keypoints", Float32MultiArray), input_qos),
        "wrist": DataWriter(participant, topic("wrist", PoseStamped), input_qos),
    }
    readers = {
        "joint_targets": DataReader(participant, topic("joint_targets", JointState), output_qos),
        "arm_target": DataReader(participant, topic("arm_target", PoseStamped), output_qos),
        "policy_output": DataReader(participant, topic("policy_output", Float32MultiArray), output_qos),
    }
    status = DataReader(participant, topic("status", String), qos(plan["status_qos"]))
    received = {name: [] for name in readers}

    def drain():
        for name, reader in readers.items():
            for sample in reader.take(N=1000):
                # Instance state changes (the station's writer going away) carry no data.
                if sample.sample_info.valid_data:
                    received[name].append(plain(sample))

    endpoints = {**{f"writer {topics[n]}": w for n, w in writers.items()},
                 **{f"reader {topics[n]}": r for n, r in readers.items()},
                 f"reader {topics['status']}": status}
    try:
        wait_for(lambda: all(matched(e) for e in endpoints.values()), MATCH_TIMEOUT_S,
                 "the station did not match every endpoint")
    except Failure as failure:
        unmatched = [
            f"{name} (incompatible QoS: {incompatible_qos(e)})" for name, e in endpoints.items()
            if not matched(e)
        ]
        raise Failure(f"{failure}; unmatched: {', '.join(unmatched)}") from None
    matched_s = time.monotonic() - started
    wait_for(lambda: len(status.take(N=100)) > 0, MATCH_TIMEOUT_S, "no station status arrived")
    drain()

    sent = {"keypoints": [], "wrist": [], "source_ns": []}
    for frame in plan["frames"]:
        now = time.time_ns()
        pose = wrist(frame["wrist"], plan["wrist_frame_id"], now)
        points = keypoints(frame["points"])
        writers["wrist"].write(pose, timestamp=now)
        writers["keypoints"].write(points, timestamp=now)
        sent["wrist"].append(plain(pose))
        sent["keypoints"].append(plain(points))
        sent["source_ns"].append(now)
        drain()
        time.sleep(plan["period_s"])

    # The station stamps a fresh joint target with its frame's source time; frames arriving
    # together are solved once, for the newest, so the last frame always gets its target.
    last = sent["source_ns"][-1]
    wait_for(lambda: any(stamp_ns(m["header"]["stamp"]) == last for m in received["joint_targets"]),
             OUTPUT_TIMEOUT_S, "no joint target for the last frame arrived", poll=drain)
    counts = {name: len(v) for name, v in received.items()}
    print(json.dumps({"kind": "done", "received": counts, "matched_s": matched_s}), flush=True)

    # Until the test closes stdin (after stopping the station), keep receiving.
    stdin_closed = threading.Event()
    threading.Thread(target=lambda: (sys.stdin.read(), stdin_closed.set()), daemon=True).start()
    while not stdin_closed.is_set():
        drain()
        time.sleep(0.005)
    drain()
    del domain
    return {"kind": "report", "matched_s": matched_s, "sent": sent, "received": received,
            "received_at_done": counts}


def main():
    with open(sys.argv[1]) as stream:
        plan = json.load(stream)
    try:
        report = run(plan)
    except Failure as failure:
        print(json.dumps({"kind": "error", "message": str(failure)}), flush=True)
        sys.exit(2)
    print(json.dumps(report), flush=True)


if __name__ == "__main__":
    main()
