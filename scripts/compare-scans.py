#!/usr/bin/env python3
"""Simple statistics of 2D laser scans, the same code for the world's logs and real recordings
(issue 11: compare the simulated office with ../shared/data/real side by side).

    scripts/compare-scans.py --lcm-log office-hokuyo.lcm [--channel LASER_SCAN]
    scripts/compare-scans.py --bag ../shared/data/real/leg_tracker_training/negative_2.bag \\
        --topics /left_scan,/right_scan,/rear_scan

Prints one line per input: clusters (consecutive valid beams in angle order whose points are at
most 0.13 m apart, leg_tracker's default cluster_dist_euclid) with at least 3 points and their
widths (first to last point: median, p10, p90, share <= 0.2 m); the share of valid beams on
straight lines (each cluster split by iterative end-point fit until no point is more than 3 cm
off its chord; pieces of at least 5 points and 0.3 m); depth edges (neighbouring valid beams
whose ranges differ by more than 0.5 m) per scan; and points between the two sides of an edge
(a valid beam whose neighbours differ by more than 0.5 m and whose range lies more than 0.1 m
inside both: what mixed pixels leave, though a slanted surface can leave one too) per 1000 valid
beams and per edge.

LCM logs are read with the project's own laser_scan_t layout (no LCM module needed); bags need
the `rosbags` package (scripts/compare-scans.sh runs it in the venv of scripts/python-env.sh).
"""
import argparse
import math
import struct
import sys

CLUSTER_GAP_M = 0.13
LINE_TOLERANCE_M = 0.03
LINE_MIN_POINTS = 5
LINE_MIN_LENGTH_M = 0.3
EDGE_JUMP_M = 0.5
BETWEEN_MARGIN_M = 0.1


def line_pieces(xs, ys, a, b, out):
    """Iterative end-point fit of points a..b: appends the point counts of straight pieces."""
    if b - a + 1 < LINE_MIN_POINTS:
        return
    dx, dy = xs[b] - xs[a], ys[b] - ys[a]
    length = math.hypot(dx, dy)
    if length == 0.0:
        return
    worst, worst_k = -1.0, a
    for k in range(a, b + 1):
        d = abs((xs[k] - xs[a]) * dy - (ys[k] - ys[a]) * dx) / length
        if d > worst:
            worst, worst_k = d, k
    if worst > LINE_TOLERANCE_M:
        line_pieces(xs, ys, a, worst_k, out)
        line_pieces(xs, ys, worst_k, b, out)
    elif length >= LINE_MIN_LENGTH_M:
        out.append(b - a + 1)


def percentile(sorted_values, q):
    if not sorted_values:
        return float("nan")
    return sorted_values[min(len(sorted_values) - 1, int(q * len(sorted_values)))]


class ScanStatistics:
    def __init__(self):
        self.scans = 0
        self.valid = 0
        self.widths = []
        self.line_beams = 0
        self.edges = 0
        self.between = 0

    def add(self, angles, ranges, valid):
        beams = sorted((a, r, v) for a, r, v in zip(angles, ranges, valid))
        r = [b[1] for b in beams]
        v = [b[2] for b in beams]
        xs = [b[1] * math.cos(b[0]) for b in beams]
        ys = [b[1] * math.sin(b[0]) for b in beams]
        self.scans += 1
        self.valid += sum(v)
        start = None

        def close(s, e):
            if e - s + 1 >= 3:
                self.widths.append(math.hypot(xs[e] - xs[s], ys[e] - ys[s]))
            pieces = []
            line_pieces(xs, ys, s, e, pieces)
            self.line_beams += sum(pieces)

        for i in range(len(beams)):
            if not v[i]:
                if start is not None:
                    close(start, i - 1)
                    start = None
            elif start is None:
                start = i
            elif math.hypot(xs[i] - xs[i - 1], ys[i] - ys[i - 1]) > CLUSTER_GAP_M:
                close(start, i - 1)
                start = i
        if start is not None:
            close(start, len(beams) - 1)
        for i in range(1, len(beams)):
            if v[i] and v[i - 1] and abs(r[i] - r[i - 1]) > EDGE_JUMP_M:
                self.edges += 1
            if 1 <= i < len(beams) - 1 and v[i - 1] and v[i] and v[i + 1] and \
                    abs(r[i + 1] - r[i - 1]) > EDGE_JUMP_M:
                low, high = min(r[i - 1], r[i + 1]), max(r[i - 1], r[i + 1])
                if low + BETWEEN_MARGIN_M < r[i] < high - BETWEEN_MARGIN_M:
                    self.between += 1

    def line(self, name):
        w = sorted(self.widths)
        narrow = 100.0 * sum(1 for x in w if x <= 0.2) / max(1, len(w))
        return (f"{name}: {self.scans} scans, {self.valid} valid beams; {len(w)} clusters: width "
                f"median {percentile(w, 0.5):.3f} m, p10 {percentile(w, 0.1):.3f}, "
                f"p90 {percentile(w, 0.9):.3f}, <= 0.2 m {narrow:.1f} %; beams on straight lines "
                f"{100.0 * self.line_beams / max(1, self.valid):.1f} %; depth edges per scan "
                f"{self.edges / max(1, self.scans):.1f}; points between the sides of an edge "
                f"{1000.0 * self.between / max(1, self.valid):.2f} per 1000 valid beams, "
                f"{100.0 * self.between / max(1, self.edges):.1f} % of edges")


