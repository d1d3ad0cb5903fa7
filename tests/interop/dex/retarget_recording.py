"""Retarget a recording's glove keypoints with dex-retargeting, for `pomdar eval --commands`.

Usage:
    retarget_recording.py IN.mcap OUT.mcap --type vector|dexpilot [--low-pass-alpha A]
                          [--urdf PATH] [--scaling S] [--origin-link LINK] [--quiet]

Reads the `std_msgs/msg/Float32MultiArray` keypoint messages on `/ingress/mano` of IN (N x 3,
row-major, metres; N = 22: forearm, wrist, then 4 per digit thumb, index, middle, ring, little,
base to tip; N = 21: the same without the forearm), keeps the DISTINCT frames in log-time order
(a frame equal to the one before it is the ingress re-publishing it, not a new frame: the same
rule as `pomdar eval`), retargets each with dex-retargeting (PyPI `dex_retargeting`, MIT, by
Yuzhe Qin; only its public API is used: `RetargetingConfig(...).build()` and
`SeqRetargeting.retarget`) onto the ORCA v1 right hand, and writes OUT with

- every `/ingress/mano` message of IN, copied raw (same schema, channel metadata, log and
  publish times, sequence numbers and bytes);
- one `sensor_msgs/msg/JointState` on `/dex/joint_states` per retargeted distinct frame, logged
  and published at that frame's log time, header stamp = that time; names = the URDF's joint
  names in dex-retargeting's (pinocchio's) order, positions = its output, unmodified (dex keeps
  the optimiser within the joint limits widened by its own 1e-3 rad epsilon, and does not clip
  afterwards: the scorer's limit-violation count shows it).

The retargeter (what is configured here, and why)
-------------------------------------------------
- vector: origin link = the wrist body (`right_wrist_jointbody`, on the wrist flexion axis,
  where the human wrist keypoint is; `--origin-link right_palm` takes the palm link, 39 mm
  further out), task links = the five fingertips, human indices
  [[0, 0, 0, 0, 0], [4, 8, 12, 16, 20]] (MediaPipe-21 order);
- dexpilot: `finger_tip_link_names` = the five fingertips, `wrist_link_name` = the same origin
  link; dex's default human indices (wrist to each tip, and tip to tip);
- `scaling_factor` = `--scaling`, default 1.0 (the human vectors are not enlarged);
  `low_pass_alpha` = `--low-pass-alpha`, default 0.2 (dex's teleoperation configs); a value
  outside [0, 1] or `none` turns the filter off;
- the wrist flexion joint (`right_wrist`) is not optimised: it is passed to dex as a fixed joint
  held at 0, as the station's `orca_full` embodiment locks it (16 finger DoF). Dex's other
  settings are its defaults (`normal_delta`, `huber_delta`, `project_dist`, `escape_dist`,
  joint limits on, no dummy free joint).

The frame the human vectors are given in (the choice that matters)
--------------------------------------------------------------------
Dex's optimisers compare the human vectors with robot link-to-link vectors in the robot's ROOT
frame (pinocchio's world: here the URDF's `world` link, the tower standing on it). The glove
reports keypoints in its own world frame, in which the hand turns freely; dex's own examples
first rotate the wrist-centred MediaPipe points into a wrist frame estimated from points 0, 5, 9
and then by its `OPERATOR2MANO` matrix, a convention that the robot configs shipped with dex
assume of their robots' base frames, and that the ORCA URDF's world frame does not follow.

So here the vectors are made rotation-consistent explicitly, with the SAME palm-frame
construction on both hands:

    y = normalise(middle base - wrist)            (towards the fingers)
    x = normalise(d - (d.y) y), d = index base - ring base   (across the knuckles)
    z = x cross y

- human: from keypoints wrist (0), index base (5), middle base (9), ring base (13), per frame:
  `R_h` (columns x, y, z in the glove's frame);
- robot: from the URDF's joint origins at q = 0 (wrist: `right_wrist`, bases:
  `right_index_abd`, `right_middle_abd`, `right_ring_abd`), computed once with pinocchio in the
  root frame: `R_r`. The wrist joint is held at 0, so the palm does not turn in the root frame.

Each wrist-centred keypoint `p - p_wrist` becomes `R_r R_h^T (p - p_wrist)`: the human hand is
turned so that its palm frame lies on the robot's, and dex's reference vectors are differences of
those points (its `target_link_human_indices`). This is also the palm frame that `pomdar eval`
scores fingertips in (`retarget::PalmFrame`; the robot's landmarks are its wrist axis and
abduction joints), so neither retargeter is scored in a frame it was not aligned to.

Alternatives, not used: (a) dex's own MANO convention (SVD frame of points 0, 5, 9, then
`OPERATOR2MANO`), which would need a further hand-measured rotation from MANO to the ORCA root
frame; (b) a frame from wrist, index base and little base (x = index - little), which differs
from this one by a few degrees of roll about y when the ring and little bases are not in line;
(c) no rotation at all, which is only right if the glove's frame happened to equal the robot's.

Frames whose keypoints are not finite or whose palm is collapsed (an axis under 2 mm) are not
retargeted: no command is written for them (the previous one stays in force) and they are
counted on stderr.
"""

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

