#!/usr/bin/env python3
"""Where the reported person identities of a recording come from (the figure that
scripts/measure-real.py counts on negative_2 and leg_tracker_demo).

    build/venv/bin/python scripts/person-identities.py OUT.lcm [OTHER.lcm]

For every identity ever reported as a person (track_t.reported and kind PERSON) in the TRACKS
of OUT.lcm: what its first measurement made it (P: a person feature, o: any other point
feature), its class and hits when it was first reported, how many scans it was reported, and
the kind after each of its first measured scans (the kind is the majority of its measurements,
docs/estimator.md, "People"). Then the count per (first kind, class at first report). With a
second log (the same recording run with other options), the same for it, and the jumps of both:
measurement updates that moved a track by more than 1 m (a track coasting with a wide gate that
took a measurement far from it), by the track's class, confirmation and kind before the update.
"""
import argparse
import collections
import math

from slammtt import recording_figures as figures

CLASS = {0: "S", 1: "M", 2: "U"}


def histories(path):
    """{id: [(seconds since the first TRACKS, track_t), ...]} over the log's TRACKS."""
    messages = list(figures.read_channels(path)["TRACKS"])
    t0 = messages[0].utime if messages else 0
    tracks = collections.defaultdict(list)
    for m in messages:
        for t in m.tracks:
            tracks[t.id].append(((m.utime - t0) / 1e6, t))
    return tracks


def kind_letter(track):
    return "P" if track.kind == figures.KIND_PERSON else "o"


def identities(tracks):
    rows = []
    for track_id, life in sorted(tracks.items()):
        reported = [(s, t) for s, t in life if t.reported and t.kind == figures.KIND_PERSON]
        if not reported:
            continue
        seconds, first = reported[0]
        kinds = "".join(kind_letter(t) for _, t in life if t.measured)[:12]
        rows.append({"id": track_id, "born": kind_letter(life[0][1]),
                     "class": CLASS[first.object_class], "hits": first.hits,
                     "first_reported_s": seconds, "reported_scans": len(reported),
                     "kinds": kinds, "x_m": first.x_m, "y_m": first.y_m})
    return rows


def jumps(tracks, over_m=1.0):
    counts = collections.Counter()
    for life in tracks.values():
        for (_, before), (_, after) in zip(life, life[1:]):
            if after.measured and math.hypot(after.x_m - before.x_m,
                                             after.y_m - before.y_m) > over_m:
                counts[CLASS[before.object_class] + ("c" if before.confirmed else "t") +
                       kind_letter(before)] += 1
    return counts


def report(path):
    tracks = histories(path)
    rows = identities(tracks)
    print(f"{path}: {len(rows)} reported person identities")
    print("| id | born | class | hits | first reported s | reported scans | kind after each "
          "measured scan | x m | y m |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['id']} | {r['born']} | {r['class']} | {r['hits']} | "
              f"{r['first_reported_s']:.1f} | {r['reported_scans']} | {r['kinds']} | "
              f"{r['x_m']:.2f} | {r['y_m']:.2f} |")
    by_origin = collections.Counter((r["born"], r["class"]) for r in rows)
    print("per (born, class at first report):",
          ", ".join(f"{b}/{c} {n}" for (b, c), n in sorted(by_origin.items())))
    moved = jumps(tracks)
    print(f"updates that moved a track > 1 m: {sum(moved.values())} (",
          ", ".join(f"{k} {n}" for k, n in sorted(moved.items())), ")\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("logs", nargs="+", help="estimator output logs (TRACKS)")
    for path in parser.parse_args().logs:
        report(path)


if __name__ == "__main__":
    main()
