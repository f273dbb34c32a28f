"""The X150 catalog, indexed for the tokeniser, the checks and the backend.

`compiler/catalogs/x150.toml` is the one table of every X150/X150E command. This module turns its
entries into `Command` records with typed accessors and builds the lookups the rest of the dialect
needs: the mnemonic table for longest-match splitting, the set of B-prefixable (`*`) commands and
the limits. Nothing here knows a command by name except the composite variable statements, whose
catalog names ("VARn=FUN", "RSIN") are not tokens.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import cached_property, lru_cache
from typing import Any

from mcc.compiler import catalog as generic

DIALECT = "x150"

# Argument classes whose value may be omitted to ask for a report (L128); the others need one.
REQUIRED_ARG = frozenset({"string", "condition"})
PRODUCT_KEYS = ("bdhxe", "pdhxe", "blhx", "pdhx", "x150ds")
MATCHES_KEPT = 20_000  # longest-match answers remembered (a long-running editor session stays bounded)


@dataclass(frozen=True)
class Field:
    """One field of a composite argument (DPC line/column, TM8 digit selectors, TX's variable)."""

    name: str
    low: int
    high: int
    digits: int = 0  # fixed width when non-zero


@dataclass(frozen=True, eq=False)
class Command:
    """One mnemonic and what the catalog says about it. The accessors are computed once per
    command (the entry never changes): the tokeniser, the lowering and the checks ask them for
    every command of a program."""

    name: str
    entry: generic.Entry

    def _get(self, key: str, default: Any = "") -> Any:
        return self.entry.get(key, default)

    @cached_property
    def exec(self) -> str:
        return self._get("exec", "?")

    @cached_property
    def address(self) -> str:
        return self._get("address", "?")

    @cached_property
    def policy(self) -> str:
        return self._get("policy", "allow")

    @cached_property
    def arg(self) -> str:
        return self._get("arg", "none")

    @cached_property
    def ir(self) -> str:
        return self._get("ir", "")

    @cached_property
    def var_subst(self) -> bool:
        return bool(self._get("var_subst", False))

    @cached_property
    def b_prefixable(self) -> bool:
        return self.exec == "I*"

    @cached_property
    def range(self) -> tuple[Any, Any] | None:
        return self.entry.range

    @cached_property
    def intervals(self) -> tuple[tuple[Any, Any], ...] | None:
        """The allowed values as closed intervals: `ranges` when the catalog gives a union (a range
        with a hole, "0, or 0.060 up"), else the one `range`."""
        union = self._get("ranges", None)
        if isinstance(union, list) and union:
            return tuple((low, high) for low, high in union)
        return (tuple(self.range),) if self.range is not None else None

    @cached_property
    def values(self) -> tuple[Any, ...] | None:
        vals = self._get("values", None)
        return tuple(vals) if isinstance(vals, list) else None

    @cached_property
    def special(self) -> tuple[Any, ...]:
        return tuple(self._get("special", ()))

    @cached_property
    def products(self) -> dict[str, str] | None:
        prods = self.entry.products
        return prods if isinstance(prods, dict) else None

    @cached_property
    def fields(self) -> tuple[Field, ...]:
        return _fields(self.entry)

    @cached_property
    def separator(self) -> str:
        return self._get("separator", ",")

    @cached_property
    def counts(self) -> tuple[int, ...]:
        counts = self._get("counts", None)
        return tuple(counts) if isinstance(counts, list) else (len(self.fields),)

    @cached_property
    def tail(self) -> str:
        return self._get("tail", "")

    @cached_property
    def value_required(self) -> bool:
        return self.arg in REQUIRED_ARG

    @cached_property
    def manual(self) -> str:
        return self.entry.manual

    def in_range(self, value: float) -> bool:
        if value in self.special:
            return True
        values = self.values
        if values is not None:
            return value in values
        intervals = self.intervals
        if intervals is None:
            return True
        for low, high in intervals:
            if low <= value <= high:
                return True
        return False


@lru_cache(maxsize=None)
def _fields(entry: generic.Entry) -> tuple[Field, ...]:
    out = []
    for raw in entry.get("fields", ()) or ():
        low, high = raw.get("range", [0, 2**31])
        out.append(Field(raw.get("name", "value"), int(low), int(high), int(raw.get("digits", 0))))
    return tuple(out)


@dataclass(frozen=True)
class X150Catalog:
    commands: dict[str, Command]  # upper-case mnemonic -> command (tokens only)
    statements: dict[str, Command]  # variable-statement sources: "FUN" -> the VARn=FUN entry, ...
    longest: int
    data: generic.Catalog
    name_run: re.Pattern  # a run of the characters some mnemonic is made of (no mnemonic goes past it)
    matches: dict[str, Command | None] = field(default_factory=dict, compare=False, repr=False)  # see `match`

    def lookup(self, name: str) -> Command | None:
        return self.commands.get(name.upper())

    def match(self, text: str, start: int = 0) -> Command | None:
        """The longest mnemonic that `text[start:]` begins with (case-insensitive)."""
        upper = text[start:start + self.longest].upper()
        matches = self.matches  # the answer depends on these few characters only: asked once each
        if upper in matches:
            return matches[upper]
        commands = self.commands
        found = None
        for length in range(self.name_run.match(upper).end(), 0, -1):
            found = commands.get(upper[:length])
            if found is not None:
                break
        if len(matches) < MATCHES_KEPT:
            matches[upper] = found
        return found

    def limit(self, key: str, field: str = "value", default: Any = None) -> Any:
        raw = self.data.table("limits").get(key)
        if isinstance(raw, dict):
            return raw.get(field, default)
        return default

    @property
    def max_terms(self) -> int:
        return int(self.data.table("condition").get("max_terms", 2))

    @property
    def relational(self) -> tuple[str, ...]:
        return tuple(self.data.table("condition").get("relational", (">", "<", "=")))

    @property
    def sources(self) -> dict[str, dict]:
        """Right-hand sides of VARn= that read the device (POS ABS FEP RSIN TQ FUN NUM SMC)."""
        return self.data.table("variables").get("sources", {})

    @property
    def arithmetic_sources(self) -> tuple[str, ...]:
        """Sources that may take part in arithmetic (VAR8=POS+50000, L4622-L4627)."""
        operands = self.data.table("variables").get("operands", ())
        return tuple(op for op in operands if op in self.sources)

    def input_functions(self) -> dict[str, dict]:
        return self.data.table("input_functions")

    def output_functions(self) -> dict[str, dict]:
        return self.data.table("output_functions")


@lru_cache(maxsize=1)
def load() -> X150Catalog:
    data = generic.load(DIALECT)
    commands: dict[str, Command] = {}
    statements: dict[str, Command] = {}
    for entry in data.entries:
        command = Command(entry.name, entry)
        if entry.name.startswith("VARn="):
            statements[entry.name.split("=", 1)[1]] = command
        elif entry.name == "RSIN":
            statements["RSIN"] = command
        elif entry.kind not in ("comment", "edit"):
            commands[entry.name.upper()] = command
    longest = max(len(name) for name in commands)
    characters = "".join(sorted({ch for name in commands for ch in name}))
    name_run = re.compile(f"[{re.escape(characters)}]*")
    return X150Catalog(commands, statements, longest, data, name_run)
