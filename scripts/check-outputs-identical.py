#!/usr/bin/env python3
"""Checks that the stack's outputs are byte-identical to those of a base commit.

    scripts/check-outputs-identical.py --base COMMIT [--build-dir build] [--work DIR]
                                       [--seeds 1-5] [--scenarios s1-crossing,...] [--jobs 2]

For every shipped scenario (config/scenarios/*.yaml; large-loop only when named) and every seed
it runs, once with the programs of the base commit and once with those of this checkout:

    slammtt-world --scenario TREE/config/scenarios/S.yaml --seed N --log world.lcm
    { cat TREE/estimator/config/S.yaml; echo "  mode: MODE"; } > MODE.yaml
    slammtt-replay world.lcm -o MODE.out.lcm --no-timing --config MODE.yaml \\
        [--stage segmenter] --stage estimator
    slammtt-eval MODE.out.lcm --json MODE.json

(TREE is the base's tree for the base run, this checkout for the other: each side runs its own
scenarios and configurations, so a renamed configuration key is checked for the same behaviour.)
Mode ml_ransac everywhere, and the baselines where scripts/measure-estimator.py runs them
(static_nn and ransac_all_pairs on s1-crossing, ransac_all_pairs on s2-lobby), so that every
association path of the estimator is covered; the segmenter stage runs on the scenarios whose
world writes scans. Then every file of the base run (world log, replay log, evaluation JSON) is
compared byte for byte with the same file of this checkout's run. The timing log is not
written: it holds wall-clock durations.

The base commit is exported (git archive) into a temporary tree of its own under WORK, built
there (its own build directory, only slammtt-world, slammtt-replay and slammtt-eval) and run;
its outputs are kept in WORK/base-HASH/ and reused by later runs, which run the base only for
scenarios and seeds it has not recorded yet (the source tree and build of the base are deleted
once its outputs are recorded). This checkout's programs are built in
--build-dir (default build/, configured if needed). Exit status 0 when every file is identical,
1 when any differs or is missing (each is listed), 2 on a usage or build error.

Needs git, cmake, ninja and python3 (no extra modules).
"""
import argparse
import concurrent.futures
import filecmp
import os
import shutil
import subprocess
import sys
import tarfile
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TARGETS = ["slammtt-world", "slammtt-replay", "slammtt-eval"]
DONE = "outputs-complete"


def fail(message):
    sys.exit(f"check-outputs-identical: {message}")


