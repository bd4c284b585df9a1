"""What the Python programs' command lines share (slammtt-import, slammtt-export,
slammtt-foxglove): a parser whose mistakes are UsageError, and a main that turns every expected
failure into one line on stderr and an exit status, as the C++ processes do:

  2  UsageError (a bad command line, "(see --help)"), or one of `usage_errors` (a bad
     configuration);
  1  one of `input_errors` (a log, a bag, LCM or a port that cannot be used), or an OSError;
  130 interrupted (Ctrl-C).
"""

import argparse
import sys


class UsageError(Exception):
    """A bad command line (one line)."""


class Parser(argparse.ArgumentParser):
    """argparse, with its mistakes raised as UsageError instead of printed and exited on."""

    def error(self, message):
        raise UsageError(message)


def run_main(program, run, argv, usage_errors=(), input_errors=()):
    """run(argv) (sys.argv[1:] when argv is None): its status, or the failure's."""
    try:
        return run(sys.argv[1:] if argv is None else argv)
    except UsageError as error:
        print(f"{program}: error: {error} (see --help)", file=sys.stderr)
        return 2
    except tuple(usage_errors) as error:
        print(f"{program}: error: {error}", file=sys.stderr)
        return 2
    except tuple(input_errors) as error:
        print(f"{program}: error: {error}", file=sys.stderr)
        return 1
    except OSError as error:
        where = f"{error.filename}: " if error.filename else ""
        print(f"{program}: error: {where}{error.strerror or error}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"{program}: interrupted", file=sys.stderr)
        return 130
