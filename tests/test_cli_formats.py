"""Report formats of `mcc check` and `mcc lint` for CI servers and tools, run as a user runs them:
GitLab Code Quality, JUnit XML, the JSON fix edits and the SARIF rules' help links (docs/CLI.md,
"Report formats"). The programs are MCode: `BR G9` names a label never defined (lexium-mcode.txt
L618, "BR G1 `Unconditional Branch to G1"), `=<` is a comparison spelt the other way round (fixed to `<=`),
and a program stored with PG but never saved with S warns (L5269: "adding an S after the
final PG")."""

from __future__ import annotations

import json
from pathlib import Path
from xml.etree import ElementTree

import pytest

from conftest import run_mcc

BAD = "PG 1\nLB G1\n  MA 100\n  BR G9\n  E\nPG\n"  # M106 (error) and M309 (warning)
CLEAN = "VA Q1\nPR Q1\n"
FIXABLE = "PG 100\n  BR G1,I5=<100\n  LB G1\nE\nPG\nS\n"


def write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("command", ["lint", "check"])
def test_gitlab_code_quality(tmp_path: Path, command: str) -> None:
    write(tmp_path / "bad.mxt", BAD)
    result = run_mcc(command, "--format", "gitlab", "bad.mxt", cwd=tmp_path)
    assert result.returncode == 1
    issues = json.loads(result.stdout)
    codes = {i["check_name"]: i for i in issues}
    assert "M106" in codes
    m106 = codes["M106"]
    assert m106["severity"] == "major" and m106["description"].startswith("M106 label G9 is not defined")
    assert m106["location"] == {"path": "bad.mxt", "positions": {"begin": {"line": 4, "column": 6},
                                                                "end": {"line": 4, "column": 8}}}
    if command == "lint":
        assert codes["M309"]["severity"] == "minor"
    # the fingerprint follows the finding, not its line number: a line added above keeps it
    write(tmp_path / "bad.mxt", "' a comment\n" + BAD)
    moved = json.loads(run_mcc(command, "--format", "gitlab", "bad.mxt", cwd=tmp_path).stdout)
    assert {i["fingerprint"] for i in moved} == {i["fingerprint"] for i in issues}


def test_gitlab_fingerprints_of_repeated_findings_differ(tmp_path: Path) -> None:
    write(tmp_path / "twice.mxt", "PG 1\n  BR G9\n  BR G9\n  E\nPG\nS\n' end\n")
    issues = json.loads(run_mcc("lint", "--format", "gitlab", "twice.mxt", cwd=tmp_path).stdout)
    fingerprints = [i["fingerprint"] for i in issues if i["check_name"] == "M106"]
    assert len(fingerprints) == 2 and len(set(fingerprints)) == 2


@pytest.mark.parametrize("command", ["lint", "check"])
def test_junit_xml(tmp_path: Path, command: str) -> None:
    write(tmp_path / "bad.mxt", BAD)
    write(tmp_path / "ok.mxt", CLEAN)
    result = run_mcc(command, "--format", "junit", "bad.mxt", "ok.mxt", cwd=tmp_path)
    assert result.returncode == 1
    root = ElementTree.fromstring(result.stdout)
    assert root.tag == "testsuites"
    suites = {s.get("name"): s for s in root.findall("testsuite")}
    assert set(suites) == {"bad.mxt", "ok.mxt"}
    failures = suites["bad.mxt"].findall("testcase/failure")
    assert failures and int(suites["bad.mxt"].get("failures")) == len(failures)
    case = next(c for c in suites["bad.mxt"].findall("testcase") if c.get("name") == "mcc.M106")
    assert case.get("line") == "4" and case.find("failure").get("type") == "error"
    assert "bad.mxt:4:6: error[M106]" in case.find("failure").text
    ok_cases = suites["ok.mxt"].findall("testcase")
    assert len(ok_cases) == 1 and ok_cases[0].find("failure") is None
    assert int(root.get("failures")) == len(failures)


def test_junit_is_valid_xml_whatever_the_file_holds(tmp_path: Path) -> None:
    """Control characters are not XML 1.0: a program holding them still gives a parsable report."""
    write(tmp_path / "ctl.mxt", 'PR "a\x01b"\nMX\x02\n')
    result = run_mcc("lint", "--format", "junit", "ctl.mxt", cwd=tmp_path)
    assert ElementTree.fromstring(result.stdout).find("testsuite/testcase/failure") is not None


def apply_edits(text: str, edits: list[dict]) -> str:
    lines = text.splitlines(keepends=True)
    starts = [0]
    for line in lines:
        starts.append(starts[-1] + len(line))

    def offset(line: int, column: int) -> int:
        return starts[line - 1] + column - 1 if line - 1 < len(starts) else len(text)

    for edit in sorted(edits, key=lambda e: (e["line"], e["column"]), reverse=True):
        start, end = offset(edit["line"], edit["column"]), offset(edit["end_line"], edit["end_column"])
        text = text[:start] + edit["content"] + text[end:]
    return text


def test_json_fixes_carry_their_edits_and_applying_them_is_what_fix_writes(tmp_path: Path) -> None:
    path = write(tmp_path / "a.mxt", FIXABLE)
    report = json.loads(run_mcc("lint", "--format", "json", str(path)).stdout)
    fixes = [d["fix"] for d in report["files"][0]["diagnostics"] if "fix" in d]
    safe = [f for f in fixes if f["applicability"] == "safe"]
    assert safe and all({"message", "applicability", "edits"} <= set(f) for f in fixes)
    assert all({"content", "line", "column", "end_line", "end_column"} == set(e) for f in fixes for e in f["edits"])
    expected = apply_edits(FIXABLE, [e for f in safe for e in f["edits"]])
    assert run_mcc("lint", "--fix", str(path)).returncode in (0, 1)
    assert path.read_text(encoding="utf-8") == expected


@pytest.mark.parametrize("command", ["lint", "check"])
def test_sarif_rules_link_to_their_documentation_page(tmp_path: Path, command: str) -> None:
    write(tmp_path / "bad.mxt", BAD)
    sarif = json.loads(run_mcc(command, "--format", "sarif", "bad.mxt", cwd=tmp_path).stdout)
    rules = {r["id"]: r for r in sarif["runs"][0]["tool"]["driver"]["rules"]}
    uri = rules["M106"]["helpUri"]
    assert uri.startswith("file://") and uri.endswith("/docs/rules/M106.md")
    from urllib.parse import unquote, urlparse

    page = Path(unquote(urlparse(uri).path))
    assert page.read_text(encoding="utf-8").startswith("# M106 ")  # the page `mcc explain M106` prints
    custom = run_mcc(command, "--format", "sarif", "--rules-url", "https://mcc.example/rules/{code}.html",
                     "bad.mxt", cwd=tmp_path)
    rules = json.loads(custom.stdout)["runs"][0]["tool"]["driver"]["rules"]
    assert {r["helpUri"] for r in rules} >= {"https://mcc.example/rules/M106.html"}


def test_sarif_results_carry_fixes(tmp_path: Path) -> None:
    write(tmp_path / "a.mxt", FIXABLE)
    sarif = json.loads(run_mcc("lint", "--format", "sarif", "a.mxt", cwd=tmp_path).stdout)
    fixed = [r for r in sarif["runs"][0]["results"] if "fixes" in r]
    assert fixed
    change = fixed[0]["fixes"][0]["artifactChanges"][0]
    assert change["artifactLocation"]["uri"] == "a.mxt"
    assert {"deletedRegion", "insertedContent"} <= set(change["replacements"][0])
