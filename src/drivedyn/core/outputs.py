"""Writing output files: by replacing, never through a link; names made safe for files and netCDF.

Every output file is written to a temporary file beside it and moved into place with
``os.replace``: a link planted at the target's name is replaced, not followed, and a reader (or a
second run) never sees half a file. A write that fails (permission, full disk, a folder in the
way) raises :class:`OutputError` naming the file, one line, and leaves no temporary file behind.

User names (pulleys, gears, study parameters, summary keys) are data: :func:`file_stem` and
:func:`nc_name` turn them into a file name or a netCDF variable name, long ones shortened with a
stable hash so that two long names stay distinct from one run to the next.
"""
from __future__ import annotations

import hashlib
import os
import re
import uuid
from pathlib import Path

from .errors import DrivedynError

#: longest file name stem written (most file systems allow 255 bytes per name)
MAX_STEM = 100
#: longest netCDF variable or dimension name written
MAX_NC_NAME = 200


class OutputError(DrivedynError, OSError):
    """A write into the output folder failed after the up-front check (one line, names the file)."""


def _hash(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()[:10]


def shorten(text: str, limit: int) -> str:
    """``text`` if it fits in ``limit`` characters, else its start, '~' and a stable hash."""
    if len(text) <= limit:
        return text
    return text[: limit - 11] + "~" + _hash(text)


#: longest unbroken word the terminal is given (names are data: the terminal library folds one
#: long word in a time that grows with the square of its length, 100 000 characters took 232 s)
MAX_WORD = 300


def shorten_words(text: str, limit: int = MAX_WORD) -> str:
    """``text`` with every run of characters without white space longer than ``limit`` shortened
    (:func:`shorten`: its start, '~' and a stable hash); the files written keep names whole."""
    if len(text) <= limit:
        return text
    return re.sub(r"\S{%d,}" % (limit + 1), lambda m: shorten(m.group(0), limit), text)


def file_stem(name: str, limit: int = MAX_STEM) -> str:
    """A file name stem for a user name: letters, digits, '.', '_', '-' kept, others as '_'."""
    safe = re.sub(r"[^A-Za-z0-9._-]", "_", name).strip(".") or "_"
    return shorten(safe, limit)


def nc_name(name: str) -> str:
    """A netCDF / HDF5 variable name for ``name``: '/' (a group separator) replaced, not too long."""
    safe = name.replace("/", "_")
    return shorten(safe, MAX_NC_NAME) if len(safe) > MAX_NC_NAME else safe


def _describe(exc: OSError) -> str:
    return exc.strerror or str(exc) or type(exc).__name__


def replace_write(path, write) -> Path:
    """Call ``write(tmp_path)`` for a temporary file beside ``path``, then move it onto ``path``.

    The move replaces whatever has that name (a file or a link; the link's target is untouched).
    Any OSError becomes an :class:`OutputError` naming ``path``.
    """
    path = Path(path)
    # the suffix stays last: writers that read the format from it (Pillow) still find it
    tmp = path.with_name(f".{path.stem[:60]}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp{path.suffix}")
    try:
        write(tmp)
        if path.is_dir() and not path.is_symlink():
            raise IsADirectoryError(21, "a folder is in the way")
        os.replace(tmp, path)
    except OSError as exc:
        try:
            tmp.unlink(missing_ok=True)
        except OSError:
            pass
        raise OutputError(f"{_shown(path)}: cannot write: {_describe(exc)}") from None
    except BaseException:
        try:
            tmp.unlink(missing_ok=True)
        except OSError:
            pass
        raise
    return path


def write_bytes(path, data: bytes) -> Path:
    def write(tmp):
        with open(tmp, "xb") as f:
            f.write(data)
    return replace_write(path, write)


def write_text(path, text: str) -> Path:
    return write_bytes(path, text.encode("utf-8"))


def check_folder(path, what: str = "the output folder") -> Path:
    """The up-front check of an output folder (``drivedyn run -o``, a study's, ``examples --to``): it
    is created (with its parents) and a file can be made in it, else an :class:`OutputError` of one
    line naming it and why. Every OSError counts, a name too long for the file system (ENAMETOOLONG:
    more than 255 bytes in one name) as much as a file in the way or a folder without permission."""
    path = Path(path)
    import tempfile

    try:
        if path.exists() and not path.is_dir():
            raise NotADirectoryError(20, "the path is a file, not a folder")
        path.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=path):
            pass
    except OSError as exc:
        raise OutputError(f"{_shown(path)}: cannot write {what} ({_describe(exc)})") from None
    return path


def _shown(path) -> str:
    """A path as a message shows it: whole, or, past 300 characters, its start and end."""
    text = str(path)
    return text if len(text) <= 300 else f"{text[:120]}...{text[-120:]} ({len(text)} characters)"


def make_folder(path) -> Path:
    """Create the folder ``path`` (and its parents); an OSError becomes an :class:`OutputError`."""
    path = Path(path)
    try:
        if path.exists() and not path.is_dir():
            raise NotADirectoryError(20, "a file is in the way")
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"{_shown(path)}: cannot create the folder: {_describe(exc)}") from None
    return path
