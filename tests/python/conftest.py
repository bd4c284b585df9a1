"""Shared helpers of the Python tools' tests (run by tests/python/run-pytest in the venv of
scripts/python-env.sh; ctest passes SLAMMTT_SOURCE_DIR and SLAMMTT_BIN_DIR)."""

import os
import pathlib
import subprocess
import sys

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("SLAMMTT_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
BIN_DIR = pathlib.Path(os.environ.get("SLAMMTT_BIN_DIR", SOURCE_DIR / "build" / "bin"))
FIXTURE_DIR = SOURCE_DIR / "tests" / "data" / "leg_tracker"
POSITIVE_FIXTURE = FIXTURE_DIR / "positive_1_extracted_first20.bag"
DEMO_FIXTURE = FIXTURE_DIR / "demo_stationary_first3s.bag"
# ../shared relative to the checkout (SLAMMTT_SHARED_DIR overrides it, e.g. for a git worktree
# elsewhere): absent on a clean clone, where the tests on real recordings are skipped.
SHARED_DIR = pathlib.Path(os.environ.get("SLAMMTT_SHARED_DIR", SOURCE_DIR.parent / "shared"))
SHARED_REAL = SHARED_DIR / "data" / "real"


def run_import(*args):
    """slammtt-import of this venv, as a program: (exit status, stdout, stderr)."""
    command = [sys.executable, "-m", "slammtt.importer.cli", *map(str, args)]
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    return done.returncode, done.stdout, done.stderr


def import_ok(*args):
    status, out, err = run_import(*args)
    assert status == 0, err
    return err


def read_log(path):
    """{channel: [message, ...]} of a log, asserting it reads whole."""
    from slammtt.lcmlog import LogReader
    reader = LogReader(path, strict=True)
    channels = {}
    for m in reader:
        channels.setdefault(m.channel, []).append(m.message)
    assert not reader.undecodable, reader.first_undecodable
    return channels


@pytest.fixture
def shared_real():
    if not SHARED_REAL.is_dir():
        pytest.skip(f"real recordings absent ({SHARED_REAL}): the tests on them are skipped")
    return SHARED_REAL


def typestore(ros_version=1):
    from rosbags.typesys import Stores, get_typestore
    return get_typestore(Stores.ROS1_NOETIC if ros_version == 1 else Stores.ROS2_HUMBLE)


def odometry(utime, x):
    """An ODOMETRY message at `utime` [us] with x_m = `x`."""
    from slammtt_msgs import odometry_t
    m = odometry_t()
    m.utime = utime
    m.x_m = x
    return m
