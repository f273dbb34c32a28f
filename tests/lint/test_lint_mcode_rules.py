"""MCode lint rules with cases beyond their documented bad/good pair (those run in
test_lint_registry.py) and beyond their fixture (tests/lint/fixtures/, test_rule_fixtures.py,
which every rule must have): the situations that make a rule wrong when it is too simple."""

from __future__ import annotations

import pytest

from helpers import codes, lines_of, lint

# (code, program that must be reported, program that must not be)
CASES = [
    ("M301",  # read through a branch condition, on the path that did not wait
     """
     PG 1
     LB G1
       MR 1000
       BR G1,P<5000
       E
     PG
     """,
     """
     PG 1
     LB G1
       MR 1000
       H
       BR G1,P<5000
       E
     PG
     """),
    ("M301",  # a subroutine that moves without waiting leaves the move running after the call
     """
     PG 1
     LB G1
       CL K1
       R1=C1
       E
     LB K1
       MA 0
       RT
     PG
     """,
     """
     PG 1
     LB G1
       MA 1000
       CL K1
       R1=C1
       E
     LB K1
       H
       RT
     PG
     """),
    ("M301",  # polling MV is a way of waiting
     """
     PG 1
     LB G1
       MA 1000
       PR "at ",P
       E
     PG
     """,
     """
     PG 1
     LB G1
       MA 1000
     LB W1
       BR W1,MV=1
       PR "at ",P
       E
     PG
     """),
    ("M302",  # BR from a subroutine to the main loop
     """
     PG 1
     LB G1
       CL K1
       E
     LB K1
       BR G1
     PG
     """,
     """
     PG 1
     LB G1
       CL K1
       E
     LB K1
       BR K2,I1=1
       RT
     LB K2
       RT
     PG
     """),
    ("M303",  # the handler re-enables the wrong bit (TP is bit 2)
     """
     PG 1
     LB G1
       TP=1000,X1
       TE=2
       E
     LB X1
       TE=1
       RT
     PG
     """,
     """
     PG 1
     LB G1
       TP=1000,X1
       TE=2
       E
     LB X1
       TE=2
       RT
     PG
     """),
    ("M303",  # one path returns early without re-enabling
     """
     PG 1
     LB G1
       TI 1,X1
       TE=1
     LB G2
       BR G2
     LB X1
       BR X2,I2=1
       TE=1
     LB X2
       RT
     PG
     """,
     """
     PG 1
     LB G1
       TI 1,X1
     LB G2
       TE=1
       BR G2
     LB X1
       RT
     PG
     """),
    ("M304",  # motion in a subroutine the SU program calls
     """
     PG 1
     LB SU
       CL K1
       E
     LB K1
       MR 100
       H
       RT
     PG
     """,
     """
     PG 1
     LB SU
       O1=1
       E
     PG
     """),
    ("M305",  # K9 is reached only by running on from G1: a label no code needs (issue 24)
     """
     PG 1
     LB G1
       MA 1000
       H
     LB K9
       E
     PG
     """,
     """
     PG 1
     LB G1
       BR G1,I1=0
       E
     PG
     PG 50
     LB K9
       E
     PG
     """),
    ("M306",  # IC alone does not make a variable used
     """
     VA Ct
     PG 1
     LB G1
       IC Ct
       BR G1
     PG
     """,
     """
     VA Ct
     PG 1
     LB G1
       IC Ct
       BR G1,Ct<10
       E
     PG
     """),
    ("M307",  # code after RT in a subroutine
     """
     PG 1
     LB G1
       CL K1
       E
     LB K1
       RT
       MR 100
     PG
     """,
     """
     PG 1
     LB G1
       CL K1
       BR G1
       E
     LB K1
       RT
     PG
     """),
    ("M308",  # a motion setting from a float register
     """
     PG 1
     LB G1
       F1=2.5
       VM=F1
       E
     PG
     """,
     """
     PG 1
     LB G1
       F1=2.5
       F2=F1*2
       PR F2
       E
     PG
     """),
    ("M309",
     """
     PG 1
     LB G1
       E
     PG
     ` no save
     """,
     """
     PG 1
     LB G1
       E
     PG
     S
     ` saved
     """),
    ("M310",
     """
     PG 1
     LB G1
       BR G2,I1=1
       E
     LB G2
       VA Q1
       Q1=P
       PR Q1
       BR G1
     PG
     """,
     """
     PG 1
     LB G1
       VA Q1
       Q1=P
       PR Q1
       E
     PG
     """),
    ("M311",  # in a branch condition
     """
     PG 1
     LB G1
       BR G1,R1-R2*2>0
       E
     PG
     """,
     """
     PG 1
     LB G1
       R1=R1+R2+R3
       BR G1,R1>R2*2
       E
     PG
     """),
    ("M312",  # a handler that runs past the end of the program
     """
     PG 1
     LB G1
       OE K1
       E
     LB K1
       PR ER
     PG
     """,
     """
     PG 1
     LB G1
       OE K1
       E
     LB K1
       PR ER
       RT
     PG
     """),
    ("M313",
     """
     PG 1
     LB G1
       MR 1000,0,1
       H 100
       E
     PG
     """,
     """
     PG 1
     LB G1
       MR 1000,0,0
       H
       E
     PG
     """),
    ("M314",
     """
     PG 1
     LB G1
       SL 1000
       MA 0
       H
       E
     PG
     """,
     """
     PG 1
     LB G1
       SL 1000
       H 100
       SL 0
     LB W1
       BR W1,MV=1
       MA 0
       H
       E
     PG
     """),
    ("M315",
     """
     TR=100,X1,2
     TP=500,X1
     PG 1
     LB X1
       RT
     PG
     """,
     """
     TP=500,X1
     PG 1
     LB X1
       RT
     PG
     """),
    ("M316",  # EX of a label in the middle of a program
     """
     PG 1
     LB G1
       O1=1
     LB G2
       BR G2
     PG
     EX G2
     """,
     """
     PG 1
     LB G1
       O1=1
     LB G2
       BR G2
     PG
     EX G1
     """),
    ("M317",
     """
     TE=127
     """,
     """
     TT=1000,X1
     TE=8
     PG 1
     LB X1
       TE=8
       RT
     PG
     """),
    ("M318",
     """
     PG 1
     LB G1
       TA=2,K6
       E
     LB K6
       RT
     PG
     """,
     """
     PG 1
     LB G1
       TA=K6,2
       E
     LB K6
       RT
     PG
     """),
    ("M319",
     """
     TI 1,X1
     TI 1,X2
     PG 1
     LB X1
       RT
     LB X2
       RT
     PG
     """,
     """
     PG 1
     LB G1
       TI 1,X1
       TE=1
       BR G1
     LB X1
       RT
     PG
     """),
    ("M320",
     """
     VA Q1
     S
     """,
     """
     VA Q1
     S
     ' end
     """),
    ("M321",
     """
     PG 1
     LB G1
       CL K1,R1=<4
       E
     LB K1
       RT
     PG
     """,
     """
     PG 1
     LB G1
       CL K1,R1<=4
       E
     LB K1
       RT
     PG
     """),
    ("M322",  # TE enables a different trip
     """
     TI 1,X1
     TP=500,X2
     TE=2
     PG 1
     LB X1
       RT
     LB X2
       TE=2
       RT
     PG
     """,
     """
     TI 1,X1
     TE=R1
     PG 1
     LB X1
       RT
     PG
     """),
    ("M323",
     """
     PG 1
     LB G1
       OE K1
       PR "start"
     LB K1
       PR ER
       RT
     PG
     """,
     """
     PG 1
     LB G1
       OE K1
       PR "start"
       BR G1
     LB K1
       PR ER
       RT
     PG
     """),
    ("M324",  # a division by 0 inside a larger expression; a divisor in a variable is not followed
     """
     VA Q1=0
     PG 1
     LB G1
       Q1=Q1+100/0
       PR Q1
       E
     PG
     """,
     """
     VA Q1=0
     VA R2=0
     PG 1
     LB G1
       Q1=100/R2
       PR Q1
       E
     PG
     """),
]


