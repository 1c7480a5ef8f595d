"""A writable place for Numba's compiled kernels, or a temporary one with one warning (docs/guarantees.md).

The kernels are compiled with `cache=True`: Numba writes them to the first writable of $NUMBA_CACHE_DIR, the
`__pycache__` folder beside each kernel module, and the user's cache folder ($XDG_CACHE_HOME/numba, by default
~/.cache/numba), and raises `RuntimeError: cannot cache function` when a kernel module is imported and none is
writable (a read-only install run from a read-only home). `prepare` runs when the package is imported, before any
kernel module: when none of those places is writable it points $NUMBA_CACHE_DIR at a new temporary folder (removed
when this process ends; worker processes inherit it), so the run compiles its kernels once more (20-60 s) instead
of failing, and `WARNING` says so.
"""

from __future__ import annotations

import atexit
import os
from pathlib import Path
import shutil
import tempfile

KERNEL_PACKAGES = (Path(__file__).parent, Path(__file__).parent / "ehl")  # the folders of the @njit modules
WARNING: str | None = None
"""Set by `prepare` when it had to use a temporary cache: the one line a command prints as a warning."""


def writable(folder: Path) -> bool:
    """`folder` exists or can be made, and a file can be written in it (as Numba checks, for any user)."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        tempfile.TemporaryFile(dir=folder).close()
    except OSError:
        return False
    return True


def user_cache() -> Path:
    """Numba's user-wide cache folder on Linux: $XDG_CACHE_HOME/numba, else ~/.cache/numba."""
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "numba"


def prepare(packages: tuple[Path, ...] = KERNEL_PACKAGES) -> str | None:
    """Point $NUMBA_CACHE_DIR at a temporary folder when Numba has nowhere to write (module docstring); the
    warning (also kept in WARNING), or None when Numba has a writable cache."""
    global WARNING
    given = os.environ.get("NUMBA_CACHE_DIR")
    if (given and writable(Path(given))) or all(writable(p / "__pycache__") for p in packages) \
            or writable(user_cache()):
        return None
    folder = tempfile.mkdtemp(prefix="tehl-numba-")
    os.environ["NUMBA_CACHE_DIR"] = folder
    owner = os.getpid()
    atexit.register(lambda: os.getpid() == owner and shutil.rmtree(folder, ignore_errors=True))
    WARNING = (f"no writable Numba cache ({given or 'NUMBA_CACHE_DIR unset'}, the package's __pycache__, "
               f"{user_cache()}): the kernels are compiled for this run only (20-60 s) in {folder}; set "
               "NUMBA_CACHE_DIR to a writable folder to keep them")
    return WARNING
