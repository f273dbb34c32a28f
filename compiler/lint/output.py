"""Machine-readable reports of a lint run: JSON (as `mcc check`), SARIF 2.1.0, GitHub annotations,
and per-code statistics. Text for people is rendered by `mcc.cli.render`.
"""

from __future__ import annotations

from collections import Counter
from pathlib import PurePath
from urllib.parse import quote

from mcc import __version__
from mcc.compiler.codes import registry
from mcc.compiler.diagnostics import Diagnostic, Severity
from mcc.compiler.lint.engine import Outcome

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
SARIF_LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}
GITHUB_LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}


def ordered(outcomes: list[Outcome]) -> list[Outcome]:
    return sorted(outcomes, key=lambda o: o.path)


def diagnostics(outcome: Outcome) -> list[Diagnostic]:
    return sorted(outcome.diagnostics, key=Diagnostic.sort_key)


def to_json(outcomes: list[Outcome]) -> dict:
    """The shape of `mcc check --format json`."""
    return {"files": [{"path": o.path, "dialect": o.dialect, "diagnostics": [d.to_json() for d in diagnostics(o)]}
                      for o in ordered(outcomes)]}


def artifact_uri(path: str) -> str:
    pure = PurePath(path)
    if pure.is_absolute():
        return pure.as_uri()
    return quote(pure.as_posix())


def sarif_rule(code: str) -> dict:
    info = registry().get(code)
    if info is None:
        return {"id": code}
    rule = {
        "id": info.code,
        "name": info.name,
        "shortDescription": {"text": info.summary},
        "fullDescription": {"text": " ".join(info.explanation.split()) or info.summary},
        "help": {"text": info.page(), "markdown": info.page()},
        "defaultConfiguration": {"level": SARIF_LEVEL[info.severity]},
        "properties": {"tags": [info.kind.value, *info.dialects]},
    }
    return rule


def sarif_result(diag: Diagnostic, path: str, index: int) -> dict:
    span = diag.span
    region = {"startLine": span.line, "startColumn": span.column,
              "endLine": span.end_line, "endColumn": max(span.end_column, span.column)}
    result = {
        "ruleId": diag.code,
        "ruleIndex": index,
        "level": SARIF_LEVEL[diag.severity],
        "message": {"text": diag.message},
        "locations": [{"physicalLocation": {"artifactLocation": {"uri": artifact_uri(path)}, "region": region}}],
    }
    if diag.fix is not None:
        result["properties"] = {"fix": diag.fix.description, "fixSafe": diag.fix.safe}
    return result


def to_sarif(outcomes: list[Outcome]) -> dict:
    all_diags = [(o.path, d) for o in ordered(outcomes) for d in diagnostics(o)]
    codes = sorted({d.code for _, d in all_diags})
    index = {code: i for i, code in enumerate(codes)}
    return {
        "$schema": SARIF_SCHEMA,
        "version": "2.1.0",
        "runs": [{
            "tool": {"driver": {"name": "mcc", "version": __version__,
                                "rules": [sarif_rule(code) for code in codes]}},
            "results": [sarif_result(d, path, index[d.code]) for path, d in all_diags],
            "columnKind": "unicodeCodePoints",
        }],
    }


def escape_data(text: str) -> str:
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def escape_property(text: str) -> str:
    return escape_data(text).replace(":", "%3A").replace(",", "%2C")


def to_github(outcomes: list[Outcome]) -> list[str]:
    """GitHub Actions workflow commands: one `::error ...::message` line per diagnostic."""
    lines = []
    for outcome in ordered(outcomes):
        for d in diagnostics(outcome):
            s = d.span
            props = (f"file={escape_property(outcome.path)},line={s.line},col={s.column},endLine={s.end_line},"
                     f"endColumn={s.end_column},title={escape_property(d.code)}")
            lines.append(f"::{GITHUB_LEVEL[d.severity]} {props}::{escape_data(d.message)}")
    return lines


def statistics(outcomes: list[Outcome]) -> list[dict]:
    """Count per code, most frequent first: code, name, severity, count, fixable."""
    counts: Counter[str] = Counter()
    fixable: Counter[str] = Counter()
    severity: dict[str, str] = {}
    for outcome in outcomes:
        for d in outcome.diagnostics:
            counts[d.code] += 1
            severity.setdefault(d.code, d.severity.value)
            if d.fix is not None:
                fixable[d.code] += 1
    rows = []
    for code, count in sorted(counts.items(), key=lambda kv: (-kv[1], kv[0])):
        info = registry().get(code)
        rows.append({"code": code, "name": info.name if info else "", "severity": severity[code],
                     "count": count, "fixable": fixable[code]})
    return rows
