"""A ROS 2 tool on Eclipse Cyclone DDS: reads what the station offers the lab's ROS tools and
calls its services the way rmw_cyclonedds does.

Usage: cyclone_tools_peer.py PLAN.json

The plan (written by tests/tests/suite/interop_cyclonedds.rs) gives the domain id, the topic and
service names, the QoS, the pacing, the glove frames and the service calls (`{"service": NAME,
"after_frame": I}`). The message types are written here from the ROS 2 Humble/Jazzy interface
definitions (tf2_msgs/TFMessage, visualization_msgs/MarkerArray with the texture, UV and
embedded-mesh fields, diagnostic_msgs/DiagnosticArray, std_srvs/srv/Trigger), with ROS 2 naming
on the wire: topic `rt/<name>`, type `<pkg>::msg::dds_::<Type>_`.

A service is called as rmw_cyclonedds calls it: the request `std_srvs::srv::dds_::Trigger_Request_`
on `rq/<service>Request`, preceded by rmw_cyclonedds' request header (the client's 64-bit id and
a 64-bit sequence number); the reply on `rr/<service>Reply` carries the same header in front of
`Trigger_Response_`. A reply is this call's when both header fields match.

The peer
1. joins the domain on loopback only and waits until every writer and reader is matched (the
   latched `/tf_static` reader is transient-local), then for the station's first status;
2. publishes the frames as cyclone_peer.py does, and after frame `after_frame` calls the
   service, waiting for its reply;
3. once it has received the joint target of the last frame, prints `{"kind": "done", ...}`;
4. keeps receiving until its stdin closes, then prints `{"kind": "report", ...}`: every message
   received on the tool topics and every call with its reply, as plain JSON with the ROS field
   names.
On failure it prints `{"kind": "error", "message": ...}` and exits with status 2.
"""

import json
import sys
import threading
import time
from dataclasses import dataclass

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import Domain, DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl import types as t
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from cyclone_peer import (
    LOOPBACK,
    MATCH_TIMEOUT_S,
    OUTPUT_TIMEOUT_S,
    Failure,
    Float32MultiArray,
    Header,
    JointState,
    Point,
    Pose,
    PoseStamped,
    Quaternion,
    String,
    incompatible_qos,
    keypoints,
    matched,
    plain,
    qos,
    stamp_ns,
    wait_for,
    wrist,
)

REPLY_TIMEOUT_S = 10.0
# The client's id in the request header (rmw_cyclonedds: the request writer's instance handle).
CLIENT_ID = 0x5A17_C0DE_0BAD_F00D


@dataclass
class Duration(IdlStruct, typename="builtin_interfaces::msg::dds_::Duration_"):
    sec: t.int32
    nanosec: t.uint32


@dataclass
class Vector3(IdlStruct, typename="geometry_msgs::msg::dds_::Vector3_"):
    x: t.float64
    y: t.float64
    z: t.float64


@dataclass
class Transform(IdlStruct, typename="geometry_msgs::msg::dds_::Transform_"):
    translation: Vector3
    rotation: Quaternion


@dataclass
class TransformStamped(IdlStruct, typename="geometry_msgs::msg::dds_::TransformStamped_"):
    header: Header
    child_frame_id: str
    transform: Transform


@dataclass
class TFMessage(IdlStruct, typename="tf2_msgs::msg::dds_::TFMessage_"):
    transforms: t.sequence[TransformStamped]


@dataclass
class ColorRGBA(IdlStruct, typename="std_msgs::msg::dds_::ColorRGBA_"):
    r: t.float32
    g: t.float32
    b: t.float32
    a: t.float32


@dataclass
class CompressedImage(IdlStruct, typename="sensor_msgs::msg::dds_::CompressedImage_"):
    header: Header
    format: str
    data: t.sequence[t.uint8]


@dataclass
class UVCoordinate(IdlStruct, typename="visualization_msgs::msg::dds_::UVCoordinate_"):
    u: t.float32
    v: t.float32


@dataclass
class MeshFile(IdlStruct, typename="visualization_msgs::msg::dds_::MeshFile_"):
    filename: str
    data: t.sequence[t.uint8]


@dataclass
class Marker(IdlStruct, typename="visualization_msgs::msg::dds_::Marker_"):
    header: Header
    ns: str
    id: t.int32
    type: t.int32
    action: t.int32
    pose: Pose
    scale: Vector3
    color: ColorRGBA
    lifetime: Duration
    frame_locked: bool
    points: t.sequence[Point]
    colors: t.sequence[ColorRGBA]
    texture_resource: str
    texture: CompressedImage
    uv_coordinates: t.sequence[UVCoordinate]
    text: str
    mesh_resource: str
    mesh_file: MeshFile
    mesh_use_embedded_materials: bool


@dataclass
class MarkerArray(IdlStruct, typename="visualization_msgs::msg::dds_::MarkerArray_"):
    markers: t.sequence[Marker]


@dataclass
class KeyValue(IdlStruct, typename="diagnostic_msgs::msg::dds_::KeyValue_"):
    key: str
    value: str


@dataclass
class DiagnosticStatus(IdlStruct, typename="diagnostic_msgs::msg::dds_::DiagnosticStatus_"):
    level: t.uint8  # `byte` (IDL octet): one unsigned byte on the wire
    name: str
    message: str
    hardware_id: str
    values: t.sequence[KeyValue]


