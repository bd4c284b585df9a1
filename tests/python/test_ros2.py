"""ROS 2 bags (sqlite3 and MCAP): the ROS 1 fixture converted by rosbags gives the same log; a
ROS 2 bag with tf and odometry gives the same log as the same messages in a ROS 1 bag."""

import pathlib
import subprocess
import sys

import pytest

from conftest import DEMO_FIXTURE, POSITIVE_FIXTURE, import_ok
from test_rosbag_import import robot_bag

CONVERT = pathlib.Path(sys.executable).parent / "rosbags-convert"


def convert(source, destination, storage, typestore):
    command = [CONVERT, "--src", source, "--dst", destination, "--dst-storage", storage]
    if typestore:
        command += ["--dst-typestore", typestore]
    subprocess.run(command, check=True, capture_output=True, timeout=120)
    return destination


@pytest.mark.parametrize("fixture", [POSITIVE_FIXTURE, DEMO_FIXTURE], ids=["positive", "demo"])
@pytest.mark.parametrize("storage", ["sqlite3", "mcap"])
@pytest.mark.parametrize("typestore", [None, "ros2_humble"], ids=["ros1-defs", "humble"])
def test_converted_fixture_imports_to_the_same_bytes(tmp_path, fixture, storage, typestore):
    ros1_log = tmp_path / "ros1.lcm"
    import_ok(fixture, "-o", ros1_log)
    bag = convert(fixture, tmp_path / "ros2", storage, typestore)
    ros2_log = tmp_path / "ros2.lcm"
    err = import_ok(bag, "-o", ros2_log)
    assert "(ROS 2)" in err
    assert ros2_log.read_bytes() == ros1_log.read_bytes()
    assert (tmp_path / "ros2.lcm.mount.yaml").read_text().splitlines()[1:] == \
        (tmp_path / "ros1.lcm.mount.yaml").read_text().splitlines()[1:]
    # The storage file itself stands for its bag.
    storage_file = next(p for p in bag.iterdir() if p.suffix in (".db3", ".mcap"))
    import_ok(storage_file, "-o", tmp_path / "file.lcm")
    assert (tmp_path / "file.lcm").read_bytes() == ros1_log.read_bytes()


@pytest.mark.parametrize("storage", ["sqlite3", "mcap"])
def test_ros2_bag_with_tf_and_odometry(tmp_path, storage):
    ros1 = robot_bag(1, mount_xyz=(0.3, -0.1, 0.2)).write(tmp_path / "robot.bag")
    ros2 = robot_bag(2, mount_xyz=(0.3, -0.1, 0.2)).write(tmp_path / "robot2", storage)
    import_ok(ros1, "-o", tmp_path / "1.lcm")
    err = import_ok(ros2, "-o", tmp_path / "2.lcm")
    assert "mount: forward 0.3000 m, left -0.1000 m, yaw 0.00 deg (static transform " \
           "base_link -> laser from /tf_static)" in err
    assert (tmp_path / "2.lcm").read_bytes() == (tmp_path / "1.lcm").read_bytes()
