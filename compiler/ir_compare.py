"""Structural comparison of IR modules that ignores where things were written.

Two programs mean the same when their IR is equal apart from source positions: `span` fields, and
the module's path. The formatter relies on this (it refuses to write a file whose IR would
change) and so do the formatter's property tests. The comparison returns the differences with a
path to each ("routines[1].blocks[0].ops[2].value.right"), which makes a failure readable.
"""

from __future__ import annotations

import dataclasses
from typing import Any

IGNORED_FIELDS = frozenset({"span", "path"})


def differences(a: Any, b: Any, where: str = "module", limit: int = 20) -> list[str]:
    """Where `a` and `b` differ, ignoring spans; empty when they are equivalent."""
    out: list[str] = []
    _compare(a, b, where, out, limit)
    return out


def equivalent(a: Any, b: Any) -> bool:
    return not differences(a, b, limit=1)


def _compare(a: Any, b: Any, where: str, out: list[str], limit: int) -> None:
    if len(out) >= limit:
        return
    if type(a) is not type(b):
        out.append(f"{where}: {type(a).__name__} != {type(b).__name__}")
        return
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        for f in dataclasses.fields(a):
            if f.name not in IGNORED_FIELDS:
                _compare(getattr(a, f.name), getattr(b, f.name), f"{where}.{f.name}", out, limit)
        return
    if isinstance(a, dict):
        if list(a) != list(b):
            out.append(f"{where}: keys {list(a)} != {list(b)}")
            return
        for key in a:
            _compare(a[key], b[key], f"{where}[{key!r}]", out, limit)
        return
    if isinstance(a, (list, tuple)):
        if len(a) != len(b):
            out.append(f"{where}: {len(a)} items != {len(b)} items")
        for i, (x, y) in enumerate(zip(a, b)):
            _compare(x, y, f"{where}[{i}]", out, limit)
        return
    if a != b:
        out.append(f"{where}: {a!r} != {b!r}")
