#!/usr/bin/env python3
"""Measures the estimator on the real recordings of ../shared/data/real, which have no ground
truth (issue 13, "Real recordings"; definitions in python/slammtt/recording_figures.py):

    build/venv/bin/python scripts/measure-real.py OUTDIR [--bin DIR] [--real DIR] [--json FILE]

- negative_2 (leg_tracker_training/negative_2.bag, /left_scan: a wheelchair driven through
  empty rooms, no odometry): reported person identities per minute (every one is false);
- leg_tracker_demo (a still Hokuyo, 1-3 people walking): reported person identities per minute,
  and the share of scans whose count of reported people equals the count of leg pairs
  perception made (and of all its person features);
- breezyslam_mines exp1, exp2 (a lab robot with wheel odometry): sharpness of the walls (the
  beams on perception's line features) with every scan placed by the estimated poses (POSE)
  and by the raw odometry (ODOMETRY).

For each recording:

    slammtt-import REC -o OUTDIR/NAME.lcm                 # writes NAME.lcm.mount.yaml
    slammtt-replay OUTDIR/NAME.lcm -o OUTDIR/NAME-mount.lcm --config OUTDIR/NAME.lcm.mount.yaml
    slammtt-replay OUTDIR/NAME.lcm -o OUTDIR/NAME-sensor.lcm --config OUTDIR/NAME.sensor.yaml
--set KEY=VALUE (repeatable) adds `KEY: VALUE` to the `estimator:` section of both
configurations (as scripts/measure-estimator.py's --set), to measure what an option costs here;
`segmenter.KEY=VALUE` to the `segmenter:` section.

--perturbed also runs the `sensor` configuration four more times, with the estimator's floors of
a line feature's sigmas (`lines_min_rho_sigma_m`, `lines_min_alpha_sigma_deg`) 1 % above and 1 %
below their values, one at a time, and reports every figure's median over the five runs
(`sensor_median`, each run in `sensor_runs`). One run's figures are not reproducible in this
sense: such a change of 1 % moves the Mines wall spread by up to 17 % and the demo's share of
scans with as many reported people as leg pairs by up to 12 % from the shipped run's
(docs/targets.md, "Real recordings: one run against five"), so a change of the method is judged
by the median of five.

Two configurations, no parameter chosen for a recording: `mount` is the import's file as it is
(the README's command: the estimator's defaults, a 360-degree view of 30 m); `sensor` is that
file plus the scanner's own field of view and range, read from the first LASER_SCAN of the
import (first and last beam angle, range_max_m), as estimator/config/office-hokuyo.yaml describes
its simulated scanner. Prints the tables and writes every figure as JSON (OUTDIR/real.json, or
--json). Runs with the Python tools' venv (scripts/python-env.sh); started with another python
it runs itself again with build/venv/bin/python when that exists.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

try:
    from slammtt import recording_figures as figures
    from slammtt.stackconfig import StackConfig
except ImportError:
    venv_python = os.path.join(ROOT, "build", "venv", "bin", "python")
    if os.path.exists(venv_python) and os.path.realpath(sys.executable) != \
            os.path.realpath(venv_python):
        os.execv(venv_python, [venv_python, *sys.argv])
    sys.exit("measure-real: the slammtt package is not importable: run it with the venv of "
             "scripts/python-env.sh (build/venv/bin/python scripts/measure-real.py OUTDIR)")

RECORDINGS = (
    # name, path under the real-data folder, figures
    ("negative_2", "leg_tracker_training/negative_2.bag", "people"),
    ("leg_tracker_demo", "leg_tracker_demo/demo_stationary_simple_environment.bag", "people"),
    ("mines_exp1", "breezyslam_mines/exp1.dat", "sharpness"),
    ("mines_exp2", "breezyslam_mines/exp2.dat", "sharpness"),
)
CONFIGS = ("mount", "sensor")


def run(command):
    done = subprocess.run([str(c) for c in command], capture_output=True, text=True)
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or [f"exit {done.returncode}"])[-1]
        sys.exit(f"measure-real: {' '.join(map(str, command))}: {last}")


def apply_settings(config, settings):
    """`KEY=VALUE` settings into the configuration's `estimator:` section, `segmenter.KEY=VALUE`
    into its `segmenter:` section (values as YAML)."""
    from ruamel.yaml import YAML
    yaml = YAML(typ="safe", pure=True)
    for setting in settings:
        key, _, value = setting.partition("=")
        section, _, name = key.rpartition(".")
        if section not in ("", "estimator", "segmenter"):
            sys.exit(f"measure-real: --set {setting}: only estimator and segmenter options")
        config.setdefault(section or "estimator", {})[name] = yaml.load(value)


# The estimator options --perturbed moves by 1 % either way (module docstring).
PERTURBED_OPTIONS = ("lines_min_rho_sigma_m", "lines_min_alpha_sigma_deg")
PERTURBATION = 0.01


def option_defaults(bin_dir):
    """{name: default} of the estimator's numeric options (`slammtt-estimator --options-table`)."""
    done = subprocess.run([os.path.join(bin_dir, "slammtt-estimator"), "--options-table"],
                          capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"measure-real: slammtt-estimator --options-table: exit {done.returncode}")
    defaults = {}
    for line in done.stdout.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 2 and cells[0].startswith("`"):
            try:
                defaults[cells[0].strip("`")] = float(cells[1])
            except ValueError:
                pass
    return defaults


