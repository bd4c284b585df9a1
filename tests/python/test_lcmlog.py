"""slammtt.lcmlog: reading what LCM's writer wrote, damaged logs, undecodable events."""

import struct

import pytest
from conftest import odometry
from slammtt_msgs import features_t, leg_labels_t

from slammtt import msgs
from slammtt.lcmlog import HEADER, LogError, LogReader, LogWriter


def write(path, events):
    with LogWriter(path) as writer:
        for utime, channel, message in events:
            writer.write(utime, channel, message)
    return path


def three_event_log(tmp_path):
    return write(tmp_path / "a.lcm", [(10, "ODOMETRY", odometry(10, 1.0)),
                                      (20, "ODOMETRY", odometry(20, 2.0)),
                                      (30, "ODOMETRY", odometry(30, 3.0))])


def event_offsets(path):
    data = path.read_bytes()
    offsets, at = [], 0
    while at < len(data):
        offsets.append(at)
        _, _, _, c, d = HEADER.unpack_from(data, at)
        at += HEADER.size + c + d
    return offsets


def test_reads_what_lcms_writer_wrote(tmp_path):
    log = three_event_log(tmp_path)
    reader = LogReader(log)
    got = [(m.channel, m.utime, m.message.x_m) for m in reader]
    assert got == [("ODOMETRY", 10, 1.0), ("ODOMETRY", 20, 2.0), ("ODOMETRY", 30, 3.0)]
    assert reader.events_read == 3 and reader.damage == "" and not reader.undecodable
    assert [e.number for e in LogReader(log).events()] == [0, 1, 2]


def test_writer_leaves_no_partial_file_on_failure(tmp_path):
    out = tmp_path / "out.lcm"
    with pytest.raises(RuntimeError):
        with LogWriter(out) as writer:
            writer.write(1, "ODOMETRY", odometry(1, 0.0))
            raise RuntimeError("boom")
    assert not out.exists() and not [p for p in tmp_path.iterdir() if ".partial" in p.name]


def test_truncated_tail_is_a_warning_and_strict_an_error(tmp_path):
    log = three_event_log(tmp_path)
    data = log.read_bytes()
    for cut in (len(data) - 5, event_offsets(log)[2] + 10, event_offsets(log)[2] + 2):
        damaged = tmp_path / "cut.lcm"
        damaged.write_bytes(data[:cut])
        reader = LogReader(damaged)
        assert [m.utime for m in reader] == [10, 20]
        assert reader.truncated
        assert reader.damage.startswith(f"truncated final event at byte {event_offsets(log)[2]}")
        with pytest.raises(LogError, match="truncated final event"):
            list(LogReader(damaged, strict=True))


def test_bad_sync_word_is_an_error_after_the_events_before_it(tmp_path):
    log = three_event_log(tmp_path)
    data = bytearray(log.read_bytes())
    second = event_offsets(log)[1]
    data[second] ^= 0xFF
    log.write_bytes(bytes(data))
    reader = LogReader(log)
    seen = []
    with pytest.raises(LogError) as error:
        for m in reader:
            seen.append(m.utime)
    assert seen == [10]
    assert str(error.value) == (f"{log}: corrupt event header at byte {second} (bad sync word); "
                                "read the 1 events before it")


def test_impossible_lengths_are_corrupt(tmp_path):
    log = three_event_log(tmp_path)
    data = bytearray(log.read_bytes())
    second = event_offsets(log)[1]
    struct.pack_into(">i", data, second + 20, -4)  # channel length
    log.write_bytes(bytes(data))
    with pytest.raises(LogError, match=f"byte {second} .channel length -4"):
        list(LogReader(log))


def test_a_length_past_the_end_with_events_after_it_is_corrupt(tmp_path):
    log = three_event_log(tmp_path)
    data = bytearray(log.read_bytes())
    _, second, third = event_offsets(log)
    struct.pack_into(">i", data, second + 24, 10_000_000)  # data length
    log.write_bytes(bytes(data))
    with pytest.raises(LogError, match=f"an event follows at byte {third}"):
        list(LogReader(log))


def test_undecodable_events_are_skipped_and_counted(tmp_path):
    good = odometry(5, 1.0).encode()
    labels = leg_labels_t()
    labels.num_legs = 1
    labels.x_m, labels.y_m = [1.0], [2.0]
    negative = bytearray(features_t().encode())
    struct.pack_into(">i", negative, 8 + 16, -1)   # num_features of an empty features_t
    log = write(tmp_path / "b.lcm", [
        (1, "ODOMETRY", good),
        (2, "X", b"\x01\x02\x03"),                          # shorter than a fingerprint
        (3, "X", b"\x00" * 8 + good[8:]),                   # unknown fingerprint
        (4, "ODOMETRY", good[:-3]),                         # truncated
        (5, "ODOMETRY", good + b"\x00"),                    # trailing byte
        (6, "LEG_LABELS", labels.encode()[:-8]),            # array cut short
        (7, "FEATURES", bytes(negative)),                   # negative count
        (8, "LEG_LABELS", labels),
    ])
    reader = LogReader(log)
    got = [(m.channel, m.utime) for m in reader]
    assert got == [("ODOMETRY", 1), ("LEG_LABELS", 8)]
    assert reader.undecodable == {"X": 2, "ODOMETRY": 2, "LEG_LABELS": 1, "FEATURES": 1}
    assert reader.first_undecodable.startswith("event 1 on X:")


def test_decode_reports_why():
    with pytest.raises(msgs.UndecodableMessage, match="unknown type fingerprint"):
        msgs.decode(b"\x00" * 16)
    huge = bytearray(leg_labels_t().encode())
    struct.pack_into(">i", huge, 16, 2**31 - 1)
    with pytest.raises(msgs.UndecodableMessage, match="not a whole leg_labels_t"):
        msgs.decode(bytes(huge))


def test_missing_file_is_one_line(tmp_path):
    with pytest.raises(LogError, match="cannot read log file"):
        list(LogReader(tmp_path / "absent.lcm"))
