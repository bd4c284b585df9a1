"""slammtt-export: a log of the stack into TUM trajectories, CSV tables, MOTChallenge files and
an MCAP file with Foxglove schemas (docs/export.md).

  slammtt-export [options] LOG (-o DIR | --tum DIR | --csv DIR | --mot DIR | --mcap FILE)...

Exit status: 0 done, 1 the log cannot be read (one line; nothing is left under a final name),
2 a bad command line or configuration.
"""

import math
import os
import pathlib
import sys

import slammtt
from slammtt.cli import Parser, UsageError, run_main
from slammtt.export import mot, tables, tum
from slammtt.export.logdata import LogData
from slammtt.lcmlog import LogError
from slammtt.stackconfig import ConfigError, StackConfig, logged_mount

PROGRAM = "slammtt-export"


def _parser():
    p = Parser(
        prog=PROGRAM, add_help=False,
        usage=f"{PROGRAM} [options] LOG (-o DIR | --tum DIR | --csv DIR | --mot DIR | "
              "--mcap FILE)...",
        description="Exports a log of the stack (any of lcm-logger, slammtt-world, "
                    "slammtt-replay, slammtt-import) for other tools: TUM trajectories (evo), "
                    "CSV tables, MOTChallenge tracks and truth (py-motmetrics, TrackEval), MCAP "
                    "with Foxglove schemas (Foxglove). Same log and options: same bytes.")
    p.add_argument("log", metavar="LOG", help="an LCM log")
    p.add_argument("-o", "--output", metavar="DIR",
                   help="every export into DIR: DIR/tum/, DIR/csv/, DIR/mot/, DIR/LOG.mcap")
    p.add_argument("--tum", metavar="DIR", help="TUM trajectories into DIR")
    p.add_argument("--csv", metavar="DIR", help="CSV tables into DIR")
    p.add_argument("--mot", metavar="DIR", help="MOTChallenge files into DIR")
    p.add_argument("--mcap", metavar="FILE", help="MCAP file with Foxglove schemas")
    p.add_argument("-c", "--config", metavar="FILE",
                   help="stack configuration: channels:, the laser mount (estimator.sensor_"
                        "forward_m / sensor_left_m; without them the log's LASER_GEOMETRY), "
                        "eval.min_beams, eval.min_moving_speed_mps")
    p.add_argument("--channel", action="append", default=[], metavar="KEY=NAME",
                   help="rename a channel (as every process)")
    p.add_argument("--min-beams", type=int, metavar="N",
                   help="MOT truth: in a log with LASER_SCAN a mover is visible with N beams "
                        "(default as slammtt-eval: eval.min_beams, segmenter.min_points, 3)")
    p.add_argument("--min-moving-speed-mps", type=float, metavar="MPS",
                   help="MOT truth: a mover slower than this stands (flag 0; default "
                        "eval.min_moving_speed_mps, else 0.2)")
    p.add_argument("--mot-box-m", type=float, default=1.0, metavar="M",
                   help="MOT: side of the square written around each point (default 1)")
    p.add_argument("--mot-sequence", metavar="NAME",
                   help="MOT: the sequence name (default: the log's file name without .lcm)")
    p.add_argument("-q", "--quiet", action="store_true", help="only warnings and errors")
    p.add_argument("-h", "--help", action="help", help="show this help and exit")
    p.add_argument("--version", action="version", version=f"{PROGRAM} {slammtt.__version__}")
    return p


def _outputs(args):
    stem = pathlib.Path(args.log).name
    if stem.endswith(".lcm"):
        stem = stem[:-4]
    out = {"tum": args.tum, "csv": args.csv, "mot": args.mot, "mcap": args.mcap}
    if args.output:
        defaults = {"tum": os.path.join(args.output, "tum"),
                    "csv": os.path.join(args.output, "csv"),
                    "mot": os.path.join(args.output, "mot"),
                    "mcap": os.path.join(args.output, stem + ".mcap")}
        out = {k: v or defaults[k] for k, v in out.items()}
    if not any(out.values()):
        raise UsageError("no output: give -o DIR or at least one of --tum, --csv, --mot, --mcap")
    return out, stem


def _truth_rules(args, config, data):
    if args.min_beams is not None:
        min_beams = args.min_beams
    elif config.has("eval", "min_beams"):
        min_beams = int(config.number("eval", "min_beams", 3, 1, 100000))
    elif config.has("segmenter", "min_points"):
        min_beams = int(config.number("segmenter", "min_points", 3, 1, 100000))
    else:
        min_beams = 3
    speed = args.min_moving_speed_mps
    if speed is None:
        speed = config.number("eval", "min_moving_speed_mps", 0.2, 0.0, 100.0)
    return mot.TruthRules(min_beams, speed, scan_log=bool(data["laser_scan"]))


