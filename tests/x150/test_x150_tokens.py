"""Reading command tokens: longest match against the catalog, the B prefix, argument classes."""

from __future__ import annotations

import pytest

from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.span import SourceFile
from mcc.compiler.x150 import parser
from mcc.compiler.x150 import syntax as st


def commands(text: str) -> list[st.Command]:
    diags = Diagnostics()
    tree = parser.parse(SourceFile("t.x150", text), diags)
    return list(tree.commands())


def one(text: str) -> st.Command:
    found = commands(text)
    assert len(found) == 1, [c.text for c in found]
    return found[0]


@pytest.mark.parametrize("text,address,mnemonic,arg_type", [
    ("1A10", 1, "A", st.Number),
    ("D-100000", None, "D", st.Number),
    ("1OUT3B", 1, "OUT", st.IoFunction),
    ("TRE_X1", None, "TRE", st.Pattern),
    ("SKEX1", None, "SKE", st.Pattern),  # not "SKEX" + "1": patterns hold X
    ("1INLXXXX10X_1XX1X0XX", 1, "INL", st.Pattern),  # not IN + LXXX...
    ("DLEDXX1", None, "DLED", st.Pattern),
    ("1OUTLXX10X1", 1, "OUTL", st.Pattern),  # not OUT + L...
    ("OX0", None, "O", st.Pattern),
    ("DSTP1", None, "DSTP", st.Number),
    ("TUNE3", None, "TUNE", st.Number),
    ("XEALL", None, "XEALL", type(None)),
    ("VARD1,0,3,2", None, "VARD", st.Fields),
    ("VAR1=VAR2+20", None, "VAR", st.VarStatement),
    ("H+", None, "H+", type(None)),
    ("GH-2", None, "GH", st.Number),
    ("STOP", None, "STOP", type(None)),
    ("ST1", None, "ST", st.Number),
    ("12XR3", 12, "XR", st.Number),
    ("L(VAR8)", None, "L", st.VarRef),
    ("#", None, "#", type(None)),
    ("#5", None, "#", st.Fields),
    ('1"2XR1"', 1, '"', st.Text),
    ('DTXT"PRESS F1"', None, "DTXT", st.Text),
    ("IF(VAR1>5 AND IN_XXXX11)", None, "IF", st.Condition),
])
def test_longest_match(text, address, mnemonic, arg_type):
    command = one(text)
    assert command.ok, command.problems
    assert (command.address, command.mnemonic, type(command.arg)) == (address, mnemonic, arg_type)


def test_b_prefix_goes_after_the_address():
    command = one("1BCPG50")
    assert (command.address, command.buffered, command.mnemonic, command.arg.value) == (1, True, "CPG", 50)
    assert one("BY").buffered and one("BY").mnemonic == "Y"
    # B, BS and BDL keep their meaning: S and DL are not '*' commands
    assert [c.mnemonic for c in commands("1B 1BS 1BDL20")] == ["B", "BS", "BDL"]


def test_b_prefix_with_the_address_inside_is_explained():
    command = one("B1CPG50")
    assert command.problems[0].code == "X002"
    assert "1BCPG50" in command.problems[0].message


def test_b_prefix_only_on_star_commands():
    command = one("BV5")
    assert command.problems and "not one of them" in command.problems[0].message


def test_pattern_groups():
    assert one("TRE_XXXXXXXXXX1").problems  # eleven user inputs
    assert one("TREXXXXXXXX").problems  # eight dedicated inputs
    assert one("TRE1_0").arg.bits == "1_0"
    assert one("tre_x1").arg.bits == "_X1"


def test_fields_and_widths():
    assert one("DPC208").arg.values == [2, 8]
    assert one("DPC28").problems[0].code == "X002"  # the column is always two digits (L1020)
    assert one("FRD").arg is None and one("FRD0,4,0").arg.values == [0, 4, 0]
    assert one("FRD0,4").problems  # e is required once c and d are given (L1175)
    tx = one("1TX1,0,5,2VAR3=").arg
    assert tx.values == [1, 0, 5] and tx.tail == "2VAR3="
    assert one("PASS0123").arg.values == [123]


def test_variable_statements():
    statement = one("VAR4=VAR1-VAR2*VAR3").arg
    assert statement.var.number == 4
    assert [op for op, _ in statement.value.rest] == ["-", "*"]
    assert one("VAR8=POS+50000").ok
    assert one("VAR2=RSIN").info.name == "RSIN"
    assert one("VAR1=FUN").info.name == "VARn=FUN"
    assert one("VAR1=FUN+1").problems  # FUN stands alone
    assert one("VAR1=VAR2*-1").ok


def test_conditions():
    cond = one("WHILE(VAR1<1 OR VAR1>10)").arg
    assert cond.joins == ["OR"] and len(cond.terms) == 2
    assert one("IF(INXXX1)").arg.terms[0].underscore is False
    for bad in ("IF(VAR1>=5)", "IF(VAR1<>5)", "IF()", "IF(VAR1>5 AND)", "IF(POS>5)", "IF(VAR1>5)X"):
        assert one(bad).problems, bad
    assert one("IF").problems  # a condition is required


def test_var_substitution_only_where_documented():
    assert one("D(VAR5)").ok
    assert one("GA(VAR5)").problems  # GA is not in the (VARn) list (L4575-L4590)


def test_unknown_command_suggests():
    command = one("IPR")
    assert command.problems[0].code == "X101" and "PR" in command.problems[0].message


def test_host_data_and_lone_address():
    assert one("!12.34").host
    assert one("2").problems[0].code == "X003"


def test_spans_point_into_the_line():
    first, second = commands("  1A10\t1BCPG50 ; c\n")
    assert (first.span.line, first.span.column, first.span.end_column) == (1, 3, 7)
    assert (second.mnemonic_span.column, second.arg.span.column) == (9, 13)