@pytest.mark.parametrize("code,bad,good", CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)])
def test_rule_reports_bad_and_accepts_good(code: str, bad: str, good: str) -> None:
    assert code in codes(bad), lint(bad)
    assert code not in codes(good), [(d.code, d.span.line, d.message) for d in lint(good)]


def test_conventional_end_after_main_loop_is_not_unreachable() -> None:
    text = """
    PG 1
    LB G1
      BR G1
      E
    PG
    """
    assert "M307" not in codes(text)


def test_position_read_points_at_the_read_and_names_the_move() -> None:
    text = """
    PG 1
    LB G1
      MA 100
      O1=1
      PR P
      E
    PG
    """
    diag = next(d for d in lint(text) if d.code == "M301")
    assert diag.span.line == 5
    assert "line 3" in diag.message


def test_unused_label_fix_deletes_the_line_and_is_unsafe() -> None:
    text = "PG 1\nLB G1\n  MA 10\nLB K9\n  E\nPG\n"
    diag = next(d for d in lint(text) if d.code == "M305")
    assert diag.fix is not None and not diag.fix.safe
    edit = diag.fix.edits[0]
    assert text[edit.span.start:edit.span.end] == "LB K9\n" and edit.text == ""


def test_a_label_nothing_reaches_is_an_entry_point() -> None:
    """A label after E or RT that no BR, CL, EX or trip names is how a host starts part of a program
    (lexium-mcode.txt L533: "EX K1 executes a program labeled K1"); issue 24 asks mcc to treat it as an entry point:
    M305 neither reports it nor offers to delete it, and leaving it with BR is not M302."""
    text = "PG 1\nLB G1\n  CL S9\n  E\nLB S9\n  MR 10\n  H\n  RT\nLB K9\n  MA 0\n  BR G1\nPG\n"
    found = codes(text)
    assert "M305" not in found and "M302" not in found, lint(text)


