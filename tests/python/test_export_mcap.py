"""slammtt-export --mcap read back by the `mcap` library (with mcap-protobuf-support's decoder):
schemas, channels, message counts and decoded values against the log (docs/export.md)."""

import math

import pytest

from conftest import export_ok, read_log, run_export, scenario_run


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    return scenario_run(tmp_path_factory, "s1-crossing", 7)


@pytest.fixture(scope="module")
def mcap_file(run, tmp_path_factory):
    path = tmp_path_factory.mktemp("mcap") / "run.mcap"
    err = export_ok(run.log, "--mcap", path, "--config", run.config)
    return path, err


def read_mcap(path):
    """(summary, metadata {name: {key: value}}, {topic: [(log_time_ns, decoded message)]})."""
    from mcap.reader import make_reader
    from mcap_protobuf.decoder import DecoderFactory
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        metadata = {m.name: m.metadata for m in reader.iter_metadata()}
        messages = {}
        for _, channel, message, decoded in reader.iter_decoded_messages(log_time_order=False):
            messages.setdefault(channel.topic, []).append((message.log_time, decoded))
    return summary, metadata, messages


@pytest.fixture(scope="module")
def contents(mcap_file):
    return read_mcap(mcap_file[0])


EXPECTED_SCHEMAS = {
    "/tf": "foxglove.FrameTransforms", "/laser_scan": "foxglove.LaserScan",
    "/laser_scan/points": "foxglove.PointCloud", "/pose": "foxglove.PoseInFrame",
    "/odometry": "foxglove.PoseInFrame", "/ground_truth/pose": "foxglove.PoseInFrame",
    "/map": "foxglove.SceneUpdate", "/tracks": "foxglove.SceneUpdate",
    "/features": "foxglove.SceneUpdate", "/ground_truth/objects": "foxglove.SceneUpdate",
    "/ground_truth/walls": "foxglove.SceneUpdate",
}


def test_schemas_channels_and_counts(run, contents):
    summary, metadata, messages = contents
    log = read_log(run.log)
    topics = {c.topic: (summary.schemas[c.schema_id].name, c.message_encoding,
                        summary.statistics.channel_message_counts[c.id])
              for c in summary.channels.values()}
    assert {t: s for t, (s, _, _) in topics.items()} == EXPECTED_SCHEMAS
    assert all(encoding == "protobuf" for _, encoding, _ in topics.values())
    for topic, channel in (("/laser_scan", "LASER_SCAN"), ("/laser_scan/points", "LASER_SCAN"),
                           ("/pose", "POSE"), ("/odometry", "ODOMETRY"),
                           ("/ground_truth/pose", "GROUND_TRUTH"), ("/map", "MAP"),
                           ("/tracks", "TRACKS"), ("/features", "FEATURES"),
                           ("/ground_truth/objects", "GROUND_TRUTH")):
        assert topics[topic][2] == len(messages[topic]) == len(log[channel]), topic
    assert metadata["slammtt"]["laser_mount_forward_m"] == "0.1"
    assert metadata["slammtt"]["log"] == run.log.name


