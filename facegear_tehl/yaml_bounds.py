"""A bound on what a YAML document expands to (docs/guarantees.md).

YAML aliases let a few hundred bytes name a billion values: nine lists of nine aliases of the list before
("billion laughs"). PyYAML builds such a document cheaply, sharing each list, but whatever walks it as a tree
(copying it, writing it out as text, hashing it) meets every value and runs for hours. A study file is copied and
written out once per variant, so before that `check_expansion` counts the values the document holds with its
aliases expanded, counting each shared list or mapping once per place it is named, in time proportional to the
distinct ones, and refuses a document above MAX_VALUES or holding itself.
"""

from __future__ import annotations

from typing import Any

from facegear_tehl.schema import CaseError

MAX_VALUES = 1_000_000  # values of an expanded study or base case: a study of 10^4 variants over a case of
# a few hundred keys stays far below; a billion-laughs document is a billion


def expanded_size(document: Any, limit: int = MAX_VALUES) -> int:
    """The values (scalars, lists, mappings, keys) of `document` with shared lists and mappings counted at every
    place; above `limit` (or for a document containing itself) a number above `limit` is returned."""
    sizes: dict[int, int] = {}
    pending: list[tuple[Any, bool]] = [(document, False)]
    while pending:  # depth first without recursion: a deep document must not overflow the stack
        value, children_done = pending.pop()
        if not isinstance(value, (list, dict)) or (id(value) in sizes and not children_done):
            continue
        children = [*value.keys(), *value.values()] if isinstance(value, dict) else value
        if not children_done:
            sizes[id(value)] = limit + 1  # in progress: met again below itself, it counts as too large
            pending.append((value, True))
            pending.extend((child, False) for child in children)
        else:
            sizes[id(value)] = min(limit + 1, 1 + sum(sizes.get(id(c), 1) if isinstance(c, (list, dict)) else 1
                                                        for c in children))
    return sizes.get(id(document), 1)


def check_expansion(document: Any, key: str, limit: int = MAX_VALUES) -> None:
    """CaseError under `key` when `document` expands to more than `limit` values (module docstring)."""
    if expanded_size(document, limit) > limit:
        raise CaseError(key, f"over {limit} values", f"a document of at most {limit} values with its aliases "
                                                     "expanded, none containing itself (aliases that repeat lists "
                                                     "within lists multiply them)")
