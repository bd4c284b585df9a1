#!/usr/bin/env python3
"""Victoria Park: our smoother against GTSAM 4.3 on the same file, same machine, same run.

    scripts/compare-victoria-park.py [--build build] [--shared ../shared] [--venv DIR]
        [--pose-update exponential|additive]

Opt-in: needs ../shared/data/real/victoria_park (or --shared) and, the first time, network for
PyPI (a venv with scripts/requirements-gtsam.txt is created under the build directory). Needs
build/bin/slammtt-smooth-dataset (cmake --build build --target slammtt-smooth-dataset).

Each solve runs in a process of its own (its peak memory is that process's ru_maxrss):
  ours   batch        slammtt-smooth-dataset FILE --mode batch        (LM from the odometry chain)
  ours   incremental  slammtt-smooth-dataset FILE --mode incremental  (Update per keyframe)
  GTSAM  batch        load2D + LevenbergMarquardtOptimizer from load2D's initial values
  GTSAM  incremental  load2D's factors fed keyframe by keyframe to ISAM2 (default parameters)
Both sides add the same prior on pose 0 (origin, sigma 1e-3) and stop LM at a relative decrease
of chi^2 below 1e-10. Our poses move by GTSAM's Pose2 retraction (pose * exp(step),
--pose-update exponential, the default here) so that both LMs damp the same steps; with
--pose-update additive (the smoother's default) they take different paths from the odometry
chain and end in different local minima (docs/smoother.md, "Victoria Park"). chi^2 is the sum of squared whitened residuals (2 x GTSAM's error).
After the incremental runs, both sides polish with their batch LM. Then each side's LM starts
from the other side's solutions: a solution the other LM does not move is an optimum both
agree on (this problem has several local minima from the odometry chain, and the two LMs
reach different ones).
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
PRIOR_SIGMA = 1e-3
RELATIVE_TOLERANCE = 1e-10
MAX_ITERATIONS = 500


def peak_rss_kib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


# ---- the GTSAM side (runs inside the venv) ----

def gtsam_problem(path):
    import gtsam
    import numpy as np
    graph, initial = gtsam.load2D(path)
    prior = gtsam.noiseModel.Diagonal.Sigmas(np.array([PRIOR_SIGMA] * 3))
    graph.add(gtsam.PriorFactorPose2(0, gtsam.Pose2(), prior))
    return graph, initial


def gtsam_lm(graph, initial):
    import gtsam
    params = gtsam.LevenbergMarquardtParams()
    params.setRelativeErrorTol(RELATIVE_TOLERANCE)
    params.setAbsoluteErrorTol(0.0)
    params.setMaxIterations(MAX_ITERATIONS)
    optimizer = gtsam.LevenbergMarquardtOptimizer(graph, initial, params)
    result = optimizer.optimize()
    return result, optimizer.iterations()


def write_solution(values, path):
    """Our solution format: POSE id x y theta / POINT id x y."""
    import gtsam
    with open(path, "w") as f:
        for key in values.keys():
            symbol = gtsam.Symbol(key)
            if chr(symbol.chr()) == "l":
                p = values.atPoint2(key)
                f.write(f"POINT {symbol.index()} {float(p[0])!r} {float(p[1])!r}\n")
            else:
                pose = values.atPose2(key)
                f.write(f"POSE {key} {pose.x()!r} {pose.y()!r} {pose.theta()!r}\n")


def gtsam_batch(path, solution):
    graph, initial = gtsam_problem(path)
    start = time.perf_counter()
    result, iterations = gtsam_lm(graph, initial)
    seconds = time.perf_counter() - start
    write_solution(result, solution)
    return {"chi_square": 2 * graph.error(result), "initial_chi_square": 2 * graph.error(initial),
            "iterations": iterations, "solve_seconds": seconds}


def gtsam_incremental(path, solution):
    import gtsam
    import numpy as np
    graph, _ = gtsam_problem(path)
    prior_factor = graph.at(graph.size() - 1)
    isam = gtsam.ISAM2(gtsam.ISAM2Params())
    step_seconds = []
    new_graph = gtsam.NonlinearFactorGraph()
    new_values = gtsam.Values()
    new_graph.add(prior_factor)
    new_values.insert(0, gtsam.Pose2())
    known = {0}

    def update():
        nonlocal new_graph, new_values
        t = time.perf_counter()
        isam.update(new_graph, new_values)
        step_seconds.append(time.perf_counter() - t)
        new_graph = gtsam.NonlinearFactorGraph()
        new_values = gtsam.Values()

    start = time.perf_counter()
    for k in range(graph.size() - 1):  # the prior is last
        factor = graph.at(k)
        keys = factor.keys()
        if isinstance(factor, gtsam.BetweenFactorPose2):  # a new keyframe
            update()
            previous = isam.calculateEstimatePose2(keys[0])
            new_values.insert(keys[1], previous.compose(factor.measured()))
            known.add(keys[1])
        else:
            pose_key, landmark_key = keys[0], keys[1]
            if landmark_key not in known:
                known.add(landmark_key)
                measured = factor.measured()
                pose = new_values.atPose2(pose_key) if new_values.exists(pose_key) \
                    else isam.calculateEstimatePose2(pose_key)
                local = measured.bearing().rotate(gtsam.Point2(measured.range(), 0.0))
                new_values.insert(landmark_key, pose.transformFrom(local))
        new_graph.add(factor)
    update()
    total = time.perf_counter() - start
    estimate = isam.calculateEstimate()
    steps = np.array(step_seconds)
    start = time.perf_counter()
    polished, _ = gtsam_lm(graph, estimate)
    polish_seconds = time.perf_counter() - start
    write_solution(estimate, solution)
    return {"chi_square": 2 * graph.error(estimate), "total_seconds": total,
            "polished_chi_square": 2 * graph.error(polished), "polish_seconds": polish_seconds,
            "update_seconds": float(steps.sum()),
            "step_p50_seconds": float(np.percentile(steps, 50)),
            "step_p99_seconds": float(np.percentile(steps, 99)),
            "step_max_seconds": float(steps.max())}


def gtsam_polish(path, solution):
    """GTSAM's LM started from one of our solutions (POSE id x y theta / POINT id x y)."""
    import gtsam
    graph, _ = gtsam_problem(path)
    values = gtsam.Values()
    with open(solution) as f:
        for line in f:
            fields = line.split()
            if fields[0] == "POSE":
                values.insert(int(fields[1]), gtsam.Pose2(*map(float, fields[2:5])))
            elif fields[0] == "POINT":
                values.insert(gtsam.symbol_shorthand.L(int(fields[1])),
                              gtsam.Point2(*map(float, fields[2:4])))
    result, iterations = gtsam_lm(graph, values)
    return {"start_chi_square": 2 * graph.error(values), "chi_square": 2 * graph.error(result),
            "iterations": iterations}