def run(command, cwd=None, quiet=True):
    result = subprocess.run(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    if result.returncode != 0:
        tail = "\n".join((result.stdout + result.stderr).strip().splitlines()[-20:])
        raise RuntimeError(f"{' '.join(command)} (exit {result.returncode}):\n{tail}")
    if not quiet:
        print(result.stdout, end="")
    return result.stdout


# Shipped scenarios left out unless named with --scenarios: large-loop's 1000 landmarks make a
# 200 MB world log and a replay of a minute per seed (docs/smoother.md, "Large loop").
LONG_SCENARIOS = {"large-loop"}


def scenarios_of(tree):
    folder = os.path.join(tree, "config", "scenarios")
    return sorted(name[:-5] for name in os.listdir(folder) if name.endswith(".yaml"))


def modes_of(scenario):
    if scenario == "s1-crossing":
        return ["ml_ransac", "static_nn", "ransac_all_pairs"]
    if scenario == "s2-lobby":
        return ["ml_ransac", "ransac_all_pairs"]
    return ["ml_ransac"]


def writes_scans(tree, scenario):
    with open(os.path.join(tree, "config", "scenarios", scenario + ".yaml")) as f:
        for line in f:
            if line.startswith("output:"):
                return line.split(":", 1)[1].split("#")[0].strip() != "features"
    return True


def build(tree, build_dir, configure_args):
    if not os.path.exists(os.path.join(build_dir, "build.ninja")):
        run(["cmake", "-S", tree, "-B", build_dir, "-G", "Ninja",
             "-DCMAKE_BUILD_TYPE=Release"] + configure_args)
    run(["nice", "cmake", "--build", build_dir, "--target"] + TARGETS)
    return os.path.join(build_dir, "bin")


def run_one(tree, bin_dir, out_dir, scenario, seed):
    """World, replay and evaluation of one scenario and seed, run inside out_dir with relative
    file names (slammtt-eval writes the log's name into its JSON); returns the files written."""
    stem = f"{scenario}-seed{seed}"
    world = stem + ".world.lcm"
    run([os.path.join(bin_dir, "slammtt-world"), "--quiet", "--scenario",
         os.path.join(tree, "config", "scenarios", scenario + ".yaml"), "--seed", str(seed),
         "--log", world], cwd=out_dir)
    files = [world]
    with open(os.path.join(tree, "estimator", "config", scenario + ".yaml")) as f:
        shipped_config = f.read()
    stages = ["--stage", "estimator"]
    if writes_scans(tree, scenario):
        stages = ["--stage", "segmenter"] + stages
    for mode in modes_of(scenario):
        config = f"{stem}.{mode}.yaml"
        with open(os.path.join(out_dir, config), "w") as f:
            f.write(shipped_config + f"  mode: {mode}\n")
        out = f"{stem}.{mode}.out.lcm"
        report = f"{stem}.{mode}.json"
        run([os.path.join(bin_dir, "slammtt-replay"), "--quiet", world, "-o", out, "--no-timing",
             "--config", config] + stages, cwd=out_dir)
        run([os.path.join(bin_dir, "slammtt-eval"), "--quiet", out, "--json", report],
            cwd=out_dir)
        os.remove(os.path.join(out_dir, config))  # an input of the run, not an output
        files += [out, report]
    return files


def run_all(tree, bin_dir, out_dir, scenarios, seeds, jobs):
    if os.path.exists(out_dir):
        shutil.rmtree(out_dir)
    os.makedirs(out_dir)
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = [pool.submit(run_one, tree, bin_dir, out_dir, s, n)
                   for s in scenarios for n in seeds]
        for future in futures:
            future.result()


def export_commit(commit, destination):
    archive = subprocess.run(["git", "-C", ROOT, "archive", "--format=tar", commit],
                             stdout=subprocess.PIPE, check=True).stdout
    os.makedirs(destination)
    with tempfile.TemporaryFile() as f:
        f.write(archive)
        f.seek(0)
        with tarfile.open(fileobj=f) as tar:
            if hasattr(tarfile, "data_filter"):
                tar.extractall(destination, filter="data")
            else:
                tar.extractall(destination)


def base_outputs(commit, work, scenarios, seeds, jobs):
    """The base's outputs directory; runs the base only for the scenarios and seeds it has not
    recorded yet (the record is the file outputs-complete: one "scenario seed" per line)."""
    base = os.path.join(work, "base-" + commit)
    outputs = os.path.join(base, "outputs")
    done_path = os.path.join(base, DONE)
    done = set()
    if os.path.exists(done_path):
        with open(done_path) as f:
            done = {tuple(line.split()) for line in f if line.strip()}
    missing = [(s, n) for s in scenarios for n in seeds if (s, str(n)) not in done]
    if not missing:
        print(f"base {commit[:12]}: outputs recorded earlier, in {outputs}")
        return outputs
    print(f"base {commit[:12]}: exporting, building and running {len(missing)} scenario-seeds "
          f"(kept in {base})")
    tree = os.path.join(base, "src")
    build_dir = os.path.join(base, "build")
    for leftover in (tree, build_dir):
        if os.path.exists(leftover):
            shutil.rmtree(leftover)
    export_commit(commit, tree)
    bin_dir = build(tree, build_dir,
                    ["-DSLAMMTT_BUILD_TESTS=OFF", "-DSLAMMTT_BUILD_BENCHMARKS=OFF"])
    unknown = sorted({s for s, _ in missing if s not in scenarios_of(tree)})
    if unknown:
        fail(f"base {commit[:12]} has no scenario {', '.join(unknown)}")
    os.makedirs(outputs, exist_ok=True)
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = [pool.submit(run_one, tree, bin_dir, outputs, s, n) for s, n in missing]
        for future in futures:
            future.result()
    shutil.rmtree(tree)
    shutil.rmtree(build_dir)
    with open(done_path, "a") as f:
        for s, n in missing:
            f.write(f"{s} {n}\n")
    return outputs


def expected_files(scenarios, seeds):
    names = []
    for s in scenarios:
        for n in seeds:
            names.append(f"{s}-seed{n}.world.lcm")
            for mode in modes_of(s):
                names += [f"{s}-seed{n}.{mode}.out.lcm", f"{s}-seed{n}.{mode}.json"]
    return sorted(names)


def compare(base_dir, head_dir, names):
    problems = []
    for name in names:
        base_file = os.path.join(base_dir, name)
        head_file = os.path.join(head_dir, name)
        if not os.path.exists(base_file):
            problems.append(f"{name}: missing in the base's outputs")
        elif not os.path.exists(head_file):
            problems.append(f"{name}: missing in this checkout's outputs")
        elif not filecmp.cmp(base_file, head_file, shallow=False):
            a = os.path.getsize(base_file)
            b = os.path.getsize(head_file)
            problems.append(f"{name}: differs ({a} bytes in the base, {b} here)")
    return len(names), problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", required=True, help="commit whose outputs are the reference")
    parser.add_argument("--build-dir", default=os.path.join(ROOT, "build"),
                        help="this checkout's build directory (default: build/)")
    parser.add_argument("--work", default=None,
                        help="where outputs go (default: BUILD_DIR/outputs-identical)")
    parser.add_argument("--seeds", default="1-5", help="first-last (default 1-5)")
    parser.add_argument("--scenarios", default=None,
                        help="comma-separated (default: every config/scenarios/*.yaml but "
                             "large-loop)")
    parser.add_argument("--jobs", type=int, default=2, help="runs in parallel (default 2)")
    args = parser.parse_args()
    first, _, last = args.seeds.partition("-")
    seeds = list(range(int(first), int(last or first) + 1))
    scenarios = (args.scenarios.split(",") if args.scenarios else
                 [s for s in scenarios_of(ROOT) if s not in LONG_SCENARIOS])
    for scenario in scenarios:
        if scenario not in scenarios_of(ROOT):
            fail(f"unknown scenario '{scenario}' (config/scenarios/)")
    build_dir = os.path.abspath(args.build_dir)
    work = os.path.abspath(args.work or os.path.join(build_dir, "outputs-identical"))
    try:
        commit = run(["git", "-C", ROOT, "rev-parse", "--verify", args.base + "^{commit}"]).strip()
        base_dir = base_outputs(commit, work, scenarios, seeds, max(1, args.jobs))
        print(f"this checkout: building in {build_dir} and running")
        bin_dir = build(ROOT, build_dir, [])
        head_dir = os.path.join(work, "head")
        run_all(ROOT, bin_dir, head_dir, scenarios, seeds, max(1, args.jobs))
    except (RuntimeError, subprocess.CalledProcessError) as error:
        print(f"check-outputs-identical: {error}", file=sys.stderr)
        sys.exit(2)
    count, problems = compare(base_dir, head_dir, expected_files(scenarios, seeds))
    for problem in problems:
        print("  " + problem)
    scope = f"{len(scenarios)} scenarios x seeds {seeds[0]}-{seeds[-1]}"
    if problems:
        print(f"DIFFERENT: {len(problems)} of {count} files differ from base {commit[:12]} "
              f"({scope})")
        sys.exit(1)
    print(f"IDENTICAL: all {count} files byte-identical to base {commit[:12]} ({scope})")


if __name__ == "__main__":
    main()
