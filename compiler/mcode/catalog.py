"""The MCode catalog, indexed for the frontend.

Reads compiler/catalogs/mcode.toml (every Lexium command, variable, flag, keyword and function) and
mcode-legacy.toml (commands of the older MDrivePlus/MForce family), expands indexed families
(F1-F8, R1-R4, ...) and answers the lookups the checks need. A profile of an older MCode family
(`[mcode] family = "mdrive-plus"`) gets that family's catalog instead (`for_profile`): the variant
in compiler/catalogs/mcode-families.toml applied to the Lexium one.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from mcc.compiler import catalog as generic
from mcc.compiler import toml

INSTRUCTION, VARIABLE, FLAG, KEYWORD = "instruction", "variable", "flag", "keyword"
FUNCTION, OPERATOR, RESERVED, FACTORY_LABEL = "function", "operator", "reserved", "factory-label"


@dataclass(frozen=True)
class Arg:
    name: str
    type: str
    range: tuple[Any, Any] | None = None
    values: tuple[Any, ...] | None = None
    optional: bool = False
    repeat: bool = False
    unit: str = ""

    @classmethod
    def from_dict(cls, raw: dict) -> "Arg":
        rng = raw.get("range")
        vals = raw.get("values")
        return cls(name=raw.get("name", "value"), type=raw.get("type", "int"),
                   range=tuple(rng) if isinstance(rng, list) and len(rng) == 2 else None,
                   values=tuple(vals) if isinstance(vals, list) else None,
                   optional=bool(raw.get("optional", False)), repeat=bool(raw.get("repeat", False)),
                   unit=raw.get("unit", ""))


@dataclass(frozen=True)
class Form:
    select: tuple[Any, Any] | None
    args: tuple[Arg, ...]


@dataclass(frozen=True)
class Command:
    """One concrete name (F3, not F1-F8) and what the catalog says of it."""

    name: str
    entry: generic.Entry
    index: int | None = None
    derived: tuple[str, ...] = ()  # derived products that have it too ([derived_products])

    @property
    def kind(self) -> str:
        return self.entry.kind

    @property
    def access(self) -> str:
        return self.entry.get("access", "")

    @property
    def mode(self) -> str:
        return self.entry.get("mode", "both")

    @property
    def ir(self) -> str:
        return self.entry.get("ir", "")

    @property
    def firmware(self) -> str:
        return self.entry.get("firmware", "")

    @property
    def products(self) -> tuple[str, ...]:
        return tuple(self.entry.products or ()) + self.derived

    @property
    def values(self) -> tuple[Any, ...] | None:
        vals = self.entry.get("values")
        return tuple(vals) if isinstance(vals, list) else None

    @property
    def writable(self) -> bool:
        return self.kind in (VARIABLE, FLAG) and self.access in ("rw", "wo", "rc", "")

    @property
    def readable(self) -> bool:
        return self.kind in (VARIABLE, FLAG, KEYWORD) and self.access != "wo"

    @property
    def is_float(self) -> bool:
        return self.ir == "register" and self.name.startswith("F")

    def forms(self) -> tuple[Form, ...]:
        return _forms(self.entry)


@lru_cache(maxsize=None)
def _forms(entry: generic.Entry) -> tuple[Form, ...]:
    if entry.get("forms"):
        return tuple(Form(tuple(f["select"]) if f.get("select") else None,
                          tuple(Arg.from_dict(a) for a in f.get("args", ())))
                     for f in entry.get("forms"))
    if entry.get("args"):
        return (Form(None, tuple(Arg.from_dict(a) for a in entry.get("args"))),)
    return ()


@dataclass(frozen=True)
class Legacy:
    name: str
    family: str
    summary: str
    lexium: str
    io_point: int | None = None


@dataclass(frozen=True)
class McodeCatalog:
    commands: dict[str, Command]
    legacy: dict[str, Legacy]
    products: dict[str, str]
    functions: dict[str, Command]
    increment_groups: frozenset[str] = frozenset()  # [increment] groups: what IC/DC may step
    family: str = ""  # "" for Lexium MCode, else the variant of mcode-families.toml
    io_setup: str = "lines"  # "lines": IS/OS per input and output; "point": S1-S4 per I/O point

    def lookup(self, name: str) -> Command | None:
        return self.commands.get(name.upper())

    def steppable(self, command: Command) -> bool:
        """Whether IC/DC may step a factory variable (not a mode or configuration one, Error 26)."""
        return command.kind == VARIABLE and command.values is None and \
            command.entry.get("group", "") in self.increment_groups

    def is_reserved(self, name: str, firmware: str = "") -> bool:
        """Whether `name` is an MCode name on a target running `firmware` ("" = the newest)."""
        upper = name.upper()
        return upper in self.commands or self.target_function(upper, firmware) is not None

    def target_function(self, name: str, firmware: str = "") -> Command | None:
        """The function `name` if the target's firmware has it. The math functions came with firmware
        6.0.01: programs for older MDrive firmware use AB, LO, ... as plain names (`VA LO=12200`)."""
        function = self.functions.get(name.upper())
        version = firmware_tuple(firmware)
        if function is None or not function.firmware or not version:  # no version given: the newest
            return function
        return function if version >= firmware_tuple(function.firmware) else None


FAMILIES_FILE = "mcode-families.toml"


def for_profile(profile) -> McodeCatalog:
    """The catalog a profile's programs are checked with: Lexium MCode, or the family its
    `[mcode] family` names (an unknown family is the Lexium catalog; `families()` lists them)."""
    family = profile.get("mcode.family", "") if profile is not None else ""
    if not family or family not in families():
        return load()
    return load_family(str(family))


@lru_cache(maxsize=1)
def _families_data() -> dict:
    return toml.load_data_file(generic.CATALOG_DIR / FAMILIES_FILE).get("variant", {})


def families() -> dict[str, dict]:
    """The MCode family variants by name (compiler/catalogs/mcode-families.toml)."""
    return _families_data()


@lru_cache(maxsize=None)
def load_family(name: str) -> McodeCatalog:
    """The catalog of an older MCode family: the commands of its `like` product, less its `absent`
    names and the commands of a newer firmware than its own, with its `override`s and its own
    entries. The family's product code is its name; its programs may use every name left out as
    their own (real MDrivePlus programs declare `VA LO=12200`, label `LB AO`)."""
    base = load()
    variant = families()[name]
    like = variant.get("like", "")
    absent = {str(n).upper() for n in variant.get("absent", ())}
    version = firmware_tuple(str(variant.get("firmware", "")))
    overrides = {str(k).upper(): v for k, v in variant.get("override", {}).items()}
    commands: dict[str, Command] = {}
    for key, command in base.commands.items():
        products = command.products
        if key in absent or (products and like not in products):
            continue
        if command.firmware and version and version < firmware_tuple(command.firmware):
            continue
        entry = command.entry
        if key in overrides:
            entry = generic.entry_from_dict({**_entry_dict(entry), **overrides[key]})
        commands[key] = Command(key, entry, command.index, command.derived + (name,))
    for raw in variant.get("entry", []):
        entry = generic.entry_from_dict({**raw, "products": [name]})
        index = entry.get("index")
        if isinstance(index, list) and len(index) == 2:
            for i in range(int(index[0]), int(index[1]) + 1):
                commands[f"{entry.name.upper()}{i}"] = Command(f"{entry.name.upper()}{i}", entry, i)
        else:
            commands[entry.name.upper()] = Command(entry.name.upper(), entry)
    functions = {} if not version else {k: f for k, f in base.functions.items()
                                        if not f.firmware or version >= firmware_tuple(f.firmware)}
    legacy = {k: v for k, v in base.legacy.items() if k not in commands}
    products = dict(base.products)
    products[name] = variant.get("title", name)
    return McodeCatalog(commands, legacy, products, functions, base.increment_groups, family=name,
                        io_setup=str(variant.get("io_setup", "lines")))


def _entry_dict(entry: generic.Entry) -> dict:
    """An entry back as the dictionary it was read from (for an override)."""
    return {"name": entry.name, "title": entry.title, "kind": entry.kind, "summary": entry.summary,
            "syntax": list(entry.syntax), "unit": entry.unit,
            "range": list(entry.range) if entry.range else None, "default": entry.default,
            "products": entry.products, "manual": entry.manual, "notes": entry.notes, **entry.extra}


def firmware_tuple(text: str) -> tuple[int, ...]:
    """'6.0.01' -> (6, 0, 1): firmware versions compare part by part."""
    return tuple(int(part) for part in re.findall(r"\d+", text))


def derived_products(entry: generic.Entry, rules: dict[str, Any]) -> tuple[str, ...]:
    """The derived products that have `entry`: those `like` a product listed, and those whose
    `groups` give the entry's group to a product listed."""
    listed = set(entry.products or ())
    if not listed:
        return ()
    found = []
    for code, rule in rules.items():
        group_base = (rule.get("groups") or {}).get(entry.get("group", ""))
        if rule.get("like") in listed or group_base in listed:
            found.append(code)
    return tuple(c for c in found if c not in listed)


@lru_cache(maxsize=1)
def load() -> McodeCatalog:
    cat = generic.load("mcode")
    rules = dict(cat.table("derived_products"))
    commands: dict[str, Command] = {}
    functions: dict[str, Command] = {}
    for entry in cat.entries:
        index = entry.get("index")
        if entry.kind == OPERATOR:
            continue
        derived = derived_products(entry, rules)
        if isinstance(index, list) and len(index) == 2:
            for i in range(int(index[0]), int(index[1]) + 1):
                name = f"{entry.name.upper()}{i}"
                commands[name] = Command(name, entry, i, derived)
        else:
            name = entry.name.upper()
            command = Command(name, entry, None, derived)
            if entry.kind == FUNCTION:
                functions[name] = command
            else:
                commands.setdefault(name, command)
    legacy_raw = toml.load_data_file(generic.CATALOG_DIR / "mcode-legacy.toml")
    legacy = {raw["name"].upper(): Legacy(raw["name"].upper(), raw["family"], raw["summary"], raw["lexium"],
                                          raw.get("io_point"))
              for raw in legacy_raw.get("legacy", [])}
    return McodeCatalog(commands, legacy, dict(cat.table("products")), functions,
                        frozenset(cat.table("increment").get("groups", ())))
