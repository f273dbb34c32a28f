"""Project configuration: `[tool.mcc]` in pyproject.toml, or the top level of mcc.toml.

The configuration of a file is the nearest one found walking up from the file's directory (an
mcc.toml wins over a pyproject.toml in the same directory; a pyproject.toml without `[tool.mcc]`
is skipped), as ruff does. `--config FILE` uses one file for everything; command-line flags
override both. Keys are documented in docs/CONFIGURATION.md.

Rule selection follows ruff's semantics: `select`, `extend-select` and `ignore` take code prefixes
("M3", "M301", "ALL"); within one layer the most specific prefix decides (an ignore wins a tie);
a later layer (the command line after the file) overrides an earlier one, and a layer that has
`select` starts afresh. Syntax errors, internal errors and configuration errors cannot be
deselected: they mean the result is not trustworthy.

A configuration mistake never passes silently: an unknown key (G102) or an invalid value (G103,
e.g. an unknown code) becomes a diagnostic on the TOML file, at the line of the key or value.
"""

from __future__ import annotations

import fnmatch
import os
import re
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

from mcc.compiler import dialects, toml
from mcc.compiler.codes import registry
from mcc.compiler.diagnostics import Diagnostic, Diagnostics, Kind, Severity
from mcc.compiler.span import SourceFile, Span
from mcc.compiler.suggest import close_matches

CONFIG_FILES = ("mcc.toml", "pyproject.toml")
ALWAYS_ON = ("G001", "G102", "G103")  # internal errors and configuration errors
SEVERITIES = tuple(s.value for s in Severity)
LIST_KEYS = ("select", "extend-select", "ignore", "exclude")
DEFAULT_FAIL_ON = "warning"  # `mcc lint` exits 1 on a warning, as ruff on any finding (docs/LINT.md)
KNOWN_KEYS = ("target", *LIST_KEYS, "fail-on", "per-file-ignores", "severity", "per-file-profiles",
              "axes",  # axes: the machine's envelope (compiler/envelope/axes.py)
              "extensions",
              "cross")  # cross: conversions between dialects (drop-drive-setup, docs/CONFIGURATION.md)


class ConfigError(Exception):
    """A command-line value that cannot be used (reported by the CLI as a usage error)."""


# ---------------------------------------------------------------------------------------------
# Selection


@dataclass(frozen=True)
class Layer:
    """One source of rule selection: the defaults, a configuration file, or the command line."""

    select: tuple[str, ...] | None = None
    extend_select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()


DEFAULT_LAYER = Layer(select=("ALL",))


def prefix_matches(prefix: str, code: str) -> bool:
    return prefix == "ALL" or code.startswith(prefix)


def specificity(prefix: str) -> int:
    return 0 if prefix == "ALL" else len(prefix)


@lru_cache(maxsize=None)
def deselectable(code: str) -> bool:
    """Syntax, internal and configuration errors are always reported."""
    if code in ALWAYS_ON:
        return False
    info = registry().get(code)
    return info is None or info.kind not in (Kind.SYNTAX, Kind.INTERNAL)


@lru_cache(maxsize=None)
def opt_in(code: str) -> bool:
    """An opt-in rule (`- opt-in:` on its page, `opt_in = true` in compiler/codes/*.toml) is enabled
    only by its own code."""
    info = registry().get(code)
    return info is not None and info.opt_in


@dataclass(frozen=True)
class Selection:
    layers: tuple[Layer, ...] = (DEFAULT_LAYER,)

    def enabled(self, code: str) -> bool:
        code = code.upper()
        if not deselectable(code):
            return True
        state = False
        exact = opt_in(code)
        for layer in self.layers:
            if layer.select is not None:
                state = False
            chosen = [(specificity(p), True) for p in (*(layer.select or ()), *layer.extend_select)
                      if (p == code if exact else prefix_matches(p, code))]
            chosen += [(specificity(p), False) for p in layer.ignore if prefix_matches(p, code)]
            if chosen:
                best = max(s for s, _ in chosen)
                state = all(on for s, on in chosen if s == best)
        return state


