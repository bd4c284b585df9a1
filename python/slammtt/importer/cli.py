"""slammtt-import: real recordings -> LCM logs of the stack's types (docs/import.md).

  slammtt-import [options] INPUT -o OUT.lcm

INPUT is a ROS 1 bag, a ROS 2 bag (its folder, or the .db3 / .mcap file in it) or a text log of
BreezySLAM's Mines recordings (.dat). Exit status: 0 done, 1 the input cannot be imported (one
line says why; no output is left behind), 2 a bad command line.
"""

import math
import os
import pathlib
import sys

import slammtt
from slammtt.cli import Parser, UsageError, run_main
from slammtt.importer import breezyslam, laser, laser_geometry, odometry, rosbag
from slammtt.importer.geometry import wrap_angles
from slammtt.importer.mount import Mount
from slammtt.importer.output import Stream, write_log
from slammtt.output_file import write_text_atomically

PROGRAM = "slammtt-import"
CHANNEL_DEFAULTS = {"laser_scan": "LASER_SCAN", "odometry": "ODOMETRY",
                    "leg_labels": "LEG_LABELS", "laser_geometry": "LASER_GEOMETRY"}


class InputError(Exception):
    """The input cannot be imported (one line)."""


def _parser():
    p = Parser(
        prog=PROGRAM, add_help=False,
        usage=f"{PROGRAM} [options] INPUT -o OUT.lcm",
        description="Turns a ROS 1 / ROS 2 bag (LaserScan, Odometry, tf, leg labels) or a "
                    "BreezySLAM text log into an LCM log of the stack's messages (LASER_SCAN, "
                    "ODOMETRY, LEG_LABELS, and LASER_GEOMETRY: the mount, field of view and "
                    "range, which the estimator takes from the log) and writes the laser mount "
                    "as a configuration snippet. Same input and options: byte-identical output.")
    p.add_argument("input", metavar="INPUT",
                   help="ROS 1 .bag, ROS 2 bag folder (or its .db3/.mcap), or breezyslam .dat")
    p.add_argument("-o", "--output", metavar="OUT.lcm", help="output log (required)")
    p.add_argument("--format", choices=("auto", "rosbag", "breezyslam"), default="auto",
                   help="input format (default auto: .dat is breezyslam, anything else a bag)")
    p.add_argument("--laser-topic", metavar="TOPIC",
                   help="LaserScan topic to import (default: the first one)")
    p.add_argument("--odometry-topic", metavar="TOPIC",
                   help="nav_msgs/Odometry topic (default: the first one)")
    p.add_argument("--no-odometry", action="store_true", help="import no odometry")
    p.add_argument("--labels-topic", metavar="TOPIC",
                   help="geometry_msgs/PoseArray topic of leg labels "
                        f"(default: {rosbag.DEFAULT_LABELS_TOPIC} when the bag has it)")
    p.add_argument("--no-labels", action="store_true", help="import no leg labels")
    p.add_argument("--time-source", choices=("header", "bag"), default="header",
                   help="utime from the header stamps (default) or the bag's receive times")
    p.add_argument("--base-frame", metavar="FRAME", default="base_link",
                   help="robot frame of the laser mount transform (default base_link)")
    p.add_argument("--mount-forward-m", type=float, metavar="M",
                   help="laser mount: forward offset (overrides the bag's transform)")
    p.add_argument("--mount-left-m", type=float, metavar="M",
                   help="laser mount: left offset (overrides the bag's transform)")
    p.add_argument("--mount-yaw-deg", type=float, metavar="DEG",
                   help="laser mount: yaw, CCW (overrides the bag's transform)")
    p.add_argument("--rotate-to-base", action="store_true",
                   help="write beam angles and labels in the robot's orientation (applies the "
                        "mount's yaw and an upside-down mount)")
    p.add_argument("--wheel-track-m", type=float, metavar="M",
                   help="distance between the wheels, for the wheel speeds of nav_msgs/Odometry "
                        "(default: unknown, NaN)")
    p.add_argument("--mount-yaml", metavar="FILE",
                   help="where the mount goes as a configuration (default OUT.lcm.mount.yaml)")
    p.add_argument("--channel", action="append", default=[], metavar="KEY=NAME",
                   help="rename a channel: laser_scan, odometry, leg_labels, laser_geometry")
    p.add_argument("-q", "--quiet", action="store_true", help="only warnings and errors")
    p.add_argument("-h", "--help", action="help", help="show this help and exit")
    p.add_argument("--version", action="version", version=f"{PROGRAM} {slammtt.__version__}")
    return p


