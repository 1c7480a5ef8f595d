"""Study file (YAML) -> validated, frozen `Study`: a base case and the variants that vary its keys.

    base: ../cases/facegear_110.yaml        # a case file, relative to the study file
    vary:                                   # case keys by dotted path; the study is their product
      gear.pinion_torque: [250, 500, 750]
      gear.pinion_speed: [1500, 3000]
    set: {solver.thermal: "off"}            # optional: the same value in every variant

Each variant is the base case's YAML mapping with the `set` values, then its `vary` values, put at their paths
(missing blocks are created), its `output` block removed (a variant's file is named by its values) and its `name`
written out (the base's name, else the base file's stem). That mapping, dumped as YAML, is the variant's
*resolved case*: `tehl run` of that text solves the same case, and the UTF-8 bytes of that text are hashed
(SHA-256): a finished file is the variant's when it holds that text. Every variant is validated through the case
schema here, before anything runs; every problem raises `CaseError` naming the study key (`vary.<path>`,
`set.<path>`), the value and what was expected, with the variant when one variant's case is invalid.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
import copy
from dataclasses import dataclass
import hashlib
import itertools
from pathlib import Path
import re
from typing import Any

import yaml

from facegear_tehl.case import Case, _Loader, parse_case, read_input
from facegear_tehl.schema import Block, CaseError, check
from facegear_tehl.yaml_bounds import check_expansion

# Variants a study may make: each is validated here (about 20 ms for a face gear case: 1000 variants of
# cases/facegear_110.yaml in 20 s) and solved later (seconds to minutes each): 10^4 variants are minutes to validate
# and a day or more of solving; a larger product of `vary` lists is a typing slip or a study to split.
MAX_VARIANTS = 10_000
HASH_DIGITS = 16  # hex digits of the SHA-256 kept in a file name: 64 bits, no collision among 1e9 variants
NAME_LENGTH = 200  # characters of a variant's file name before '.h5': below the 255 of common file systems
RESERVED_BLOCK = "output"  # not a study key: each variant's file is named by its values


class _Dumper(yaml.SafeDumper):
    """Writes resolved cases; quotes every string the case loader would read as a number (its YAML 1.2 floats,
    e.g. '1e-3'), so that the text reads back to the same mapping."""

    yaml_implicit_resolvers = _Loader.yaml_implicit_resolvers


@dataclass(frozen=True)
class Variant:
    """One case of a study: its varied values (path -> value, in the study's order), its resolved case text,
    the case parsed from that text and the SHA-256 of the text's UTF-8 bytes (hex)."""

    index: int
    values: tuple[tuple[str, Any], ...]
    text: str
    case: Case
    digest: str

    @property
    def file_name(self) -> str:
        """The variant's result file in the study folder, named by its varied values:
        'pinion_torque=250_pinion_speed=1500.h5' (each key by its last name, or its whole path when two varied keys
        share it); characters other than letters, digits, '.', '=', '-' become '_', and when that changes a value,
        or the name would pass NAME_LENGTH, the first HASH_DIGITS hex digits of the digest follow (two variants
        never share a name)."""
        leaves = [path.rsplit(".", 1)[-1] for path, _ in self.values]
        parts = [f"{leaf if leaves.count(leaf) == 1 else path}={value_text(value)}"
                 for leaf, (path, value) in zip(leaves, self.values)]
        name = "_".join(re.sub(r"[^\w.=-]", "_", part) for part in parts)
        lossy = any(re.search(r"[^\w.=-]", part) for part in parts) or len(name) > NAME_LENGTH
        return f"{name[:NAME_LENGTH]}_{self.digest[:HASH_DIGITS]}.h5" if lossy else f"{name}.h5"

    @property
    def label(self) -> str:
        """'gear.pinion_torque=250, gear.pinion_speed=1500'."""
        return ", ".join(f"{path}={value_text(value)}" for path, value in self.values)


@dataclass(frozen=True)
class Study:
    """A validated study file: the varied paths and their values, and every variant in product order (the last
    varied key changes fastest)."""

    path: Path
    base: Path
    vary: tuple[tuple[str, tuple[Any, ...]], ...]
    fixed: tuple[tuple[str, Any], ...]
    variants: tuple[Variant, ...]

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(path for path, _ in self.vary)


def value_text(value: Any) -> str:
    """A varied value as one line of YAML flow text ('250', 'off', '[-4.5, 1.5]')."""
    return yaml.dump(value, Dumper=_Dumper, default_flow_style=True, width=10**6).strip().removesuffix("...").strip()


def resolved_text(mapping: Mapping[str, Any]) -> str:
    """The YAML text of a resolved case (block style, keys in their order)."""
    return yaml.dump(dict(mapping), Dumper=_Dumper, sort_keys=False, allow_unicode=True, width=120)


def digest(text: str) -> str:
    """SHA-256 (hex) of the UTF-8 bytes of a resolved case's text: what a finished result file is checked by."""
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def load_study(path: str | Path, announce: Callable[[int], None] | None = None,
               fixed: tuple[tuple[str, Any], ...] = ()) -> Study:
    """Read and validate a study file and every variant it makes (CaseError on any problem, nothing run);
    `announce` is told the number of variants before they are validated; `fixed`: (path, value) pairs of the
    command line set in every variant over the file's `set:` (`tehl study --accuracy`)."""
    path = Path(path)
    return parse_study(read_input(path, "study file"), path, announce, fixed)


def parse_study(text: str, path: Path, announce: Callable[[int], None] | None = None,
                overrides: tuple[tuple[str, Any], ...] = ()) -> Study:
    """Parse and validate the YAML text of the study file at `path` (base is relative to its folder); at most
    MAX_VARIANTS variants, their number told to `announce` before they are validated; `overrides` replace the
    `set:` values of their paths."""
    top = Block(_yaml(text, "(file)", "a study: base:, vary:, optional set:"), "")
    base_path = path.parent / top.string("base")
    base_text = _read_base(base_path)
    base = _yaml(base_text, "base", "a case file")
    check(isinstance(base, dict), "base", str(base_path), "a case file (a mapping of case keys)")
    vary_block = top.block("vary")
    vary = tuple((key, _values(key, vary_block.get(key))) for key in vary_block.raw)
    check(bool(vary), "vary", {}, "at least one case key with a list of values, e.g. gear.pinion_torque: [250, 500]")
    set_raw = top.get("set", {})
    check(isinstance(set_raw, dict), "set", set_raw, "a mapping of case keys to values")
    replaced = {key for key, _ in overrides}
    fixed = tuple((str(key), value) for key, value in set_raw.items() if str(key) not in replaced) + overrides
    top.finish()
    paths = [("vary", key) for key, _ in vary] + [("set", key) for key, _ in fixed]
    _check_paths(paths)
    count = _count(vary)
    check(count <= MAX_VARIANTS, "vary", f"{count} variants", f"at most {MAX_VARIANTS} variants (the product of the "
                                                              "lengths of the vary lists): split the study")
    if announce is not None:
        announce(count)
    base = {key: value for key, value in base.items() if key != RESERVED_BLOCK}
    base.setdefault("name", base_path.stem)
    base = {"name": base.pop("name"), **base}
    variants = []
    for index, values in enumerate(itertools.product(*(values for _, values in vary))):
        chosen = tuple(zip((key for key, _ in vary), values))
        variants.append(_variant(index, base, fixed, chosen, count))
    return Study(path=path, base=base_path, vary=vary, fixed=fixed, variants=tuple(variants))


def _count(vary: tuple[tuple[str, tuple[Any, ...]], ...]) -> int:
    count = 1
    for _, values in vary:
        count *= len(values)
    return count


def _yaml(text: str, key: str, expected: str) -> Any:
    """The YAML document of `text`, read like a case file; CaseError under `key` if it is not YAML or empty."""
    try:
        raw = yaml.load(text, Loader=_Loader)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "unknown position"
        raise CaseError(key, f"YAML syntax error at {where}", "valid YAML") from None
    except (ValueError, RecursionError):
        raise CaseError(key, "a value YAML cannot read", "valid YAML") from None
    if raw is None:
        raise CaseError(key, "an empty document", expected)
    check_expansion(raw, key)  # an alias bomb: refused before it is copied and written out per variant
    return raw


def _read_base(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except OSError as exc:
        raise CaseError("base", str(path), f"a readable case file relative to the study file ({exc.strerror})") \
            from None
    except UnicodeDecodeError:
        raise CaseError("base", str(path), "a UTF-8 case file") from None


def _values(key: str, raw: Any) -> tuple[Any, ...]:
    """The values of one varied key: a non-empty list of distinct values."""
    where = f"vary.{key}"
    check(isinstance(raw, list) and len(raw) > 0, where, raw, "a non-empty list of values, e.g. [250, 500, 750]")
    # a number by its value (1 and 1.0 make one case), anything else by its text
    shown = [float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else value_text(value)
             for value in raw]
    repeated = next((value for value, text in zip(raw, shown) if shown.count(text) > 1), None)
    check(len(set(shown)) == len(shown), where, repeated, "distinct values (a value given twice makes one variant "
                                                          "twice)")
    return tuple(raw)


def _check_paths(paths: list[tuple[str, str]]) -> None:
    """Each study path: dotted case keys, not under `output`, none given twice or inside another."""
    for section, path in paths:
        parts = path.split(".")
        check(all(part.strip() == part and part for part in parts), f"{section}.{path}", path,
              "a dotted path of case keys, e.g. gear.pinion_torque")
        check(parts[0] != RESERVED_BLOCK, f"{section}.{path}", path,
              "a case key outside output (each variant's file is named by its values)")
    for (section, path), (other_section, other) in itertools.combinations(paths, 2):
        nested = path == other or other.startswith(path + ".") or path.startswith(other + ".")
        check(not nested, f"{other_section}.{other}", other,
              f"a path not given twice nor inside another ({section}.{path})")


def _put(mapping: dict[str, Any], section: str, path: str, value: Any) -> None:
    """mapping[a][b][c] = value for path 'a.b.c', creating missing blocks; CaseError when the path crosses a
    value that is not a block."""
    node = mapping
    parts = path.split(".")
    for depth, part in enumerate(parts[:-1]):
        child = node.get(part)
        if child is None:
            child = node[part] = {}
        check(isinstance(child, dict), f"{section}.{path}", value,
              f"a path through blocks of the case ({'.'.join(parts[:depth + 1])} is {value_text(child)}, "
              "not a block)")
        node = child
    node[parts[-1]] = copy.deepcopy(value)


def _variant(index: int, base: dict[str, Any], fixed: tuple[tuple[str, Any], ...],
             chosen: tuple[tuple[str, Any], ...], count: int) -> Variant:
    """Variant `index`: the base with the fixed then the chosen values, validated through the case schema."""
    mapping = copy.deepcopy(base)
    for section, pairs in (("set", fixed), ("vary", chosen)):
        for path, value in pairs:
            _put(mapping, section, path, value)
    text = resolved_text(mapping)
    if yaml.load(text, Loader=_Loader) != mapping:  # the dump must read back to the same case
        raise CaseError("vary", ", ".join(f"{p}={value_text(v)}" for p, v in chosen),
                        "values that YAML writes and reads back unchanged")
    try:
        case = parse_case(text, name=str(mapping["name"]))
    except CaseError as exc:
        raise _study_error(exc, fixed, chosen, index, count) from None
    return Variant(index=index, values=chosen, text=text, case=case, digest=digest(text))


def _study_error(exc: CaseError, fixed: tuple[tuple[str, Any], ...], chosen: tuple[tuple[str, Any], ...],
                 index: int, count: int) -> CaseError:
    """A variant's case error under the study key that set it (`vary.<path>`, `set.<path>`), or under the case
    key if it comes from the base file; the variant is named either way."""
    key = exc.key
    for section, pairs in (("vary", chosen), ("set", fixed)):
        if any(key == path or key.startswith(path + ".") for path, _ in pairs):
            key = f"{section}.{key}"
            break
    else:
        if key != "(file)":
            key = f"base: {key}"
    label = ", ".join(f"{path}={value_text(value)}" for path, value in chosen)
    return CaseError(key, exc.value, f"{exc.expected} (variant {index + 1} of {count}: {label})")
