"""The registry of diagnostic codes.

Every diagnostic code mcc can emit is described once: its name, kind, default severity, the
dialects it applies to, and an explanation page with a bad and a good example. `mcc explain CODE`,
the SARIF rule table and `docs/rules/` are all rendered from it.

Two places hold the descriptions, never both for one code:

- `compiler/codes/*.toml`: the codes of the frontends, backends, simulator and linter, as data;
- a lint rule's own module, `compiler/lint/rules/<package>/<code>_<name>.py`, or a semantic check's,
  `compiler/checks/<dialect>/<code>_<name>.py`: its docstring *is* its page, exactly as `mcc
  explain` prints it (issue 26: "a new lint rule is one module plus its fixture"; decisions 0016,
  0021), and the registry reads the code's facts back from the page (`parse_page`). The page is
  read from the file as text, without importing the module (a `mcc explain` imports no rule or
  check), and only when the code is first asked for: `mcc check` of a clean file reads none.

Every semantic code (the 1xx) also says where it is reported (`emitted`, paths in the mcc package):
the module of its check, or the stages a TOML entry lists (`emitted = ["compiler/mcode/resolve.py"]`);
tests/checks/test_check_registry.py fails on a code reported in a file its entry does not name.
"""

from __future__ import annotations

import os
import re
import sys
from dataclasses import dataclass, field, replace
from functools import lru_cache
from pathlib import Path

from mcc.compiler import toml
from mcc.compiler.diagnostics import Kind, Severity


CODES_DIR = Path(__file__).parent / "codes"
RULES_DIR = Path(__file__).parent / "lint" / "rules"  # one package per dialect, one module per rule
CHECKS_DIR = Path(__file__).parent / "checks"  # the semantic checks: the same layout (compiler/checks/)
PACKAGE_ROOT = Path(__file__).parent.parent  # `emitted` paths are relative to it (compiler/mcode/resolve.py)
RULE_NAME = re.compile(r"^([a-z]\d{3})_([a-z0-9_]+)$")  # a rule's module: m301_position_read_while_moving
CODE = re.compile(r"[A-Z]\d{3}")  # a diagnostic code: a prefix letter, three digits


@dataclass(frozen=True)
class CodeInfo:
    code: str
    name: str
    kind: Kind
    severity: Severity
    summary: str
    explanation: str = ""
    bad: str = ""
    good: str = ""
    dialects: tuple[str, ...] = ()
    fixable: bool = False
    manual: str = ""
    # an opt-in rule runs only when its own code is selected (`extend-select = ["A315"]`), never
    # through `ALL` or a shorter prefix: a style some projects want and most do not (docs/LINT.md)
    opt_in: bool = False
    config: str = ""  # the `[tool.mcc]` configuration the examples are checked with (envelope rules)
    # where the code is reported, relative to the mcc package (not part of the page: `mcc explain`
    # is for users); a page module reports its own code
    emitted: tuple[str, ...] = field(default=(), compare=False)

    def page(self) -> str:
        """The explanation page as Markdown."""
        parts = [f"# {self.code} {self.name}", "",
                 f"{self.summary}", "",
                 f"- kind: {self.kind.value}",
                 f"- default severity: {self.severity.value}",
                 f"- dialects: {', '.join(self.dialects) or 'all'}",
                 f"- fix available: {'yes' if self.fixable else 'no'}"]
        if self.opt_in:
            parts.append(f"- opt-in: off unless selected by its code (`extend-select = [\"{self.code}\"]`)")
        if self.manual:
            parts.append(f"- manual: {self.manual}")
        if self.explanation:
            parts += ["", "## What it means", "", self.explanation.strip()]
        if self.config:
            parts += ["", "## Configuration", "", "The examples are checked with this pyproject.toml:", "",
                      "```toml", self.config.strip("\n"), "```"]
        if self.bad:
            parts += ["", "## Bad", "", "```", self.bad.strip("\n"), "```"]
        if self.good:
            parts += ["", "## Good", "", "```", self.good.strip("\n"), "```"]
        return "\n".join(parts) + "\n"