# The repository's sibling shared/ folder (../shared from the repository root).
DEFAULT_URDF = (Path(__file__).resolve().parents[3].parent
                / "shared/reference/orcahand_v1_right.urdf")
KEYPOINT_TOPIC = "/ingress/mano"
COMMAND_TOPIC = "/dex/joint_states"
DIGITS = ["thumb", "index", "middle", "ring", "pinky"]
TIP_LINKS = [f"right_{d}_fingertip" for d in DIGITS]
WRIST_JOINT = "right_wrist"
ROBOT_WRIST_LANDMARK = "right_wrist"
ROBOT_BASE_LANDMARKS = {"index": "right_index_abd", "middle": "right_middle_abd",
                        "ring": "right_ring_abd"}
# MediaPipe-21 indices of the human landmarks.
MP_WRIST, MP_INDEX_BASE, MP_MIDDLE_BASE, MP_RING_BASE = 0, 5, 9, 13
MIN_PALM_AXIS_M = 0.002

JOINT_STATE_MSG = """std_msgs/Header header
string[] name
float64[] position
float64[] velocity
float64[] effort

================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id

================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
"""


def palm_rotation(wrist, index_base, middle_base, ring_base):
    """Columns x, y, z of the palm frame (see the module doc), or None when collapsed."""
    y = middle_base - wrist
    y_len = np.linalg.norm(y)
    if not np.isfinite(y_len) or y_len < MIN_PALM_AXIS_M:
        return None
    y = y / y_len
    d = index_base - ring_base
    x = d - y * np.dot(d, y)
    x_len = np.linalg.norm(x)
    if not np.isfinite(x_len) or x_len < MIN_PALM_AXIS_M:
        return None
    x = x / x_len
    return np.column_stack([x, y, np.cross(x, y)])


def stripped_urdf(urdf_path: Path, out_dir: Path) -> Path:
    """A copy of the URDF without <visual> and <collision> (kinematics only): its meshes are
    `package://` paths that are not on this machine, and dex / pinocchio need none of them."""
    from lxml import etree

    tree = etree.parse(str(urdf_path))
    for tag in ("visual", "collision"):
        for element in tree.getroot().iter(tag):
            element.getparent().remove(element)
    out = out_dir / urdf_path.name
    tree.write(str(out), xml_declaration=True, encoding="utf-8")
    return out


