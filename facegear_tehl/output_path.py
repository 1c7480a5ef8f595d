"""Where a command may write: one policy for every command that writes a file (docs/guarantees.md).

A command's output path is checked before anything is solved or written (CaseError under the option or case key
that named it, exit 2, no file):

- never one of the command's input files (the same resolved path, or the same file by device and inode, as a
  hard link or a symbolic link to it is), whatever --force says;
- never an existing file that this program did not write, unless --force: an HDF5 file is ours when its root
  carries the attribute filetype = results.FILETYPE; a CSV or other text file when `ours` says so;
- never a directory, a device, a FIFO or a socket (the result is renamed onto its path, which would replace a
  device node such as /dev/null with a file), and only under a writable directory;
- a case's `output.file` is resolved against the case file's folder and must stay inside it (no `..` or absolute
  path that leads elsewhere): a case received from someone else cannot write over files outside its own folder;
- `tehl run` never replaces a result file with one holding fewer converged points (a run that lost points to a
  killed worker or a failed solve): its result goes beside it, named by the time, with a warning.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from datetime import datetime
import os
from pathlib import Path

from facegear_tehl.results import FILETYPE, ResultFileError, read_result
from facegear_tehl.schema import CaseError

HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"  # the HDF5 format signature at offset 0 (HDF5 File Format Specification 3.0)

Ownership = Callable[[Path], bool]
"""Whether an existing file at a path is one this program wrote (and may therefore replace)."""


def is_result_file(path: Path) -> bool:
    """An HDF5 file whose root attribute `filetype` is ours (results.FILETYPE); False for anything else, including
    a file that cannot be read."""
    import h5py  # only a command that writes over an existing file needs it

    try:
        with open(path, "rb") as stream:
            if stream.read(len(HDF5_SIGNATURE)) != HDF5_SIGNATURE:
                return False
        with h5py.File(path, "r") as h5:
            return h5.attrs.get("filetype") == FILETYPE
    except (OSError, ValueError, KeyError):
        return False


def starts_with(header: str) -> Ownership:
    """A text file is ours when its first line starts with `header` (a CSV this program writes)."""

    def ours(path: Path) -> bool:
        try:
            with open(path, encoding="utf-8") as stream:
                return stream.readline().startswith(header)
        except (OSError, UnicodeDecodeError):
            return False

    return ours


def same_file(a: Path, b: Path) -> bool:
    """`a` and `b` are one file: the same resolved path, or the same device and inode (hard or symbolic links)."""
    if a.resolve() == b.resolve():
        return True
    try:
        return os.path.samefile(a, b)
    except OSError:  # one of them does not exist: then they are not one file
        return False


def checked_output(key: str, target: Path, *, inputs: Sequence[Path] = (), force: bool = False,
                   ours: Ownership = is_result_file, what: str = "a tehl result") -> Path:
    """`target` if a command may write it (module docstring); CaseError under `key` otherwise."""
    writable_location(key, target)
    if target.exists() and not target.is_file():  # a device, a FIFO, a socket: renaming onto it would replace it
        raise CaseError(key, str(target), "a regular file path (this is a device, FIFO or socket; not even --force "
                                          "writes over it)")
    for source in inputs:
        if same_file(target, source):
            raise CaseError(key, str(target), f"a path other than the input {source} (it would be overwritten)")
    if (target.exists() or target.is_symlink()) and not force and not ours(target):
        raise CaseError(key, str(target), f"a new file or {what} file to replace (this file was not written by "
                                          "tehl; --force overwrites it)")
    return target


def writable_location(key: str, target: Path) -> Path:
    """`target`, unless it is a directory or its nearest existing folder is not a writable directory (CaseError)."""
    if target.is_dir():
        raise CaseError(key, str(target), "a file path, not a directory")
    folder = target.absolute().parent
    while not folder.exists():
        folder = folder.parent
    if not folder.is_dir() or not os.access(folder, os.W_OK):
        raise CaseError(key, str(target), f"a path under a writable directory ({folder} is not)")
    return target


def inside_case_folder(key: str, case_file: Path, value: str) -> Path:
    """A case's output path `value`, resolved against the case file's folder; CaseError under `key` if it leads out
    of that folder."""
    folder = case_file.parent.resolve()
    target = (folder / value).resolve()
    if not target.is_relative_to(folder):
        raise CaseError(key, value, f"a path inside the case's folder {folder} (a case may not write elsewhere; "
                                    "give -o to write there)")
    return case_file.parent / value


def converged_points(path: Path) -> int:
    """Converged points of the result file at `path`; 0 when there is none or it cannot be read."""
    try:
        return sum(point.converged for point in read_result(path, fields=False).points.values())
    except ResultFileError:
        return 0


def keeping_the_better(target: Path, converged: int) -> tuple[Path, str]:
    """Where a result with `converged` converged points goes: `target`, unless the result file there holds more
    converged points (an earlier, better run); then a new file beside it, named by the time, and a sentence
    saying so. A worse run never replaces a better file."""
    kept = converged_points(target) if target.exists() else 0
    if kept <= converged:
        return target, ""
    stamp = datetime.now().strftime("%Y%m%dT%H%M%S")
    beside = target.with_name(f"{target.stem}.{stamp}{target.suffix}")
    counter = 1
    while beside.exists():
        beside = target.with_name(f"{target.stem}.{stamp}-{counter}{target.suffix}")
        counter += 1
    return beside, (f"{target} holds {kept} converged points and this run {converged}: kept it, and wrote this run's "
                    f"result to {beside}")
