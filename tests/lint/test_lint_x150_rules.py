"""X150 lint rules with cases beyond their documented bad/good pair (test_lint_registry.py) and
beyond their fixture (tests/lint/fixtures/, test_rule_fixtures.py, which every rule must have)."""

from __future__ import annotations

import pytest

from conftest import sample_files
from helpers import codes, lint

SEQ = "1XE1\n1XD1\n{body}1XT\n"


def seq(body: str) -> str:
    return SEQ.format(body=body)


CASES = [
    ("X301",  # the settings are made on one branch only
     seq("1IF(VAR1>1)\n1A10\n1V5\n1NIF\n1D100\n1G\n"),
     "1A10 1V5\n" + seq("1D100\n1G\n")),  # the set-up stream before the sequence counts
    ("X301",  # a called sequence starts with what holds at every call
     "1XE2\n1XD2\n1D10\n1G\n1XT\n" + seq("1XR2\n"),
     "1XE2\n1XD2\n1D10\n1G\n1XT\n" + seq("1A1\n1V1\n1XR2\n")),
    ("X302",
     seq("1L0\n1A1 1V1 1D1 1G\n1N\n"),
     seq("1L\n1A1 1V1 1D1 1G\n1IF(IN_1)\n1XG2\n1NIF\n1N\n")),
    ("X303",
     seq("1T1\n") + "1XE9\n1XD9\n1T1\n1XT\n1XP1\n",
     seq("1T1\n") + "1XE9\n1XD9\n1T1\n1XT\n1XP1\n1XR(VAR1)\n"),  # chosen at run time: not checked
    ("X304",
     seq("; explain\n1T1\n"),
     "; explain\n" + seq("1T1\n")),
    ("X305",
     seq("1T1\n") + "1XWHEN1\n1WHEN(IN_1)\n",
     seq("1T1\n1XR2\n") + "1XE2\n1XD2\n1WHEN(IN_1)\n1XT\n1XWHEN1\n1WHEN(IN_1)\n"),
    ("X306",
     seq("1WHEN(IN_X1)\n"),
     seq("1WHEN(IN_X1)\n") + "1XWHEN1\n"),
    ("X307",
     seq("1A1 1V1 1MC 1G\n"),
     seq("1A1 1V1 1MC 1G\n1T2\n1V0\n")),
    ("X308",
     "1VAR1=VAR2+VAR3/2\n",
     "1VAR1=VAR2*VAR3/2\n1VAR4=VAR1*2+1\n"),
    ("X309",
     seq("1VAR2=VAR1/0\n"),
     seq("1VAR2=VAR1/3\n")),
    ("X310",
     seq("1A1 1V1\n1OFF\n1D100 1G\n"),
     seq("1A1 1V1\n1OFF\n1ON\n1D100 1G\n")),
    ("X311",
     seq("1MN 1MPA 1A1 1V1\n1D500 1G\n1L3\n1G\n1N\n"),
     seq("1MN 1MPI 1A1 1V1\n1D500 1G\n1L3\n1G\n1N\n")),
    ("X312",
     seq("1A1 1V1\n1H 1D+100 1G\n"),
     seq("1A1 1V1\n1D+100 1G\n1H 1G\n")),
    ("X313",
     "1V0\n" + seq("1A1\n1D100 1G\n"),
     "1V0\n" + seq("1A1\n1V3\n1D100 1G\n")),
]


@pytest.mark.parametrize("code,bad,good", CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)])
def test_rule_reports_bad_and_accepts_good(code: str, bad: str, good: str) -> None:
    assert code in codes(bad, "p.x150"), lint(bad, "p.x150")
    assert code not in codes(good, "p.x150"), [(d.code, d.span.line, d.message) for d in lint(good, "p.x150")]


def test_comments_in_one_sequence_are_reported_once() -> None:
    found = [d for d in lint(seq("1T1 ; a\n; b\n1T2 ; c\n"), "p.x150") if d.code == "X304"]
    assert len(found) == 1 and found[0].notes == ("2 more comments in this sequence",)


def test_samples_have_no_lint_errors() -> None:
    for path in sample_files("x150"):
        diags = lint(path.read_text(encoding="utf-8"), path.name)
        assert not [d for d in diags if d.severity.value == "error"], (path, diags)
