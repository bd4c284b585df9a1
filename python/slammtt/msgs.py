"""The project's LCM message types (lcmtypes/*.lcm) for Python, and a decoder that finds a
message's type from its fingerprint.

The classes are generated into the venv as package `slammtt_msgs` by scripts/python-env.sh
(lcm-gen of PyPI's lcm package). Every encoded LCM message starts with its type's 8-byte
fingerprint (LCM type specification), so a log can be decoded without knowing which type each
channel carries.
"""

import io
import struct

try:
    import slammtt_msgs
except ImportError as error:  # pragma: no cover - only without the venv step
    raise ImportError(
        "the Python LCM types (slammtt_msgs) are not generated: run scripts/python-env.sh"
    ) from error

# Every type of lcmtypes/, by name: slammtt_msgs.laser_scan_t, ...
TYPES = {
    name: getattr(slammtt_msgs, name)
    for name in sorted(dir(slammtt_msgs))
    if name.endswith("_t") and hasattr(getattr(slammtt_msgs, name), "_get_packed_fingerprint")
}

BY_FINGERPRINT = {cls._get_packed_fingerprint(): cls for cls in TYPES.values()}

# What the generated decoders raise on bytes that are not a whole message of their type.
_DECODE_ERRORS = (ValueError, struct.error, IndexError, TypeError, OverflowError,
                  UnicodeDecodeError, MemoryError)


class UndecodableMessage(ValueError):
    """The bytes are not exactly one message of a known slammtt_msgs type (one line why)."""


def decode(data):
    """The message encoded in `data` (bytes), of the type its fingerprint names.

    Raises UndecodableMessage when the fingerprint is unknown, the bytes end inside the message,
    bytes follow it, or an array count is negative or larger than the bytes can hold. The
    generated decoders allocate only what the bytes hold (struct checks the size first).
    """
    data = bytes(data)
    if len(data) < 8:
        raise UndecodableMessage(f"{len(data)} bytes: shorter than a type fingerprint")
    cls = BY_FINGERPRINT.get(data[:8])
    if cls is None:
        raise UndecodableMessage(f"unknown type fingerprint 0x{data[:8].hex()}")
    buffer = io.BytesIO(data)
    try:
        message = cls.decode(buffer)
    except _DECODE_ERRORS as error:
        raise UndecodableMessage(f"not a whole {cls.__name__} ({error})") from None
    if buffer.tell() != len(data):
        raise UndecodableMessage(
            f"{len(data) - buffer.tell()} bytes after a whole {cls.__name__}")
    problem = _count_problem(message)
    if problem:
        raise UndecodableMessage(f"not a whole {cls.__name__} ({problem})")
    return message


def _count_problem(message):
    """A negative array count decodes as an empty array (range() of it is empty): say so."""
    for field, dimensions in zip(message.__slots__, message.__dimensions__):
        value = getattr(message, field)
        for dimension in dimensions or ():
            count = getattr(message, dimension) if isinstance(dimension, str) else dimension
            if count < 0 or len(value) != count:
                return f"{field}: count {count}, {len(value)} elements"
        elements = value if dimensions else [value]
        for element in elements:
            if hasattr(element, "__dimensions__"):
                problem = _count_problem(element)
                if problem:
                    return problem
    return ""
