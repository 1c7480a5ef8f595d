"""The checks a result file passes before any of its data is read (results.read_result; docs/guarantees.md).

A result file may come from anyone: damaged on disk, edited by hand, or made to harm. Before reading data,
`check_layout` walks every link of the file and refuses (ResultFileError naming the file and the object):

- a soft or external link: a tehl result holds none, and following one would read another file's data, or loop;
  likewise a dataset whose data lie in an external raw file or that is a virtual dataset mapping other files;
- a dangling link, or an object nested deeper than the layout (results.py) nests groups;
- a dataset that is not numbers or text, has more than two dimensions, or declares more bytes than it stores can
  give: an unfiltered dataset must store at least what it declares (the rest would be fill values), a filtered
  one at most MAX_INFLATION times less; a 51 KB file declaring a 4 GB array is refused before 4 GB are allocated;
- in each group of scalars (the points, /contact, /sweep, /cycle), `units` that is not a JSON mapping of names to
  unit strings, or a scalar that is not a number; a root attribute that is not text where text belongs.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # h5py is imported where a file is read, as in results.py: `tehl validate` does not need it
    import h5py

MAX_INFLATION = 1032  # deflate's largest compression ratio, 1032:1 (zlib technical details, Adler): no filtered
# dataset of ours (shuffle + deflate) can hold more than this many bytes per byte stored
MAX_DEPTH = 2  # groups below the root: /points/<name>; /contact, /heat, /sweep, /cycle hold datasets only
# /points/<name>/solve, the solve record, and /points/<name>/accuracy, the accuracy target's record: groups of
# attributes alone, one level deeper
RECORDS = ("solve", "accuracy")
MAX_DIMENSIONS = 2  # fields (ny, nx) and vector columns (rows, components)
ROOT_TEXT = ("format_version", "tehl_version", "created", "case_name", "case_yaml", "status", "message",
             "warnings", "models", "overrides")
POINT_KINDS = ("axis", "field", "history", "scale")  # the `kind` attribute of a point's datasets
SCALAR_GROUPS = ("contact", "sweep", "cycle")  # table groups whose attributes hold scalars with `units`
_JSON_KINDS = {"warnings": list, "models": dict, "overrides": dict}


class ResultFileError(Exception):
    """A file that is not a readable tehl result (missing, not HDF5, other program, other format, damaged)."""


def check_layout(h5: h5py.File, path: Path) -> None:
    """ResultFileError unless every link, dataset and scalar attribute of the open file `h5` is as a result file
    of ours lays them out (module docstring); reads no dataset."""
    import h5py

    _check_root(h5, path)
    _walk(h5, "", 0, path)
    points = h5.get("points")
    if not isinstance(points, h5py.Group):
        raise _damaged(path, "/points", "a group of points")
    for name, group in points.items():
        if not isinstance(group, h5py.Group):
            raise _damaged(path, f"/points/{name}", "a group (one point)")
        _check_point(group, f"/points/{name}", path)
    for name in SCALAR_GROUPS:
        group = h5.get(name)
        if group is not None:
            if not isinstance(group, h5py.Group):
                raise _damaged(path, f"/{name}", "a group (a table)")
            _check_scalars(group, f"/{name}", path)


def _damaged(path: Path, where: str, expected: str) -> ResultFileError:
    return ResultFileError(f"{path}: damaged tehl result ({where}: expected {expected}); write it again with "
                           "tehl run")


def _check_root(h5: h5py.File, path: Path) -> None:
    for key in ROOT_TEXT:
        if not isinstance(h5.attrs.get(key), str):
            raise _damaged(path, f"/.{key}", "a text attribute")
    for key, kind in _JSON_KINDS.items():
        _check_json(h5.attrs, key, kind, "/", path)


def _check_json(attrs: Any, key: str, kind: type, where: str, path: Path) -> Any:
    """The JSON text attribute `key` parsed; ResultFileError unless it is text holding a `kind`."""
    text = attrs.get(key)
    try:
        value = json.loads(text) if isinstance(text, str) else None
    except ValueError:
        value = None
    if not isinstance(value, kind):
        raise _damaged(path, f"{where}.{key}", f"JSON text of a {kind.__name__}")
    return value


def _check_scalars(group: h5py.Group, where: str, path: Path) -> None:
    """`units` a JSON mapping of names to unit strings, each name an attribute holding one real number."""
    units = _check_json(group.attrs, "units", dict, where, path)
    for key, unit in units.items():
        value = group.attrs.get(key)
        number = isinstance(value, (int, float, np.integer, np.floating, np.bool_)) and np.ndim(value) == 0
        if not isinstance(unit, str) or not number:
            raise _damaged(path, f"{where}.{key}", "one real number with its unit")


def _check_point(group: h5py.Group, where: str, path: Path) -> None:
    """A point: its scalars, `models` a JSON mapping, and datasets of numbers, each of a known kind: axes 1-D,
    fields (ny, nx) over them."""
    _check_scalars(group, where, path)
    _check_json(group.attrs, "models", dict, where, path)
    if not isinstance(group.attrs.get("message"), str):
        raise _damaged(path, f"{where}.message", "a text attribute")
    shapes: dict[str, list[tuple[int, ...]]] = {kind: [] for kind in POINT_KINDS}
    for name, dataset in group.items():
        if name in RECORDS and not hasattr(dataset, "dtype"):  # a record (checked by the walk)
            continue
        kind = dataset.attrs.get("kind")
        if kind not in POINT_KINDS or dataset.dtype.kind not in "biuf":
            raise _damaged(path, f"{where}/{name}", f"numbers of a kind among {', '.join(POINT_KINDS)}")
        shapes[kind].append(dataset.shape)
    axes = {name: group[name].shape for name in ("x", "y") if name in group}
    grid = (axes.get("y", (0,))[0], axes.get("x", (0,))[0])
    if any(shape != grid for shape in shapes["field"]) or any(len(shape) != 1 for shape in shapes["axis"]):
        raise _damaged(path, where, f"fields of the shape (ny, nx) = {grid} of its axes x and y")


def _walk(group: h5py.Group, where: str, depth: int, path: Path) -> None:
    """Every link below `group`: hard links only, to groups no deeper than MAX_DEPTH and to sound datasets."""
    import h5py

    for name in group:
        link = group.get(name, getlink=True)
        at = f"{where}/{name}"
        if isinstance(link, (h5py.SoftLink, h5py.ExternalLink)):
            raise _damaged(path, at, "no soft or external link (a tehl result holds none; links are not followed)")
        item = group.get(name)
        if isinstance(item, h5py.Group) and depth == MAX_DEPTH and name in RECORDS:
            if len(item):
                raise _damaged(path, at, f"the {name} record holds attributes alone")
        elif isinstance(item, h5py.Group):
            if depth >= MAX_DEPTH:
                raise _damaged(path, at, f"groups at most {MAX_DEPTH} deep")
            _walk(item, at, depth + 1, path)
        elif isinstance(item, h5py.Dataset):
            _check_dataset(item, at, path)
        else:
            raise _damaged(path, at, "a group or a dataset")


def _check_dataset(dataset: h5py.Dataset, where: str, path: Path) -> None:
    """Numbers or text, at most MAX_DIMENSIONS dimensions, and no more bytes declared than stored (module)."""
    import h5py

    text = h5py.check_string_dtype(dataset.dtype) is not None
    if not text and dataset.dtype.kind not in "biuf":
        raise _damaged(path, where, f"numbers or text, not {dataset.dtype}")
    if dataset.ndim > MAX_DIMENSIONS:
        raise _damaged(path, where, f"at most {MAX_DIMENSIONS} dimensions, not {dataset.ndim}")
    layout = dataset.id.get_create_plist()
    if dataset.is_virtual or layout.get_external_count() > 0:
        raise _damaged(path, where, "data stored in this file (not in an external raw file, not a virtual dataset "
                                    "mapping other files)")
    declared = dataset.size * dataset.dtype.itemsize
    stored = dataset.id.get_storage_size()
    filtered = layout.get_nfilters() > 0
    if declared > stored * (MAX_INFLATION if filtered else 1):
        raise _damaged(path, where, f"the {declared} bytes it declares stored in the file (it stores {stored})")