# ---------------------------------------------------------------------------------------------
# Settings


@dataclass(frozen=True)
class Settings:
    """Everything the linter needs to know about one file's configuration (picklable)."""

    root: str = "."  # the directory per-file-ignores and exclude patterns are relative to
    path: str | None = None  # the configuration file, when there is one
    targets: tuple[tuple[str, str], ...] = ()  # (dialect or "*", profile name or absolute path)
    selection: Selection = field(default_factory=Selection)
    severity: tuple[tuple[str, str], ...] = ()  # (code prefix, severity)
    per_file_ignores: tuple[tuple[str, tuple[str, ...]], ...] = ()
    fail_on: str = "warning"  # DEFAULT_FAIL_ON
    exclude: tuple[str, ...] = ()
    # glob -> profile (name or absolute path), in the file's order: the first glob that matches a
    # file and names a profile of its dialect chooses it (compiler/selection.py)
    per_file_profiles: tuple[tuple[str, str], ...] = ()
    cli_profile: str | None = None  # --profile: wins over everything (compiler/selection.py)
    axes: tuple = ()  # (axis, envelope.axes.AxisEnvelope): `[tool.mcc.axes.<axis>]`, in steps
    # extension (lower case, no dot) -> dialect: `extensions = {lxt = "mcode"}`; wins over the
    # built-in extensions, loses to --dialect (docs/CONFIGURATION.md)
    extensions: tuple[tuple[str, str], ...] = ()
    # `cross.drop-drive-setup`: a conversion leaves out the drive set-up the target configures outside
    # the program (G051, backends/drive_setup.py); false refuses it as before (docs/decisions/0016)
    drop_drive_setup: bool = True

    def dialect_for(self, path: str) -> str | None:
        """The dialect `extensions` gives `path` by its extension, or None."""
        suffix = os.path.splitext(path)[1].lower().lstrip(".")
        for ext, dialect in self.extensions:
            if ext == suffix:
                return dialect
        return None

    def profile_for_path(self, path: str, dialect: str) -> tuple[str, str] | None:
        """(glob, profile) of the first `per-file-profiles` entry that matches `path` for `dialect`."""
        if not self.per_file_profiles:
            return None
        rel = relative_to(path, self.root)
        for pattern, spec in self.per_file_profiles:
            if glob_matches(pattern, rel) and load_profile(spec).dialect == dialect:
                return pattern, spec
        return None

    def profile_spec(self, dialect: str) -> str | None:
        for key, spec in self.targets:
            if key == dialect:
                return spec
        for key, spec in self.targets:
            if key == "*":
                return spec
        return None

    def profile(self, dialect: str):
        """The profile for files of `dialect`, or None for the dialect's default."""
        spec = self.profile_spec(dialect)
        if spec is None:
            return None
        prof = load_profile(spec)
        return prof if prof.dialect == dialect else None

    def enabled(self, code: str, path: str) -> bool:
        if not self.selection.enabled(code):
            return False
        if not deselectable(code.upper()):
            return True
        return not any(prefix_matches(p, code) for p in self.ignored_for(path))

    def ignored_for(self, path: str) -> tuple[str, ...]:
        if not self.per_file_ignores:
            return ()
        rel = relative_to(path, self.root)
        out: list[str] = []
        for pattern, codes in self.per_file_ignores:
            if glob_matches(pattern, rel):
                out.extend(codes)
        return tuple(out)

    def severity_of(self, code: str, default: Severity) -> Severity:
        best = -1
        result = default
        for prefix, value in self.severity:
            if prefix_matches(prefix, code) and specificity(prefix) > best:
                best, result = specificity(prefix), Severity(value)
        return result

    def excluded(self, path: str) -> bool:
        """Whether `exclude` skips `path`: git's pattern language, relative to `root`
        (compiler/lint/ignore.py); a path outside `root` is never excluded."""
        if not self.exclude:
            return False
        from mcc.compiler.lint import ignore

        rel = relative_to(path, self.root)
        if rel.startswith("../") or Path(rel).is_absolute():
            return False
        patterns = tuple("/" + p[2:] if p.startswith("./") else p for p in self.exclude)
        return ignore.matches(patterns, rel, os.path.isdir(path))

    def with_overrides(self, overrides: "Overrides") -> "Settings":
        layers = self.selection.layers
        if overrides.layer != Layer():
            layers = (*layers, overrides.layer)
        # the command line's profile wins for its own dialect, over a directive and the file's keys
        return Settings(self.root, self.path, self.targets, Selection(layers), self.severity, self.per_file_ignores,
                        overrides.fail_on or self.fail_on, self.exclude, self.per_file_profiles,
                        overrides.profile or self.cli_profile, self.axes, extensions=self.extensions,
                        drop_drive_setup=self.drop_drive_setup)


