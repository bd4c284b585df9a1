"""Every command of the README's "Looking at the data" (its exports and Foxglove part), run as
written, on a scenario's replay in place of the office run (s1-crossing seed 7, 20 s, and its
configuration), with out/ a temporary folder: the exports, evo_ape (which prints slammtt-eval's
ATE), and slammtt-foxglove playing the log and live from LCM (each until it serves, then
SIGTERM: exit 0). In a network namespace of its own (netns-run), where the fixed port 8765 and
LCM's multicast are private."""

import os
import re
import shlex
import signal
import subprocess

import pytest

from conftest import BIN_DIR, SOURCE_DIR, scenario_run, venv_program


def readme_commands():
    readme = (SOURCE_DIR / "README.md").read_text()
    section = readme.split("## Looking at the data\n", 1)[1].split("\n## ", 1)[0]
    section = section.split("### Exports and the Foxglove view\n", 1)[1].split("\n### ", 1)[0]
    block = re.search(r"```sh\n(.*?)```", section, re.S).group(1)
    return [line.split("#", 1)[0].strip() for line in block.splitlines() if line.strip()]


def test_readme_lists_the_commands():
    commands = readme_commands()
    programs = [shlex.split(c)[0] for c in commands]
    assert programs == ["scripts/python-env.sh", "build/bin/slammtt-export",
                        "build/venv/bin/evo_ape", "build/bin/slammtt-foxglove",
                        "build/bin/slammtt-foxglove"]


def test_readme_commands_run(netns, tmp_path_factory):
    if not (BIN_DIR / "slammtt-export").exists():
        pytest.skip(f"{BIN_DIR}/slammtt-export is not written (configure the build)")
    run = scenario_run(tmp_path_factory, "s1-crossing", 7)
    out = tmp_path_factory.mktemp("out")
    # The office run's replay is named out/office-seed1-replay.lcm: the scenario's log takes
    # its place, under that name, with its own configuration.
    (out / "office-seed1-replay.lcm").write_bytes(run.log.read_bytes())
    home = tmp_path_factory.mktemp("home")
    env = dict(os.environ, HOME=str(home), MPLBACKEND="Agg")
    ran = []
    for command in readme_commands():
        words = [w.replace("estimator/config/office.yaml", str(run.config)) for w in
                 shlex.split(command)]
        words = [str(out / w[4:]) if w.startswith("out/") else w for w in words]
        program = words[0]
        if program == "scripts/python-env.sh":
            continue                      # the venv these tests run in
        if program.startswith("build/bin/"):
            words[0] = str(BIN_DIR / program[len("build/bin/"):])
        elif program.startswith("build/venv/bin/"):
            words[0] = str(venv_program(os.path.basename(program)))   # the venv of this test
        if program.endswith("slammtt-foxglove"):
            process = subprocess.Popen(words, stderr=subprocess.PIPE, text=True, cwd=SOURCE_DIR,
                                       env=env)
            try:
                line = process.stderr.readline()
                assert "serving ws://127.0.0.1:8765" in line, line + process.stderr.read()
            finally:
                process.send_signal(signal.SIGTERM)
                err = process.stderr.read()
                assert process.wait(timeout=30) == 0, err
        else:
            done = subprocess.run(words, capture_output=True, text=True, cwd=SOURCE_DIR,
                                  env=env, timeout=600)
            assert done.returncode == 0, done.stdout + done.stderr
            if program.endswith("evo_ape"):
                rmse = float(re.search(r"rmse\s+([0-9.]+)", done.stdout).group(1))
                assert rmse == pytest.approx(run.report["ate_rmse_m"], abs=1e-6)
        ran.append(os.path.basename(program))
    assert ran == ["slammtt-export", "evo_ape", "slammtt-foxglove", "slammtt-foxglove"]
    export = out / "office-export"
    assert (export / "tum" / "estimate.tum").exists() and (export / "csv" / "map.csv").exists()
    assert (export / "mot" / "frames.csv").exists()
    assert (export / "office-seed1-replay.mcap").stat().st_size > 100000


def spy_commands():
    readme = (SOURCE_DIR / "README.md").read_text()
    section = readme.split("### The raw messages: lcm-spy\n", 1)[1].split("\n## ", 1)[0]
    block = re.search(r"```sh\n(.*?)```", section, re.S).group(1)
    return [line.split("#", 1)[0].strip() for line in block.splitlines() if line.strip()]


def test_readme_lcm_spy_commands_run(netns, tmp_path_factory):
    """The lcm-spy block as written, on an Xvfb display: the spy starts in the background, the
    log (a scenario's replay in place of the office run's) plays onto the bus to its end, and
    the spy, still running, stops on SIGTERM."""
    import shutil
    import time
    commands = spy_commands()
    assert [shlex.split(c)[0] for c in commands] == ["build/bin/slammtt-lcm-spy",
                                                     "lcm-logplayer"]
    assert commands[0].endswith("&")
    spy = BIN_DIR / "slammtt-lcm-spy"
    if not spy.exists():
        pytest.skip(f"{spy} is not written: the build found no JDK (scripts/install-deps.sh)")
    if shutil.which("Xvfb") is None:
        pytest.skip("no Xvfb (Debian package xvfb, scripts/install-deps.sh): the spy needs a "
                    "display")
    run = scenario_run(tmp_path_factory, "s1-crossing", 7, duration_s=5)
    xvfb = subprocess.Popen(["Xvfb", "-displayfd", "1", "-nolisten", "tcp"],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        display = xvfb.stdout.readline().strip()
        assert display.isdigit(), display
        env = dict(os.environ, DISPLAY=f":{display}")
        process = subprocess.Popen(shlex.split(commands[0].rstrip("& ")), cwd=SOURCE_DIR,
                                   env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                   text=True)
        try:
            time.sleep(3)
            assert process.poll() is None, process.stdout.read()
            words = [str(run.log) if w == "out/office-seed1-replay.lcm" else w
                     for w in shlex.split(commands[1])]
            played = subprocess.run(words, capture_output=True, text=True, cwd=SOURCE_DIR,
                                    env=env, timeout=120)
            assert played.returncode == 0, played.stderr
            assert process.poll() is None, process.stdout.read()
        finally:
            process.send_signal(signal.SIGTERM)
            process.wait(timeout=30)
        types = len(list((SOURCE_DIR / "lcmtypes").glob("*.lcm")))
        assert f"Found {types} LCM types" in process.stdout.read()
    finally:
        xvfb.terminate()
        xvfb.wait(timeout=30)
