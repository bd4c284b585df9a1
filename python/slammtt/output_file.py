"""Output files that are never written through a planted link (as runtime/output_file.h).

A tool writes its output under a partial name beside the final path and renames it into place
when it is complete. The partial name is created here exclusively and without following links
(O_CREAT | O_EXCL | O_NOFOLLOW, mode 0666 less the umask), "<path>.partial.<pid>.<n>" with the
first free n: a file or a link someone planted under that name, dangling or not, is never
opened, only skipped. The rename replaces a file or a link at the final path instead of writing
through it.
"""

import os

# Names tried before giving up (each taken one is a file or a link that is not ours).
MAX_TRIES = 1000


def create_partial(path):
    """Creates the partial file of `path`; returns (fd, partial_path). OSError naming `path` when
    no name is free or the directory cannot be written."""
    path = os.fspath(path)
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC
    for n in range(MAX_TRIES):
        partial = f"{path}.partial.{os.getpid()}.{n}"
        try:
            return os.open(partial, flags, 0o666), partial
        except FileExistsError:
            continue
    raise OSError(f"{path}: cannot create the output file: {MAX_TRIES} partial names taken")


def reopen_path(fd, partial):
    """A path that opens the very file `fd` refers to, for writers that take a path only (LCM's
    lcm.EventLog): /proc/self/fd/N where /proc is mounted, so that the name cannot be swapped
    under the writer; else the partial name itself."""
    proc = f"/proc/self/fd/{fd}"
    return proc if os.path.exists(proc) else partial


def write_text_atomically(path, text):
    """Writes `text` (UTF-8) to `path` through a partial file; nothing under `path` until it is
    whole, and the partial file removed on failure."""
    fd, partial = create_partial(path)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(partial, path)
    except BaseException:
        if os.path.lexists(partial):
            os.remove(partial)
        raise