def _check(args):
    if args.min_beams is not None and not 1 <= args.min_beams <= 100000:
        raise UsageError("--min-beams must be in [1, 100000]")
    if args.min_moving_speed_mps is not None and not (
            math.isfinite(args.min_moving_speed_mps) and 0 <= args.min_moving_speed_mps <= 100):
        raise UsageError("--min-moving-speed-mps must be in [0, 100]")
    if not (math.isfinite(args.mot_box_m) and 0 < args.mot_box_m <= 1000):
        raise UsageError("--mot-box-m must be in (0, 1000]")


def run(argv):
    args = _parser().parse_args(argv)
    _check(args)
    outputs, stem = _outputs(args)
    config = StackConfig(args.config)
    try:
        channels = config.channels(args.channel)
    except ValueError as error:
        raise UsageError(str(error)) from None
    mount = config.mount()
    info = (lambda line: None) if args.quiet else (
        lambda line: print(f"{PROGRAM}: {line}", file=sys.stderr))
    if not os.path.isfile(args.log):
        raise LogError(f"{args.log}: no such file")
    if outputs["mcap"] and not config.mount_given():
        logged = logged_mount(args.log, channels["laser_geometry"])
        if logged is not None:
            mount = logged
            info(f"laser mount from {channels['laser_geometry']}: forward {mount[0]:g} m, "
                 f"left {mount[1]:g} m")
    data = None
    if outputs["tum"] or outputs["csv"] or outputs["mot"]:
        data = LogData(args.log, channels)
        _report_input(data, info)
    if outputs["tum"]:
        written = tum.write_tum(data, outputs["tum"])
        info(f"TUM: {', '.join(f'{k}.tum ({n} poses)' for k, n in written.items()) or 'none'}"
             f" -> {outputs['tum']}")
    if outputs["csv"]:
        counts = tables.write_tables(data, outputs["csv"])
        info(f"CSV: {', '.join(f'{k} ({n} rows)' for k, n in counts.items())} -> "
             f"{outputs['csv']}")
    if outputs["mot"]:
        sequence = args.mot_sequence or stem
        if not sequence or "/" in sequence or sequence in (".", ".."):
            raise UsageError(f"--mot-sequence '{sequence}' is not a file name")
        counts = mot.write_mot(data, outputs["mot"], sequence, _truth_rules(args, config, data),
                               args.mot_box_m)
        info(f"MOT: {counts['frames']} frames, {counts['truth_rows']} truth rows "
             f"({counts['truth_scored']} scored), {counts['track_rows']} track rows (frame "
             f"{counts['tracks_frame']}) -> {outputs['mot']}")
    if outputs["mcap"]:
        from slammtt.export.mcap_file import write_mcap   # the Foxglove SDK only when needed
        topics, converter, reader = write_mcap(args.log, outputs["mcap"], channels, mount)
        if reader.damage:
            print(f"{PROGRAM}: warning: {args.log}: {reader.damage}", file=sys.stderr)
        for channel, count in sorted(converter.skipped.items()):
            print(f"{PROGRAM}: warning: MCAP: skipped {count} {channel} messages with values "
                  "that are not finite", file=sys.stderr)
        info(f"MCAP: {sum(topics.counts.values())} messages on {len(topics.counts)} topics "
             f"({', '.join(f'{t} {n}' for t, n in sorted(topics.counts.items()))}) -> "
             f"{outputs['mcap']}")
    return 0


def _report_input(data, info):
    present = [f"{data.name(k)} {len(v)}" for k, v in data.messages.items() if v]
    info(f"{data.path}: {', '.join(present) or 'no message of the stack'}")
    if data.damage:
        print(f"{PROGRAM}: warning: {data.path}: {data.damage}", file=sys.stderr)
    for channel, count in sorted(data.undecodable.items()):
        print(f"{PROGRAM}: warning: skipped {count} undecodable {channel} messages "
              f"(first: {data.first_undecodable})", file=sys.stderr)
    for note in data.notes:
        channel = note.split(":")[0]
        print(f"{PROGRAM}: warning: {note}; {data.rejected[channel]} rejected in all",
              file=sys.stderr)


def main(argv=None):
    return run_main(PROGRAM, run, argv, usage_errors=(ConfigError,), input_errors=(LogError,))


if __name__ == "__main__":
    sys.exit(main())
