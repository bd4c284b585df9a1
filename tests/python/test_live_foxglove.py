"""slammtt-foxglove, live from LCM and playing a log, checked by a WebSocket client (the
`websockets` package) speaking Foxglove's WebSocket protocol: advertised channels and schemas,
and decoded messages equal to what was published (docs/export.md, "Live view").

Run in a network namespace of its own (tests/support/netns-run, as ctest runs it): the LCM
traffic never leaves it."""

import base64
import json
import re
import signal
import struct
import subprocess
import sys
import time

import pytest

from conftest import BIN_DIR, read_log, run_module, scenario_run

URL = "udpm://239.255.76.67:7667?ttl=0"
ALL_TOPICS = {"/tf", "/laser_scan", "/laser_scan/points", "/pose", "/smoothed_pose",
              "/odometry", "/ground_truth/pose", "/map", "/tracks", "/features",
              "/ground_truth/objects", "/ground_truth/walls", "/leg_labels"}


class Bridge:
    """slammtt-foxglove as a child process on a free port."""

    def __init__(self, *args):
        self.process = subprocess.Popen(
            [sys.executable, "-m", "slammtt.foxglove.bridge", "--port", "0", *map(str, args)],
            stderr=subprocess.PIPE, text=True)
        line = self.process.stderr.readline()
        match = re.search(r"serving ws://127\.0\.0\.1:(\d+) ", line)
        assert match, line + self.process.stderr.read()
        self.port = int(match.group(1))

    def stop(self):
        """SIGTERM; (exit status, the rest of stderr)."""
        self.process.send_signal(signal.SIGTERM)
        err = self.process.stderr.read()
        return self.process.wait(timeout=30), err

    def kill(self):
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()


class FoxgloveClient:
    """The client side of Foxglove's WebSocket protocol: serverInfo and advertise (JSON),
    subscribe, binary message data (opcode 1: subscription id u32, log time u64, payload),
    payloads decoded from the advertised protobuf schemas."""

    def __init__(self, port):
        from websockets.sync.client import connect
        self._connection = connect(f"ws://127.0.0.1:{port}", subprotocols=["foxglove.sdk.v1"],
                                   open_timeout=10)
        self.socket = self._connection.__enter__()
        self.server_info = None
        self.channels = {}          # topic -> advertised channel
        self.decoders = {}          # subscription id -> (topic, decoder)
        deadline = time.monotonic() + 10
        while (self.server_info is None or not ALL_TOPICS <= set(self.channels)) and \
                time.monotonic() < deadline:
            self._handle(self.socket.recv(timeout=10))

    def _handle(self, frame):
        if isinstance(frame, str):
            op = json.loads(frame)
            if op["op"] == "serverInfo":
                self.server_info = op
            elif op["op"] == "advertise":
                for channel in op["channels"]:
                    self.channels[channel["topic"]] = channel
            return None
        if frame[0] != 1:
            return None                      # time (opcode 2) and others
        subscription, log_time = struct.unpack_from("<IQ", frame, 1)
        topic, decoder = self.decoders[subscription]
        return topic, log_time, decoder(frame[13:])

    def subscribe(self, *topics):
        from mcap.records import Schema
        from mcap_protobuf.decoder import DecoderFactory
        subscriptions = []
        for topic in topics:
            channel = self.channels[topic]
            schema = Schema(id=channel["id"], name=channel["schemaName"], encoding="protobuf",
                            data=base64.b64decode(channel["schema"]))
            sub_id = len(self.decoders) + 1
            self.decoders[sub_id] = (topic, DecoderFactory().decoder_for("protobuf", schema))
            subscriptions.append({"id": sub_id, "channelId": channel["id"]})
        self.socket.send(json.dumps({"op": "subscribe", "subscriptions": subscriptions}))

    def messages(self, seconds, until=None):
        """[(topic, log_time_ns, decoded)] received within `seconds`, or until until(list)."""
        out = []
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline and not (until and until(out)):
            try:
                frame = self.socket.recv(timeout=max(0.01, deadline - time.monotonic()))
            except TimeoutError:
                break
            message = self._handle(frame)
            if message is not None:
                out.append(message)
        return out

    def close(self):
        self._connection.__exit__(None, None, None)


def pose(utime, x_m, y_m, heading_rad):
    from slammtt_msgs import pose_t
    p = pose_t()
    p.utime, p.x_m, p.y_m, p.heading_rad = utime, x_m, y_m, heading_rad
    return p


def tracks(utime, track_id, x_m, y_m):
    from slammtt_msgs import track_t, tracks_t
    t = track_t()
    t.id, t.x_m, t.y_m, t.vx_mps, t.object_class, t.confirmed = track_id, x_m, y_m, 1.0, 1, True
    t.measured, t.reported = True, True
    t.covariance = [0.04 if i % 5 == 0 else 0.0 for i in range(16)]
    message = tracks_t()
    message.utime, message.tracks, message.num_tracks = utime, [t], 1
    return message


