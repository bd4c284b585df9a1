"""The Python package and its generated LCM types."""

import pathlib
import re

import slammtt
from slammtt import msgs

from conftest import SOURCE_DIR


def test_version_is_the_cmake_projects():
    cmake = (SOURCE_DIR / "CMakeLists.txt").read_text()
    version = re.search(r"project\(slammtt VERSION ([0-9.]+)", cmake).group(1)
    assert slammtt.__version__ == version
    pyproject = (SOURCE_DIR / "python" / "pyproject.toml").read_text()
    assert re.search(r'^version = "([0-9.]+)"', pyproject, re.M).group(1) == version


def test_every_lcm_type_is_generated():
    names = {p.stem for p in (SOURCE_DIR / "lcmtypes").glob("*.lcm")}
    assert names == set(msgs.TYPES)
    assert len(msgs.BY_FINGERPRINT) == len(names)


def test_boolean_arrays_decode_as_lists():
    # Debian's lcm-gen 1.3.1 made laser_scan_t.valid a map iterator (TypeError on indexing).
    from slammtt_msgs import laser_scan_t
    scan = laser_scan_t()
    scan.num_beams = 3
    scan.angle_rad = [0.0, 0.1, 0.2]
    scan.range_m = [1.0, 2.0, 3.0]
    scan.intensity = [0.0, 0.0, 0.0]
    scan.valid = [True, False, True]
    decoded = msgs.decode(scan.encode())
    assert decoded.valid == [True, False, True]
    assert decoded.valid[1] is False


def test_types_are_not_committed():
    tracked = [p for p in (SOURCE_DIR / "python").rglob("*_t.py")]
    assert tracked == []
    assert not (SOURCE_DIR / "python" / "slammtt_msgs").exists()
    assert pathlib.Path(msgs.slammtt_msgs.__file__).resolve().parent.parent != \
        (SOURCE_DIR / "python").resolve()
