"""The README's commands for a real recording, run as written (with /tmp/ a temporary folder):
the block after "A real recording" (the venv, slammtt-import of negative_2.bag, slammtt-replay
with the mount it wrote) and the "Pictures" block of "Looking at the data" (slammtt-eval --plots
on that replay: no GROUND_TRUTH, so it draws the pictures, scores nothing and exits 1, as the
README says). Skipped, with the reason, without ../shared/data/real."""

import re
import shlex
import subprocess

from conftest import BIN_DIR, SOURCE_DIR

PICTURES = {"trajectory.svg", "map.svg", "tracks.svg", "identities.svg", "errors.svg",
            "scan.svg"}


def sh_block_after(text, marker):
    block = re.search(r"```sh\n(.*?)```", text.split(marker, 1)[1], re.S).group(1)
    return [line.split("#", 1)[0].strip() for line in block.splitlines()
            if line.split("#", 1)[0].strip()]


def readme_blocks():
    readme = (SOURCE_DIR / "README.md").read_text()
    looking = readme.split("## Looking at the data\n", 1)[1]
    return (sh_block_after(readme, "A real recording (a ROS 1 / ROS 2 bag"),
            sh_block_after(looking, "### Pictures\n"))


def test_the_blocks_hold_the_import_replay_and_pictures_commands():
    recording, pictures = readme_blocks()
    assert [shlex.split(c)[0] for c in recording] == [
        "scripts/python-env.sh", "build/bin/slammtt-import", "build/bin/slammtt-replay"]
    assert [shlex.split(c)[0] for c in pictures] == ["build/bin/slammtt-eval"]


def run_as_written(command, tmp_path):
    words = [w.replace("/tmp/", f"{tmp_path}/") for w in shlex.split(command)]
    if words[0].startswith("build/bin/"):
        words[0] = str(BIN_DIR / words[0][len("build/bin/"):])
    return subprocess.run(words, capture_output=True, text=True, cwd=SOURCE_DIR, timeout=600)


def test_a_real_recording_imports_replays_and_is_drawn(shared_real, tmp_path):
    recording, pictures = readme_blocks()
    for command in recording[1:]:               # the first makes the venv this test runs in
        done = run_as_written(command, tmp_path)
        assert done.returncode == 0, done.stderr
    done = run_as_written(pictures[0], tmp_path)
    assert done.returncode == 1, done.stderr    # nothing to score: exit 1, pictures drawn
    assert "pictures of what the log holds, nothing scored" in done.stdout + done.stderr
    assert "no GROUND_TRUTH" in done.stderr
    drawn = {p.name for p in (tmp_path / "n2-pictures").iterdir()}
    assert drawn == PICTURES
    assert all((tmp_path / "n2-pictures" / name).stat().st_size > 1000 for name in drawn)
