"""Write the same glove recording with two independent MCAP writers, for the station to read.

Usage: write_mcap.py PLAN.json OUT_DIR

The plan (written by tests/tests/suite/interop_mcap.rs) holds the frames: log time, keypoint rows
(the lab's Float32MultiArray N x 3 layout) and the wrist pose (PoseStamped with its stamp and
frame), plus a few joint states and notes. Two files are written into OUT_DIR:

- `rosbags/rosbags.mcap`: a rosbag2 bag by `rosbags` (storage plugin mcap, zstd chunks), with
  its own message definitions (the ROS 2 Humble typestore), its own CDR serializer and offered
  QoS profiles in the v9 (named) spelling; log time = publish time, sequence 0, as it writes;
- `mcap_ros2.mcap`: the `mcap` writer with `mcap-ros2-support` (lz4 chunks), the schemas below
  (ROS 2 .msg texts as rosbag2 concatenates them), publish time = log time - 1 ms, sequence
  numbers from 1.

Prints `{"rosbags": PATH, "mcap_ros2": PATH}`.
"""

import json
import sys
from pathlib import Path

import numpy as np

SEPARATOR = "=" * 80

# ROS 2 message definitions, for the mcap-ros2-support writer (which takes the schema as text).
MSG = {
    "builtin_interfaces/Time": "int32 sec\nuint32 nanosec\n",
    "std_msgs/Header": "builtin_interfaces/Time stamp\nstring frame_id\n",
    "std_msgs/String": "string data\n",
    "std_msgs/MultiArrayDimension": "string label\nuint32 size\nuint32 stride\n",
    "std_msgs/MultiArrayLayout": "MultiArrayDimension[] dim\nuint32 data_offset\n",
    "std_msgs/Float32MultiArray": "MultiArrayLayout layout\nfloat32[] data\n",
    "geometry_msgs/Point": "float64 x\nfloat64 y\nfloat64 z\n",
    "geometry_msgs/Quaternion": "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n",
    "geometry_msgs/Pose": "Point position\nQuaternion orientation\n",
    "geometry_msgs/PoseStamped": "std_msgs/Header header\nPose pose\n",
    "sensor_msgs/JointState": (
        "std_msgs/Header header\nstring[] name\nfloat64[] position\nfloat64[] velocity\n"
        "float64[] effort\n"
    ),
}
DEPENDENCIES = {
    "std_msgs/Float32MultiArray": ["std_msgs/MultiArrayLayout", "std_msgs/MultiArrayDimension"],
    "geometry_msgs/PoseStamped": [
        "std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/Pose",
        "geometry_msgs/Point", "geometry_msgs/Quaternion",
    ],
    "sensor_msgs/JointState": ["std_msgs/Header", "builtin_interfaces/Time"],
    "std_msgs/String": [],
}


def schema_text(name):
    parts = [MSG[name]]
    for dependency in DEPENDENCIES[name]:
        parts.append(f"{SEPARATOR}\nMSG: {dependency}\n{MSG[dependency]}")
    return "\n".join(parts)


def full_name(name):
    package, message = name.split("/")
    return f"{package}/msg/{message}"


def split_ns(ns):
    return ns // 1_000_000_000, ns % 1_000_000_000


def messages(plan):
    """(log time, topic, type, message as plain dicts) in log-time order."""
    out = []
    for frame in plan["frames"]:
        rows = frame["points"]
        layout = {
            "dim": [
                {"label": "dim_0", "size": len(rows), "stride": 3 * len(rows)},
                {"label": "dim_1", "size": 3, "stride": 3},
            ],
            "data_offset": 0,
        }
        wrist = frame["wrist"]
        sec, nanosec = split_ns(wrist["stamp_ns"])
        pose = {
            "header": {"stamp": {"sec": sec, "nanosec": nanosec}, "frame_id": wrist["frame_id"]},
            "pose": {
                "position": dict(zip("xyz", wrist["position"])),
                "orientation": dict(zip("xyzw", wrist["orientation"])),
            },
        }
        t = frame["log_time_ns"]
        out.append((t, plan["wrist_topic"], "geometry_msgs/PoseStamped", pose))
        out.append((t, plan["keypoints_topic"], "std_msgs/Float32MultiArray",
                    {"layout": layout, "data": [v for row in rows for v in row]}))
    for joints in plan["joint_states"]:
        sec, nanosec = split_ns(joints["stamp_ns"])
        message = {key: joints[key] for key in ("name", "position", "velocity", "effort")}
        message["header"] = {"stamp": {"sec": sec, "nanosec": nanosec}, "frame_id": ""}
        out.append((joints["log_time_ns"], plan["joint_states_topic"], "sensor_msgs/JointState",
                    message))
    for note in plan["notes"]:
        out.append((note["log_time_ns"], plan["notes_topic"], "std_msgs/String",
                    {"data": note["text"]}))
    return sorted(out, key=lambda m: m[0])


