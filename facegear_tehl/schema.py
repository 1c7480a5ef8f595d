"""Reading YAML blocks with key-path error messages.

Every problem with a case file raises `CaseError(key_path, value, expected)`; the CLI prints its one-line
message and exits with code 2. Block readers use `Block`, which tracks which keys were read so that
unknown keys are reported with a "did you mean" hint.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
import dataclasses
import difflib
import math
import reprlib
from typing import Any


class CaseError(ValueError):
    """Invalid case input: names the key path, the offending value and what was expected."""

    def __init__(self, key: str, value: Any, expected: str):
        self.key = key
        self.value = value
        self.expected = expected
        shown = _SHORT.repr(value)  # bounded: a YAML alias can make a value too large to print in full
        if len(shown) > 60:
            shown = shown[:57] + "..."
        key = key if key.isprintable() else repr(key)  # one line: a key from the file may hold a newline
        super().__init__(f"{key}: got {shown}; expected {expected}")


_SHORT = reprlib.Repr()
_SHORT.maxlevel, _SHORT.maxlist, _SHORT.maxdict, _SHORT.maxstring, _SHORT.maxother = 3, 4, 4, 60, 60
_MISSING = object()


def _is_finite_number(value: Any) -> bool:
    """An int or float (not a bool) that is finite as a float (an int beyond 1.8e308 is not)."""
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        return False
    try:
        return math.isfinite(value)
    except OverflowError:
        return False


class Block:
    """A mapping from the case file at `path` ('' for the file's top level), read key by key.

    Call `finish()` after reading to reject keys that were not read (unknown keys).
    """

    def __init__(self, raw: Any, path: str):
        if not isinstance(raw, Mapping):
            raise CaseError(path or "(file)", raw, "a mapping of keys to values")
        for key in raw:
            if not isinstance(key, str):
                raise CaseError(f"{path}.{key}" if path else str(key), key, "string keys")
        self.raw = raw
        self.path = path
        self._known: set[str] = set()

    def key_path(self, key: str) -> str:
        return f"{self.path}.{key}" if self.path else key

    def has(self, key: str) -> bool:
        self._known.add(key)
        return key in self.raw and self.raw[key] is not None

    def get(self, key: str, default: Any = _MISSING) -> Any:
        self._known.add(key)
        if key not in self.raw or self.raw[key] is None:
            if default is _MISSING:
                raise CaseError(self.key_path(key), None, "this key to be present (it is required)")
            return default
        return self.raw[key]

    def number(
        self,
        key: str,
        default: Any = _MISSING,
        *,
        positive: bool = False,
        nonnegative: bool = False,
        low: float | None = None,
        high: float | None = None,
        open_low: bool = False,
        open_high: bool = False,
        unit: str = "",
    ) -> float:
        """A finite real number with optional bounds; `unit` only decorates the message."""
        value = self.get(key, default)
        if value is default and default is not _MISSING:
            return value
        suffix = f" in {unit}" if unit else ""
        if not _is_finite_number(value):
            raise CaseError(self.key_path(key), value, f"a finite number{suffix}")
        value = float(value)
        if positive and not value > 0.0:
            raise CaseError(self.key_path(key), value, f"a positive number{suffix}")
        if nonnegative and value < 0.0:
            raise CaseError(self.key_path(key), value, f"a number >= 0{suffix}")
        if low is not None and (value < low or (open_low and value == low)):
            rel = ">" if open_low else ">="
            raise CaseError(self.key_path(key), value, f"a number {rel} {low:g}{suffix}")
        if high is not None and (value > high or (open_high and value == high)):
            rel = "<" if open_high else "<="
            raise CaseError(self.key_path(key), value, f"a number {rel} {high:g}{suffix}")
        return value

    def integer(self, key: str, default: Any = _MISSING, *, low: int | None = None, high: int | None = None) -> int:
        value = self.get(key, default)
        if value is default and default is not _MISSING:
            return value
        if isinstance(value, bool) or not (
            isinstance(value, int) or (isinstance(value, float) and math.isfinite(value) and value.is_integer())
        ):
            raise CaseError(self.key_path(key), value, "an integer")
        value = int(value)
        if low is not None and value < low:
            raise CaseError(self.key_path(key), value, f"an integer >= {low}")
        if high is not None and value > high:
            raise CaseError(self.key_path(key), value, f"an integer <= {high}")
        return value

    def choice(self, key: str, options: Iterable[str], default: Any = _MISSING) -> str:
        options = tuple(options)
        value = self.get(key, default)
        if not isinstance(value, str) or value not in options:
            raise CaseError(self.key_path(key), value, "one of " + ", ".join(options))
        return value

    def string(self, key: str, default: Any = _MISSING) -> str:
        value = self.get(key, default)
        if not isinstance(value, str):
            raise CaseError(self.key_path(key), value, "a string")
        return value

    def interval(self, key: str, default: Any = _MISSING) -> tuple[float, float]:
        """A two-number list [low, high] with low < high."""
        value = self.get(key, default)
        if value is default and default is not _MISSING:
            return tuple(value)
        if (
            not isinstance(value, (list, tuple))
            or len(value) != 2
            or not all(_is_finite_number(v) for v in value)
        ):
            raise CaseError(self.key_path(key), value, "a list of two finite numbers [low, high]")
        low, high = float(value[0]), float(value[1])
        if not low < high:
            raise CaseError(self.key_path(key), value, "[low, high] with low < high")
        return low, high

    def block(self, key: str, default: Any = _MISSING) -> Block:
        value = self.get(key, default)
        return Block(value, self.key_path(key))

    def finish(self) -> None:
        """Reject keys that no reader asked for."""
        for key in self.raw:
            if key not in self._known:
                hint = difflib.get_close_matches(key, sorted(self._known), n=1)
                expected = f"no such key (did you mean '{hint[0]}'?)" if hint else (
                    "one of the known keys: " + ", ".join(sorted(self._known))
                )
                raise CaseError(self.key_path(key), self.raw[key], expected)


def check(condition: bool, key: str, value: Any, expected: str) -> None:
    """Raise CaseError unless `condition` holds (for cross-key checks)."""
    if not condition:
        raise CaseError(key, value, expected)


def defaults(cls: type) -> dict[str, Any]:
    """The default of each field of the dataclass `cls` that has one: the parsers' only source of defaults."""
    return {f.name: f.default for f in dataclasses.fields(cls) if f.default is not dataclasses.MISSING}
