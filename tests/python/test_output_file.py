"""slammtt.output_file: the Python tools' outputs (LogWriter's logs, slammtt-import's mount
file) are never written through a link planted at a partial name or at the output's own name.
Before: LogWriter opened "<path>.partial" with LCM's fopen("w") and slammtt-import its
"<mount>.partial" with open("w"), and a link planted there received the output (the target
overwritten, the link left in place)."""

import os

import pytest
from conftest import odometry

from slammtt.lcmlog import LogReader, LogWriter
from slammtt.output_file import create_partial, write_text_atomically

VICTIM_TEXT = b"not yours to overwrite\n"


def plant_links(tmp_path, out):
    """Links at every partial name a writer of `out` could pick first (the old fixed one and
    the first new ones), dangling and onto a victim file; returns the victim's path."""
    victim = tmp_path / "victim.txt"
    victim.write_bytes(VICTIM_TEXT)
    os.symlink(victim, f"{out}.partial")
    os.symlink(victim, f"{out}.partial.{os.getpid()}.0")
    os.symlink(tmp_path / "missing.txt", f"{out}.partial.{os.getpid()}.1")
    return victim


def leftovers(tmp_path):
    return sorted(p.name for p in tmp_path.iterdir() if ".partial." in p.name and
                  not p.is_symlink())


def test_log_writer_never_writes_through_a_planted_link(tmp_path):
    out = tmp_path / "out.lcm"
    victim = plant_links(tmp_path, out)
    with LogWriter(out) as writer:
        writer.write(10, "ODOMETRY", odometry(10, 1.5))
        partial = writer.partial
    assert victim.read_bytes() == VICTIM_TEXT
    assert partial == f"{out}.partial.{os.getpid()}.2"  # the first free name
    assert not (tmp_path / "missing.txt").exists()
    assert [m.message.x_m for m in LogReader(out)] == [1.5]
    assert leftovers(tmp_path) == []


def test_a_link_at_the_output_name_is_replaced_not_followed(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_bytes(VICTIM_TEXT)
    out = tmp_path / "out.lcm"
    os.symlink(victim, out)
    with LogWriter(out) as writer:
        writer.write(10, "ODOMETRY", odometry(10, 2.5))
    assert victim.read_bytes() == VICTIM_TEXT
    assert not out.is_symlink()
    assert [m.message.x_m for m in LogReader(out)] == [2.5]

    mount = tmp_path / "out.lcm.mount.yaml"
    os.symlink(victim, mount)
    write_text_atomically(mount, "rplidar: {}\n")
    assert victim.read_bytes() == VICTIM_TEXT
    assert not mount.is_symlink() and mount.read_text() == "rplidar: {}\n"


def test_text_output_never_writes_through_a_planted_link(tmp_path):
    mount = tmp_path / "run.lcm.mount.yaml"
    victim = plant_links(tmp_path, mount)
    write_text_atomically(mount, "estimator: {}\n")
    assert victim.read_bytes() == VICTIM_TEXT
    assert mount.read_text() == "estimator: {}\n"
    assert leftovers(tmp_path) == []


def test_a_failed_write_leaves_nothing(tmp_path):
    out = tmp_path / "out.lcm"
    with pytest.raises(RuntimeError):
        with LogWriter(out) as writer:
            writer.write(1, "ODOMETRY", odometry(1, 0.0))
            raise RuntimeError("boom")
    assert not out.exists() and leftovers(tmp_path) == []


def test_partial_files_are_new_and_private_to_the_umask(tmp_path):
    old = os.umask(0o027)
    try:
        fd, partial = create_partial(tmp_path / "x.lcm")
    finally:
        os.umask(old)
    os.close(fd)
    assert os.stat(partial).st_mode & 0o777 == 0o640
    fd2, partial2 = create_partial(tmp_path / "x.lcm")  # the first name is taken: the next
    os.close(fd2)
    assert partial2 != partial


def test_no_free_name_is_an_error_naming_the_output(tmp_path, monkeypatch):
    monkeypatch.setattr("slammtt.output_file.MAX_TRIES", 2)
    out = tmp_path / "y.lcm"
    for n in range(2):
        os.symlink(tmp_path / "nowhere", f"{out}.partial.{os.getpid()}.{n}")
    with pytest.raises(OSError, match="y.lcm: cannot create the output file"):
        create_partial(out)