@dataclass
class Registry:
    codes: dict[str, CodeInfo] = field(default_factory=dict)
    pages: dict[str, Path] = field(default_factory=dict)  # rule modules whose page is not read yet

    def get(self, code: str) -> CodeInfo | None:
        code = code.upper()
        info = self.codes.get(code)
        if info is None and code in self.pages:
            path = self.pages.pop(code)
            info = self.codes[code] = replace(read_rule_page(path), emitted=(module_path(path),))
        return info

    def __contains__(self, code: str) -> bool:
        return code.upper() in self.codes or code.upper() in self.pages

    def __iter__(self):
        for code in list(self.pages):
            self.get(code)
        return iter(sorted(self.codes.values(), key=lambda c: c.code))

    def names(self) -> list[str]:
        """Every registered code, without reading the rule pages not read yet."""
        return sorted({*self.codes, *self.pages})


def _load_file(path: Path) -> list[CodeInfo]:
    data = toml.load_data_file(path)
    infos = []
    for raw in data.get("code", []):
        infos.append(CodeInfo(
            code=raw["code"].upper(),
            name=raw["name"],
            kind=Kind(raw["kind"]),
            severity=Severity(raw["severity"]),
            summary=raw["summary"],
            explanation=raw.get("explanation", ""),
            bad=raw.get("bad", ""),
            good=raw.get("good", ""),
            dialects=tuple(raw.get("dialects", ())),
            fixable=bool(raw.get("fixable", False)),
            manual=raw.get("manual", ""),
            opt_in=bool(raw.get("opt_in", False)),
            config=raw.get("config", ""),
            emitted=tuple(raw.get("emitted", ())),
        ))
    return infos


def module_path(path: Path) -> str:
    """A module's path as `emitted` writes it: relative to the mcc package, with slashes."""
    try:
        return path.resolve().relative_to(PACKAGE_ROOT.resolve()).as_posix()
    except ValueError:  # a page outside the package (a test's temporary module)
        return path.as_posix()


# lint rule pages -----------------------------------------------------------------------------------

def rule_modules(root: Path = RULES_DIR) -> dict[str, Path]:
    """code -> the module of the lint rule (or, with CHECKS_DIR, the check) that owns it
    (`<package>/<code>_<name>.py`), found by listing the packages (a directory listing: no file is
    read, no module imported)."""
    found: dict[str, Path] = {}
    try:
        packages = sorted(entry for entry in root.iterdir()
                          if entry.is_dir() and not entry.name.startswith(("_", ".")))
    except OSError:
        return found
    for package in packages:
        for name in sorted(os.listdir(package)):
            match = RULE_NAME.match(name[:-3]) if name.endswith(".py") else None
            if match:
                code = match.group(1).upper()
                if code in found:
                    raise ValueError(f"two lint rule modules for {code}: {found[code]} and {package / name}")
                found[code] = package / name
    return found


def module_docstring(text: str) -> str:
    """The docstring a rule module starts with, as written (a raw string: no escapes)."""
    body = text.lstrip("\ufeff")
    for opening in ('r"""', '"""'):
        if body.startswith(opening):
            end = body.find('"""', len(opening))
            if end >= 0:
                return body[len(opening):end]
    return ""


def read_rule_page(path: Path) -> CodeInfo:
    """The CodeInfo of the rule in `path`, read from its docstring; its code and name must be the
    ones its file is named after (a test checks every module; this keeps a wrong one from loading)."""
    info = parse_page(module_docstring(path.read_text(encoding="utf-8")), str(path))
    match = RULE_NAME.match(path.stem)
    if match is None or (info.code.lower(), info.name.replace("-", "_")) != match.groups():
        raise ValueError(f"{path}: the page is {info.code} {info.name}, the file name says otherwise")
    return info


PAGE_FACTS = {"kind", "default severity", "dialects", "fix available", "opt-in", "manual"}
CONFIG_INTRO = "The examples are checked with this pyproject.toml:"