def relative_to(path: str, root: str) -> str:
    try:
        return Path(os.path.abspath(path)).relative_to(os.path.abspath(root)).as_posix()
    except ValueError:
        return Path(path).as_posix()


def glob_matches(pattern: str, rel: str) -> bool:
    """fnmatch-style; a pattern without '/' also matches the base name (as ruff does)."""
    pattern = pattern.strip("/") if not pattern.startswith("./") else pattern[2:]
    if fnmatch.fnmatchcase(rel, pattern) or fnmatch.fnmatchcase(rel, pattern.rstrip("/") + "/*"):
        return True
    return "/" not in pattern and fnmatch.fnmatchcase(rel.rsplit("/", 1)[-1], pattern)


@lru_cache(maxsize=None)
def load_profile(spec: str):
    from mcc.compiler import profiles

    return profiles.load(spec)


# ---------------------------------------------------------------------------------------------
# Command-line overrides


@dataclass(frozen=True)
class Overrides:
    layer: Layer = Layer()
    profile: str | None = None
    fail_on: str | None = None


def parse_codes(values: tuple[str, ...] | list[str]) -> tuple[str, ...]:
    """Flatten "M301,M302" and repeated flags; unknown prefixes raise ConfigError."""
    out = []
    for value in values:
        for part in re.split(r"[,\s]+", value.strip()):
            if not part:
                continue
            code = part.upper()
            if not valid_prefix(code):
                raise ConfigError(f"unknown rule code or prefix '{part}' (see `mcc explain --list`)")
            out.append(code)
    return tuple(out)


def overrides(select=(), extend_select=(), ignore=(), profile: str | None = None,
              fail_on: str | None = None) -> Overrides:
    layer = Layer(parse_codes(select) if select else None, parse_codes(extend_select), parse_codes(ignore))
    if profile:
        from mcc.compiler import profiles

        try:
            load_profile(profile)
        except profiles.ProfileError as exc:
            raise ConfigError(str(exc)) from None
    return Overrides(layer, profile, fail_on)


@lru_cache(maxsize=None)
def valid_prefix(prefix: str) -> bool:
    return prefix == "ALL" or any(code.startswith(prefix) for code in registry().names())


# ---------------------------------------------------------------------------------------------
# Finding and reading configuration files


@lru_cache(maxsize=None)
def find(directory: str) -> str | None:
    """The nearest configuration file at or above `directory`."""
    current = Path(os.path.abspath(directory))
    for folder in (current, *current.parents):
        for name in CONFIG_FILES:
            candidate = folder / name
            if candidate.is_file() and (name != "pyproject.toml" or has_tool_table(candidate)):
                return str(candidate)
    return None


def has_tool_table(path: Path) -> bool:
    try:
        data = toml.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, toml.TOMLDecodeError):
        return False
    return isinstance(data.get("tool"), dict) and "mcc" in data["tool"]


@dataclass
class Loaded:
    settings: Settings
    diagnostics: list[Diagnostic]
    source: SourceFile | None