def read_lcm_scans(path, channel):
    """laser_scan_t messages of `channel` in an LCM event log (big-endian, as LCM encodes)."""
    with open(path, "rb") as f:
        data = f.read()
    pos = 0
    while pos + 28 <= len(data):
        sync, _, _, channel_len, data_len = struct.unpack_from(">IqqII", data, pos)
        if sync != 0xEDA1DA01:
            raise SystemExit(f"{path}: not an LCM log (bad sync word at byte {pos})")
        pos += 28
        name = data[pos:pos + channel_len].decode()
        pos += channel_len
        message = data[pos:pos + data_len]
        pos += data_len
        if name != channel:
            continue
        # fingerprint, utime, sequence, scan_duration_us, range_min_m, range_max_m, num_beams
        _, _, _, _, _, _, n = struct.unpack_from(">qqqqffi", message, 0)
        offset = 8 * 4 + 4 * 2 + 4
        angles = struct.unpack_from(f">{n}f", message, offset)
        ranges = struct.unpack_from(f">{n}f", message, offset + 4 * n)
        valid = struct.unpack_from(f">{n}b", message, offset + 12 * n)
        yield angles, ranges, [x != 0 for x in valid]


def read_bag_scans(path, topics):
    """sensor_msgs/LaserScan of `topics` (REP 117: NaN, inf and out-of-range are no return)."""
    from pathlib import Path
    from rosbags.highlevel import AnyReader
    with AnyReader([Path(path)]) as reader:
        connections = [c for c in reader.connections if c.topic in topics]
        if not connections:
            raise SystemExit(f"{path}: none of the topics {','.join(topics)}")
        for connection, _, raw in reader.messages(connections=connections):
            m = reader.deserialize(raw, connection.msgtype)
            ranges = [float(x) for x in m.ranges]
            angles = [m.angle_min + m.angle_increment * i for i in range(len(ranges))]
            valid = [math.isfinite(x) and m.range_min <= x <= m.range_max for x in ranges]
            yield angles, [x if ok else 0.0 for x, ok in zip(ranges, valid)], valid


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--lcm-log")
    parser.add_argument("--channel", default="LASER_SCAN")
    parser.add_argument("--bag")
    parser.add_argument("--topics", default="/scan")
    parser.add_argument("--name")
    args = parser.parse_args()
    if bool(args.lcm_log) == bool(args.bag):
        parser.error("give exactly one of --lcm-log and --bag")
    stats = ScanStatistics()
    scans = read_lcm_scans(args.lcm_log, args.channel) if args.lcm_log else \
        read_bag_scans(args.bag, args.topics.split(","))
    for angles, ranges, valid in scans:
        stats.add(angles, ranges, valid)
    print(stats.line(args.name or args.lcm_log or args.bag))


if __name__ == "__main__":
    sys.exit(main())