def test_frame_transforms_chain_world_map_base_laser(run, contents):
    _, _, messages = contents
    log = read_log(run.log)
    edges = {}
    for _, tf in messages["/tf"]:
        for t in tf.transforms:
            edges.setdefault((t.parent_frame_id, t.child_frame_id), []).append(t)
    assert set(edges) >= {("map", "base_link"), ("base_link", "laser"), ("world", "map"),
                          ("map", "odom")}
    # The laser mount of the configuration (estimator.sensor_forward_m: 0.1).
    mount = edges[("base_link", "laser")][0]
    assert (mount.translation.x, mount.translation.y, mount.rotation.w) == (0.1, 0.0, 1.0)
    # map -> base_link is every POSE.
    poses = log["POSE"]
    base = edges[("map", "base_link")]
    assert len(base) == len(poses)
    for k in (0, len(poses) // 2, len(poses) - 1):
        t, p = base[k], poses[k]
        assert t.timestamp.seconds * 1000000 + t.timestamp.nanos // 1000 == p.utime
        assert (t.translation.x, t.translation.y) == (p.x_m, p.y_m)
        heading = 2.0 * math.atan2(t.rotation.z, t.rotation.w)
        assert math.remainder(heading - p.heading_rad, 2 * math.pi) == pytest.approx(0, abs=1e-12)
    # Constant transforms come again at least once a second of message time.
    times = sorted(t.timestamp.seconds + t.timestamp.nanos * 1e-9
                   for t in edges[("base_link", "laser")])
    assert max(b - a for a, b in zip(times, times[1:])) <= 1.0 + 1e-9
    # world -> map is slammtt-eval's anchoring: the estimate drawn through it lies on the truth
    # at the anchoring scan.
    anchor = run.report["detail"]["robot"]["anchor"]
    world_map = edges[("world", "map")][0]
    assert world_map.translation.x == pytest.approx(anchor["x_m"], abs=1e-12)
    assert world_map.translation.y == pytest.approx(anchor["y_m"], abs=1e-12)


def test_poses_scans_landmarks_tracks_decode_to_the_logs_values(run, contents):
    _, _, messages = contents
    log = read_log(run.log)
    k = len(log["POSE"]) // 2
    pose_time, pose = messages["/pose"][k]
    assert pose_time == log["POSE"][k].utime * 1000 and pose.frame_id == "map"
    assert (pose.pose.position.x, pose.pose.position.y) == (log["POSE"][k].x_m,
                                                            log["POSE"][k].y_m)

    _, scan = messages["/laser_scan"][k]
    beams = log["LASER_SCAN"][k]
    assert scan.frame_id == "laser" and len(scan.ranges) == beams.num_beams
    assert scan.start_angle == pytest.approx(beams.angle_rad[0], abs=1e-7)
    assert scan.end_angle == pytest.approx(beams.angle_rad[-1], abs=1e-6)
    for i in range(beams.num_beams):   # evenly spaced beams map one to one
        if beams.valid[i]:
            assert scan.ranges[i] == pytest.approx(beams.range_m[i], rel=1e-7)
        else:
            assert math.isnan(scan.ranges[i])
    _, cloud = messages["/laser_scan/points"][k]
    assert len(cloud.data) == 16 * sum(bool(v) for v in beams.valid)

    _, update = messages["/map"][-1]
    final = log["MAP"][-1]
    entities = {e.id: e for e in update.entities}
    assert set(entities) == {f"landmark/{l.id}" for l in final.landmarks}
    for l in final.landmarks:
        e = entities[f"landmark/{l.id}"]
        assert e.frame_id == "map" and e.texts[0].text == str(l.id)
        assert (e.spheres[0].pose.position.x, e.spheres[0].pose.position.y) == (l.x_m, l.y_m)
        ellipse = e.lines[0].points
        assert len(ellipse) == 33 and ellipse[0] == ellipse[-1]
        # 2-sigma ellipse: every point at Mahalanobis distance 2 from the landmark.
        c = list(l.covariance)
        det = c[0] * c[3] - c[1] * c[2]
        for p in ellipse[::8]:
            dx, dy = p.x - l.x_m, p.y - l.y_m
            d2 = (c[3] * dx * dx - 2 * c[1] * dx * dy + c[0] * dy * dy) / det
            assert d2 == pytest.approx(4.0, rel=1e-6)

    # Tracks: one entity per track with its id, deletions of tracks that are gone.
    deleted = 0
    for (_, update), message in zip(messages["/tracks"], log["TRACKS"]):
        assert sorted(e.id for e in update.entities) == sorted(f"track/{t.id}"
                                                               for t in message.tracks)
        deleted += len(update.deletions)
    assert deleted > 0
    _, update = next((u for u in messages["/tracks"] if u[1].entities))
    assert update.entities[0].texts[0].text.split()[0] == update.entities[0].id.split("/")[1]
    assert len(update.entities[0].lines[0].points) == 33

    _, features = messages["/features"][k]
    by_id = {e.id: e for e in features.entities}
    assert len(by_id["point_features"].spheres) == log["FEATURES"][k].num_features
    assert all(e.frame_id == "laser" for e in features.entities)
    _, objects = messages["/ground_truth/objects"][k]
    assert len(objects.entities) == len(log["GROUND_TRUTH"][k].objects)


def test_same_log_same_bytes(run, mcap_file, tmp_path):
    again = tmp_path / "again.mcap"
    export_ok(run.log, "--mcap", again, "--config", run.config)
    assert again.read_bytes() == mcap_file[0].read_bytes()


def test_not_finite_messages_are_skipped_and_counted(run, tmp_path):
    from slammtt.lcmlog import LogReader, LogWriter
    log = tmp_path / "nan.lcm"
    poses = 0
    with LogWriter(log) as writer:
        for channel, utime, message in LogReader(run.log):
            if channel == "POSE":
                poses += 1
                if poses % 10 == 0:
                    message.x_m = float("nan")
            writer.write(utime, channel, message.encode())
    out = tmp_path / "nan.mcap"
    status, _, err = run_export(log, "--mcap", out)
    assert status == 0, err
    assert f"skipped {poses // 10} POSE messages with values that are not finite" in err
    _, _, messages = read_mcap(out)
    assert len(messages["/pose"]) == poses - poses // 10
    assert all(math.isfinite(p.pose.position.x) for _, p in messages["/pose"])
    assert not list(tmp_path.glob("*.partial*"))


def test_a_link_planted_at_the_output_is_replaced_not_written_through(run, tmp_path):
    victim = tmp_path / "victim"
    victim.write_text("keep me")
    out = tmp_path / "run.mcap"
    out.symlink_to(victim)
    export_ok(run.log, "--mcap", out)
    assert victim.read_text() == "keep me"
    assert not out.is_symlink() and read_mcap(out)[0].statistics.message_count > 1000


def test_without_a_mount_in_the_configuration_the_logs_geometry_gives_it(run, tmp_path):
    # The world log's LASER_GEOMETRY: s1-crossing's laser 0.1 m ahead of the axle.
    path = tmp_path / "bare.mcap"
    err = export_ok(run.log, "--mcap", path)
    assert "laser mount from LASER_GEOMETRY: forward 0.1 m, left 0 m" in err
    _, metadata, messages = read_mcap(path)
    assert metadata["slammtt"]["laser_mount_forward_m"] == "0.1"
    mounts = [t for _, tf in messages["/tf"] for t in tf.transforms
              if (t.parent_frame_id, t.child_frame_id) == ("base_link", "laser")]
    assert mounts and all(t.translation.x == 0.1 for t in mounts)