@lru_cache(maxsize=None)
def load(path: str | None, display: str | None = None) -> Loaded:
    """Read one configuration file (cached): its settings and the diagnostics about it."""
    if path is None:
        return Loaded(Settings(root=os.getcwd()), [], None)
    shown = display or display_path(path)
    from mcc.compiler.files import read_bytes  # only regular files: never blocks on a FIFO

    try:
        text = read_bytes(path).decode("utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        diags = Diagnostics()
        diags.add("G103", Span(shown, 1, 1, 1, 1), f"cannot read the configuration file: {exc}")
        return Loaded(Settings(root=str(Path(path).parent)), diags.items, None)
    return parse(text, path, shown)


def display_path(path: str) -> str:
    rel = os.path.relpath(path)
    return path if rel.startswith("..") else rel


def parse(text: str, path: str, shown: str | None = None) -> Loaded:
    source = SourceFile(shown or path, text)
    reader = Reader(source, Path(path))
    settings = reader.read()
    return Loaded(settings, sorted(reader.diags.items, key=Diagnostic.sort_key), source)


class Reader:
    """Validates one configuration file's table and turns it into `Settings`."""

    def __init__(self, source: SourceFile, path: Path):
        self.source = source
        self.path = path
        self.diags = Diagnostics()
        self.base: tuple[str, ...] = ("tool", "mcc") if path.name == "pyproject.toml" else ()
        self.locator = Locator(source)

    # positions ---------------------------------------------------------------------------------
    def span(self, keys: tuple[str, ...], needle: str | None = None) -> Span:
        return self.locator.span(self.base + keys, needle)

    def error(self, code: str, keys: tuple[str, ...], message: str, needle: str | None = None) -> None:
        self.diags.add(code, self.span(keys, needle), message)

    # reading -----------------------------------------------------------------------------------
    def read(self) -> Settings:
        root = str(self.path.parent)
        try:
            data = toml.loads(self.source.text)
        except toml.TOMLDecodeError as exc:
            at = toml_error_offset(self.source, str(exc))
            span = self.source.span(at, at)
            self.diags.add("G103", span, f"invalid TOML: {exc}")
            return Settings(root=root, path=str(self.path))
        table: Any = data
        for key in self.base:
            table = table.get(key, {}) if isinstance(table, dict) else {}
        if not isinstance(table, dict):
            self.error("G103", (), "the mcc configuration must be a table")
            return Settings(root=root, path=str(self.path))
        for key in table:
            if key not in KNOWN_KEYS:
                near = close_matches(key.replace("_", "-"), KNOWN_KEYS, n=1, cutoff=0.6)
                hint = f"; did you mean '{near[0]}'?" if near else f" (known keys: {', '.join(KNOWN_KEYS)})"
                self.error("G102", (key,), f"unknown configuration key '{key}'{hint}")
        lists = {key: self.codes(table, key) for key in ("select", "extend-select", "ignore")}
        layer = Layer(lists["select"] if "select" in table else None, lists["extend-select"] or (),
                      lists["ignore"] or ())
        layers = (DEFAULT_LAYER, layer) if layer != Layer() else (DEFAULT_LAYER,)
        return Settings(root=root, path=str(self.path), targets=self.targets(table.get("target")),
                        selection=Selection(layers), severity=self.severities(table.get("severity")),
                        per_file_ignores=self.per_file(table.get("per-file-ignores")),
                        fail_on=self.fail_on(table.get("fail-on")), exclude=self.strings(table, "exclude"),
                        per_file_profiles=self.per_file_profiles(table.get("per-file-profiles")),
                        axes=self.axes(table.get("axes")),
                        extensions=self.extensions(table.get("extensions")),
                        drop_drive_setup=self.cross(table.get("cross")))

    def strings(self, table: dict, key: str) -> tuple[str, ...]:
        value = table.get(key)
        if value is None:
            return ()
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            self.error("G103", (key,), f"'{key}' must be a list of strings")
            return ()
        return tuple(value)

    def codes(self, table: dict, key: str, keys: tuple[str, ...] | None = None) -> tuple[str, ...]:
        values = self.strings(table, key) if keys is None else self.string_list(table[key], keys)
        good = []
        for value in values:
            if valid_prefix(value.upper()):
                good.append(value.upper())
            else:
                self.error("G103", keys or (key,), f"unknown rule code or prefix '{value}' in '{(keys or (key,))[-1]}' "
                                                    "(see `mcc explain --list`)", needle=value)
        return tuple(good)

    def string_list(self, value: Any, keys: tuple[str, ...]) -> tuple[str, ...]:
        if isinstance(value, str):
            return (value,)
        if isinstance(value, list) and all(isinstance(v, str) for v in value):
            return tuple(value)
        self.error("G103", keys, f"'{keys[-1]}' must be a list of codes")
        return ()

    def targets(self, value: Any) -> tuple[tuple[str, str], ...]:
        if value is None:
            return ()
        items = [("*", value, ("target",))] if isinstance(value, str) else \
            [(k, v, ("target", k)) for k, v in value.items()] if isinstance(value, dict) else None
        if items is None:
            self.error("G103", ("target",), "'target' must be a profile name, a path, or a table dialect -> profile")
            return ()
        out = []
        for dialect, spec, keys in items:
            if dialect != "*" and dialect not in dialects.names():
                self.error("G103", keys, f"'{dialect}' is not a dialect ({', '.join(dialects.names())})")
                continue
            if not isinstance(spec, str):
                self.error("G103", keys, "a target is a profile name or a path to a profile file")
                continue
            resolved = self.profile_path(spec)
            try:
                prof = load_profile(resolved)
            except Exception as exc:  # ProfileError, or a profile file with broken contents
                self.error("G103", keys, str(exc), needle=spec)
                continue
            if dialect != "*" and prof.dialect != dialect:
                self.error("G103", keys, f"profile '{spec}' is for {prof.dialect}, not {dialect}", needle=spec)
                continue
            out.append((dialect, resolved))
        return tuple(out)

    def profile_path(self, spec: str) -> str:
        candidate = self.path.parent / spec
        if spec.endswith(".toml") or "/" in spec or candidate.is_file():
            return str(candidate)
        return spec

    def severities(self, value: Any) -> tuple[tuple[str, str], ...]:
        if value is None:
            return ()
        if not isinstance(value, dict):
            self.error("G103", ("severity",), "'severity' must be a table: code = \"error\" | \"warning\" | \"info\"")
            return ()
        out = []
        for code, level in value.items():
            keys = ("severity", code)
            if not valid_prefix(code.upper()):
                self.error("G103", keys, f"unknown rule code or prefix '{code}' in 'severity'")
            elif level not in SEVERITIES:
                self.error("G103", keys, f"severity of {code} must be one of {', '.join(SEVERITIES)}, not {level!r}")
            else:
                out.append((code.upper(), level))
        return tuple(out)

    def per_file(self, value: Any) -> tuple[tuple[str, tuple[str, ...]], ...]:
        if value is None:
            return ()
        if not isinstance(value, dict):
            self.error("G103", ("per-file-ignores",), "'per-file-ignores' must be a table: \"glob\" = [codes]")
            return ()
        return tuple((pattern, self.codes(value, pattern, ("per-file-ignores", pattern))) for pattern in value)

    def per_file_profiles(self, value: Any) -> tuple[tuple[str, str], ...]:
        """`per-file-profiles = {"arcus/*.prg" = "pmx-2ed-sa"}`: glob -> profile name or path."""
        if value is None:
            return ()
        if not isinstance(value, dict):
            self.error("G103", ("per-file-profiles",), "'per-file-profiles' must be a table: \"glob\" = \"profile\"")
            return ()
        out = []
        for pattern, spec in value.items():
            keys = ("per-file-profiles", pattern)
            if not isinstance(spec, str):
                self.error("G103", keys, "a per-file profile is a profile name or a path to a profile file")
                continue
            resolved = self.profile_path(spec)
            try:
                load_profile(resolved)
            except Exception as exc:  # ProfileError, or a profile file with broken contents
                self.error("G103", keys, str(exc), needle=spec)
                continue
            out.append((pattern, resolved))
        return tuple(out)

    def extensions(self, value: Any) -> tuple[tuple[str, str], ...]:
        """`extensions = {lxt = "mcode", txt = "mcode"}`: a file extension (with or without its dot)
        -> the dialect its files are written in."""
        if value is None:
            return ()
        if not isinstance(value, dict):
            self.error("G103", ("extensions",), "'extensions' must be a table: extension = \"dialect\", "
                                                "e.g. extensions = {lxt = \"mcode\"}")
            return ()
        known = dialects.names()
        out = []
        for ext, dialect in value.items():
            keys = ("extensions", ext)
            name = ext.strip().lstrip(".").lower()
            if not name or not re.fullmatch(r"[a-z0-9_.+-]+", name):
                self.error("G103", keys, f"'{ext}' is not a file extension (write it without the dot: lxt = \"mcode\")")
                continue
            if not isinstance(dialect, str) or dialect not in known:
                near = close_matches(str(dialect).lower(), known, n=1, cutoff=0.5)
                hint = f"; did you mean '{near[0]}'?" if near else ""
                self.error("G103", keys, f"'{dialect}' is not a dialect ({', '.join(known)}){hint}",
                           needle=dialect if isinstance(dialect, str) else None)
                continue
            out.append((name, dialect))
        return tuple(out)
    def axes(self, value: Any) -> tuple:
        """`[tool.mcc.axes.<axis>]`: the envelope of each axis (compiler/envelope/axes.py)."""
        if value is None:
            return ()
        from mcc.compiler.envelope import axes

        found, problems = axes.parse(value)
        for keys, code, message in problems:
            self.error(code, keys, message)
        return tuple(sorted(found.items()))

    def cross(self, value: Any) -> bool:
        """`cross.drop-drive-setup = false` (or `[tool.mcc.cross]`): whether a conversion leaves out
        the drive set-up the target configures outside the program; true unless set."""
        if value is None:
            return True
        if not isinstance(value, dict):
            self.error("G103", ("cross",), "'cross' must be a table: cross.drop-drive-setup = true or false")
            return True
        for key in value:
            if key != "drop-drive-setup":
                self.error("G102", ("cross", key), f"unknown configuration key 'cross.{key}' (known: drop-drive-setup)")
        drop = value.get("drop-drive-setup", True)
        if not isinstance(drop, bool):
            self.error("G103", ("cross", "drop-drive-setup"), "'cross.drop-drive-setup' must be true or false")
            return True
        return drop

    def fail_on(self, value: Any) -> str:
        if value is None:
            return DEFAULT_FAIL_ON
        if value not in SEVERITIES:
            self.error("G103", ("fail-on",), f"'fail-on' must be one of {', '.join(SEVERITIES)}, not {value!r}")
            return DEFAULT_FAIL_ON
        return value


def toml_error_offset(source: SourceFile, message: str) -> int:
    """Where tomllib's message says the error is ("at line 3, column 7" or "at end of document")."""
    match = re.search(r"line (\d+), column (\d+)", message)
    if match is None:
        return len(source.text.rstrip("\n")) if "end of document" in message else 0
    line = min(int(match.group(1)), source.line_count)
    return min(source.line_starts[line - 1] + int(match.group(2)) - 1, len(source.text))


# ---------------------------------------------------------------------------------------------
# Where keys are in the TOML text (tomllib gives values, not positions)

HEADER = re.compile(r"^\s*\[\[?\s*([^\]]+?)\s*\]\]?\s*(?:#.*)?$")
KEY = re.compile(r"""^\s*((?:"[^"]*"|'[^']*'|[A-Za-z0-9_\-]+)(?:\s*\.\s*(?:"[^"]*"|'[^']*'|[A-Za-z0-9_\-]+))*)\s*=""")
KEY_PART = re.compile(r"""\s*("[^"]*"|'[^']*'|[A-Za-z0-9_\-]+)\s*(?:\.|$)""")


def split_key(text: str) -> tuple[str, ...]:
    return tuple(part.strip("\"'") for part in KEY_PART.findall(text))


@dataclass
class Located:
    start: int  # offset of the key
    end: int  # offset just after the key
    value_start: int
    value_end: int


class Locator:
    """Maps dotted key paths to the text of their key and value, well enough for error positions."""

    def __init__(self, source: SourceFile):
        self.source = source
        self.entries: dict[tuple[str, ...], Located] = {}
        self.scan()

    def scan(self) -> None:
        text = self.source.text
        table: tuple[str, ...] = ()
        offset = 0
        lines = text.split("\n")
        skip_until = -1
        for line in lines:
            start = offset
            offset += len(line) + 1
            if start < skip_until:
                continue
            header = HEADER.match(line)
            if header:
                table = split_key(header.group(1))
                key_start = start + line.index(header.group(1))
                self.entries.setdefault(table, Located(key_start, key_start + len(header.group(1)), offset, offset))
                continue
            key = KEY.match(line)
            if not key:
                continue
            key_start = start + line.index(key.group(1))
            value_start = start + key.end()
            value_end = value_extent(text, value_start)
            skip_until = value_end
            self.entries[table + split_key(key.group(1))] = Located(key_start, key_start + len(key.group(1)),
                                                                    value_start, value_end)

    def span(self, keys: tuple[str, ...], needle: str | None = None) -> Span:
        for cut in range(len(keys), -1, -1):
            found = self.entries.get(keys[:cut])
            if found is None:
                continue
            if cut == len(keys):
                if needle is not None:
                    at = find_string(self.source.text, needle, found.value_start, found.value_end)
                    if at is not None:
                        return self.source.span(*at)
                return self.source.span(found.start, found.end)
            # the rest of the path is inside an inline table or a value: look for its last key
            inner = find_string(self.source.text, keys[-1], found.value_start, found.value_end, bare=True)
            if inner is not None:
                return self.source.span(*inner)
            return self.source.span(found.start, found.end)
        return self.source.span(0, 0)


def find_string(text: str, needle: str, start: int, end: int, bare: bool = False) -> tuple[int, int] | None:
    for quoted in (f'"{needle}"', f"'{needle}'"):
        at = text.find(quoted, start, end)
        if at >= 0:
            return at, at + len(quoted)
    if bare:
        match = re.compile(rf"(?<![A-Za-z0-9_\-]){re.escape(needle)}(?![A-Za-z0-9_\-])").search(text, start, end)
        if match:
            return match.start(), match.end()
    return None


def value_extent(text: str, start: int) -> int:
    """The offset just after a TOML value starting at `start` (arrays and inline tables may span lines)."""
    depth = 0
    i = start
    n = len(text)
    while i < n:
        ch = text[i]
        if ch in "\"'":
            triple = text.startswith(ch * 3, i)
            close = text.find(ch * 3 if triple else ch, i + (3 if triple else 1))
            if close < 0:
                return n
            i = close + (3 if triple else 1)
            continue
        if ch == "#":
            newline = text.find("\n", i)
            if newline < 0 or depth == 0:
                return n if newline < 0 else newline
            i = newline
            continue
        if ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "\n" and depth <= 0:
            return i
        i += 1
    return n


# ---------------------------------------------------------------------------------------------
# The configuration of one file


@dataclass
class Resolver:
    """Settings per file: discovery (or one forced file), command-line overrides, and every
    configuration file's diagnostics collected once."""

    overrides: Overrides = field(default_factory=Overrides)
    config_file: str | None = None
    isolated: bool = False
    seen: dict[str, Loaded] = field(default_factory=dict)

    def for_path(self, path: str) -> Settings:
        if self.isolated:
            location = None
        elif self.config_file is not None:
            location = os.path.abspath(self.config_file)
        else:
            location = find(os.path.dirname(os.path.abspath(path)) or ".")
        loaded = load(location)
        if location is not None:
            self.seen.setdefault(location, loaded)
        return loaded.settings.with_overrides(self.overrides)

    def diagnostics(self) -> list[tuple[str, list[Diagnostic], SourceFile | None]]:
        return [(display_path(p), loaded.diagnostics, loaded.source) for p, loaded in self.seen.items()
                if loaded.diagnostics]