def test_live_channels_and_messages_from_lcm(netns):
    import lcm
    bridge = Bridge("--lcm-url", URL)
    client = None
    try:
        client = FoxgloveClient(bridge.port)
        assert client.server_info["name"].startswith("slammtt-foxglove")
        assert "time" in client.server_info["capabilities"]
        assert ALL_TOPICS <= set(client.channels)
        assert client.channels["/pose"]["schemaName"] == "foxglove.PoseInFrame"
        assert client.channels["/tracks"]["schemaName"] == "foxglove.SceneUpdate"
        assert client.channels["/laser_scan"]["schemaName"] == "foxglove.LaserScan"
        assert client.channels["/tf"]["schemaName"] == "foxglove.FrameTransforms"
        assert all(c["encoding"] == "protobuf" for c in client.channels.values())
        client.subscribe("/pose", "/tracks", "/tf")

        bus = lcm.LCM(URL)
        bus.publish("POSE", b"\x00not an lcm message")        # undecodable: counted
        bad = pose(1700000000000000, float("nan"), 0.0, 0.0)  # NaN: skipped
        bus.publish("POSE", bad.encode())
        received = []
        # A subscription reaches the server some time after it is sent: publish until the
        # client has heard both channels (each utime once, so each message is told apart).
        for k in range(200):
            utime = 1700000000000000 + (k + 1) * 100000
            bus.publish("POSE", pose(utime, 1.0 + k, 2.0, 0.5).encode())
            bus.publish("TRACKS", tracks(utime, 7, 3.0 + k, -1.0).encode())
            received += client.messages(0.05)
            topics = {t for t, _, _ in received}
            if {"/pose", "/tracks", "/tf"} <= topics:
                break
        poses = [(t, m) for topic, t, m in received if topic == "/pose"]
        assert poses, received
        for log_time, p in poses:
            k = (log_time // 1000 - 1700000000000000) // 100000 - 1
            assert p.frame_id == "map"
            assert (p.pose.position.x, p.pose.position.y) == (1.0 + k, 2.0)
            assert p.pose.orientation.z == pytest.approx(0.24740395925452294)   # sin(0.25)
        updates = [(t, m) for topic, t, m in received if topic == "/tracks"]
        assert updates
        log_time, update = updates[-1]
        k = (log_time // 1000 - 1700000000000000) // 100000 - 1
        entity = update.entities[0]
        assert entity.id == "track/7" and entity.frame_id == "map"
        assert entity.texts[0].text == "7 moving"
        assert entity.spheres[0].pose.position.x == 3.0 + k
        assert len(entity.lines[0].points) == 33         # the 2-sigma ellipse
        transforms = [m for topic, _, m in received if topic == "/tf"]
        frames = {(t.parent_frame_id, t.child_frame_id) for m in transforms
                  for t in m.transforms}
        assert ("map", "base_link") in frames
    finally:
        if client:
            client.close()
        status, err = bridge.stop()
    assert status == 0, err
    assert "1 undecodable, 1 with values that are not finite skipped" in err


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    return scenario_run(tmp_path_factory, "s1-crossing", 7)


def test_plays_a_log_in_the_mcap_schemas(netns, run):
    log = read_log(run.log)
    pose_by_utime = {p.utime: p for p in log["POSE"]}
    scan_by_utime = {s.utime: s for s in log["LASER_SCAN"]}
    bridge = Bridge(run.log, "--config", run.config, "--loop", "--speed", "20")
    client = None
    try:
        client = FoxgloveClient(bridge.port)
        client.subscribe("/pose", "/laser_scan", "/tf", "/map")
        received = client.messages(
            60, until=lambda out: len({t for t, _, _ in out}) == 4 and len(out) > 40)
    finally:
        if client:
            client.close()
        status, err = bridge.stop()
    assert status == 0, err
    assert {t for t, _, _ in received} == {"/pose", "/laser_scan", "/tf", "/map"}
    for topic, log_time, message in received:
        utime = log_time // 1000
        if topic == "/pose":
            p = pose_by_utime[utime]
            assert (message.pose.position.x, message.pose.position.y) == (p.x_m, p.y_m)
        elif topic == "/laser_scan":
            scan = scan_by_utime[utime]
            assert message.frame_id == "laser" and len(message.ranges) == scan.num_beams
        elif topic == "/tf":
            for t in message.transforms:
                if (t.parent_frame_id, t.child_frame_id) == ("base_link", "laser"):
                    assert t.translation.x == 0.1      # the mount of the configuration


def test_command_line(tmp_path):
    status, out, _ = run_module("slammtt.foxglove.bridge", "--help")
    assert status == 0 and "--lcm-url" in out and "--loop" in out
    status, out, _ = run_module("slammtt.foxglove.bridge", "--version")
    assert status == 0 and out.startswith("slammtt-foxglove 0.1.0")
    for args, expected in ((["--port", "70000"], 2), (["--speed", "2"], 2),
                           (["x.lcm", "--speed", "0"], 2), (["--bogus"], 2),
                           ([tmp_path / "absent.lcm"], 1)):
        status, _, err = run_module("slammtt.foxglove.bridge", *args)
        assert status == expected, err
        assert len(err.strip().splitlines()) == 1 and err.startswith("slammtt-foxglove: error:")
    launcher = BIN_DIR / "slammtt-foxglove"
    if launcher.exists():
        done = subprocess.run([str(launcher), "--version"], capture_output=True, text=True,
                              timeout=60)
        assert done.returncode == 0 and done.stdout.startswith("slammtt-foxglove "), done.stderr


def test_playback_wait_survives_a_due_time_passing_between_two_clock_reads(monkeypatch):
    """The wait before each log message read the clock twice (test, then slice length); when
    the due time passed in between, time.sleep got a negative length and the bridge died
    (ValueError, seen once in CI). A clock that jumps past the due time at every read is that
    race on every call."""
    from slammtt.foxglove import bridge

    readings = iter([0.0, 0.2, 0.4, 0.6])
    slept = []
    monkeypatch.setattr(bridge.time, "monotonic", lambda: next(readings))
    monkeypatch.setattr(bridge.time, "sleep", slept.append)

    class NoStop:
        requested = False

    bridge._sleep_until(0.1, NoStop())
    assert slept == [0.05]
    assert all(length >= 0 for length in slept)