def parse_page(text: str, where: str = "page") -> CodeInfo:
    """A code's facts from its page, the Markdown `CodeInfo.page` writes (the inverse of `page`:
    tests/lint/test_rule_modules.py checks `parse_page(p).page() == p` for every rule module)."""
    lines = text.split("\n")

    def fail(why: str) -> ValueError:
        return ValueError(f"{where}: {why} (write the page as `mcc explain` prints it: docs/LINT.md)")

    title = re.fullmatch(r"# ([A-Z]\d{3}) ([a-z0-9-]+)", lines[0] if lines else "")
    if title is None or len(lines) < 4 or lines[1] or lines[3]:
        raise fail("the page must start with '# CODE name', a blank line, the summary and a blank line")
    facts: dict[str, str] = {}
    at = 4
    while at < len(lines) and lines[at].startswith("- "):
        key, _, value = lines[at][2:].partition(": ")
        if key not in PAGE_FACTS:
            raise fail(f"unknown fact '- {key}:'")
        facts[key] = value
        at += 1
    sections: dict[str, str] = {}
    current = None
    for line in lines[at:]:
        heading = re.fullmatch(r"## (.+)", line)
        if heading:
            current = heading.group(1)
            sections[current] = ""
        elif current is not None:
            sections[current] += line + "\n"
        elif line:
            raise fail(f"text before the first section: {line!r}")
    unknown = set(sections) - {"What it means", "Configuration", "Bad", "Good"}
    if unknown:
        raise fail(f"unknown section '## {sorted(unknown)[0]}'")

    def block(name: str, fence: str = "```") -> str:
        body = sections.get(name, "").strip("\n")
        if name == "Configuration" and body:
            intro, _, body = body.partition("\n\n")
            if intro != CONFIG_INTRO:
                raise fail(f"the configuration section starts with '{CONFIG_INTRO}'")
        if not body:
            return ""
        if not (body.startswith(fence + "\n") and body.endswith("\n```")):
            raise fail(f"'## {name}' holds one {fence} block")
        return body[len(fence) + 1:-3]  # the example with its last newline, as a program file ends

    dialects = facts.get("dialects", "all")
    try:
        return CodeInfo(
            code=title.group(1), name=title.group(2), kind=Kind(facts.get("kind", "lint")),
            severity=Severity(facts.get("default severity", "")), summary=lines[2],
            explanation=sections["What it means"].strip("\n") + "\n" if "What it means" in sections else "",
            bad=block("Bad"), good=block("Good"),
            dialects=() if dialects == "all" else tuple(d.strip() for d in dialects.split(",")),
            fixable=facts.get("fix available") == "yes", manual=facts.get("manual", ""),
            opt_in="opt-in" in facts, config=block("Configuration", "```toml"),
        )
    except ValueError as exc:
        raise fail(str(exc)) from None


@lru_cache(maxsize=1)
def registry() -> Registry:
    reg = Registry()
    for path in sorted(CODES_DIR.glob("*.toml")):
        for info in _load_file(path):
            if info.code in reg.codes:
                raise ValueError(f"{path.name}: duplicate diagnostic code {info.code}")
            reg.codes[info.code] = info
    for code, path in [*rule_modules().items(), *rule_modules(CHECKS_DIR).items()]:
        if code in reg.codes or code in reg.pages:
            raise ValueError(f"{code} is described twice: in {reg.pages.get(code, 'compiler/codes/')} and in {path}")
        reg.pages[code] = path
    return reg


def write_docs(directory: Path) -> list[Path]:
    """Render one Markdown page per code into `directory` (docs/rules/) plus an index."""
    directory.mkdir(parents=True, exist_ok=True)
    written = []
    lines = ["# Diagnostic codes", "", "One page per code; `mcc explain CODE` prints the same text.", "",
             "| code | name | kind | severity | dialects | summary |", "|---|---|---|---|---|---|"]
    for info in registry():
        path = directory / f"{info.code}.md"
        path.write_text(info.page(), encoding="utf-8")
        written.append(path)
        lines.append(f"| [{info.code}]({info.code}.md) | {info.name} | {info.kind.value} | "
                     f"{info.severity.value} | {', '.join(info.dialects) or 'all'} | {info.summary} |")
    index = directory / "README.md"
    index.write_text("\n".join(lines) + "\n", encoding="utf-8")
    written.append(index)
    return written


if __name__ == "__main__":  # python -m mcc.compiler.codes docs/rules
    for p in write_docs(Path(sys.argv[1] if len(sys.argv) > 1 else "docs/rules")):
        print(p)
