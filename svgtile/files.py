"""Writing output files: one atomic writer for every SVG, GeoJSON, PNG and JSON svgtile makes.

Beside :mod:`svgtile.errors` because, like it, it serves every stage's boundary (the commands,
the map fill, the previews, the Inkscape installer) and no stage of the pipeline: ``svg/writer``
makes XML text, this module puts text or bytes on disk.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import sys
import tempfile
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import BinaryIO

from svgtile.errors import OutputError, SvgtileError

#: The most bytes svgtile reads from one input file (an exemplar, map, tile, styles file …);
#: a larger file is refused before it is read.  Textures read back by ``score`` may be larger
#: (:data:`MAX_TEXTURE_BYTES`): two million motifs make some 180 MB of SVG.
MAX_INPUT_BYTES = 64 * 2**20
MAX_TEXTURE_BYTES = 512 * 2**20
#: Temporary files are named ``.NAME.svgtile-PID-XXXXXXXX.tmp`` so that the next write of NAME can
#: sweep those a killed process (SIGKILL, a power cut) left behind.
TMP_TAG = ".svgtile-"


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
    if out.is_symlink():
        try:
            os.stat(out)
        except OSError as exc:
            if exc.errno == errno.ELOOP:  # written through, the loop would be replaced by a file
                raise OutputError("is a symbolic link that loops; give another name", source=str(out)) from None
    folder = out.parent
    if not folder.is_dir():
        problem = "is a file, not a folder" if folder.exists() else "does not exist"
        raise OutputError(f"folder {str(folder)!r} {problem}", source=str(out))


def read_input(path: str | Path, *, error: type[SvgtileError] = SvgtileError,
               limit: int = MAX_INPUT_BYTES) -> bytes:
    """The bytes of the input file ``path``, read with a bound.

    A named pipe, a device (``/dev/zero``) or a socket is refused instead of read (a pipe with no
    writer would block for ever, a device never ends), and so is a file over ``limit`` bytes, so
    that no input makes svgtile run away before it has looked at it.

    Raises
    ------
    error
        (an :class:`SvgtileError` subclass, the caller's) naming the file: it cannot be read,
        is not a regular file, or is too large.
    """
    source = str(path)
    try:
        st = os.stat(path)
    except OSError as exc:
        raise error(f"cannot read file ({exc.strerror or exc})", source=source) from None
    if stat.S_ISDIR(st.st_mode):
        raise error("is a folder, not a file", source=source)
    if not stat.S_ISREG(st.st_mode):
        raise error(f"is {_kind_of(st.st_mode)}, not a regular file; svgtile reads files only", source=source)
    if st.st_size > limit:
        raise error(f"is {st.st_size / 2**20:,.0f} MB, more than svgtile reads ({limit / 2**20:,.0f} MB)",
                    source=source)  # fmt: skip
    try:
        with open(path, "rb") as fh:
            data = fh.read(limit + 1)  # the file may have grown since the stat
    except OSError as exc:
        raise error(f"cannot read file ({exc.strerror or exc})", source=source) from None
    if len(data) > limit:
        raise error(f"is more than svgtile reads ({limit / 2**20:,.0f} MB)", source=source)
    if data[:2] == b"\x1f\x8b":
        raise error("is gzip-compressed (an .svgz?); decompress it first: gunzip -c FILE.svgz > FILE.svg",
                    source=source)  # fmt: skip
    return data


def _kind_of(mode: int) -> str:
    for test, name in ((stat.S_ISFIFO, "a named pipe"), (stat.S_ISCHR, "a device"), (stat.S_ISBLK, "a device"),
                       (stat.S_ISSOCK, "a socket")):  # fmt: skip
        if test(mode):
            return name
    return "not a regular file"


def check_paths(inputs: Iterable[str | Path | tuple[str | Path, str]], outputs: Iterable[str | Path]) -> None:
    """Raise :class:`OutputError` if any output is one of the inputs (under any spelling).

    Every command calls it, through :mod:`svgtile.cli.main`, with every path it reads and every
    file it will write, before it reads or writes anything: ``-o map.svg`` with
    ``--region map.svg#qal`` must not replace the user's map with a texture.  ``-`` (standard
    output) never clashes.

    Parameters
    ----------
    inputs : paths, or (path, what) pairs where ``what`` names the input in the message
        (``"the exemplar"``, ``"--region map.svg#qal"``)
    outputs : the files the command will write
    """
    ins = [(Path(p[0]), p[1]) if isinstance(p, tuple) else (Path(p), "an input file") for p in inputs]
    for out in outputs:
        if str(out) == "-":
            continue
        for p, what in ins:
            if str(p) != "-" and same_file(out, p):
                raise OutputError(f"refusing to overwrite {what}; choose another output name", source=str(out))


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
    with atomic_output(out, protect=protect) as fh:
        fh.write(raw)


def sweep_temporary(out: str | Path) -> list[Path]:
    """Remove the temporary files of ``out`` that a killed svgtile left (its process is gone).

    A signal svgtile can catch (SIGINT, SIGTERM) removes its temporary file on the way out
    (:func:`write_file`); only SIGKILL or a crash leave one, and the next write of the same
    file sweeps it.  Returns the files removed.
    """
    out = Path(out)
    removed = []
    try:
        leftovers = list(out.parent.glob(f".{_glob_escape(out.name)}{TMP_TAG}*-*.tmp"))
    except OSError:
        return removed
    for tmp in leftovers:
        pid_text = tmp.name[len(f".{out.name}{TMP_TAG}"):].split("-", 1)[0]
        if not pid_text.isdigit() or _alive(int(pid_text)):
            continue
        try:
            tmp.unlink()
            removed.append(tmp)
        except OSError:
            pass
    return removed


def _glob_escape(name: str) -> str:
    return "".join(f"[{c}]" if c in "*?[" else c for c in name)


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # another user's process
        return True
    return True


def same_file(a: str | Path, b: str | Path) -> bool:
    """Do ``a`` and ``b`` name one file (``./d/../x.svg`` and ``x.svg``, symlinks, hard links)?"""
    try:
        if Path(a).resolve() == Path(b).resolve():
            return True
    except (OSError, RuntimeError):  # a symlink loop (RuntimeError before Python 3.13)
        pass
    try:
        return os.path.samefile(a, b)
    except (OSError, ValueError):  # one of them does not exist (or loops)
        return False


def _write_stdout(data: str | bytes, raw: bytes) -> None:
    """Write to standard output; a closed or full one is an :class:`OutputError`, a reader that
    left (EPIPE) is :class:`BrokenPipeError`, which the CLI ends quietly."""
    stream = sys.stdout
    if stream is None:  # started with standard output closed (``>&-``)
        raise OutputError("standard output is closed", source="-")
    try:
        _write_stream(stream, data, raw)
    except BrokenPipeError:
        raise
    except (OSError, ValueError) as exc:  # ENOSPC (``>/dev/full``), EBADF, a closed file object
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        _discard(stream)
        raise OutputError(f"cannot write to standard output ({reason})", source="-") from None


def _discard(stream) -> None:
    """Point ``stream``'s descriptor at the null device, so that the data still buffered is not
    flushed again at exit (a second, Python-worded error after svgtile's one line)."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(devnull, stream.fileno())
        finally:
            os.close(devnull)
    except (OSError, AttributeError, ValueError):
        pass


def _write_stream(stream, data: str | bytes, raw: bytes) -> None:
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
    sweep_temporary(out)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{out.name}{TMP_TAG}{os.getpid()}-", suffix=".tmp", dir=out.parent)
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
