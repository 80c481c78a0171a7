"""Writing output files: one atomic writer for every SVG, GeoJSON, PNG and JSON svgtile makes.

Beside :mod:`svgtile.errors` because, like it, it serves every stage's boundary (the commands,
the map fill, the previews, the Inkscape installer) and no stage of the pipeline: ``svg/writer``
makes XML text, this module puts text or bytes on disk.
"""

from __future__ import annotations

import contextlib
import os
import stat
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import BinaryIO

from svgtile.errors import OutputError


def check_output(out: str | Path, *, protect: tuple[str | Path, ...] = ()) -> None:
    """Raise :class:`OutputError` unless ``out`` can be written (``-`` always can).

    ``out`` must not be any path in ``protect`` (under any spelling, symlink or hard link), must
    not be a folder, and its folder must exist.  Call it before the work to fail early;
    :func:`write_file` calls it again.
    """
    if str(out) == "-":
        return
    out = Path(out)
    for p in protect:
        if same_file(out, Path(p)):
            raise OutputError("refusing to overwrite an input file", source=str(out))
    if out.is_dir():
        raise OutputError("is a folder; give a file name", source=str(out))
    folder = out.parent
    if not folder.is_dir():
        problem = "is a file, not a folder" if folder.exists() else "does not exist"
        raise OutputError(f"folder {str(folder)!r} {problem}", source=str(out))


def write_file(data: str | bytes, out: str | Path, *, protect: tuple[str | Path, ...] = ()) -> None:
    """Write ``data`` to ``out`` atomically (``-`` is standard output).

    Parameters
    ----------
    data : str (written as UTF-8 with its ``\\n`` line ends untouched) or bytes (a PNG …)
    out : the file, or ``-`` for standard output
    protect : paths that must not be overwritten (the inputs), under any spelling

    The data goes to a temporary file in the target folder that is flushed to disk and renamed
    into place, so a failure (or an interrupt) never leaves half a file, and a file that was
    there stays untouched; the temporary file is removed on any failure.  A symbolic link is
    written through (the file it points to is replaced); a device or FIFO (``/dev/null``, a named
    pipe) is written into directly, never replaced.  A new file gets the usual permissions
    (``0o666`` less the umask); a replaced file keeps its permissions.

    Raises
    ------
    OutputError
        The path is protected or unusable, or writing failed (disk full, no permission …).
    """
    raw = data.encode("utf-8") if isinstance(data, str) else bytes(data)
    if str(out) == "-":
        _write_stdout(data, raw)
        return
    check_output(out, protect=protect)
    out = Path(out)
    try:
        special = not stat.S_ISREG(os.stat(out).st_mode)  # follows symlinks
    except OSError:  # no such file (yet)
        special = False
    if special:  # a device (/dev/null) or a FIFO: a rename would replace it with a regular file
        try:
            with open(out, "wb") as fh:
                fh.write(raw)
        except OSError as exc:
            raise OutputError(f"cannot write ({exc.strerror or exc})", source=str(out)) from None
        return
    if out.is_symlink():  # replace the file the link points to, not the link
        out = Path(os.path.realpath(out))
    mode = _file_mode(out)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{out.name}.", suffix=".tmp", dir=out.parent)
    except OSError as exc:
        raise OutputError(f"cannot write here ({exc.strerror or exc})", source=str(out)) from None
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(raw)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, mode)
        os.replace(tmp, out)
    except OSError as exc:
        Path(tmp).unlink(missing_ok=True)
        raise OutputError(f"cannot write ({exc.strerror or exc})", source=str(out)) from None
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def same_file(a: str | Path, b: str | Path) -> bool:
    """Do ``a`` and ``b`` name one file (``./d/../x.svg`` and ``x.svg``, symlinks, hard links)?"""
    if Path(a).resolve() == Path(b).resolve():
        return True
    try:
        return os.path.samefile(a, b)
    except OSError:  # one of them does not exist
        return False


def _write_stdout(data: str | bytes, raw: bytes) -> None:
    stream = sys.stdout
    binary = getattr(stream, "buffer", None)
    if binary is None:  # a text-only stream (an embedding application's)
        if not isinstance(data, str):
            raise OutputError("standard output takes text only here", source="-")
        stream.write(data)
    else:  # bytes, so the document is the same as the file on every platform
        stream.flush()
        view = memoryview(raw)
        while view:  # a pipe whose reader left may take part and report success
            written = binary.write(view)
            if not written:
                raise OutputError("standard output takes no more data", source="-")
            view = view[written:]
        binary.flush()
    stream.flush()


def _file_mode(out: Path) -> int:
    """Permissions for the file written at ``out`` (mkstemp's are ``0o600``)."""
    try:
        return stat.S_IMODE(os.stat(out).st_mode)
    except OSError:
        umask = os.umask(0o022)
        os.umask(umask)
        return 0o666 & ~umask


@contextlib.contextmanager
def atomic_output(out: str | Path, *, protect: tuple[str | Path, ...] = ()) -> Iterator[BinaryIO]:
    """A binary file to write ``out`` piece by piece, put in place only if the block succeeds.

    The streaming counterpart of :func:`write_file`, with its guarantees: the pieces go to a
    temporary file in the target folder, flushed to disk and renamed into place when the block
    ends; on any failure (or an interrupt) the temporary file is removed and a file that was at
    ``out`` stays untouched.  ``-`` is standard output, written as the pieces come.

    Raises
    ------
    OutputError
        The path is protected or unusable, or writing failed.
    """
    if str(out) == "-":
        stream = sys.stdout
        yield getattr(stream, "buffer", stream)
        stream.flush()
        return
    check_output(out, protect=protect)
    out = Path(out)
    try:
        special = not stat.S_ISREG(os.stat(out).st_mode)
    except OSError:
        special = False
    if special:  # a device or FIFO is written into, never replaced (as write_file does)
        try:
            with open(out, "wb") as fh:
                yield fh
        except OSError as exc:
            raise OutputError(f"cannot write ({exc.strerror or exc})", source=str(out)) from None
        return
    if out.is_symlink():  # replace the file the link points to, not the link
        out = Path(os.path.realpath(out))
    mode = _file_mode(out)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{out.name}.", suffix=".tmp", dir=out.parent)
    except OSError as exc:
        raise OutputError(f"cannot write here ({exc.strerror or exc})", source=str(out)) from None
    try:
        with os.fdopen(fd, "wb") as fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, mode)
        os.replace(tmp, out)
    except OSError as exc:
        Path(tmp).unlink(missing_ok=True)
        raise OutputError(f"cannot write ({exc.strerror or exc})", source=str(out)) from None
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
