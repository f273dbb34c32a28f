"""The Arcus catalog, indexed for the frontend and the backend.

Reads compiler/catalogs/arcus.toml once. Every keyword is recognised by the catalog's `pattern`
(a regex for the keyword token with its glued axis letter, bit number, direction or P/N suffix),
matched case-insensitively and anchored, the LONGEST match winning: that one rule resolves all
the prefix traps of the language (END/ENDIF, SSPD/SSPDM, P/PS, E/EO/ECLEAR, Z/ZHOME, DO/DO7, ...)
without a line of keyword-specific code.

Each pattern is rewritten once with named groups so that a match also tells which axis, bit,
direction and suffix were written: `[XYZU]` is the axis, `[+-]` the direction, `[PN]` the
suffix, any other bracketed digit class (with its quantifier) the index.

The catalog describes the standalone language of the whole Arcus family (PMX-4EX-SA, PMX-2ED-SA,
ACE-SDE, DMX-ETH). `load(product)` gives one product's view: an entry with `products` exists only
on the products it names (the others meet it as "a statement of another controller", A121), and
the catalog's `[variants."<product>"."<entry id>"]` tables replace keys of an entry for that
product (its bit range, value range, pattern). Data, not code: docs/dialects/arcus.md, "Family".
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import Any

from mcc.compiler import catalog as generic

ASCII_ONLY = "ascii-only"
OTHER_PRODUCT = "other-product"
CLASS = re.compile(r"\[([^\]]*)\]([+*?]?)")


def _named(pattern: str) -> str:
    """'SYN[XYZU]C' -> 'SYN(?P<axis>[XYZU])C'; 'DO[1-8]' -> 'DO(?P<index>[1-8])'."""

    def replace(match: re.Match) -> str:
        body, quant = match.group(1), match.group(2)
        if body == "XYZU":
            group = "axis"
        elif body == "+-":
            group = "dir"
        elif body == "PN":
            group = "suffix"
        else:
            group = "index"
        if quant == "?":
            return f"(?P<{group}>[{body}])?"
        return f"(?P<{group}>[{body}]{quant})"

    return CLASS.sub(replace, pattern)


def _stem(pattern: str) -> str:
    """The literal letters a pattern starts with: 'JOG[XYZU][+-]' -> 'JOG'."""
    match = re.match(r"[A-Za-z]+", pattern)
    return match.group(0).upper() if match else ""


@dataclass(frozen=True, eq=False)
class Keyword:
    """One catalog entry, with typed access to the Arcus keys (see the catalog's header). Each
    accessor is computed once per keyword (the entry never changes): the resolver, the lowering
    and the backend ask them for every statement of a program."""

    entry: generic.Entry
    regex: re.Pattern
    stem: str

    def get(self, key: str, default: Any = None) -> Any:
        return self.entry.get(key, default)

    @cached_property
    def id(self) -> str:
        return self.entry.get("id", self.entry.name)

    @cached_property
    def name(self) -> str:
        return self.entry.name

    @cached_property
    def kind(self) -> str:
        return self.entry.kind

    @cached_property
    def form(self) -> str:
        return self.entry.get("form", "")

    @cached_property
    def axis(self) -> str:
        return self.entry.get("axis", "none")

    @cached_property
    def ir(self) -> str:
        return self.entry.get("ir", "")

    @cached_property
    def readable(self) -> bool:
        return bool(self.entry.get("read", False))

    @cached_property
    def writable(self) -> bool:
        return bool(self.entry.get("write", False))

    @cached_property
    def in_condition(self) -> bool:
        return bool(self.entry.get("condition", False))

    @cached_property
    def in_operation(self) -> bool:
        return bool(self.entry.get("operand", False))

    @cached_property
    def literal_only(self) -> bool:
        return bool(self.entry.get("literal_only", False))

    @cached_property
    def index_range(self) -> tuple[int, int] | None:
        rng = self.entry.get("bit") or self.entry.get("index")
        return (int(rng[0]), int(rng[1])) if isinstance(rng, list) and len(rng) == 2 else None

    @cached_property
    def range(self) -> tuple[int, int] | None:
        return self.entry.range

    @cached_property
    def unit(self) -> str:
        return self.entry.unit

    @cached_property
    def example(self) -> str:
        examples = self.entry.get("examples") or []
        return examples[0] if examples else (self.entry.syntax[0] if self.entry.syntax else self.name)

    @cached_property
    def usage(self) -> str:
        return "; ".join(self.entry.syntax[:3])

    def spell(self, axis: str = "", index: int | None = None, direction: int = 0, suffix: str = "") -> str:
        """The keyword as typed, from its pattern: ('HSPD', 'X') -> 'HSPDX'; ('SYNS', 'Y') -> 'SYNYS'."""
        return _spell(self.entry.get("pattern", self.name), axis, index, direction, suffix)


@lru_cache(maxsize=4096)
def _spell(pattern: str, axis: str, index: int | None, direction: int, suffix: str) -> str:
    def replace(match: re.Match) -> str:
        body = match.group(1)
        if body == "XYZU":
            return axis if axis in ("X", "Y", "Z", "U") else ""
        if body == "+-":
            return "+" if direction >= 0 else "-"
        if body == "PN":
            return suffix
        return "" if index is None else str(index)

    return CLASS.sub(replace, pattern).upper()


@dataclass(frozen=True)
class Match:
    """A keyword found at the start of a text, and the glued pieces the pattern captured."""

    keyword: Keyword
    end: int  # characters of the text the keyword took
    axis: str = ""
    index: int | None = None
    direction: int = 0
    suffix: str = ""


DEFAULT_PRODUCT = "pmx-4ex-sa"


def available(entry: generic.Entry, product: str) -> bool:
    """Whether the entry exists on `product` (an entry without `products` exists on every one)."""
    return not entry.products or product in entry.products


def _variant(entry: generic.Entry, overrides: dict) -> generic.Entry:
    """The entry with some of its keys replaced for one product."""
    raw = {"name": entry.name, "title": entry.title, "kind": entry.kind, "summary": entry.summary,
           "syntax": list(entry.syntax), "unit": entry.unit, "default": entry.default, "products": entry.products,
           "manual": entry.manual, "notes": entry.notes, **entry.extra}
    if entry.range is not None:
        raw["range"] = list(entry.range)
    raw.update(overrides)
    return generic.entry_from_dict(raw)


def _keyword(entry: generic.Entry) -> Keyword:
    pattern = entry.get("pattern", "")
    return Keyword(entry, re.compile(_named(pattern), re.IGNORECASE), _stem(pattern))


class ArcusCatalog:
    def __init__(self, raw: generic.Catalog, product: str = DEFAULT_PRODUCT):
        self.raw = raw
        self.product = product
        self.keywords: list[Keyword] = []
        self.elsewhere: list[Keyword] = []  # statements of the family's other products
        self.by_first: dict[str, list[Keyword]] = {}
        self.by_name: dict[str, list[Keyword]] = {}
        self._matches: dict[str, Match | None] = {}  # texts repeat a lot (WAITX, V1, DO7)
        self._elsewhere: dict[str, Match | None] = {}  # the same for match_elsewhere
        variants = (raw.data.get("variants", {}) or {}).get(product, {}) or {}
        for entry in raw.entries:
            pattern = entry.get("pattern", "")
            if not pattern or not pattern[0].isalpha():
                continue  # the ';' comment entry: the grammar handles it
            if not available(entry, product):
                self.elsewhere.append(_keyword(entry))
                continue
            override = variants.get(entry.get("id", entry.name))
            keyword = _keyword(_variant(entry, override) if isinstance(override, dict) else entry)
            self.keywords.append(keyword)
            self.by_first.setdefault(keyword.stem[0], []).append(keyword)
            self.by_name.setdefault(entry.name.upper(), []).append(keyword)

    def table(self, key: str) -> dict:
        return self.raw.table(key)

    def limit(self, dotted: str, default: Any = None) -> Any:
        node: Any = self.raw.data.get("limits", {})
        for part in dotted.split("."):
            if not isinstance(node, dict) or part not in node:
                return default
            node = node[part]
        return node

    def match(self, text: str) -> Match | None:
        """The longest keyword at the start of `text` (upper case expected)."""
        try:
            return self._matches[text]
        except KeyError:
            pass
        if len(self._matches) > 20000:
            self._matches.clear()
        found = self._matches[text] = self._match(text)
        return found

    def _match(self, text: str) -> Match | None:
        best: Match | None = None
        for keyword in self.by_first.get(text[:1], ()):
            found = keyword.regex.match(text)
            if found is None or (best is not None and found.end() <= best.end):
                continue
            groups = found.groupdict()
            index = groups.get("index")
            best = Match(keyword, found.end(), (groups.get("axis") or "").upper(),
                         int(index) if index else None,
                         {"+": 1, "-": -1}.get(groups.get("dir") or "", 0), (groups.get("suffix") or "").upper())
        return best

    def match_elsewhere(self, text: str) -> Match | None:
        """The longest statement of another product of the family at the start of `text` (for
        "a PMX-4EX-SA statement: the ACE-SDE does not have it"); asked for every statement, so
        the answer per text is kept, as `match` keeps its own."""
        try:
            return self._elsewhere[text]
        except KeyError:
            pass
        if len(self._elsewhere) > 20000:
            self._elsewhere.clear()
        found = self._elsewhere[text] = self._match_elsewhere(text)
        return found

    def _match_elsewhere(self, text: str) -> Match | None:
        best: Match | None = None
        for keyword in self.elsewhere:
            if keyword.kind == ASCII_ONLY:
                continue
            found = keyword.regex.match(text)
            if found is not None and (best is None or found.end() > best.end):
                best = Match(keyword, found.end())
        return best

    def stems(self, text: str) -> list[Keyword]:
        """Keywords whose literal stem starts `text`, longest stem first (for 'JOGX needs a direction')."""
        found = [k for k in self.by_first.get(text[:1], ()) if text.startswith(k.stem)]
        return sorted(found, key=lambda k: -len(k.stem))

    def lookup(self, name: str, axis: str = "", index: int | None = None) -> Keyword | None:
        """The entry of a canonical name, choosing the bit form (DO[1-8]) when an index is given."""
        candidates = self.by_name.get(name.upper(), [])
        for keyword in candidates:
            has_index = keyword.index_range is not None
            if has_index == (index is not None):
                return keyword
        return candidates[0] if candidates else None

    def names(self) -> list[str]:
        return sorted({k.name for k in self.keywords if k.kind not in (ASCII_ONLY, OTHER_PRODUCT)})


@lru_cache(maxsize=None)
def load(product: str = DEFAULT_PRODUCT) -> ArcusCatalog:
    """The catalog as `product` has it (an unknown product code reads as the PMX-4EX-SA)."""
    raw = generic.load("arcus")
    known = raw.data.get("products", {}) or {}
    return ArcusCatalog(raw, product if product in known else DEFAULT_PRODUCT)
