"""The registry of diagnostic codes.

Every diagnostic code mcc can emit is described once, as data, in `compiler/codes/*.toml`: its
name, kind, default severity, the dialects it applies to, and an explanation page with a bad and a
good example. `mcc explain CODE`, the SARIF rule table and `docs/rules/` are all rendered from it.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

from mcc.compiler import toml
from mcc.compiler.diagnostics import Kind, Severity


CODES_DIR = Path(__file__).parent / "codes"


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

    def get(self, code: str) -> CodeInfo | None:
        return self.codes.get(code.upper())

    def __contains__(self, code: str) -> bool:
        return code.upper() in self.codes

    def __iter__(self):
        return iter(sorted(self.codes.values(), key=lambda c: c.code))


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
        ))
    return infos


@lru_cache(maxsize=1)
def registry() -> Registry:
    reg = Registry()
    for path in sorted(CODES_DIR.glob("*.toml")):
        for info in _load_file(path):
            if info.code in reg.codes:
                raise ValueError(f"{path.name}: duplicate diagnostic code {info.code}")
            reg.codes[info.code] = info
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
