"""The imported messages as one LCM log: channels merged by utime, each in its source order.

Every event's log timestamp is its message's utime. The channels are merged by utime (ties:
ODOMETRY before LASER_GEOMETRY before LASER_SCAN before LEG_LABELS, so the odometry of a scan's
moment and the laser's geometry are there when the scan is processed, and a scan's labels
follow it); within a channel the order of the source
is kept, never sorted. A channel whose utimes go backwards or repeat is reported: the stack
drops a message that is not newer than the previous one of its stream (estimator
messages_out_of_order), and starts its estimation over on a step back of more than
time_jump_back_restart_s (2 s) - the importer does not hide that by reordering.
"""

import dataclasses
import heapq

from slammtt.lcmlog import LogWriter


@dataclasses.dataclass
class Stream:
    channel: str
    events: list = dataclasses.field(default_factory=list)   # (utime, message), source order

    def add(self, utime, message):
        self.events.append((int(utime), message))

    def order_report(self):
        """One line about utimes that go backwards or repeat, or ""."""
        backwards = repeats = 0
        first = ""
        for k in range(1, len(self.events)):
            previous, current = self.events[k - 1][0], self.events[k][0]
            if current > previous:
                continue
            if current == previous:
                repeats += 1
            else:
                backwards += 1
            if not first:
                first = (f"first at message {k}: utime {current} after {previous}")
        if backwards == 0 and repeats == 0:
            return ""
        return (f"{self.channel}: {backwards} utimes go backwards and {repeats} repeat ({first})"
                "; the stack drops a message not newer than the previous one of its channel, "
                "and the estimator starts over after a step back of more than 2 s")


def write_log(path, streams):
    """Writes the streams (in tie-break order) to `path`; returns (events, first, last utime)."""
    keyed = [[(utime, rank, index, message) for index, (utime, message) in enumerate(s.events)]
             for rank, s in enumerate(streams)]
    channels = [s.channel for s in streams]
    first = last = None
    with LogWriter(path) as writer:
        # heapq.merge takes each stream as it is: a stream that is not sorted stays in its
        # own order, and the merge is still deterministic.
        for utime, rank, _, message in heapq.merge(*keyed, key=lambda e: (e[0], e[1])):
            writer.write(utime, channels[rank], message)
            first = utime if first is None else first
            last = utime
        events = writer.events_written
    return events, first, last
