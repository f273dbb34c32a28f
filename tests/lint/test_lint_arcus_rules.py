"""Arcus lint rules with cases beyond their documented bad/good pair (test_lint_registry.py) and
beyond their fixture (tests/lint/fixtures/, test_rule_fixtures.py, which every rule must have)."""

from __future__ import annotations

import pytest

from helpers import codes, lint
from conftest import sample_files

SPEEDS = "HSPD=20000\nLSPD=500\nACC=300\n"

CASES = [
    ("A301",  # the read is in a condition, and only WAITY was done
     SPEEDS + "X1000Y1000\nWAITY\nIF PX>500\nDO1=1\nENDIF\nEND\n",
     SPEEDS + "X1000Y1000\nWAITX\nWAITY\nIF PX>500\nDO1=1\nENDIF\nEND\n"),
    ("A301",  # polling MSTX is waiting; reading the speed while jogging is fine
     SPEEDS + "HOMEX+\nV1=EX\nEND\n",
     SPEEDS + "X1000\nWHILE MSTX!=0\nDELAY=5\nENDWHILE\nV1=PX\nJOGY+\nV2=PSY\nSTOPY\nEND\n"),
    ("A302",  # only one path sets the speeds
     "IF DI1=1\n" + SPEEDS + "ENDIF\nX1000\nEND\n",
     "HSPDX=1000\nLSPDX=10\nACCX=100\nX1000\nEND\n"),  # all three per axis is enough (L449-L457)
    ("A302",  # a subroutine that moves before its caller set the speeds
     "GOSUB 1\n" + SPEEDS + "END\nSUB 1\nX100\nENDSUB\n",
     SPEEDS + "GOSUB 1\nEND\nSUB 1\nX100\nENDSUB\n"),
    ("A303",
     "V1=0\nWHILE V1<1000\nV1=V1+1\nENDWHILE\nEND\n",
     SPEEDS + "WHILE DI1=0\nX100\nWAITX\nENDWHILE\nEND\n"),
    ("A304",  # S-curve set on one branch
     "IF DI1=1\nSCVY=1\nENDIF\nSSPDMY=1\nSSPDY=5000\nEND\n",
     "SCVY=1\nSSPDMX=1\nSSPDX=5000\nEND\n"),
    ("A305",
     SPEEDS + "JOGX+\nSTOPX\nEND\n",
     "EO1=1\n" + SPEEDS + "JOGX+\nSTOPX\nEND\n"),
    ("A306",  # indirect recursion
     "GOSUB 1\nEND\nSUB 1\nGOSUB 2\nENDSUB\nSUB 2\nGOSUB 1\nENDSUB\n",
     "GOSUB 1\nEND\nSUB 1\nGOSUB 2\nENDSUB\nSUB 2\nDO1=1\nENDSUB\n"),
    ("A307",
     "END\nSUB 5\nDO1=1\nENDSUB\n",
     "GOSUB 5\nEND\nSUB 5\nDO1=1\nENDSUB\n"),
    ("A308",  # written on one branch only
     "IF DI1=1\nV1=5\nENDIF\nV2=V1\nEND\n",
     "IF DI1=1\nV1=5\nELSE\nV1=6\nENDIF\nV2=V1\nEND\n"),
    ("A308",  # a subroutine reads what its caller did not write
     "GOSUB 1\nEND\nSUB 1\nV2=V1\nENDSUB\n",
     "V1=1\nGOSUB 1\nEND\nSUB 1\nV2=V1\nENDSUB\n"),
    ("A309",
     "V1=7\nV2=V1%0\nEND\n",
     "V1=7\nV2=V1%3\nEND\n"),
    ("A310",
     SPEEDS + "ABS\nIF DI1=1\nINC\nENDIF\nARCP0:100:90000\nWAITX\nEND\n",
     SPEEDS + "INC\nX100\nWAITX\nABS\nARCP0:100:90000\nWAITX\nEND\n"),
    ("A311",
     SPEEDS + "SSPDMZ=3\nJOGZ+\nSSPDZ=50000\nSTOPZ\nWAITZ\nHOMEZ-\nEND\n",
     SPEEDS + "SSPDMZ=3\nJOGZ+\nSSPDZ=50000\nSTOPZ\nWAITZ\nSSPDMZ=0\nHOMEZ-\nEND\n"),
    ("A312",
     "SYNYO\nDO=255\nEND\n",
     "SYNYO\nSYNYF\nDO=255\nEND\n"),
    ("A313",
     "V1=1\nWHILE 2<1\nV1=2\nENDWHILE\nEND\n",
     "V1=1\nIF V1<1\nV1=2\nENDIF\nEND\n"),
    ("A314",
     SPEEDS + "JOGU-\nSTOPX\nEND\n",
     SPEEDS + "JOGU-\nDELAY=500\nSTOP\nEND\n"),
    ("A315",
     "DO1=1  ; lamp on\nEND\n",
     "; lamp on\nDO1=1\nEND\n"),
]


@pytest.mark.parametrize("code,bad,good", CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)])
def test_rule_reports_bad_and_accepts_good(code: str, bad: str, good: str) -> None:
    assert code in codes(bad, "p.prg"), lint(bad, "p.prg")
    assert code not in codes(good, "p.prg"), [(d.code, d.span.line, d.message) for d in lint(good, "p.prg")]


def test_move_before_speed_is_reported_once_per_routine() -> None:
    found = [d for d in lint("X1\nX2\nX3\nEND\n", "p.prg") if d.code == "A302"]
    assert [d.span.line for d in found] == [1]


def test_unused_subroutine_fix_deletes_the_block() -> None:
    from mcc.compiler.lint import fixes

    text = "END\n; helper\nSUB 5\nDO1=1\nENDSUB\n"
    diag = next(d for d in lint(text, "p.prg") if d.code == "A307")
    assert not diag.fix.safe
    assert fixes.apply(text, [diag.fix])[0] == "END\n; helper\n"


def test_trailing_comment_fix_moves_the_comment_above() -> None:
    from mcc.compiler.lint import fixes

    text = "WHILE 1=1\n  DO1=1   ; lamp\nENDWHILE\n"
    diag = next(d for d in lint(text, "p.prg") if d.code == "A315")
    assert fixes.apply(text, [diag.fix])[0] == "WHILE 1=1\n  ; lamp\n  DO1=1\nENDWHILE\n"


def test_samples_have_no_lint_errors() -> None:
    for path in sample_files("arcus"):
        diags = lint(path.read_text(encoding="utf-8"), path.name)
        assert not [d for d in diags if d.severity.value == "error"], (path, diags)
