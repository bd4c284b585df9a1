"""An MCAP file of a log in Foxglove's schemas (slammtt.foxglove.convert), written by the
Foxglove SDK's MCAP writer (protobuf messages, zstd chunks, with the summary, statistics and
message indexes a viewer seeks with). Written to a partial file (slammtt.output_file: created
exclusively, never through a planted link) and renamed to FILE when whole."""

import os

import foxglove

import slammtt
from slammtt.foxglove.convert import ChannelSet, Converter
from slammtt.lcmlog import LogReader
from slammtt.output_file import create_partial


def write_mcap(log_path, path, channels, mount):
    """Converts every message of the log, in log order; returns (ChannelSet, Converter,
    LogReader) for the counts."""
    path = os.fspath(path)
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    fd, partial = create_partial(path)
    context = foxglove.Context()
    converter = Converter(channels, mount)
    reader = LogReader(log_path)
    try:
        with os.fdopen(fd, "w+b") as out, \
                foxglove.open_mcap(out, context=context) as writer:
            topics = ChannelSet(context)
            for channel, _, message in reader:
                for output in converter.convert(channel, message):
                    topics.log(output)
            writer.write_metadata("slammtt", {
                "log": os.path.basename(os.fspath(log_path)),
                "exporter": f"slammtt-export {slammtt.__version__}",
                "laser_mount_forward_m": repr(converter.mount.x_m),
                "laser_mount_left_m": repr(converter.mount.y_m),
            })
    except BaseException:
        if os.path.lexists(partial):
            os.remove(partial)
        raise
    os.replace(partial, path)
    return topics, converter, reader
