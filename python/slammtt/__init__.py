"""slammtt's Python tools: the LCM types of lcmtypes/ (package slammtt_msgs, generated into the
venv by scripts/python-env.sh), a reader and writer of LCM logs (slammtt.lcmlog) and
slammtt-import (slammtt.importer)."""

__version__ = "0.1.0"  # the CMake project's version (tests/python/test_package.py checks)
