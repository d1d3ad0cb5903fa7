"""Decode every message of an MCAP file with independent readers and print a JSON report.

Usage: read_mcap.py FILE.mcap

Readers: the `mcap` package with `mcap-ros2-support` (decodes CDR with the file's own ros2msg
schemas) and `rosbags` (its own CDR and msg parser). The report lists, per reader, the message
count per topic and the first decoding error if any; the exit status is non-zero when either
reader fails on any message.
"""

import json
import sys
from collections import Counter


def read_with_mcap(path):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    counts = Counter()
    with open(path, "rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        for _schema, channel, _message, decoded in reader.iter_decoded_messages():
            counts[channel.topic] += 1
            # Touch every field so a wrong layout raises.
            repr(decoded)
        stats = summary.statistics if summary else None
        return {
            "counts": dict(counts),
            "statistics_message_count": stats.message_count if stats else None,
            "profile": reader.get_header().profile,
        }


def read_with_rosbags(path):
    from rosbags.highlevel import AnyReader
    from pathlib import Path

    counts = Counter()
    with AnyReader([Path(path)]) as reader:
        for connection, _timestamp, rawdata in reader.messages():
            message = reader.deserialize(rawdata, connection.msgtype)
            repr(message)
            counts[connection.topic] += 1
    return {"counts": dict(counts)}


def main():
    path = sys.argv[1]
    report = {}
    failed = False
    for name, read in (("mcap_ros2", read_with_mcap), ("rosbags", read_with_rosbags)):
        try:
            report[name] = read(path)
        except Exception as error:  # report, never hide
            report[name] = {"error": f"{type(error).__name__}: {error}"}
            failed = True
    print(json.dumps(report, sort_keys=True))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
