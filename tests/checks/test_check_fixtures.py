"""Every registered semantic check runs on its fixture (issue 26: a check is one module plus its
fixture, as a lint rule is).

`tests/checks/fixtures/<CODE>.<ext>` is a small program of the check's dialect whose header comment
cites the manual lines the check rests on. Each line that must be reported carries an annotation
in a comment, `<severity>: <CODE>` (`' error: M106`, `; warning: X127`), in the format of the lint
fixtures (tests/lint/test_rule_fixtures.py). The file is checked as `mcc check` checks it, with its
dialect's default profile, and every diagnostic it gets must be annotated, and every annotation
reported: the fixture shows its check's code, and the codes the check also reports (`also`), and
nothing else.

A check without a fixture or a fixture without a check fails
`test_every_check_has_one_fixture_and_every_fixture_a_check`.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from fixture_annotations import MANUAL_LINE, expected

from mcc.compiler import checks, dialects, profiles
from mcc.compiler.span import SourceFile

FIXTURES = Path(__file__).parent / "fixtures"
CHECKS = checks.load_all()


def fixture_of(code: str) -> Path:
    found = sorted(FIXTURES.glob(f"{code}.*"))
    assert len(found) == 1, f"{code} needs exactly one fixture tests/checks/fixtures/{code}.<ext>, found {found}"
    return found[0]


def test_every_check_has_one_fixture_and_every_fixture_a_check() -> None:
    codes = {p.name.split(".")[0] for p in FIXTURES.iterdir() if not p.name.startswith(".")}
    assert codes == set(CHECKS), (f"checks without a fixture: {sorted(set(CHECKS) - codes)}; "
                                  f"fixtures without a check: {sorted(codes - set(CHECKS))}")
    for code in CHECKS:
        dialect = dialects.from_path(fixture_of(code).name)
        assert dialect is not None and dialect.name == CHECKS[code].dialect, f"{fixture_of(code).name}: not {code}'s dialect"


@pytest.mark.parametrize("code", sorted(CHECKS))
def test_check_reports_exactly_the_annotated_lines(code: str) -> None:
    path = fixture_of(code)
    text = path.read_text(encoding="utf-8")
    head = "\n".join(text.splitlines()[:3])
    assert MANUAL_LINE.search(head), \
        f"{path.name}: the header comment cites the manual line the check rests on"
    dialect = dialects.from_path(path.name)
    analysis = dialect.load_frontend().analyze(SourceFile(path.name, text), profiles.load(dialect.default_profile))
    wanted = expected(text, dialect.comment)
    assert (code in {c for _, _, c in wanted}), f"{path.name} annotates no {code}: show at least one finding"
    assert {c for _, _, c in wanted} <= set(CHECKS[code].codes), f"{path.name} annotates another check's code"
    reported = {(d.span.line, d.severity.value, d.code) for d in analysis.diagnostics}
    assert reported == wanted, (f"{path.name}: reported but not annotated {sorted(reported - wanted)}, "
                                f"annotated but not reported {sorted(wanted - reported)}")