def run_gtsam(args):
    if args.gtsam == "batch":
        out = gtsam_batch(args.file, args.gtsam_solution)
    elif args.gtsam == "incremental":
        out = gtsam_incremental(args.file, args.gtsam_solution)
    else:
        out = gtsam_polish(args.file, args.gtsam_solution)
    out["peak_rss_kib"] = peak_rss_kib()
    print(json.dumps(out))


# ---- the driver (system python3, standard library only) ----

def ensure_venv(venv):
    python = os.path.join(venv, "bin", "python")
    stamp = os.path.join(venv, "requirements-gtsam.txt")
    requirements = os.path.join(HERE, "requirements-gtsam.txt")
    with open(requirements) as f:
        wanted = f.read()
    if os.path.exists(stamp) and open(stamp).read() == wanted and os.path.exists(python):
        return python
    print(f"compare-victoria-park: creating {venv} (gtsam 4.3.0 from PyPI)", file=sys.stderr)
    subprocess.run([sys.executable, "-m", "venv", venv], check=True)
    subprocess.run([python, "-m", "pip", "install", "-q", "-r", requirements], check=True)
    with open(stamp, "w") as f:
        f.write(wanted)
    return python


def run_json(command):
    done = subprocess.run(command, check=True, capture_output=True, text=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def relative(a, b):
    return abs(a - b) / max(abs(a), abs(b))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--shared", default=os.path.join(ROOT, "..", "shared"))
    parser.add_argument("--venv", default=None)
    parser.add_argument("--json", default=None, help="write every figure here too")
    parser.add_argument("--pose-update", choices=["exponential", "additive"],
                        default="exponential",
                        help="how our smoother moves a pose (default: GTSAM's retraction)")
    parser.add_argument("--gtsam", choices=["batch", "incremental", "polish"],
                        help=argparse.SUPPRESS)
    parser.add_argument("--gtsam-solution", help=argparse.SUPPRESS)
    parser.add_argument("--file", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.gtsam:
        return run_gtsam(args)

    data = os.path.join(args.shared, "data", "real", "victoria_park", "victoria_park.txt")
    if not os.path.exists(data):
        sys.exit(f"compare-victoria-park: no {data} (use --shared DIR)")
    tool = os.path.join(args.build, "bin", "slammtt-smooth-dataset")
    if not os.path.exists(tool):
        sys.exit(f"compare-victoria-park: no {tool} (cmake --build {args.build} "
                 "--target slammtt-smooth-dataset)")
    python = ensure_venv(args.venv or os.path.join(args.build, "venv-gtsam"))
    me = os.path.abspath(__file__)
    solutions = os.path.join(args.build, "victoria-park")
    os.makedirs(solutions, exist_ok=True)

    figures = {}
    for mode in ("batch", "incremental"):
        ours = os.path.join(solutions, f"ours-{mode}.txt")
        theirs = os.path.join(solutions, f"gtsam-{mode}.txt")
        print(f"compare-victoria-park: ours {mode} ...", file=sys.stderr)
        figures[f"ours_{mode}"] = run_json([tool, data, "--mode", mode, "--solution", ours,
                                            "--polish", "--pose-update", args.pose_update])
        print(f"compare-victoria-park: GTSAM {mode} ...", file=sys.stderr)
        figures[f"gtsam_{mode}"] = run_json([python, me, "--gtsam", mode, "--file", data,
                                             "--gtsam-solution", theirs])
    # The same optimum from the same start: each side's LM from the other's solutions.
    for mode in ("batch", "incremental"):
        print(f"compare-victoria-park: GTSAM LM from our {mode} solution ...", file=sys.stderr)
        figures[f"gtsam_from_ours_{mode}"] = run_json(
            [python, me, "--gtsam", "polish", "--file", data, "--gtsam-solution",
             os.path.join(solutions, f"ours-{mode}.txt")])
        print(f"compare-victoria-park: our LM from GTSAM's {mode} solution ...", file=sys.stderr)
        figures[f"ours_from_gtsam_{mode}"] = run_json(
            [tool, data, "--mode", "batch", "--pose-update", args.pose_update, "--initial",
             os.path.join(solutions, f"gtsam-{mode}.txt")])

    ob, gb = figures["ours_batch"], figures["gtsam_batch"]
    oi, gi = figures["ours_incremental"], figures["gtsam_incremental"]
    rows = [
        ("batch: initial chi^2", ob["initial_chi_square"], gb["initial_chi_square"]),
        ("batch: final chi^2", ob["chi_square"], gb["chi_square"]),
        ("batch: LM iterations", ob["iterations"], gb["iterations"]),
        ("batch: solve wall time (s)", ob["solve_seconds"], gb["solve_seconds"]),
        ("batch: peak memory (MiB)", ob["peak_rss_kib"] / 1024, gb["peak_rss_kib"] / 1024),
        ("incremental: final chi^2", oi["chi_square"], gi["chi_square"]),
        ("incremental: total wall time (s)", oi["total_seconds"], gi["total_seconds"]),
        ("incremental: ISAM2 update() calls only (s)", None, gi["update_seconds"]),
        ("incremental: per-step p50 (ms)", oi["step_p50_seconds"] * 1e3,
         gi["step_p50_seconds"] * 1e3),
        ("incremental: per-step p99 (ms)", oi["step_p99_seconds"] * 1e3,
         gi["step_p99_seconds"] * 1e3),
        ("incremental: peak memory (MiB)", oi["peak_rss_kib"] / 1024, gi["peak_rss_kib"] / 1024),
        ("incremental, then batch LM: chi^2", oi["polished_chi_square"],
         gi["polished_chi_square"]),
        ("incremental, then batch LM: LM time (s)", oi["polish_seconds"], gi["polish_seconds"]),
    ]
    print(f"{'Victoria Park (6969 poses, 151 landmarks)':46s} {'ours':>18s} {'GTSAM 4.3.0':>18s}")
    for name, ours, theirs in rows:
        def cell(v):
            if v is None:
                return "-"
            return f"{v:.10g}" if isinstance(v, float) else str(v)
        print(f"{name:46s} {cell(ours):>18s} {cell(theirs):>18s}")
    for mode in ("batch", "incremental"):
        p = figures[f"gtsam_from_ours_{mode}"]
        print(f"GTSAM LM from our {mode} solution: chi^2 {p['start_chi_square']:.10g} -> "
              f"{p['chi_square']:.10g} in {p['iterations']} iterations "
              f"(relative change {relative(p['start_chi_square'], p['chi_square']):.2e})")
        q = figures[f"ours_from_gtsam_{mode}"]
        print(f"our LM from GTSAM's {mode} solution: chi^2 {q['initial_chi_square']:.10g} -> "
              f"{q['chi_square']:.10g} in {q['iterations']} iterations "
              f"(relative change {relative(q['initial_chi_square'], q['chi_square']):.2e})")
    print(f"same optimum, batch (relative difference of final chi^2): "
          f"{relative(ob['chi_square'], gb['chi_square']):.2e} (target 1e-6)")
    print(f"same optimum, incremental: {relative(oi['chi_square'], gi['chi_square']):.2e} "
          f"(target 1e-6)")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(figures, f, indent=1)


if __name__ == "__main__":
    main()
