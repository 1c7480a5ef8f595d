"""One `tehl study` at a time in a study folder (docs/guarantees.md).

Two studies run on one folder would both compute every unfinished variant and write the same files and index. The
study holds an exclusive advisory lock (flock(2)) on LOCK_FILE in its folder while it computes and writes; a
second study on the folder is refused with the pid of the first. The kernel drops the lock when its holder ends,
however it ends (SIGKILL too), so no lock outlives its study; the file itself stays, empty of meaning.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
import fcntl
import os
from pathlib import Path

from facegear_tehl.schema import CaseError

LOCK_FILE = ".tehl-study.lock"


@contextmanager
def exclusive(folder: Path, key: str) -> Iterator[None]:
    """Hold the folder's lock for the block; CaseError under `key` if another process holds it."""
    descriptor = os.open(folder / LOCK_FILE, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        try:
            fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.pread(descriptor, 32, 0).decode("ascii", "replace").strip() or "another process"
            raise CaseError(key, str(folder), f"a folder no other tehl study is running in (pid {holder} is; wait "
                                              "for it to end, or choose another folder)") from None
        os.ftruncate(descriptor, 0)
        os.pwrite(descriptor, f"{os.getpid()}\n".encode(), 0)
        yield
    finally:
        os.close(descriptor)
