"""Cuts the test fixture of tests/data/leg_tracker out of the leg_tracker bags (BSD 3-Clause,
Copyright (c) 2018, Angus Leigh; SOURCE.md beside this file):

  build/venv/bin/python tests/data/leg_tracker/make_fixture.py ../shared/data/real \\
      tests/data/leg_tracker

- positive_1_extracted_first20.bag: the first 20 /training_scan messages of
  leg_tracker_training/positive_1_extracted.bag with their /leg_cluster_positions (the label
  message before each scan in bag order); /visualization_marker_array left out;
- demo_stationary_first3s.bag: the /scan messages of the first 3 s (bag time) of
  leg_tracker_demo/demo_stationary_simple_environment.bag.
Messages are copied byte for byte, with their bag times and the bags' own message definitions,
by rosbags' ROS 1 writer (uncompressed). Running it again gives the same bytes.
"""

import pathlib
import sys

from rosbags.rosbag1 import Reader, Writer


def copy(source, destination, keep):
    """Writes the messages for which keep(connection, bag_time_ns, index_of_topic) is true;
    keep returns None to stop."""
    destination.unlink(missing_ok=True)
    with Reader(source) as reader, Writer(destination) as writer:
        connections = {}
        counts = {}
        for connection, bag_time_ns, raw in reader.messages():
            index = counts.get(connection.topic, 0)
            decision = keep(connection, bag_time_ns - reader.start_time, index)
            if decision is None:
                break
            counts[connection.topic] = index + 1
            if not decision:
                continue
            if connection.id not in connections:
                ext = connection.ext
                connections[connection.id] = writer.add_connection(
                    connection.topic, connection.msgtype, msgdef=connection.msgdef.data,
                    md5sum=connection.digest, callerid=ext.callerid, latching=ext.latching)
            writer.write(connections[connection.id], bag_time_ns, raw)


def main(shared, out):
    shared, out = pathlib.Path(shared), pathlib.Path(out)
    scans = 20

    def first_scans(connection, _, index):
        if connection.topic == "/training_scan" and index >= scans:
            return None
        return connection.topic in ("/training_scan", "/leg_cluster_positions") and \
            index < scans

    copy(shared / "leg_tracker_training/positive_1_extracted.bag",
         out / "positive_1_extracted_first20.bag", first_scans)

    def first_seconds(connection, since_start_ns, _):
        if since_start_ns >= 3_000_000_000:
            return None
        return connection.topic == "/scan"

    copy(shared / "leg_tracker_demo/demo_stationary_simple_environment.bag",
         out / "demo_stationary_first3s.bag", first_seconds)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
