"""Decode every message of an MCAP file with independent readers and print a JSON report.

Usage: read_mcap.py [--values] FILE.mcap

Readers: the `mcap` package with `mcap-ros2-support` (decodes CDR with the file's own ros2msg
schemas) and `rosbags` (its own CDR and msg parser). The report lists, per reader, the message
count per topic and the first decoding error if any; with `--values`, also every decoded message
per topic in log-time order, as plain JSON keyed by the schema's field names. The exit status is
non-zero when either reader fails on any message.
"""

import dataclasses
import json
import sys
from collections import Counter, defaultdict


def plain(value):
    """A decoded message as dicts and lists keyed by the schema's field names."""
    if dataclasses.is_dataclass(value):  # rosbags (`__msgtype__` names the type, not a field)
        # Types built from a file's schemas carry the constants (`Marker.ADD`) as dataclass
        # fields; ROS names constants in upper case and fields in lower case.
        return {
            f.name: plain(getattr(value, f.name))
            for f in dataclasses.fields(value)
            if not f.name.startswith("__") and not f.name.isupper()
        }
    if hasattr(value, "__slots__") and hasattr(value, "_type"):  # mcap-ros2-support
        return {name: plain(getattr(value, name)) for name in value.__slots__}
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        return value.tolist()
    if isinstance(value, (bytes, bytearray, memoryview)):  # mcap-ros2-support's uint8[]
        return list(value)
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    return value


def read_with_mcap(path, values):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    counts = Counter()
    decoded_values = defaultdict(list)
    with open(path, "rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        for _schema, channel, _message, decoded in reader.iter_decoded_messages():
            counts[channel.topic] += 1
            # Touch every field so a wrong layout raises.
            repr(decoded)
            if values:
                decoded_values[channel.topic].append(plain(decoded))
        stats = summary.statistics if summary else None
        report = {
            "counts": dict(counts),
            "statistics_message_count": stats.message_count if stats else None,
            "profile": reader.get_header().profile,
        }
    if values:
        report["values"] = decoded_values
    return report


def read_with_rosbags(path, values):
    from rosbags.highlevel import AnyReader
    from pathlib import Path

    counts = Counter()
    decoded_values = defaultdict(list)
    with AnyReader([Path(path)]) as reader:
        for connection, _timestamp, rawdata in reader.messages():
            message = reader.deserialize(rawdata, connection.msgtype)
            repr(message)
            counts[connection.topic] += 1
            if values:
                decoded_values[connection.topic].append(plain(message))
    report = {"counts": dict(counts)}
    if values:
        report["values"] = decoded_values
    return report


def main():
    values = "--values" in sys.argv[1:]
    path = [a for a in sys.argv[1:] if a != "--values"][0]
    report = {}
    failed = False
    for name, read in (("mcap_ros2", read_with_mcap), ("rosbags", read_with_rosbags)):
        try:
            report[name] = read(path, values)
        except Exception as error:  # report, never hide
            report[name] = {"error": f"{type(error).__name__}: {error}"}
            failed = True
    print(json.dumps(report, sort_keys=True))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