def test_trip_argument_order_fix_swaps_the_arguments() -> None:
    from mcc.compiler.lint import fixes

    text = "PG 1\nLB G1\n  TA=2,K6\n  E\nLB K6\n  RT\nPG\n"
    diag = next(d for d in lint(text) if d.code == "M318")
    fixed, count = fixes.apply(text, [diag.fix])
    assert count == 1 and "TA=K6,2" in fixed


def test_rules_do_not_run_on_files_with_syntax_errors() -> None:
    text = "PG 1\nLB G1\n  MA (100\n  E\nLB K9\n  RT\nPG\n"
    found = codes(text)
    assert "M001" in found and not any(c.startswith("M3") for c in found)


def test_samples_have_no_lint_errors() -> None:
    from conftest import sample_files

    for path in sample_files("mcode"):
        diags = lint(path.read_text(encoding="utf-8"), path.name)
        assert not [d for d in diags if d.severity.value == "error"], (path, diags)


def test_rule_lines() -> None:
    text = """
    VA Q1
    PG 1
    LB G1
      R1=R2+R3*2
      E
    PG
    """
    assert lines_of("M306", text) == [1]
    assert lines_of("M311", text) == [4]


def test_a_trip_the_frontend_rejected_still_counts_as_defined() -> None:
    text = "PG 1\nLB G1\n  TP=Ds*3,X2\n  TE=2\n  E\nLB X2\n  TE=2\n  RT\nPG\nS\n' k\n"
    found = codes(text)
    assert "M117" in found and "M317" not in found  # Ds is undeclared: one error, not two


def test_position_reads_outside_a_program_are_not_reported() -> None:
    assert "M301" not in codes("MA 20000\nPR P\n")  # immediate mode: H does not exist there