def _check_options(args):
    if not args.output:
        raise UsageError("-o OUT.lcm is required")
    for name in ("mount_forward_m", "mount_left_m", "mount_yaw_deg", "wheel_track_m"):
        value = getattr(args, name)
        if value is not None and not math.isfinite(value):
            raise UsageError(f"--{name.replace('_', '-')} must be a finite number")
    if args.wheel_track_m is not None and args.wheel_track_m <= 0:
        raise UsageError("--wheel-track-m must be positive")
    if args.no_odometry and args.odometry_topic:
        raise UsageError("--no-odometry and --odometry-topic exclude each other")
    if args.no_labels and args.labels_topic:
        raise UsageError("--no-labels and --labels-topic exclude each other")
    channels = dict(CHANNEL_DEFAULTS)
    for text in args.channel:
        key, sep, name = text.partition("=")
        if not sep or not name:
            raise UsageError(f"--channel expects KEY=NAME, got '{text}'")
        if key not in channels:
            raise UsageError(f"--channel: unknown channel key '{key}' "
                             f"(keys: {', '.join(sorted(channels))})")
        channels[key] = name
    if len(set(channels.values())) != len(channels):
        raise UsageError("--channel: two channels with the same name")
    return channels


class Reporter:
    def __init__(self, quiet):
        self.quiet = quiet
        self.warning_count = 0

    def info(self, line):
        if not self.quiet:
            print(f"{PROGRAM}: {line}", file=sys.stderr)

    def warning(self, line):
        self.warning_count += 1
        print(f"{PROGRAM}: warning: {line}", file=sys.stderr)


def _format(args):
    if args.format != "auto":
        return args.format
    return "breezyslam" if pathlib.Path(args.input).suffix == ".dat" else "rosbag"


def _options_mount(args, tf_mount):
    given = [v is not None for v in (args.mount_forward_m, args.mount_left_m, args.mount_yaw_deg)]
    if not any(given):
        return None
    base = tf_mount or Mount()
    mount = Mount(forward_m=args.mount_forward_m if given[0] else base.forward_m,
                  left_m=args.mount_left_m if given[1] else base.left_m,
                  yaw_rad=math.radians(args.mount_yaw_deg) if given[2] else base.yaw_rad,
                  upside_down=base.upside_down, tilt_rad=base.tilt_rad,
                  source="--mount-* options" + (", the rest from the bag's transform"
                                                if tf_mount and not all(given) else ""))
    return mount


def _choose_mount(args, tf_mount, report):
    mount = _options_mount(args, tf_mount)
    if mount is None:
        return tf_mount or Mount()
    if tf_mount is not None:
        differs = (abs(mount.forward_m - tf_mount.forward_m) > 1e-6 or
                   abs(mount.left_m - tf_mount.left_m) > 1e-6 or
                   abs(mount.yaw_rad - tf_mount.yaw_rad) > 1e-6)
        if differs:
            report.warning(f"the options' mount differs from the bag's transform "
                           f"({tf_mount.describe()}); the options are used")
    return mount


def _scan_stream(channel, scans, mount, rotate):
    stream = Stream(channel)
    for sequence, scan in enumerate(scans):
        if rotate:
            scan.angle_rad = wrap_angles(mount.beam_angles_in_base(scan.angle_rad)).astype(
                scan.angle_rad.dtype)
        stream.add(scan.utime, laser.to_message(scan, sequence).encode())
    return stream


def _geometry_stream(channel, scans, mount, rotate, laser_name):
    """LASER_GEOMETRY; its source names the laser, not the input file, so that a bag and its
    ROS 2 conversion import to the same bytes."""
    stream = Stream(channel)
    text = f"slammtt-import, {laser_name}; mount from {mount.source}"
    for utime, message in laser_geometry.geometry_messages(scans, mount, rotate, text):
        stream.add(utime, message.encode())
    return stream


def _odometry_stream(channel, readings):
    stream = Stream(channel)
    for sequence, reading in enumerate(readings):
        stream.add(reading.utime, odometry.to_message(reading, sequence).encode())
    return stream


def _report_scans(channel, scans, report):
    counts = laser.BeamCounts()
    beams = set()
    for scan in scans:
        counts.add(scan.counts)
        beams.add(int(scan.range_m.size))
    if not scans:
        report.warning(f"{channel}: no scan imported")
        return
    per_scan = (f"{min(beams)}" if len(beams) == 1 else f"{min(beams)}-{max(beams)}")
    report.info(f"{channel}: {len(scans)} scans of {per_scan} beams; REP 117: {counts.line()}")
    dropped = sum(1 for scan in scans if scan.intensities_dropped)
    if dropped:
        report.warning(f"{channel}: {dropped} scans had an intensities array of another length "
                       "than ranges; their intensities are 0")
    zero = sum(1 for scan in scans if scan.utime == 0)
    if zero:
        report.warning(f"{channel}: {zero} scans have the stamp 0 (try --time-source bag)")


