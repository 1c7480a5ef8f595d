"""The unit of a case key as the commented case templates state it (`tehl init`: the comment after each key), for
axis labels of figures over case keys (study maps)."""

from __future__ import annotations

from functools import cache
import re

from facegear_tehl.templates import case_template

# The unit words the template comments open with; a comment opening with anything else (a symbol like N1, a
# sentence) gives no unit.
UNITS = ("m", "m/s", "N", "N m", "rpm", "deg", "degC", "K", "Pa", "Pa s", "1/Pa", "1/K", "kg/m^3", "W/(m K)",
         "J/(kg K)", "mm^2/s")


@cache
def _template_lines() -> tuple[str, ...]:
    return tuple(line for kind in ("gear", "contact") for line in case_template(kind, "case.yaml").splitlines())


def key_unit(dotted: str) -> str | None:
    """The unit of the case key `dotted` (e.g. gear.pinion_torque -> 'N m'), None when the templates state none."""
    leaf = dotted.rsplit(".", 1)[-1]
    pattern = re.compile(rf"^\s*#?\s*{re.escape(leaf)}:[^#]*#\s*(\S+)(?: (\S+))?")
    for line in _template_lines():
        match = pattern.match(line)
        if match:
            first, second = (word.rstrip(",;") for word in match.groups(""))
            for candidate in (f"{first} {second}", first):  # 'N m', 'Pa s', 'W/(m K)' before 'm', 'Pa'
                if candidate in UNITS:
                    return candidate
    return None


def key_label(dotted: str) -> str:
    """'pinion torque (N m)' for gear.pinion_torque; the key's words alone when it has no unit."""
    unit = key_unit(dotted)
    words = dotted.rsplit(".", 1)[-1].replace("_", " ")
    return f"{words} ({unit})" if unit else words