def perturbations(settings, defaults):
    """The four extra settings lists of --perturbed: each option 1 % up, then 1 % down."""
    given = {}
    for setting in settings:
        key, _, value = setting.partition("=")
        given[key.removeprefix("estimator.")] = value
    runs = []
    for name in PERTURBED_OPTIONS:
        if name not in given and name not in defaults:
            sys.exit(f"measure-real: --perturbed: slammtt-estimator has no option {name}")
        try:
            value = float(given[name]) if name in given else defaults[name]
        except ValueError:
            sys.exit(f"measure-real: --set {name}={given[name]}: not a number")
        for factor in (1.0 + PERTURBATION, 1.0 - PERTURBATION):
            runs.append([*settings, f"{name}={value * factor!r}"])
    return runs


def median_figures(runs):
    """Every figure's median over the runs (the same keys; nested dicts likewise); NaN when a
    run's figure is NaN (a figure some run could not measure has no median)."""
    first = runs[0]
    if isinstance(first, dict):
        return {k: median_figures([r[k] for r in runs]) for k in first}
    if any(isinstance(v, float) and math.isnan(v) for v in runs):
        return math.nan
    return statistics.median(runs)


def check_settings(settings):
    """Exits with one line when a --set setting is not KEY=VALUE of a known section."""
    for setting in settings:
        key, equals, _ = setting.partition("=")
        section, _, name = key.rpartition(".")
        if not equals or not name or section not in ("", "estimator", "segmenter"):
            sys.exit(f"measure-real: --set {setting}: expected KEY=VALUE, KEY an estimator "
                     "option or segmenter.KEY")


def write_set_config(mount_yaml, settings, path):
    """The import's mount file with --set's settings."""
    from ruamel.yaml import YAML
    with open(mount_yaml, encoding="utf-8") as f:
        config = YAML(typ="safe", pure=True).load(f)
    apply_settings(config, settings)
    with open(path, "w", encoding="utf-8") as f:
        f.write(f"# {os.path.basename(mount_yaml)} with --set (scripts/measure-real.py).\n")
        YAML().dump(config, f)


def write_sensor_config(mount_yaml, scan, path, settings=()):
    """The import's mount file plus the scanner's field of view and range (module docstring)."""
    from ruamel.yaml import YAML
    yaml = YAML(typ="safe", pure=True)
    with open(mount_yaml, encoding="utf-8") as f:
        config = yaml.load(f)
    apply_settings(config, settings)
    angles = [math.degrees(a) for a in scan.angle_rad]
    estimator = config.setdefault("estimator", {})
    estimator["field_of_view_start_deg"] = round(min(angles), 6)
    estimator["field_of_view_end_deg"] = round(max(angles), 6)
    estimator["max_range_m"] = round(float(scan.range_max_m), 6)
    with open(path, "w", encoding="utf-8") as f:
        f.write(f"# {os.path.basename(mount_yaml)} plus the field of view and range of the "
                "scanner's first LASER_SCAN (scripts/measure-real.py).\n")
        YAML().dump(config, f)


def mount_of(config_path):
    config = StackConfig(config_path)
    forward_m, left_m = config.mount()
    yaw_deg = config.number("estimator", "sensor_yaw_deg", 0.0, -360.0, 360.0)
    return forward_m, left_m, math.radians(yaw_deg)


def people_figures(log):
    tracks, features = log["TRACKS"], log["FEATURES"]
    identities, per_minute = figures.person_identities_per_minute(tracks)
    return {"minutes": figures.span_minutes(tracks), "person_identities": identities,
            "person_identities_per_minute": per_minute,
            **figures.count_agreement(tracks, features)}


