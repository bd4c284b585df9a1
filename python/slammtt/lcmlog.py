"""Reading and writing LCM log files.

LCM's log file format (LCM documentation, "LCM Log File Format"): each event is a 28-byte
header - sync word 0xEDA1DA01, int64 event number, int64 timestamp [us], int32 channel length,
int32 data length, all big-endian - then the channel name and the data. The reader walks that
layout itself, so that it can say exactly where a log is damaged (as tools/replay/log_scan.h
does for the C++ tools); logs are written by LCM's own writer (lcm.EventLog).

Damage, as the C++ tools classify it:
- truncated tail: the file ends inside its last event (a logger killed mid-write). Every
  complete event is read; `LogReader.damage` says where, and with strict=True it is an error;
- corrupt: a bad sync word or impossible lengths while more bytes follow. Every event before it
  is read, then LogError is raised with one line saying where.

An event whose data is not a whole message of a known type is skipped and counted
(`LogReader.undecodable`, per channel), never raised.
"""

import collections
import os
import struct

import lcm

from slammtt import msgs
from slammtt.output_file import create_partial, reopen_path

SYNC_WORD = 0xEDA1DA01
HEADER = struct.Struct(">IqqII")
# LCM refuses channel names of 1000 bytes or more when it reads a log (lcm eventlog.c).
MAX_CHANNEL_BYTES = 1000

Event = collections.namedtuple("Event", "number timestamp_us channel data")
Message = collections.namedtuple("Message", "channel utime message")
Message.__doc__ = ("One decoded event: its channel, the event's timestamp [us] (the moment it "
                   "was logged; the message's own utime is message.utime) and the message.")


class LogError(Exception):
    """A log that cannot be read on: one line, with the path and the byte offset."""


class LogReader:
    """The events of an LCM log, in file order.

    for event in LogReader(path).events(): raw Event(number, timestamp_us, channel, data)
    for m in LogReader(path): decoded Message(channel, utime, message), undecodable events
    skipped and counted in .undecodable ({channel: count}) with the first reason in
    .first_undecodable.
    After iterating: .events_read, .damage ("" or one line), .truncated (bool).
    """

    def __init__(self, path, strict=False):
        self.path = os.fspath(path)
        self.strict = strict
        self.events_read = 0
        self.damage = ""
        self.truncated = False
        self.undecodable = collections.Counter()
        self.first_undecodable = ""

    def __iter__(self):
        for event in self.events():
            try:
                message = msgs.decode(event.data)
            except msgs.UndecodableMessage as error:
                if not self.undecodable:
                    self.first_undecodable = f"event {event.number} on {event.channel}: {error}"
                self.undecodable[event.channel] += 1
                continue
            yield Message(event.channel, event.timestamp_us, message)

    def events(self):
        try:
            with open(self.path, "rb") as log:
                log.seek(0, os.SEEK_END)
                size = log.tell()
                log.seek(0)
                yield from self._walk(log, size)
        except OSError as error:
            raise LogError(f"{self.path}: cannot read log file ({error.strerror})") from None

    def _walk(self, log, size):
        offset = 0
        while offset < size:
            header = log.read(HEADER.size)
            sync = header[:4]
            if sync != struct.pack(">I", SYNC_WORD)[:len(sync)]:
                self._fail(offset, "bad sync word")
            if len(header) < HEADER.size:
                self._truncated(offset, f"{len(header)} of at least {HEADER.size} header "
                                        "bytes present")
                return
            _, number, timestamp, channel_bytes, data_bytes = HEADER.unpack(header)
            if not 0 < channel_bytes < MAX_CHANNEL_BYTES or data_bytes >= 2**31:
                self._fail(offset, f"channel length {_int32(channel_bytes)}, data length "
                                   f"{_int32(data_bytes)}")
            event_bytes = HEADER.size + channel_bytes + data_bytes
            if offset + event_bytes > size:
                follower = _next_event_header(log, offset + 4, size)
                if follower >= 0:
                    self._fail(offset, f"it runs {offset + event_bytes - size} bytes past the "
                                       f"end, but an event follows at byte {follower}")
                self._truncated(offset, f"{size - offset} of {event_bytes} bytes present")
                return
            channel = log.read(channel_bytes).decode("utf-8", "replace")
            data = log.read(data_bytes)
            self.events_read += 1
            offset += event_bytes
            yield Event(number, timestamp, channel, data)

    def _fail(self, offset, why):
        self.damage = f"corrupt event header at byte {offset} ({why})"
        raise LogError(f"{self.path}: {self.damage}; read the {self.events_read} events "
                       "before it")

    def _truncated(self, offset, why):
        self.truncated = True
        self.damage = f"truncated final event at byte {offset} ({why})"
        if self.strict:
            raise LogError(f"{self.path}: {self.damage}")


def _int32(value):
    return value - 2**32 if value >= 2**31 else value


def _next_event_header(log, start, size):
    """Offset of the first plausible whole event header at or after `start`, or -1: tells a
    truncated tail (nothing follows) from a damaged length field (events follow)."""
    log.seek(start)
    rest = log.read()
    sync = struct.pack(">I", SYNC_WORD)
    at = rest.find(sync)
    while 0 <= at <= len(rest) - HEADER.size:
        _, _, _, channel_bytes, data_bytes = HEADER.unpack_from(rest, at)
        if (0 < channel_bytes < MAX_CHANNEL_BYTES and data_bytes < 2**31 and
                start + at + HEADER.size + channel_bytes + data_bytes <= size):
            return start + at
        at = rest.find(sync, at + 1)
    return -1


class LogWriter:
    """Writes an LCM log with LCM's own writer, to a partial file (slammtt.output_file: created
    exclusively, never through a planted link), renamed to PATH by close(): a failure leaves no
    half log behind (as slammtt-replay's writer). Use as a context manager; an exception inside
    the block removes the partial file."""

    def __init__(self, path):
        self.path = os.fspath(path)
        fd, self.partial = create_partial(self.path)
        self.events_written = 0
        try:
            self._log = lcm.EventLog(reopen_path(fd, self.partial), "w", overwrite=True)
        except BaseException:
            os.remove(self.partial)
            raise
        finally:
            os.close(fd)

    def write(self, utime, channel, message):
        """One event at timestamp `utime` [us] holding `message` (a slammtt_msgs object or
        bytes)."""
        data = message if isinstance(message, (bytes, bytearray)) else message.encode()
        self._log.write_event(int(utime), channel, bytes(data))
        self.events_written += 1

    def close(self):
        self._log.close()
        os.replace(self.partial, self.path)

    def abort(self):
        self._log.close()
        if os.path.lexists(self.partial):
            os.remove(self.partial)

    def __enter__(self):
        return self

    def __exit__(self, kind, value, traceback):
        if kind is None:
            self.close()
        else:
            self.abort()
        return False