def write_with_mcap_ros2(plan, path):
    from mcap.writer import CompressionType
    from mcap_ros2.writer import Writer

    with open(path, "wb") as stream:
        writer = Writer(stream, compression=CompressionType.LZ4)
        schemas = {}
        for sequence, (t, topic, name, message) in enumerate(messages(plan), start=1):
            if name not in schemas:
                schemas[name] = writer.register_msgdef(full_name(name), schema_text(name))
            writer.write_message(topic, schemas[name], message, log_time=t,
                                 publish_time=t - 1_000_000, sequence=sequence)
        writer.finish()


def to_rosbags(store, name, value):
    """A plain-dict message as the rosbags typestore's class (numpy arrays for number lists)."""
    types = store.types

    def header(h):
        stamp = types["builtin_interfaces/msg/Time"](**h["stamp"])
        return types["std_msgs/msg/Header"](stamp=stamp, frame_id=h["frame_id"])

    if name == "std_msgs/Float32MultiArray":
        dims = [types["std_msgs/msg/MultiArrayDimension"](**d) for d in value["layout"]["dim"]]
        layout = types["std_msgs/msg/MultiArrayLayout"](
            dim=dims, data_offset=value["layout"]["data_offset"])
        return types[full_name(name)](layout=layout, data=np.array(value["data"], np.float32))
    if name == "geometry_msgs/PoseStamped":
        pose = types["geometry_msgs/msg/Pose"](
            position=types["geometry_msgs/msg/Point"](**value["pose"]["position"]),
            orientation=types["geometry_msgs/msg/Quaternion"](**value["pose"]["orientation"]))
        return types[full_name(name)](header=header(value["header"]), pose=pose)
    if name == "sensor_msgs/JointState":
        arrays = {k: np.array(value[k], np.float64) for k in ("position", "velocity", "effort")}
        return types[full_name(name)](header=header(value["header"]), name=value["name"], **arrays)
    if name == "std_msgs/String":
        return types[full_name(name)](data=value["data"])
    raise ValueError(f"no rosbags builder for {name}")


def write_with_rosbags(plan, bag_dir):
    from rosbags.interfaces import (Qos, QosDurability, QosHistory, QosLiveliness,
                                    QosReliability, QosTime)
    from rosbags.rosbag2 import Writer
    from rosbags.rosbag2.enums import CompressionFormat, CompressionMode, StoragePlugin
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.ROS2_HUMBLE)
    infinite = QosTime(sec=9223372036, nsec=854775807)
    qos = Qos(QosHistory.KEEP_LAST, plan["qos_depth"], QosReliability.RELIABLE,
              QosDurability.VOLATILE, infinite, infinite, QosLiveliness.AUTOMATIC, infinite, False)
    writer = Writer(bag_dir, version=9, storage_plugin=StoragePlugin.MCAP)
    writer.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
    connections = {}
    with writer:
        for t, topic, name, message in messages(plan):
            if topic not in connections:
                connections[topic] = writer.add_connection(
                    topic, full_name(name), typestore=store, offered_qos_profiles=[qos])
            data = store.serialize_cdr(to_rosbags(store, name, message), full_name(name))
            writer.write(connections[topic], t, data)
    return bag_dir / f"{bag_dir.name}.mcap"


def main():
    with open(sys.argv[1]) as stream:
        plan = json.load(stream)
    out = Path(sys.argv[2])
    mcap_path = out / "mcap_ros2.mcap"
    write_with_mcap_ros2(plan, mcap_path)
    rosbags_path = write_with_rosbags(plan, out / "rosbags")
    print(json.dumps({"rosbags": str(rosbags_path), "mcap_ros2": str(mcap_path)}))


if __name__ == "__main__":
    main()
