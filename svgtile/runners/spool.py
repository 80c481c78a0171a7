"""Finished pieces of an output, kept on disk until the file is put together in world order.

Units finish in any order, and an output's head (the motif count in a texture's metadata, the
failed-unit count and the symbols of a map) is known only when the last one has: so each
finished piece — a band's ``<use>`` lines, its GeoJSON features — is appended to a spool file
as it comes, and only its place in the spool is remembered.  The output is then written head
first, pieces in world order, straight from the spool: the writer holds one piece at a time,
never the whole map.
"""

from __future__ import annotations

import tempfile
from collections.abc import Hashable
from typing import BinaryIO

#: Bytes copied from the spool to the output at a time.
CHUNK = 1 << 20


class Spool:
    """Text pieces by key, in an anonymous temporary file (removed when closed).

    Use as a context manager; :meth:`put` a piece once per key, :meth:`copy` it out later.
    """

    def __init__(self, folder: str | None = None) -> None:
        self._file = tempfile.TemporaryFile(prefix="svgtile-spool-", dir=folder)
        self._where: dict[Hashable, tuple[int, int]] = {}
        self._end = 0

    def __enter__(self) -> Spool:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        self._file.close()

    def put(self, key: Hashable, text: str) -> None:
        """Keep ``text`` (UTF-8) under ``key``; an empty text is remembered without a write."""
        data = text.encode("utf-8")
        self._file.seek(self._end)
        self._file.write(data)
        self._where[key] = (self._end, len(data))
        self._end += len(data)

    def __contains__(self, key: Hashable) -> bool:
        return key in self._where

    def size(self, key: Hashable) -> int:
        """Bytes kept under ``key`` (0 for an empty piece or none)."""
        return self._where.get(key, (0, 0))[1]

    def copy(self, key: Hashable, out: BinaryIO) -> None:
        """Write the piece kept under ``key`` to ``out``, a chunk at a time."""
        start, left = self._where[key]
        self._file.seek(start)
        while left:
            chunk = self._file.read(min(CHUNK, left))
            out.write(chunk)
            left -= len(chunk)
