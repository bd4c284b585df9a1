"""slammtt-foxglove: the stack's channels in Foxglove, live or from a log (docs/export.md,
"Live view"), over Foxglove's WebSocket protocol (the Foxglove SDK's server), in the schemas of
the MCAP export (slammtt.foxglove.convert: one conversion for both).

  slammtt-foxglove [options]          live: every channel of the stack from LCM
  slammtt-foxglove [options] LOG      plays a log at --speed times its pace (--loop: again)

Every topic of the conversion is advertised at start, so a viewer that connects first sees the
channels before any message. The server also sends the time of the latest message (Foxglove's
Time capability). It listens on --host (127.0.0.1: this machine only) and --port; the line
"serving ws://HOST:PORT" on stderr gives the port actually bound (--port 0: any free one).

Exit status: 0 stopped by SIGINT or SIGTERM, or the log played to its end (without --loop);
1 the log, LCM or the port cannot be used (one line); 2 a bad command line or configuration.
"""

import math
import os
import re
import signal
import sys
import time

import slammtt
from slammtt import msgs
from slammtt.cli import Parser, UsageError, run_main
from slammtt.lcmlog import LogError, LogReader
from slammtt.stackconfig import ConfigError, StackConfig

PROGRAM = "slammtt-foxglove"


def _parser():
    p = Parser(prog=PROGRAM, add_help=False, usage=f"{PROGRAM} [options] [LOG]",
                description="Serves the stack's channels to Foxglove over a WebSocket (open "
                            "ws://HOST:PORT in Foxglove): live from LCM, or from LOG, in the "
                            "schemas of slammtt-export --mcap.")
    p.add_argument("log", metavar="LOG", nargs="?", help="play this log instead of LCM")
    p.add_argument("--host", default="127.0.0.1",
                   help="address to listen on (default 127.0.0.1: this machine only)")
    p.add_argument("--port", type=int, default=8765,
                   help="port to listen on (default 8765; 0: any free port, printed)")
    p.add_argument("-c", "--config", metavar="FILE",
                   help="stack configuration: lcm.url, channels:, the laser mount "
                        "(estimator.sensor_forward_m / sensor_left_m; without them the "
                        "stream's LASER_GEOMETRY)")
    p.add_argument("--lcm-url", metavar="URL",
                   help="LCM URL (default: lcm.url of --config, $LCM_DEFAULT_URL, the stack's "
                        "udpm://239.255.76.67:7667?ttl=0)")
    p.add_argument("--channel", action="append", default=[], metavar="KEY=NAME",
                   help="rename a channel (as every process)")
    p.add_argument("--speed", type=float, default=1.0,
                   help="LOG: times the log's pace, in (0, 1000] (default 1)")
    p.add_argument("--loop", action="store_true", help="LOG: play it again from the start")
    p.add_argument("-q", "--quiet", action="store_true", help="only warnings and errors")
    p.add_argument("-h", "--help", action="help", help="show this help and exit")
    p.add_argument("--version", action="version", version=f"{PROGRAM} {slammtt.__version__}")
    return p


class _Stop:
    """Set by SIGINT or SIGTERM."""

    def __init__(self):
        self.requested = False
        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, self._handle)

    def _handle(self, *_):
        self.requested = True


class Bridge:
    """Converts messages of one stream and logs them to the server's channels."""

    def __init__(self, server, context, channels, mount, mount_from_log=False):
        from slammtt.foxglove.convert import ChannelSet, Converter
        self.server = server
        self.channels = channels
        self.mount = mount
        self.mount_from_log = mount_from_log
        self.topics = ChannelSet(context, eager=True)
        self._converter_class = Converter
        self.converter = Converter(channels, mount, mount_from_log=mount_from_log)
        self.undecodable = 0
        self.messages = 0

    def restart(self):
        """A new stream (the log again): transforms and anchoring from scratch."""
        self.converter = self._converter_class(self.channels, self.mount,
                                               mount_from_log=self.mount_from_log)

    def data(self, channel, data):
        if channel not in self.converter.key_of:
            return
        try:
            message = msgs.decode(data)
        except msgs.UndecodableMessage:
            self.undecodable += 1
            return
        self.message(channel, message)

    def message(self, channel, message):
        outputs = self.converter.convert(channel, message)
        for output in outputs:
            self.topics.log(output)
        if outputs:
            self.messages += 1
            self.server.broadcast_time(outputs[-1].log_time_ns)