def sharpness_figures(log, config_path):
    scans, mount = log["LASER_SCAN"], mount_of(config_path)
    features = {f.utime: f for f in log["FEATURES"]}
    masks = [figures.wall_beams(scan, features[scan.utime]) for scan in scans]
    segments = figures.line_segments(log["MAP"][-1])
    utimes = [s.utime for s in scans]
    result = {"map_lines": len(segments)}
    for name, poses in (("estimate", log["POSE"]), ("odometry", log["ODOMETRY"])):
        points = figures.scan_points(scans, figures.trajectory_at(poses, utimes), mount, masks)
        result[name] = figures.sharpness(points, segments)
    return result


def measure(bin_dir, real_dir, outdir, name, relative, kind, settings=(), perturbed=()):
    """The figures of one recording; `perturbed`: the settings lists of the extra sensor runs."""
    stem = os.path.join(outdir, name)
    imported = stem + ".lcm"
    run([os.path.join(bin_dir, "slammtt-import"), "-q", os.path.join(real_dir, relative),
         "-o", imported])
    first_scan = next(iter(figures.read_channels(imported)["LASER_SCAN"]))
    config_paths = {"mount": imported + ".mount.yaml", "sensor": stem + ".sensor.yaml"}
    write_sensor_config(config_paths["mount"], first_scan, config_paths["sensor"], settings)
    if settings:
        config_paths["mount"] = stem + ".mount-set.yaml"
        write_set_config(imported + ".mount.yaml", settings, config_paths["mount"])
    for k, extra in enumerate(perturbed):
        config_paths[f"sensor_{k + 1}"] = f"{stem}.sensor-{k + 1}.yaml"
        write_sensor_config(imported + ".mount.yaml", first_scan, config_paths[f"sensor_{k + 1}"],
                            extra)
    result = {}
    for config, path in config_paths.items():
        out = f"{stem}-{config}.lcm"
        run([os.path.join(bin_dir, "slammtt-replay"), "-q", "--no-timing", imported, "-o", out,
             "--config", path])
        log = figures.read_channels(out)
        result[config] = (people_figures(log) if kind == "people"
                          else sharpness_figures(log, path))
    if perturbed:
        runs = [result.pop(f"sensor_{k + 1}") for k in range(len(perturbed))]
        result["sensor_runs"] = [result["sensor"], *runs]
        result["sensor_median"] = median_figures(result["sensor_runs"])
    return result


def print_tables(results):
    print("| recording | config | minutes | person identities | per minute | reported people "
          "per scan | leg pairs per scan | scans where reported = leg pairs | reported = "
          "person features |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, by_config in results.items():
        for config, f in by_config.items():
            if isinstance(f, dict) and "person_identities" in f:
                print(f"| {name} | {config} | {f['minutes']:.2f} | {f['person_identities']} | "
                      f"{f['person_identities_per_minute']:.1f} | {f['mean_reported']:.2f} | "
                      f"{f['mean_pairs']:.2f} | {f['match_pairs']:.3f} | "
                      f"{f['match_person_features']:.3f} |")
    print()
    print("| recording | config | placed by | wall spread m (1 m cells) | occupied 5 cm cells | "
          "RMS to final MAP lines m | share within 0.5 m of a MAP line | wall points |")
    print("|---|---|---|---|---|---|---|---|")
    for name, by_config in results.items():
        for config, f in by_config.items():
            for trajectory in ("estimate", "odometry"):
                if isinstance(f, dict) and trajectory in f:
                    s = f[trajectory]
                    print(f"| {name} | {config} | {trajectory} | {s['wall_spread_m']:.4f} | "
                          f"{s['occupied_cells']} | {s['map_line_rms_m']:.4f} | "
                          f"{s['map_line_share']:.3f} | {s['wall_points']} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("outdir")
    parser.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    parser.add_argument("--real", default=os.path.join(ROOT, "..", "shared", "data", "real"),
                        help="the real recordings (default ../shared/data/real)")
    parser.add_argument("--json", default=None, help="default OUTDIR/real.json")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="an estimator option (segmenter.KEY: a segmenter option) for both "
                             "configurations (repeatable)")
    parser.add_argument("--perturbed", action="store_true",
                        help="four more sensor runs with two noise floors 1 %% off; medians")
    args = parser.parse_args()
    if not os.path.isdir(args.real):
        sys.exit(f"measure-real: {args.real}: no such folder (the real recordings)")
    check_settings(args.set)
    os.makedirs(args.outdir, exist_ok=True)
    perturbed = perturbations(args.set, option_defaults(args.bin)) if args.perturbed else ()
    results = {name: measure(args.bin, args.real, args.outdir, name, relative, kind,
                             args.set, perturbed)
               for name, relative, kind in RECORDINGS}
    print_tables(results)
    path = args.json or os.path.join(args.outdir, "real.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(results, f, indent=2, sort_keys=True)
        f.write("\n")
    print(f"\nmeasure-real: figures in {path}", file=sys.stderr)


if __name__ == "__main__":
    main()