def build_retargeting(kind, urdf, origin_link, scaling, alpha):
    from dex_retargeting.retargeting_config import RetargetingConfig
    import pinocchio as pin

    # Joint names of the URDF's revolute joints, to leave the wrist out of the optimisation.
    model = pin.buildModelFromUrdf(str(urdf))
    dof_names = [n for i, n in enumerate(model.names) if model.nqs[i] > 0]
    finger_joints = [n for n in dof_names if n != WRIST_JOINT]
    common = dict(
        urdf_path=str(urdf),
        target_joint_names=finger_joints,
        scaling_factor=scaling,
        low_pass_alpha=alpha,
        add_dummy_free_joint=False,
    )
    if kind == "vector":
        config = RetargetingConfig(
            type="vector",
            target_origin_link_names=[origin_link] * 5,
            target_task_link_names=TIP_LINKS,
            target_link_human_indices=np.array([[0, 0, 0, 0, 0], [4, 8, 12, 16, 20]]),
            **common,
        )
    else:
        config = RetargetingConfig(
            type="dexpilot",
            finger_tip_link_names=TIP_LINKS,
            wrist_link_name=origin_link,
            **common,
        )
    return config.build()


def robot_palm_rotation(retargeting):
    """The robot palm frame's rotation in dex's root frame, from the URDF's joint origins with
    every joint at 0 (the wrist is held there; the landmarks are rigid with the palm)."""
    import pinocchio as pin

    model = retargeting.optimizer.robot.model
    data = model.createData()
    pin.forwardKinematics(model, data, pin.neutral(model))

    def joint_position(name):
        if not model.existJointName(name):
            raise SystemExit(f"the URDF has no joint '{name}' (a palm-frame landmark)")
        return np.array(data.oMi[model.getJointId(name)].translation)

    rotation = palm_rotation(
        joint_position(ROBOT_WRIST_LANDMARK),
        joint_position(ROBOT_BASE_LANDMARKS["index"]),
        joint_position(ROBOT_BASE_LANDMARKS["middle"]),
        joint_position(ROBOT_BASE_LANDMARKS["ring"]),
    )
    if rotation is None:
        raise SystemExit("the robot's palm landmarks are degenerate")
    return rotation