def _import_rosbag(args, channels, report):
    selection = rosbag.Selection(
        laser_topic=args.laser_topic, odometry_topic=args.odometry_topic,
        use_odometry=not args.no_odometry, labels_topic=args.labels_topic,
        use_labels=not args.no_labels, time_source=args.time_source,
        base_frame=args.base_frame, wheel_track_m=args.wheel_track_m)
    try:
        content = rosbag.read_bag(args.input, selection)
    except rosbag.BagError as error:
        raise InputError(f"{args.input}: {error}") from None
    report.info(f"{args.input} ({content.description})")
    for line in content.notes:
        report.info(line)
    for line in content.warnings:
        report.warning(line)
    for what, (count, first) in sorted(content.skipped.items()):
        report.warning(f"skipped {count} {what} (first: {first})")
    mount = _choose_mount(args, content.tf_mount, report)
    laser_name = f"laser topic {content.laser_topic} (frame {content.laser_frame})"
    source = f"{pathlib.Path(args.input).name}, {laser_name}"
    # The scans first: --rotate-to-base turns their beams, which gives the geometry's view.
    scans = _scan_stream(channels["laser_scan"], content.scans, mount, args.rotate_to_base)
    # Stream order is the tie order at equal utimes: the geometry before the scan it holds for.
    streams = [_odometry_stream(channels["odometry"], content.odometry),
               _geometry_stream(channels["laser_geometry"], content.scans, mount,
                                args.rotate_to_base, laser_name),
               scans]
    if content.odometry:
        report.info(f"{channels['odometry']}: {len(content.odometry)} messages")
    _report_scans(channels["laser_scan"], content.scans, report)
    if content.labels_topic:
        labels = Stream(channels["leg_labels"])
        for label in content.labels:
            labels.add(label.utime, rosbag.label_message(
                label, mount if args.rotate_to_base else None).encode())
        legs = sum(len(label.x_m) for label in content.labels)
        report.info(f"{channels['leg_labels']}: {len(content.labels)} labelled scans, "
                    f"{legs} legs")
        streams.append(labels)
    return streams, mount, source


def _import_breezyslam(args, channels, report):
    for option in ("laser_topic", "odometry_topic", "labels_topic"):
        if getattr(args, option):
            raise UsageError(f"--{option.replace('_', '-')} is for bags, not breezyslam logs")
    refusals = breezyslam.Refusals()
    try:
        readings = list(breezyslam.read_readings(args.input, refusals))
    except OSError as error:
        raise InputError(f"{args.input}: cannot read ({error.strerror})") from None
    report.info(f"{args.input} (BreezySLAM text log): {len(readings)} lines read")
    if refusals.count:
        report.warning(f"skipped {refusals.count} malformed lines (first: {refusals.first})")
    if not readings:
        raise InputError(f"{args.input}: no line of the breezyslam format "
                           f"({refusals.first or 'empty file'})")
    scans = [r.scan for r in readings]
    odometry_readings = [r.odometry for r in readings]
    mount = _choose_mount(args, breezyslam.MOUNT, report)
    scan_stream = _scan_stream(channels["laser_scan"], scans, mount, args.rotate_to_base)
    streams = [_odometry_stream(channels["odometry"], [] if args.no_odometry
                                else odometry_readings),
               _geometry_stream(channels["laser_geometry"], scans, mount, args.rotate_to_base,
                                "BreezySLAM log"),
               scan_stream]
    if not args.no_odometry:
        path_m = sum(math.hypot(b.x_m - a.x_m, b.y_m - a.y_m)
                     for a, b in zip(odometry_readings, odometry_readings[1:]))
        report.info(f"{channels['odometry']}: {len(odometry_readings)} messages, path "
                    f"{path_m:.2f} m")
    _report_scans(channels["laser_scan"], scans, report)
    return streams, mount, pathlib.Path(args.input).name


def run(argv):
    args = _parser().parse_args(argv)
    channels = _check_options(args)
    report = Reporter(args.quiet)
    output = os.fspath(args.output)
    if os.path.exists(args.input) and os.path.exists(output) and \
            os.path.samefile(args.input, output):
        raise UsageError("the output is the input file")
    if not os.path.exists(args.input):
        raise InputError(f"{args.input}: no such file or folder")
    kind = _format(args)
    if kind == "breezyslam":
        streams, mount, source = _import_breezyslam(args, channels, report)
    else:
        streams, mount, source = _import_rosbag(args, channels, report)
    for stream in streams:
        line = stream.order_report()
        if line:
            report.warning(line)
    for line in mount.warnings(args.rotate_to_base):
        report.warning(line)
    events, first, last = write_log(output, [s for s in streams if s.events])
    mount_path = args.mount_yaml or output + ".mount.yaml"
    header = [f"Laser mount of {source}: {mount.describe()}.",
              f"Written by {PROGRAM} {slammtt.__version__}; "
              "slammtt-replay LOG --config THIS_FILE takes it as it is."]
    write_text_atomically(mount_path, mount.yaml(header, args.rotate_to_base))
    report.info(f"mount: {mount.describe()} -> {mount_path}")
    span = (last - first) * 1e-6 if events else 0.0
    report.info(f"wrote {output}: {events} events, {span:.1f} s")
    return 0


def main(argv=None):
    return run_main(PROGRAM, run, argv, input_errors=(InputError,))


if __name__ == "__main__":
    sys.exit(main())