def _sleep_until(due, stop):
    """Sleeps until monotonic time `due` or a stop request, in slices of at most 50 ms.

    The time left is read once per slice: reading the clock twice (once to test, once to
    compute the slice) can give a negative slice when `due` passes in between.
    """
    while not stop.requested:
        left = due - time.monotonic()
        if left <= 0:
            return
        time.sleep(min(0.05, left))


def _play(bridge, path, speed, loop, stop):
    while not stop.requested:
        reader = LogReader(path)
        start_wall = None
        first_us = None
        for event in reader.events():
            if stop.requested:
                return
            if first_us is None:
                first_us, start_wall = event.timestamp_us, time.monotonic()
            due = start_wall + (event.timestamp_us - first_us) * 1e-6 / speed
            _sleep_until(due, stop)
            bridge.data(event.channel, event.data)
        if reader.damage:
            print(f"{PROGRAM}: warning: {path}: {reader.damage}", file=sys.stderr)
        if not loop or first_us is None:
            return
        bridge.restart()


def _live(bridge, url, stop):
    import lcm
    try:
        bus = lcm.LCM(url)
    except (RuntimeError, OSError) as error:
        raise LogError(f"cannot open LCM at {url} ({error})") from None
    for name in bridge.channels.values():
        bus.subscribe(re.escape(name), bridge.data)
    while not stop.requested:
        try:
            bus.handle_timeout(100)
        except OSError:
            # LCM's select() interrupted by SIGINT/SIGTERM fails before the Python handler has
            # run: give it the moment to.
            time.sleep(0.05)
            if not stop.requested:
                raise


def run(argv):
    args = _parser().parse_args(argv)
    if not 0 <= args.port <= 65535:
        raise UsageError("--port must be in [0, 65535]")
    if not (math.isfinite(args.speed) and 0 < args.speed <= 1000):
        raise UsageError("--speed must be in (0, 1000]")
    if args.log is None and (args.loop or args.speed != 1.0):
        raise UsageError("--loop and --speed apply to a LOG")
    config = StackConfig(args.config)
    try:
        channels = config.channels(args.channel)
    except ValueError as error:
        raise UsageError(str(error)) from None
    mount = config.mount()
    url = args.lcm_url or config.lcm_url()
    if args.log is not None and not os.path.isfile(args.log):
        raise LogError(f"{args.log}: no such file")

    import foxglove
    from foxglove.websocket import Capability
    context = foxglove.Context()
    try:
        server = foxglove.start_server(name=f"{PROGRAM} {slammtt.__version__}", host=args.host,
                                       port=args.port, context=context,
                                       capabilities=[Capability.Time])
    except Exception as error:   # the SDK raises its own error type for a port in use
        raise LogError(f"cannot listen on {args.host}:{args.port} ({error})") from None
    stop = _Stop()
    bridge = Bridge(server, context, channels, mount, mount_from_log=not config.mount_given())
    source = f"playing {args.log}" if args.log is not None else f"live from LCM {url}"
    print(f"{PROGRAM}: serving ws://{args.host}:{server.port} ({source})", file=sys.stderr,
          flush=True)
    try:
        if args.log is not None:
            _play(bridge, args.log, args.speed, args.loop, stop)
        else:
            _live(bridge, url, stop)
    finally:
        server.stop()
    if not args.quiet:
        skipped = sum(bridge.converter.skipped.values())
        print(f"{PROGRAM}: served {bridge.messages} messages ({bridge.undecodable} undecodable, "
              f"{skipped} with values that are not finite skipped)", file=sys.stderr)
    return 0


def main(argv=None):
    return run_main(PROGRAM, run, argv, usage_errors=(ConfigError,), input_errors=(LogError,))


if __name__ == "__main__":
    sys.exit(main())