@dataclass
class DiagnosticArray(IdlStruct, typename="diagnostic_msgs::msg::dds_::DiagnosticArray_"):
    header: Header
    status: t.sequence[DiagnosticStatus]


# rmw_cyclonedds puts its request header (`cdds_request_header_t`: uint64 guid, int64 seq) in
# front of the request and reply payloads, under the service's own type names.
@dataclass
class TriggerRequest(IdlStruct, typename="std_srvs::srv::dds_::Trigger_Request_"):
    client_guid: t.uint64
    sequence_number: t.int64
    structure_needs_at_least_one_member: t.uint8


@dataclass
class TriggerResponse(IdlStruct, typename="std_srvs::srv::dds_::Trigger_Response_"):
    client_guid: t.uint64
    sequence_number: t.int64
    success: bool
    message: str


def latched_qos(depth):
    return Qos(
        Policy.Reliability.Reliable(max_blocking_time=duration(seconds=1)),
        Policy.History.KeepLast(depth),
        Policy.Durability.TransientLocal,
    )


class Service:
    """One Trigger service, called over rmw_cyclonedds' request/reply topics."""

    def __init__(self, participant, name, service_qos):
        self.name = name
        self.request = DataWriter(
            participant, Topic(participant, f"rq{name}Request", TriggerRequest), service_qos
        )
        self.reply = DataReader(
            participant, Topic(participant, f"rr{name}Reply", TriggerResponse), service_qos
        )

    def call(self, sequence_number):
        request = TriggerRequest(
            client_guid=CLIENT_ID,
            sequence_number=sequence_number,
            structure_needs_at_least_one_member=0,
        )
        self.request.write(request)
        replies = []

        def answered():
            replies.extend(s for s in self.reply.take(N=10) if s.sample_info.valid_data)
            return any(
                r.client_guid == CLIENT_ID and r.sequence_number == sequence_number
                for r in replies
            )

        wait_for(answered, REPLY_TIMEOUT_S, f"no reply from {self.name}")
        return {"service": self.name, "request": plain(request),
                "replies": [plain(r) for r in replies]}


def open_endpoints(participant, plan):
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
        "tf": DataReader(participant, topic("tf", TFMessage), output_qos),
        "tf_static": DataReader(participant, topic("tf_static", TFMessage), latched_qos(1)),
        "markers": DataReader(participant, topic("markers", MarkerArray), output_qos),
        "diagnostics": DataReader(participant, topic("diagnostics", DiagnosticArray), output_qos),
    }
    status = DataReader(participant, topic("status", String), qos(plan["status_qos"]))
    service_qos = qos(plan["service_qos"])
    services = {name: Service(participant, name, service_qos) for name in plan["services"]}
    return writers, readers, status, services


def wait_until_matched(writers, readers, status, services):
    endpoints = {**{f"writer {n}": w for n, w in writers.items()},
                 **{f"reader {n}": r for n, r in readers.items()},
                 "reader status": status}
    for name, service in services.items():
        endpoints[f"request writer {name}"] = service.request
        endpoints[f"reply reader {name}"] = service.reply
    try:
        wait_for(lambda: all(matched(e) for e in endpoints.values()), MATCH_TIMEOUT_S,
                 "the station did not match every endpoint")
    except Failure as failure:
        unmatched = [
            f"{name} (incompatible QoS: {incompatible_qos(e)})" for name, e in endpoints.items()
            if not matched(e)
        ]
        raise Failure(f"{failure}; unmatched: {', '.join(unmatched)}") from None


def run(plan):
    started = time.monotonic()
    domain = Domain(plan["domain_id"], LOOPBACK)  # keep: the participant joins this domain
    participant = DomainParticipant(plan["domain_id"])
    writers, readers, status, services = open_endpoints(participant, plan)
    received = {name: [] for name in readers}

    def drain():
        for name, reader in readers.items():
            for sample in reader.take(N=1000):
                if sample.sample_info.valid_data:
                    received[name].append(plain(sample))

    wait_until_matched(writers, readers, status, services)
    matched_s = time.monotonic() - started
    wait_for(lambda: len(status.take(N=100)) > 0, MATCH_TIMEOUT_S, "no station status arrived")

    calls_after = {}
    for call in plan["calls"]:
        calls_after.setdefault(call["after_frame"], []).append(call["service"])
    calls, last_source_ns = [], None
    for i, frame in enumerate(plan["frames"]):
        now = time.time_ns()
        writers["wrist"].write(wrist(frame["wrist"], plan["wrist_frame_id"], now), timestamp=now)
        writers["keypoints"].write(keypoints(frame["points"]), timestamp=now)
        last_source_ns = now
        drain()
        time.sleep(plan["period_s"])
        for name in calls_after.get(i, []):
            calls.append(services[name].call(len(calls) + 1))
            drain()

    wait_for(lambda: any(stamp_ns(m["header"]["stamp"]) == last_source_ns
                         for m in received["joint_targets"]),
             OUTPUT_TIMEOUT_S, "no joint target for the last frame arrived", poll=drain)
    counts = {name: len(v) for name, v in received.items()}
    print(json.dumps({"kind": "done", "received": counts, "matched_s": matched_s}), flush=True)

    stdin_closed = threading.Event()
    threading.Thread(target=lambda: (sys.stdin.read(), stdin_closed.set()), daemon=True).start()
    while not stdin_closed.is_set():
        drain()
        time.sleep(0.005)
    drain()
    del domain
    return {"kind": "report", "matched_s": matched_s, "received": received, "calls": calls}


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
