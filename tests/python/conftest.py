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


# The stack's programs a test runs on a shipped scenario (skipped when they are not built).
WORLD = BIN_DIR / "slammtt-world"
REPLAY_PROGRAM = BIN_DIR / "slammtt-replay"
EVAL = BIN_DIR / "slammtt-eval"


def run_module(module, *args, timeout=300, env=None):
    """`python -m module args` of this venv: (exit status, stdout, stderr)."""
    done = subprocess.run([sys.executable, "-m", module, *map(str, args)], capture_output=True,
                          text=True, timeout=timeout, env=env)
    return done.returncode, done.stdout, done.stderr


def run_export(*args):
    return run_module("slammtt.export.cli", *args)


def export_ok(*args):
    status, out, err = run_export(*args)
    assert status == 0, err
    return err


def venv_program(name):
    """A program of this venv (evo_ape, evo_rpe, ...)."""
    return pathlib.Path(sys.executable).parent / name


class ScenarioRun:
    """A shipped scenario's scans through slammtt-replay, its slammtt-eval JSON report, and the
    estimator configuration both used."""

    def __init__(self, directory, scenario, seed, duration_s):
        import json
        self.config = SOURCE_DIR / "estimator" / "config" / f"{scenario}.yaml"
        world = directory / "world.lcm"
        self.log = directory / f"{scenario}-seed{seed}.lcm"
        self.report_path = directory / "report.json"
        for command in (
                [WORLD, "--scenario", scenario, "--seed", seed, "--duration", duration_s,
                 "--output", "scans", "--log", world],
                [REPLAY_PROGRAM, "-q", "--no-timing", world, "-o", self.log, "--config",
                 self.config],
                [EVAL, self.log, "--config", self.config, "--json", self.report_path]):
            done = subprocess.run(list(map(str, command)), capture_output=True, text=True,
                                  timeout=600)
            assert done.returncode == 0, done.stderr
        self.report = json.loads(self.report_path.read_text())


def scenario_run(tmp_path_factory, scenario, seed, duration_s=20):
    for program in (WORLD, REPLAY_PROGRAM, EVAL):
        if not program.exists():
            pytest.skip(f"{program} is not built: the tests on a scenario's log are skipped")
    return ScenarioRun(tmp_path_factory.mktemp(f"{scenario}-{seed}"), scenario, seed,
                       duration_s)


@pytest.fixture
def netns():
    """Skips a test that uses LCM unless it runs in a private network namespace (ctest runs
    test_live_*.py through tests/support/netns-run)."""
    if os.environ.get("SLAMMTT_IN_NETNS") != "1":
        pytest.skip("not in a private network namespace (run it through ctest or "
                    "tests/support/netns-run): LCM tests are skipped")


def evo_stats(program, *args, home):
    """An evo program of this venv (evo_ape, evo_rpe) run as a user runs it, with HOME (where
    evo keeps its settings) in `home`; its statistics (rmse, max, mean, ...) read back from
    --save_results."""
    from evo.tools import file_interface
    results = home / f"{program}-results.zip"
    env = dict(os.environ, HOME=str(home), MPLBACKEND="Agg")
    done = subprocess.run([str(venv_program(program)), *map(str, args), "--no_warnings",
                           "--save_results", str(results)], capture_output=True, text=True,
                          env=env, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    stats = file_interface.load_res_file(str(results)).stats
    results.unlink()
    return stats
