"""Generic loading of the dialect catalogs (`compiler/catalogs/<dialect>.toml`).

The catalog is the one table of every command of a dialect. This module reads the keys all
dialects share (see compiler/catalogs/README.md) and keeps the dialect's own keys in `extra`;
each frontend wraps the entries with the accessors it needs.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

from mcc.compiler import toml

CATALOG_DIR = Path(__file__).parent / "catalogs"
COMMON_KEYS = {"name", "title", "kind", "summary", "syntax", "unit", "range", "default",
               "products", "manual", "notes"}


@dataclass(frozen=True, eq=False)
class Entry:
    name: str
    title: str
    kind: str
    summary: str = ""
    syntax: tuple[str, ...] = ()
    unit: str = ""
    range: tuple[Any, Any] | None = None
    default: Any = None
    products: Any = None
    manual: str = ""
    notes: str = ""
    extra: dict = field(default_factory=dict, compare=False, hash=False)

    def get(self, key: str, default: Any = None) -> Any:
        return self.extra.get(key, default)

    def describe(self) -> str:
        """Hover / explain text."""
        lines = [f"{self.name} — {self.title} ({self.kind})", self.summary]
        if self.syntax:
            lines.append("syntax: " + "; ".join(self.syntax))
        if self.range:
            lines.append(f"range: {self.range[0]} … {self.range[1]}" + (f" {self.unit}" if self.unit else ""))
        elif self.unit:
            lines.append(f"unit: {self.unit}")
        if self.default is not None:
            lines.append(f"default: {self.default}")
        if self.manual:
            lines.append(f"manual: {self.manual}")
        if self.notes:
            lines.append(f"note: {self.notes}")
        return "\n".join(line for line in lines if line)


@dataclass(frozen=True)
class Catalog:
    dialect: str
    entries: tuple[Entry, ...]
    data: dict = field(compare=False, hash=False, default_factory=dict)

    def table(self, key: str) -> dict:
        """A top-level table of the catalog file ([products], [limits], ...)."""
        return self.data.get(key, {})


def entry_from_dict(raw: dict) -> Entry:
    rng = raw.get("range")
    return Entry(
        name=str(raw["name"]),
        title=raw.get("title", ""),
        kind=raw.get("kind", ""),
        summary=raw.get("summary", ""),
        syntax=tuple(raw.get("syntax", ())),
        unit=raw.get("unit", ""),
        range=tuple(rng) if isinstance(rng, list) and len(rng) == 2 else None,
        default=raw.get("default"),
        products=raw.get("products"),
        manual=raw.get("manual", ""),
        notes=raw.get("notes", ""),
        extra={k: v for k, v in raw.items() if k not in COMMON_KEYS},
    )


@lru_cache(maxsize=None)
def load(dialect: str) -> Catalog:
    data = toml.load_data_file(CATALOG_DIR / f"{dialect}.toml")
    entries = tuple(entry_from_dict(raw) for raw in data.get("entry", []))
    return Catalog(dialect=dialect, entries=entries,
                   data={k: v for k, v in data.items() if k != "entry"})