def read_keypoints(path):
    """(header, schema, channel, messages) of the keypoint topic, messages sorted by log time
    (stable: file order within equal times), each with its decoded N x 3 array."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    factory = DecoderFactory()
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        header = reader.get_header()
        messages = []
        schema = channel = decoder = None
        for sch, chan, message in reader.iter_messages(topics=[KEYPOINT_TOPIC],
                                                       log_time_order=False):
            if channel is None:
                schema, channel = sch, chan
                decoder = factory.decoder_for(chan.message_encoding, sch)
            elif chan.id != channel.id:
                raise SystemExit(f"{path}: more than one channel on {KEYPOINT_TOPIC}")
            decoded = decoder(message.data)
            points = np.asarray(decoded.data, dtype=np.float32)
            messages.append((message, points))
    if not messages:
        raise SystemExit(f"{path}: no messages on {KEYPOINT_TOPIC}")
    messages.sort(key=lambda m: m[0].log_time)
    return header, schema, channel, messages


def to_mediapipe21(points):
    n = points.size // 3
    if points.size % 3 or n not in (21, 22):
        return None
    rows = points.reshape(n, 3).astype(np.float64)
    return rows[1:] if n == 22 else rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input", type=Path)
    parser.add_argument("output", type=Path)
    parser.add_argument("--type", choices=["vector", "dexpilot"], required=True)
    parser.add_argument("--low-pass-alpha", default="0.2",
                        help="dex's low-pass alpha (default 0.2); 'none' or outside [0, 1]: "
                        "no filter")
    parser.add_argument("--urdf", type=Path, default=DEFAULT_URDF)
    parser.add_argument("--scaling", type=float, default=1.0,
                        help="dex's scaling_factor of the human vectors (default 1.0)")
    parser.add_argument("--origin-link", default="right_wrist_jointbody",
                        help="robot link of the human wrist (default right_wrist_jointbody)")
    parser.add_argument("--quiet", action="store_true")
    args = parser.parse_args(argv)

    alpha = -1.0 if args.low_pass_alpha.lower() in ("none", "off") else float(args.low_pass_alpha)
    import torch

    torch.set_num_threads(1)  # tiny tensors: threads only add overhead

    from mcap.writer import Writer
    from mcap_ros2._dynamic import serialize_dynamic

    started = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="dex-urdf-") as tmp:
        urdf = stripped_urdf(args.urdf.resolve(), Path(tmp))
        retargeting = build_retargeting(args.type, urdf, args.origin_link, args.scaling, alpha)
    joint_names = list(retargeting.joint_names)
    fixed_names = retargeting.optimizer.fixed_joint_names
    fixed_qpos = np.zeros(len(fixed_names))
    rotation_robot = robot_palm_rotation(retargeting)
    indices = np.asarray(retargeting.optimizer.target_link_human_indices)
    encode = serialize_dynamic("sensor_msgs/msg/JointState", JOINT_STATE_MSG)[
        "sensor_msgs/msg/JointState"]

    header, schema, channel, messages = read_keypoints(args.input)
    distinct = skipped = 0
    solve_s = []
    previous = None
    args.output.parent.mkdir(parents=True, exist_ok=True)
    with open(args.output, "wb") as stream:
        writer = Writer(stream)
        writer.start(profile=header.profile or "ros2", library="pomdar tests/interop/dex")
        schema_id = writer.register_schema(schema.name, schema.encoding, schema.data)
        channel_id = writer.register_channel(channel.topic, channel.message_encoding, schema_id,
                                             dict(channel.metadata))
        js_schema = writer.register_schema("sensor_msgs/msg/JointState", "ros2msg",
                                           JOINT_STATE_MSG.encode())
        js_channel = writer.register_channel(COMMAND_TOPIC, "cdr", js_schema)
        js_sequence = 0
        for message, points in messages:
            writer.add_message(channel_id, message.log_time, message.data, message.publish_time,
                               message.sequence)
            if previous is not None and np.array_equal(points, previous):
                continue
            previous = points
            distinct += 1
            rows = to_mediapipe21(points)
            if rows is None or not np.all(np.isfinite(rows)):
                skipped += 1
                continue
            rotation_human = palm_rotation(rows[MP_WRIST], rows[MP_INDEX_BASE],
                                           rows[MP_MIDDLE_BASE], rows[MP_RING_BASE])
            if rotation_human is None:
                skipped += 1
                continue
            aligned = (rows - rows[MP_WRIST]) @ rotation_human @ rotation_robot.T
            ref_value = aligned[indices[1]] - aligned[indices[0]]
            tic = time.perf_counter()
            qpos = retargeting.retarget(ref_value, fixed_qpos)
            solve_s.append(time.perf_counter() - tic)
            t = message.log_time
            js_sequence += 1
            data = encode({
                "header": {"stamp": {"sec": t // 1_000_000_000, "nanosec": t % 1_000_000_000},
                           "frame_id": ""},
                "name": joint_names,
                "position": [float(v) for v in qpos],
                "velocity": [],
                "effort": [],
            })
            writer.add_message(js_channel, t, data, t, js_sequence)
        writer.finish()

    if not args.quiet:
        solve = np.array(solve_s) * 1e3 if solve_s else np.array([math.nan])
        print(
            f"{args.input} -> {args.output}: dex {args.type} (alpha "
            f"{'off' if not 0 <= alpha <= 1 else alpha}, scaling {args.scaling}, origin "
            f"{args.origin_link}): {len(messages)} keypoint messages, {distinct} distinct frames, "
            f"{js_sequence} commands, {skipped} skipped; solve {np.mean(solve):.2f} ms mean, "
            f"{np.percentile(solve, 99):.2f} ms p99; {time.perf_counter() - started:.1f} s total",
            file=sys.stderr,
        )


if __name__ == "__main__":
    main()
