"""The temporary files beside a target that make writes atomic, and the removal of those a killed writer left
(docs/guarantees.md).

Every file is written to a hidden temporary file beside its target and renamed onto it when complete, so a crash
leaves the previous file. A writer killed with SIGKILL (or a machine lost) leaves that temporary file behind. Its
name carries the writer's pid, `.<target name>.<pid>-<random>.tmp`: the next write of the same target removes
every such file whose writer is no longer running, and leaves those of a live writer alone.
"""

from __future__ import annotations

import os
from pathlib import Path
import re
import secrets

_TEMPORARY = re.compile(r"\.(?P<name>.+)\.(?P<pid>\d+)-[0-9a-f]+\.tmp")


def temporary_beside(target: Path) -> Path:
    """A new temporary file name beside `target`, carrying this process's pid."""
    return target.with_name(f".{target.name}.{os.getpid()}-{secrets.token_hex(6)}.tmp")


def remove_stale(target: Path) -> list[Path]:
    """Remove the temporary files of `target` left by writers that no longer run; the files removed."""
    removed = []
    try:
        siblings = list(target.parent.glob(f".{target.name}.*.tmp"))
    except OSError:
        return removed
    for path in siblings:
        match = _TEMPORARY.fullmatch(path.name)
        if match and match["name"] == target.name and not _running(int(match["pid"])):
            path.unlink(missing_ok=True)
            removed.append(path)
    return removed


def _running(pid: int) -> bool:
    """A process with this pid exists (one of another user counts: its file is left alone)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True
    return True
