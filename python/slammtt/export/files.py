"""Writing export files through slammtt.output_file: a partial file created exclusively (never
through a link planted at its name), renamed to PATH once whole, so that a failure never leaves
half a file under the final name (as slammtt-replay's and slammtt-import's writers)."""

import csv
import io
import os

from slammtt.output_file import write_text_atomically


def write_text(path, text):
    """`text` into `path`, creating its folder."""
    path = os.fspath(path)
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    write_text_atomically(path, text)


def write_csv(path, header, rows):
    """A CSV file: the header row, then the rows (numbers written as Python's repr, which reads
    back to the same double)."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(header)
    for row in rows:
        writer.writerow([number_text(v) for v in row])
    write_text(path, out.getvalue())


def number_text(value):
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def seconds_text(utime):
    """A utime [us] as exact decimal seconds: 1234567 -> '1.234567'."""
    sign = "-" if utime < 0 else ""
    utime = abs(utime)
    return f"{sign}{utime // 1000000}.{utime % 1000000:06d}"
