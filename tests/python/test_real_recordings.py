"""slammtt-import on every real recording of ../shared/data/real (skipped, with a message, when
that folder is absent): every bag and every laser topic imports with the counts of BAGS.md, and
the BreezySLAM logs give their scan counts and a plausible odometry path."""

import math
import re

import pytest

from slammtt.importer import cli

from conftest import SHARED_REAL, read_log

BAG_FOLDERS = ("leg_tracker_training", "leg_tracker_demo")


def bags_md_topics():
    """[(bag file name, topic, type, count)] of every BAGS.md table."""
    rows = []
    for folder in BAG_FOLDERS:
        bags_md = SHARED_REAL / folder / "BAGS.md"
        if not bags_md.exists():
            continue
        bag = None
        for line in bags_md.read_text().splitlines():
            heading = re.match(r"### `(.+\.bag)`", line)
            if heading:
                bag = heading.group(1)
            row = re.match(r"\| `([^`]+)` \| `([^`]+)` \| (\d+) \|", line)
            if row and bag:
                rows.append((bag, row.group(1), row.group(2), int(row.group(3))))
    return rows


def bag_file(name):
    found = sorted(p for folder in BAG_FOLDERS for p in (SHARED_REAL / folder).rglob(name))
    assert len(found) == 1, (name, found)
    return found[0]


def laser_topics():
    return [(bag, topic, count) for bag, topic, kind, count in bags_md_topics()
            if kind == "sensor_msgs/LaserScan"]


def run(capsys, *args):
    status = cli.main([str(a) for a in args])
    err = capsys.readouterr().err
    assert status == 0, err
    return err


def test_the_recordings_are_there(shared_real):
    # Guards against BAGS.md moving away silently: 11 bags, 13 laser topics.
    assert len({bag for bag, _, _ in laser_topics()}) == 11
    assert len(laser_topics()) == 13


@pytest.mark.parametrize("bag, topic, count", laser_topics() or [("", "", 0)],
                         ids=[f"{b}:{t}" for b, t, _ in laser_topics()] or ["absent"])
def test_every_laser_topic_imports_with_its_scan_count(shared_real, tmp_path, capsys, bag,
                                                       topic, count):
    out = tmp_path / "out.lcm"
    err = run(capsys, bag_file(bag), "-o", out, "--laser-topic", topic)
    log = read_log(out)
    scans = log["LASER_SCAN"]
    assert len(scans) == count
    assert "skipped" not in err
    valid = sum(sum(s.valid) for s in scans) / sum(s.num_beams for s in scans)
    assert 0.3 < valid < 0.9
    assert all(b.utime < a.utime for b, a in zip(scans, scans[1:]))
    labels = [(t, c) for b, t, kind, c in bags_md_topics()
              if b == bag and kind == "geometry_msgs/PoseArray"]
    if labels:
        assert len(log["LEG_LABELS"]) == labels[0][1]
        assert [m.utime for m in log["LEG_LABELS"]] == [s.utime for s in scans]


def test_negative_2_has_three_lasers_and_the_first_is_the_default(shared_real, tmp_path,
                                                                  capsys):
    err = run(capsys, bag_file("negative_2.bag"), "-o", tmp_path / "n.lcm")
    assert "sensor_msgs/LaserScan topic /left_scan: the first of 3 (/left_scan, /rear_scan, " \
           "/right_scan); choose another with --laser-topic" in err
    assert len(read_log(tmp_path / "n.lcm")["LASER_SCAN"]) == 435


def test_labels_per_scan_match_bags_md(shared_real, tmp_path, capsys):
    # BAGS.md: average poses per message of each positive_N_extracted.bag.
    averages = {}
    bags_md = (SHARED_REAL / "leg_tracker_training" / "BAGS.md").read_text()
    for bag, average in re.findall(r"### `(positive_\d_extracted\.bag)`.*?PoseArray.*?"
                                   r"([0-9.]+) poses/message", bags_md, re.S):
        averages[bag] = float(average)
    assert len(averages) == 4
    for bag, average in sorted(averages.items()):
        out = tmp_path / f"{bag}.lcm"
        run(capsys, bag_file(bag), "-o", out)
        labels = read_log(out)["LEG_LABELS"]
        assert round(sum(m.num_legs for m in labels) / len(labels), 2) == average, bag


@pytest.mark.parametrize("name, scans, seconds", [("exp1.dat", 756, 74.6),
                                                  ("exp2.dat", 641, 63.2)])
def test_breezyslam_logs(shared_real, tmp_path, capsys, name, scans, seconds):
    out = tmp_path / "mines.lcm"
    err = run(capsys, shared_real / "breezyslam_mines" / name, "-o", out)
    assert "skipped" not in err and "warning" not in err
    log = read_log(out)
    odometry, laser = log["ODOMETRY"], log["LASER_SCAN"]
    assert len(laser) == len(odometry) == scans
    assert all(s.num_beams == 682 for s in laser)
    span_s = (laser[-1].utime - laser[0].utime) * 1e-6
    assert span_s == pytest.approx(seconds, abs=0.05)
    steps = sorted(math.hypot(b.x_m - a.x_m, b.y_m - a.y_m) / ((b.utime - a.utime) * 1e-6)
                   for a, b in zip(odometry, odometry[1:]))
    path_m = sum(math.hypot(b.x_m - a.x_m, b.y_m - a.y_m)
                 for a, b in zip(odometry, odometry[1:]))
    # A lab robot driven through rooms and a corridor: about walking pace on average (measured
    # 0.62 and 0.70 m/s), and no interval faster than a running person (measured peaks over
    # 0.1 s: 1.70 and 2.99 m/s, docs/import.md).
    assert 0.2 < path_m / span_s < 1.2, path_m
    assert steps[len(steps) // 2] < 1.5
    assert steps[-1] < 4.0
    turned = sum(abs(math.remainder(b.heading_rad - a.heading_rad, 2 * math.pi))
                 for a, b in zip(odometry, odometry[1:]))
    assert turned < 4 * path_m   # not spinning in place: under 4 rad per metre driven
