"""The parts of the stack configuration (one YAML file, config/*.yaml) that the Python tools
read: channel names, the LCM URL, the laser mount and the evaluation's options.

Precedence, as in the C++ processes (runtime/channels.h, runtime/process.h): the defaults, then
the file's `channels:` section, then `--channel KEY=NAME` options. The file is read strictly: a
top-level section the stack does not know, a channel key it does not know, or a value of the
wrong kind is a ConfigError of one line naming the file and the key. The sections of other
programs are not checked here (their programs do that).
"""

import math
import os

from ruamel.yaml import YAML
from ruamel.yaml.error import YAMLError

# runtime/process.cc's list of sections.
SECTIONS = ("lcm", "channels", "segmenter", "estimator", "smoother", "rplidar", "p3dx", "robot",
            "replay", "eval")

# runtime/channels.cc, plus the channel slammtt-import writes (leg_labels). The exports read the
# smoother's pose (smoothed_pose) when a log has it.
CHANNEL_DEFAULTS = {
    "odometry": "ODOMETRY", "velocity_command": "VELOCITY_COMMAND",
    "laser_scan": "LASER_SCAN", "laser_geometry": "LASER_GEOMETRY", "features": "FEATURES",
    "pose": "POSE", "map": "MAP",
    "tracks": "TRACKS", "ground_truth": "GROUND_TRUTH", "stage_timing": "STAGE_TIMING",
    "lidar_status": "LIDAR_STATUS", "base_status": "BASE_STATUS",
    "estimator_status": "ESTIMATOR_STATUS", "leg_labels": "LEG_LABELS",
    "smoother_input": "SMOOTHER_INPUT", "smoothed_pose": "SMOOTHED_POSE",
    "smoothed_map": "SMOOTHED_MAP", "smoothed_trajectory": "SMOOTHED_TRAJECTORY",
}

DEFAULT_LCM_URL = "udpm://239.255.76.67:7667?ttl=0"


class ConfigError(Exception):
    """A configuration that cannot be used (one line)."""


class StackConfig:
    """A stack configuration file, or the defaults (path None)."""

    def __init__(self, path=None):
        self.path = os.fspath(path) if path is not None else None
        self.root = {}
        if self.path is None:
            return
        try:
            with open(self.path, encoding="utf-8") as f:
                root = YAML(typ="safe", pure=True).load(f)
        except OSError as error:
            raise ConfigError(f"{self.path}: cannot read ({error.strerror})") from None
        except YAMLError as error:
            mark = getattr(error, "problem_mark", None)
            where = f":{mark.line + 1}" if mark is not None else ""
            problem = getattr(error, "problem", None) or str(error).splitlines()[0]
            raise ConfigError(f"{self.path}{where}: not YAML ({problem})") from None
        if root is None:
            root = {}
        if not isinstance(root, dict):
            raise ConfigError(f"{self.path}: the top level must be a mapping of sections")
        for key in root:
            if key not in SECTIONS:
                raise ConfigError(f"{self.path}: unknown section '{key}' "
                                  f"(sections: {', '.join(SECTIONS)})")
        self.root = root

    def section(self, name):
        value = self.root.get(name) or {}
        if not isinstance(value, dict):
            raise ConfigError(f"{self.path}: {name}: must be a mapping")
        return value

    def number(self, section, key, default, low, high):
        """section.key as a finite float in [low, high], or `default` when it is absent."""
        values = self.section(section)
        if key not in values:
            return default
        value = values[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or \
                not math.isfinite(value) or not low <= value <= high:
            raise ConfigError(f"{self.path}: {section}.{key}: expected a number in "
                              f"[{low:g}, {high:g}], got {value!r}")
        return float(value)

    def has(self, section, key):
        return key in self.section(section)

    def channels(self, overrides=()):
        """{key: channel name}: defaults, the channels: section, then KEY=NAME overrides."""
        names = dict(CHANNEL_DEFAULTS)
        for key, name in self.section("channels").items():
            if key not in names:
                raise ConfigError(f"{self.path}: channels.{key}: unknown channel key "
                                  f"(keys: {', '.join(sorted(names))})")
            if not isinstance(name, str) or not name:
                raise ConfigError(f"{self.path}: channels.{key}: expected a channel name")
            names[key] = name
        for text in overrides:
            key, sep, name = text.partition("=")
            if not sep or not key or not name:
                raise ValueError(f"--channel expects KEY=NAME, got '{text}'")
            if key not in names:
                raise ValueError(f"--channel: unknown channel key '{key}' "
                                 f"(keys: {', '.join(sorted(names))})")
            names[key] = name
        if len(set(names.values())) != len(names):
            raise ValueError("two channel keys with the same channel name")
        return names

    def lcm_url(self):
        """lcm.url of the file, else $LCM_DEFAULT_URL, else the stack's default (ttl=0)."""
        url = self.section("lcm").get("url")
        if url is not None:
            if not isinstance(url, str) or not url:
                raise ConfigError(f"{self.path}: lcm.url: expected a URL")
            return url
        return os.environ.get("LCM_DEFAULT_URL") or DEFAULT_LCM_URL

    def mount(self):
        """(forward_m, left_m) of the laser on the robot: estimator.sensor_forward_m /
        sensor_left_m (paper eqs. 10-11, a and b), 0 when absent; within 100 m, as
        slammtt-eval reads them."""
        return (self.number("estimator", "sensor_forward_m", 0.0, -100.0, 100.0),
                self.number("estimator", "sensor_left_m", 0.0, -100.0, 100.0))

    def mount_given(self):
        """Whether the file gives the mount (estimator.sensor_forward_m or sensor_left_m);
        without it the log's LASER_GEOMETRY does (logged_mount)."""
        values = self.section("estimator")
        return "sensor_forward_m" in values or "sensor_left_m" in values


def logged_mount(log_path, channel):
    """(forward_m, left_m) of the log's first LASER_GEOMETRY with finite values within 100 m,
    or None (docs/estimator.md, "Laser geometry")."""
    import math
    from slammtt import msgs
    from slammtt.lcmlog import LogReader
    for event in LogReader(log_path).events():
        if event.channel != channel:
            continue
        try:
            m = msgs.decode(event.data)
        except msgs.UndecodableMessage:
            continue
        values = (getattr(m, "mount_forward_m", math.nan), getattr(m, "mount_left_m", math.nan))
        if all(math.isfinite(v) and abs(v) <= 100.0 for v in values):
            return values
    return None
