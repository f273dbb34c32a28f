"""Machine-readable reports of a lint or check run: JSON (as `mcc check`), SARIF 2.1.0, GitHub
annotations, GitLab Code Quality, JUnit XML, and per-code statistics. Text for people is rendered
by `mcc.cli.render`.

Each report takes a list of entries with `path`, `dialect`, `diagnostics` and `source` (a
`SourceFile` or None): the lint engine's `Outcome` and the driver's `CheckResult` both fit.
"""

from __future__ import annotations

import hashlib
import os
import re
from collections import Counter
from pathlib import Path, PurePath
from urllib.parse import quote
from xml.etree import ElementTree

from mcc import __version__
from mcc.compiler.codes import registry
from mcc.compiler.diagnostics import Diagnostic, Severity
from mcc.compiler.lint.engine import Outcome

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
SARIF_LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}
GITHUB_LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}
GITLAB_SEVERITY = {Severity.ERROR: "major", Severity.WARNING: "minor", Severity.INFO: "info"}
RULES_DIR = Path(__file__).resolve().parents[2] / "docs" / "rules"  # the pages `mcc explain` prints


def help_uri(code: str, rules_url: str | None = None) -> str | None:
    """Where a code's documentation page is: `rules_url` with `{code}` filled in (e.g. the pages
    of docs/rules/ on the web server of your choice), else the page in mcc's docs/rules/ as a
    file URI when mcc runs from a checkout (the pages are generated from compiler/codes/*.toml by
    `python -m mcc.compiler.codes docs/rules`), else None."""
    if rules_url:
        return rules_url.replace("{code}", code)
    page = RULES_DIR / f"{code}.md"
    return page.as_uri() if page.is_file() else None


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


def sarif_rule(code: str, rules_url: str | None = None) -> dict:
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
    uri = help_uri(info.code, rules_url)
    if uri:
        rule["helpUri"] = uri
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
        result["fixes"] = [{
            "description": {"text": diag.fix.description},
            "artifactChanges": [{
                "artifactLocation": {"uri": artifact_uri(path)},
                "replacements": [{"deletedRegion": {"startLine": e.span.line, "startColumn": e.span.column,
                                                    "endLine": e.span.end_line, "endColumn": e.span.end_column},
                                  "insertedContent": {"text": e.text}} for e in diag.fix.edits],
            }],
        }]
    return result


def to_sarif(outcomes: list[Outcome], rules_url: str | None = None) -> dict:
    all_diags = [(o.path, d) for o in ordered(outcomes) for d in diagnostics(o)]
    codes = sorted({d.code for _, d in all_diags})
    index = {code: i for i, code in enumerate(codes)}
    return {
        "$schema": SARIF_SCHEMA,
        "version": "2.1.0",
        "runs": [{
            "tool": {"driver": {"name": "mcc", "version": __version__,
                                "rules": [sarif_rule(code, rules_url) for code in codes]}},
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


def report_path(path: str) -> str:
    """A path as CI servers want it: relative to the current directory (the repository's root
    in a CI job) when it is below it, with forward slashes."""
    full = os.path.abspath(path)
    rel = os.path.relpath(full)
    return PurePath(full if rel.startswith("..") else rel).as_posix()


def source_line(outcome, diag: Diagnostic) -> str:
    source = outcome.source
    return source.line_text(diag.span.line).strip() if source is not None else ""


def to_gitlab(outcomes: list[Outcome]) -> list[dict]:
    """GitLab Code Quality: a JSON array of findings (docs.gitlab.com, "Code Quality report
    format"). The fingerprint stays the same when lines move: it hashes the path, the code, the
    message and the text of the line, and counts repeats of the same finding."""
    issues = []
    seen: Counter[str] = Counter()
    for outcome in ordered(outcomes):
        path = report_path(outcome.path)
        for d in diagnostics(outcome):
            key = "\0".join((path, d.code, d.message, source_line(outcome, d)))
            seen[key] += 1
            fingerprint = hashlib.sha256(f"{key}\0{seen[key]}".encode("utf-8")).hexdigest()
            s = d.span
            issues.append({
                "description": f"{d.code} {d.message}",
                "check_name": d.code,
                "fingerprint": fingerprint,
                "severity": GITLAB_SEVERITY[d.severity],
                "location": {"path": path, "positions": {"begin": {"line": s.line, "column": s.column},
                                                         "end": {"line": s.end_line, "column": s.end_column}}},
            })
    return issues


XML_INVALID = re.compile("[^\t\n\r\u0020-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def xml_text(text: str) -> str:
    """Text XML 1.0 can carry: control characters quoted from a source line become U+FFFD."""
    return XML_INVALID.sub("\ufffd", text)


def to_junit(outcomes: list[Outcome]) -> str:
    """JUnit XML, as CI servers show test results: one test suite per file, one failing test case
    per finding (its type the severity), and one passing case for a file without findings."""
    suites = ElementTree.Element("testsuites", name="mcc")
    total = failures = 0
    for outcome in ordered(outcomes):
        path = report_path(outcome.path)
        found = diagnostics(outcome)
        suite = ElementTree.SubElement(suites, "testsuite", name=xml_text(path), tests=str(max(1, len(found))),
                                       failures=str(len(found)), errors="0", skipped="0")
        if not found:
            ElementTree.SubElement(suite, "testcase", name="No problems found", classname=xml_text(path))
        for d in found:
            s = d.span
            case = ElementTree.SubElement(suite, "testcase", name=f"mcc.{d.code}", classname=xml_text(path),
                                          file=xml_text(path), line=str(s.line))
            failure = ElementTree.SubElement(case, "failure", message=xml_text(d.message), type=d.severity.value)
            failure.text = xml_text(f"{path}:{s.line}:{s.column}: {d.severity.value}[{d.code}] {d.message}")
        total += max(1, len(found))
        failures += len(found)
    suites.set("tests", str(total))
    suites.set("failures", str(failures))
    ElementTree.indent(suites)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ElementTree.tostring(suites, encoding="unicode") + "\n"


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
