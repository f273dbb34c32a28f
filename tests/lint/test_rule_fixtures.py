"""Every lint rule runs on its fixture (issue 26: a rule is one module plus its fixture).

`tests/lint/fixtures/<CODE>.<ext>` is a small program of one of the rule's dialects whose header
comment cites the manual lines the rule rests on. Each line the rule must report carries an
annotation in a comment, `<severity>: <CODE>` (`' warning: M301`, `; error: A306`); every other
line must not be reported. The rule runs alone (only its code selected; an envelope rule with the
configuration its page gives), and the lines, severities and codes it reports must equal the
annotations. A fixable rule also has `<CODE>.fixed.<ext>`: the fixture with every fix the rule
offers applied once, unsafe ones included. `MCC_UPDATE_SNAPSHOTS=1` rewrites the `.fixed` files
from what the rules do now (review the diff before committing it).

A rule without a fixture, a fixture without a rule, a snapshot of a rule without a fix or a
fixable rule without a snapshot fails `test_every_rule_has_one_fixture_and_every_fixture_a_rule`.
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

import pytest
from fixture_annotations import MANUAL_LINE, expected

from mcc.compiler import config, dialects
from mcc.compiler.codes import registry
from mcc.compiler.config import Settings
from mcc.compiler.lint import engine, fixes
from mcc.compiler.lint.rules import load_all

FIXTURES = Path(__file__).parent / "fixtures"
RULES = sorted(load_all())
UPDATE = os.environ.get("MCC_UPDATE_SNAPSHOTS") == "1"


def fixture_of(code: str) -> Path:
    found = [p for p in FIXTURES.glob(f"{code}.*") if ".fixed." not in p.name]
    assert len(found) == 1, f"{code} needs exactly one fixture tests/lint/fixtures/{code}.<ext>, found {found}"
    return found[0]


def fixed_of(path: Path) -> Path:
    return path.with_name(f"{path.stem}.fixed{path.suffix}")


def dialect_of(path: Path) -> dialects.Dialect:
    found = dialects.from_path(path.name)
    assert found is not None, f"{path.name}: not an extension of any dialect"
    return found


def settings_for(code: str) -> Settings:
    """Only `code` selected (an opt-in rule is enabled by its own code), with the configuration its
    page's examples are checked with (the envelope rules need an envelope)."""
    selection = config.Selection((config.Layer(select=(code,)),))
    info = registry().get(code)
    if not info.config:
        return Settings(selection=selection)
    loaded = config.parse(info.config, "pyproject.toml")
    assert not loaded.diagnostics, f"{code}'s page gives an invalid configuration"
    return dataclasses.replace(loaded.settings, selection=selection)


def run(code: str):
    path = fixture_of(code)
    text = path.read_text(encoding="utf-8")
    _, diags = engine.lint_text(path.name, text, settings_for(code))
    return path, text, diags


def test_every_rule_has_one_fixture_and_every_fixture_a_rule() -> None:
    names = sorted(p.name for p in FIXTURES.iterdir() if not p.name.startswith("."))
    codes = {name.split(".")[0] for name in names}
    assert codes == set(RULES), (f"rules without a fixture: {sorted(set(RULES) - codes)}; "
                                 f"fixtures without a rule: {sorted(codes - set(RULES))}")
    for code in RULES:
        path = fixture_of(code)
        assert dialect_of(path).name in registry().get(code).dialects, f"{path.name}: not a dialect of {code}"
        assert fixed_of(path).exists() == registry().get(code).fixable, \
            f"{code}: a fixable rule has a {fixed_of(path).name} snapshot, and only a fixable rule"
    expected_names = {fixture_of(c).name for c in RULES} | {fixed_of(fixture_of(c)).name for c in RULES
                                                            if registry().get(c).fixable}
    assert set(names) == expected_names, f"unexpected files: {sorted(set(names) - expected_names)}"


@pytest.mark.parametrize("code", RULES)
def test_rule_reports_exactly_the_annotated_lines(code: str) -> None:
    path, text, diags = run(code)
    head = "\n".join(text.splitlines()[:3])
    assert MANUAL_LINE.search(head), \
        f"{path.name}: the header comment cites the manual line the rule rests on"
    others = [(d.code, d.span.line, d.message) for d in diags if d.code != code]
    assert not others, f"{path.name} must be a program the frontend reads: {others}"
    wanted = expected(text, dialect_of(path).comment)
    assert wanted, f"{path.name} annotates no line: show at least one finding"
    assert {code for _, _, code in wanted} == {code}, f"{path.name} annotates another rule's code"
    reported = {(d.span.line, d.severity.value, d.code) for d in diags}
    assert reported == wanted, (f"{path.name}: reported but not annotated {sorted(reported - wanted)}, "
                                f"annotated but not reported {sorted(wanted - reported)}")


@pytest.mark.parametrize("code", [c for c in RULES if registry().get(c).fixable])
def test_fixes_give_the_snapshot(code: str) -> None:
    path, text, diags = run(code)
    offered = [d.fix for d in diags if d.code == code and d.fix is not None]
    assert offered, f"{code} is fixable but offers no fix on {path.name}"
    fixed, applied = fixes.apply(text, offered)
    assert applied == len(offered), f"{path.name}: fixes that overlap each other"
    snapshot = fixed_of(path)
    if UPDATE:
        snapshot.write_text(fixed, encoding="utf-8")
    assert fixed != text
    assert fixed == snapshot.read_text(encoding="utf-8"), \
        f"{snapshot.name} is stale: MCC_UPDATE_SNAPSHOTS=1 pytest {__file__} rewrites it (review the diff)"
