"""slammtt-export of the estimator's line landmarks (walls and furniture sides in MAP) on the
office scenario: every line of every MAP message in map_lines.csv, and each line of the last
MAP as an entity `line/<id>` of the MCAP file's /map, read back by the csv module and the
`mcap` library (docs/export.md)."""

import csv

import pytest

from conftest import export_ok, read_log, scenario_run
from test_export_mcap import read_mcap


@pytest.fixture(scope="module")
def office(tmp_path_factory):
    run = scenario_run(tmp_path_factory, "office", 1)
    out = tmp_path_factory.mktemp("office-export")
    export_ok(run.log, "--csv", out / "csv", "--mcap", out / "run.mcap", "--config", run.config)
    return run, out, read_log(run.log)


def test_map_lines_csv_holds_every_line_of_every_map(office):
    _, out, log = office
    with open(out / "csv" / "map_lines.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    expected = [(m.utime, l) for m in log["MAP"] for l in m.lines]
    assert len(expected) > 0, "the office run mapped no line: nothing to export"
    assert len(rows) == len(expected)
    for row, (utime, line) in zip(rows, expected):
        assert int(row["utime_us"]) == utime and int(row["id"]) == line.id
        assert float(row["rho_m"]) == line.rho_m and float(row["alpha_rad"]) == line.alpha_rad
        assert float(row["var_alpha_rad2"]) == line.covariance[3]
        assert (float(row["from_x_m"]), float(row["to_y_m"])) == (line.from_x_m, line.to_y_m)


def test_tracks_csv_says_kind_and_whether_reported(office):
    _, out, log = office
    with open(out / "csv" / "tracks.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    tracks = [t for m in log["TRACKS"] for t in m.tracks]
    assert len(rows) == len(tracks) > 0
    for row, t in zip(rows, tracks):
        assert row["kind"] == ("person" if t.kind == 1 else "other")
        assert int(row["reported"]) == int(t.reported)
        assert int(row["measured"]) == int(t.measured)
        assert float(row["coasting_s"]) == t.coasting_s
    assert {row["kind"] for row in rows} == {"person", "other"}


def test_mcap_map_draws_the_line_landmarks(office):
    _, out, log = office
    _, _, messages = read_mcap(out / "run.mcap")
    _, update = messages["/map"][-1]
    final = log["MAP"][-1]
    entities = {e.id: e for e in update.entities}
    assert final.num_lines > 0
    assert {i for i in entities if i.startswith("line/")} == {f"line/{l.id}"
                                                              for l in final.lines}
    for l in final.lines:
        e = entities[f"line/{l.id}"]
        assert e.frame_id == "map" and e.texts[0].text == str(l.id)
        a, b = e.lines[0].points
        assert (a.x, a.y, b.x, b.y) == (l.from_x_m, l.from_y_m, l.to_x_m, l.to_y_m)
