#!/bin/sh
# The pictures of the README and docs/tools.md (docs/images/*.svg), made by the real pipeline:
#   s1-crossing seed 7 (world point features) -> slammtt-replay with its estimator configuration
#     and the smoother -> slammtt-eval --plots:
#     s1-crossing-{trajectory,map,tracks,identities,errors}.svg;
#   office seed 1 (scans) -> segmenter and estimator (replay) -> slammtt-eval --plots with the
#     office configuration (the laser mount): office-scan.svg.
# The same commands as the main job's steps 2 and 3 (scripts/run-main-job.sh), run in a scratch
# directory; every step is deterministic, so the same code gives the same bytes.
#
#   scripts/make-readme-pictures.sh [--bin DIR] [OUTDIR]   write the pictures (default
#                                                          OUTDIR: docs/images)
#   scripts/make-readme-pictures.sh [--bin DIR] --check    compare them with docs/images: exit 1
#                                                          naming each picture that differs
# DIR: the programs (default build/bin). The test readme_pictures_current runs --check: after a
# change to the estimator, the evaluation or the pictures, run this script and commit the result.
set -eu
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="$root/build/bin"
out="$root/docs/images"
check=0
while [ $# -gt 0 ]; do
  case "$1" in
    --bin) bin="$2"; shift 2 ;;
    --check) check=1; shift ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    -*) echo "make-readme-pictures.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) out="$1"; shift ;;
  esac
done
for program in slammtt-world slammtt-replay slammtt-eval; do
  if [ ! -x "$bin/$program" ]; then
    echo "make-readme-pictures.sh: $bin/$program missing: build first (scripts/build.sh)" >&2
    exit 2
  fi
done
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
cd "$scratch"

"$bin/slammtt-world" --quiet --scenario s1-crossing --seed 7 --log s1-crossing-seed7.lcm
"$bin/slammtt-replay" --quiet --no-timing s1-crossing-seed7.lcm -o s1-crossing-seed7-replay.lcm \
  --config "$root/estimator/config/s1-crossing.yaml" --smoother
# The log's name is written into the pictures' captions: the main job's name for it.
mkdir -p out && mv s1-crossing-seed7-replay.lcm out/
"$bin/slammtt-eval" --quiet out/s1-crossing-seed7-replay.lcm --json s1-report.json \
  --plots s1-pictures > /dev/null

"$bin/slammtt-world" --quiet --scenario office --seed 1 --log office-seed1.lcm
"$bin/slammtt-replay" --quiet --no-timing office-seed1.lcm -o out/office-seed1-replay.lcm \
  --config "$root/estimator/config/office.yaml"
"$bin/slammtt-eval" --quiet out/office-seed1-replay.lcm \
  --config "$root/estimator/config/office.yaml" --json office-report.json \
  --plots office-pictures > /dev/null

mkdir -p made
for picture in trajectory map tracks identities errors; do
  cp "s1-pictures/$picture.svg" "made/s1-crossing-$picture.svg"
done
cp office-pictures/scan.svg made/office-scan.svg
cp s1-report.json made/s1-crossing-report.json  # for the test's counts; not in docs/images

if [ "$check" -eq 1 ]; then
  stale=0
  for made in made/*.svg; do
    name="$(basename "$made")"
    if ! cmp -s "$made" "$root/docs/images/$name"; then
      echo "docs/images/$name is not what the pipeline draws now" >&2
      stale=1
    fi
  done
  if [ "$stale" -ne 0 ]; then
    echo "make-readme-pictures.sh: run scripts/make-readme-pictures.sh and commit docs/images" >&2
    exit 1
  fi
  # The identity timeline marks as many switches and fragmentations as the report counts.
  for what in id_switches:id-switch fragmentations:fragmentation; do
    key="${what%%:*}"
    role="${what##*:}"
    reported="$(sed -n "s/^  \"$key\": \([0-9]*\),*$/\1/p" made/s1-crossing-report.json)"
    drawn="$(grep -c "class=\"$role\"" made/s1-crossing-identities.svg || true)"
    if [ "$reported" != "$drawn" ]; then
      echo "s1-crossing-identities.svg: $drawn $role markers, the report counts $key $reported" >&2
      exit 1
    fi
    echo "s1-crossing: $key $reported, $drawn $role markers"
  done
  echo "docs/images: $(ls made/*.svg | wc -l) pictures current"
  exit 0
fi
mkdir -p "$out"
cp made/*.svg "$out/"
echo "wrote $(ls made/*.svg | wc -l) pictures into $out"
