"""Reading YAML blocks with key-path error messages.

Every problem with a case file is a `CaseError(key_path, value, expected)`; the CLI prints its one-line
message and exits with code 2. Block readers use `Block`, which tracks which keys were read so that
unknown keys are reported with a "did you mean" hint (also when the key meant is a required one).

Inside `collecting(...)` (how `case.parse_case` reads a file) the readers record every problem instead of
raising at the first, and hand back a stand-in value so that reading goes on; `attempt(...)` parses one
block and stops it quietly where what follows would build on a bad value. At the end one `CaseErrors` names
them all, one line each. Outside, the first problem raises, as a plain `CaseError`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from contextvars import ContextVar
import dataclasses
import difflib
import math
import reprlib
from typing import Any, TypeVar

T = TypeVar("T")


class CaseError(ValueError):
    """Invalid case input: names the key path, the offending value and what was expected."""

    def __init__(self, key: str, value: Any, expected: str):
        self.key = key
        self.value = value
        self.expected = expected
        shown = _SHORT.repr(value)  # bounded: a YAML alias can make a value too large to print in full
        if len(shown) > 60:
            shown = shown[:57] + "..."
        # one line: a key from the file may hold a newline; only such a part of the path is quoted, so that the
        # message still starts with the block it belongs to (solver.domain.'\x01', not 'solver.domain.\x01')
        key = ".".join(part if part.isprintable() else repr(part) for part in key.split("."))
        super().__init__(f"{key}: got {shown}; expected {expected}")


class CaseErrors(CaseError):
    """Several problems of one case, one line each (key, value and expected of the first, for callers that
    look at one)."""

    def __init__(self, errors: list[CaseError]):
        first = errors[0]
        super().__init__(first.key, first.value, first.expected)
        self.errors = tuple(errors)
        self.args = ("\n".join(str(error) for error in errors),)


class _Abandon(CaseError):
    """Stops reading a block whose problems are already recorded (what follows would build on bad values)."""

    def __init__(self) -> None:
        super().__init__("", None, "")


class _Collector:
    """The problems and warnings found so far, and where the block being read started (`attempt`)."""

    def __init__(self) -> None:
        self.errors: list[CaseError] = []
        self.warnings: list[str] = []
        self.starts: list[int] = []

    def clean(self) -> bool:
        """No problem recorded since the innermost `attempt` began."""
        return len(self.errors) == (self.starts[-1] if self.starts else 0)


_COLLECTOR: ContextVar[_Collector | None] = ContextVar("case_collector", default=None)
_SHORT = reprlib.Repr()
_SHORT.maxlevel, _SHORT.maxlist, _SHORT.maxdict, _SHORT.maxstring, _SHORT.maxother = 3, 4, 4, 60, 60
_MISSING = object()


def collecting(parse: Callable[[], T]) -> tuple[T, tuple[str, ...]]:
    """`parse()` with every problem recorded; its result and the warnings, or CaseError (one problem) or
    CaseErrors (several, in the order found)."""
    collector = _Collector()
    token = _COLLECTOR.set(collector)
    try:
        result = attempt(parse)
    finally:
        _COLLECTOR.reset(token)
    if len(collector.errors) > 1:
        raise CaseErrors(collector.errors)
    if collector.errors:
        raise collector.errors[0]
    return result, tuple(collector.warnings)


def attempt(parse: Callable[[], T]) -> T | None:
    """`parse()` as one block of a case: None if it had problems (all recorded). A CaseError it raises is
    recorded unless the block already has one (then it is most likely a consequence); any other error is
    passed on unless the block already has a problem that explains it. Outside `collecting`: `parse()`."""
    collector = _COLLECTOR.get()
    if collector is None:
        return parse()
    collector.starts.append(len(collector.errors))
    try:
        return parse()
    except _Abandon:
        return None
    except CaseError as exc:
        if collector.clean():
            collector.errors.append(exc)
        return None
    except Exception:
        if collector.clean():
            raise
        return None
    finally:
        collector.starts.pop()


def warn(key: str, message: str) -> None:
    """A remark on a plausible-looking but suspicious value (printed as 'warning: <key>: <message>')."""
    collector = _COLLECTOR.get()
    if collector is not None:
        collector.warnings.append(f"{key}: {message}")


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
        self._missing: dict[str, CaseError] = {}  # required keys found missing, by key

    def key_path(self, key: str) -> str:
        return f"{self.path}.{key}" if self.path else key

    def has(self, key: str) -> bool:
        self._known.add(key)
        return key in self.raw and self.raw[key] is not None

    def get(self, key: str, default: Any = _MISSING) -> Any:
        self._known.add(key)
        if key not in self.raw or self.raw[key] is None:
            if default is _MISSING:
                error = CaseError(self.key_path(key), None, "this key to be present (it is required)")
                self._missing[key] = error
                raise error
            return default
        return self.raw[key]

    def _failed(self, error: CaseError, stand_in: Any) -> Any:
        """Raise `error`, or inside `collecting` record it and return `stand_in` so that reading goes on."""
        collector = _COLLECTOR.get()
        if collector is None:
            raise error
        collector.errors.append(error)
        return stand_in

    def _usual(self, key: str, value: float, usual: tuple[float, float] | None, unit: str, hint: str) -> None:
        """Warn when `value` lies outside the range `usual` of real contacts (a unit mistaken, most likely)."""
        if usual is not None and not usual[0] <= value <= usual[1]:
            warn(self.key_path(key), f"{value:g} {unit} is outside the usual {usual[0]:g} to {usual[1]:g} {unit}"
                 + (f"; {hint}" if hint else "; check its unit"))

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
        usual: tuple[float, float] | None = None,
        hint: str = "",
    ) -> float:
        """A finite real number with optional bounds; `unit` only decorates the message. Outside `usual` (the
        range real contacts take) it is accepted with a warning, `hint` saying what may be wrong."""
        try:
            value = self._number(key, default, positive, nonnegative, low, high, open_low, open_high, unit)
        except CaseError as error:
            return self._failed(error, math.nan if default is _MISSING else default)
        if value is not default:
            self._usual(key, value, usual, unit, hint)
        return value

    def _number(self, key: str, default: Any, positive: bool, nonnegative: bool, low: float | None,
                high: float | None, open_low: bool, open_high: bool, unit: str) -> float:
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
        try:
            return self._integer(key, default, low, high)
        except CaseError as error:
            return self._failed(error, 0 if default is _MISSING else default)

    def _integer(self, key: str, default: Any, low: int | None, high: int | None) -> int:
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
        try:
            value = self.get(key, default)
            if not isinstance(value, str) or value not in options:
                raise CaseError(self.key_path(key), value, "one of " + ", ".join(options))
        except CaseError as error:
            return self._failed(error, options[0] if default is _MISSING else default)
        return value

    def string(self, key: str, default: Any = _MISSING) -> str:
        try:
            value = self.get(key, default)
            if not isinstance(value, str):
                raise CaseError(self.key_path(key), value, "a string")
        except CaseError as error:
            return self._failed(error, "" if default is _MISSING else default)
        return value

    def interval(self, key: str, default: Any = _MISSING) -> tuple[float, float]:
        """A two-number list [low, high] with low < high."""
        try:
            return self._interval(key, default)
        except CaseError as error:
            return self._failed(error, (math.nan, math.nan) if default is _MISSING else tuple(default))

    def _interval(self, key: str, default: Any) -> tuple[float, float]:
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
        """The block under `key`; inside `collecting`, a missing or malformed block is recorded and ends the
        reading of the block that holds it (see `attempt`)."""
        try:
            return Block(self.get(key, default), self.key_path(key))
        except CaseError as error:
            self._failed(error, None)
            raise _Abandon() from None

    def finish(self) -> None:
        """Reject keys that no reader asked for. A misspelt required key is named as the unknown key with a
        "did you mean" (instead of the required one as missing). Inside `collecting`, every unknown key is
        recorded, and a block with a problem ends here."""
        collector = _COLLECTOR.get()
        for key in self.raw:
            if key in self._known:
                continue
            hint = difflib.get_close_matches(key, sorted(self._known), n=1)
            if hint and hint[0] in self._missing:
                expected = f"no such key (did you mean '{hint[0]}'? it is required and missing)"
            elif hint:
                expected = f"no such key (did you mean '{hint[0]}'?)"
            else:
                expected = "one of the known keys: " + ", ".join(sorted(self._known))
            error = CaseError(self.key_path(key), self.raw[key], expected)
            if collector is None:
                raise error
            missing = self._missing.pop(hint[0]) if hint and hint[0] in self._missing else None
            place = [i for i, recorded in enumerate(collector.errors) if recorded is missing]
            if place:  # named in place of the missing key's error
                collector.errors[place[0]] = error
            else:
                collector.errors.append(error)
        if collector is not None and not collector.clean():
            raise _Abandon()


def check(condition: bool, key: str, value: Any, expected: str) -> None:
    """Raise CaseError unless `condition` holds (for cross-key checks). Inside `collecting` it is recorded
    and reading goes on; skipped when the block already has a problem (its values may be stand-ins)."""
    if condition:
        return
    collector = _COLLECTOR.get()
    if collector is None:
        raise CaseError(key, value, expected)
    if collector.clean():
        collector.errors.append(CaseError(key, value, expected))


def defaults(cls: type) -> dict[str, Any]:
    """The default of each field of the dataclass `cls` that has one: the parsers' only source of defaults."""
    return {f.name: f.default for f in dataclasses.fields(cls) if f.default is not dataclasses.MISSING}
