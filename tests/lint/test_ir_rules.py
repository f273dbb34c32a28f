"""The lint rules written once over the IR (compiler/lint/rules/shared/): one rule, each dialect's
code and words; and the symbol table and def-use chains the analysis keeps (compiler/symbols.py)."""

from __future__ import annotations

import importlib
import string
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from helpers import codes, lint
from mcc.compiler import driver
from mcc.compiler.codes import registry
from mcc.compiler.lint.rules import RULES, load_all
from mcc.compiler.lint.rules.shared import voice as voices

load_all()
SPOKEN = {code: rule.voice for code, rule in RULES.items() if rule.voice is not None}
SHARED_DIR = Path(voices.__file__).parent
SHARED = {path.stem: importlib.import_module(f"mcc.compiler.lint.rules.shared.{path.stem}")
          for path in sorted(SHARED_DIR.glob("*.py")) if path.stem not in ("__init__", "helpers", "voice")}


def analysis(text: str, path: str):
    return driver.check_file(path, text=text).analysis


# the tables -----------------------------------------------------------------------------------------

@pytest.mark.parametrize("code", sorted(SPOKEN))
def test_each_dialect_gives_a_shared_rule_its_own_registered_code_and_every_message(code: str) -> None:
    voice = SPOKEN[code]
    [(name, spoken_code)] = voice.codes.items()
    assert spoken_code == code
    shared = SHARED[name.replace("-", "_")]
    info = registry().get(code)
    assert info is not None and info.dialects == (voice.dialect,), code
    assert RULES[code].dialects == (voice.dialect,)
    assert RULES[code].check.__doc__ == voices.check_of(shared).__doc__
    variants = getattr(shared, "VARIANTS", None)
    if variants is None:
        assert name in voice.messages, f"{code} has no message for {name}"
    for variant in variants or ():
        assert f"{name}.{variant}" in voice.messages, f"{code} has no message for {name}.{variant}"


def test_a_shared_rule_has_one_code_per_dialect_and_codes_are_not_shared() -> None:
    seen: dict[tuple[str, str], str] = {}
    for code, voice in SPOKEN.items():
        [name] = voice.codes
        assert code[0] == {"mcode": "M", "arcus": "A", "x150": "X"}[voice.dialect]
        assert (name, voice.dialect) not in seen, (code, seen.get((name, voice.dialect)))
        seen[(name, voice.dialect)] = code
    assert {name for name, _ in seen} == {shared.NAME for shared in SHARED.values()}, "a shared rule no dialect has"


# one meaning, three spellings ---------------------------------------------------------------------

DIVISION = {
    "mcode": ("program.mxt", "VA Q1=0\nPG 1\nLB G1\n  Q1=7/0\n  PR Q1\n  E\nPG\nS\n' end\n", "M324"),
    "arcus": ("program.prg", "V1=7/0\nEND\n", "A309"),
    "x150": ("program.x150", "1XE1\n1XD1\n1VAR1=7/0\n1XT\n", "X309"),
}


@pytest.mark.parametrize("dialect", sorted(DIVISION))
def test_division_by_zero_is_one_rule_with_each_dialects_code(dialect: str) -> None:
    path, text, code = DIVISION[dialect]
    found = [d for d in lint(text, path) if d.code == code]
    assert len(found) == 1
    assert found[0].span.line == (4 if dialect == "mcode" else 1 if dialect == "arcus" else 3)
    assert "zero" in found[0].message


ENDLESS = {
    "mcode": ("program.mxt", "SL 2000\n", "SL 0\n", "M313"),
    "arcus": ("program.prg", "HSPD=1000\nJOGX+\n", "STOPX\n", "A314"),
    "x150": ("program.x150", "1MC\n1H-\n1A10\n1V10\n1G\n", "1S\n", "X307"),
}


@pytest.mark.parametrize("dialect", sorted(ENDLESS))
def test_motion_never_stopped_and_the_stop_that_ends_it(dialect: str) -> None:
    path, moving, stop, code = ENDLESS[dialect]
    if dialect == "arcus":
        assert code in codes(moving + "END\n", path)
        assert code not in codes(moving + stop + "END\n", path)
    else:
        assert code in codes(moving, path)
        assert code not in codes(moving + stop, path)


def test_an_input_set_up_as_soft_stop_stops_a_slew() -> None:
    assert "M313" not in codes("IS=1,5,1\nSL 2000\n")


def test_a_slew_from_a_variable_may_be_a_stop_and_is_not_reported() -> None:
    text = "VA R3=0\nPG 1\nLB G1\n  SL 2000\n  H 100\n  SL R3\n  BR G1\nPG\nS\n' end\n"
    assert "M313" not in codes(text)


def test_x150_reports_a_g_kept_as_text_once_but_every_known_continuous_move() -> None:
    one = "1XE1\n1XD1\n1D(VAR1)\n1MC\n1G\n1G\n1XT\n"  # the sign of D is known at run time only
    assert codes(one, "p.x150").count("X307") == 1
    known = "1MC\n1H-\n1A10\n1V10\n1G\n2MC\n2H+\n2A10\n2V10\n2G\n"
    assert codes(known, "p.x150").count("X307") == 2


# what the shared versions do better than the copies they replace -----------------------------------

def test_move_before_speed_counts_a_setting_made_for_the_axis() -> None:
    diag = next(d for d in lint("ACCX=200\nX2000\nEND\n", "p.prg") if d.code == "A302")
    assert "HSPD, LSPD are set" in diag.message and "ACC" not in diag.message


def test_position_read_after_a_subroutine_that_waits_is_not_reported_in_arcus() -> None:
    head = "HSPD=1000\nLSPD=100\nACC=100\nX1000\nGOSUB 1\nV1=PX\nEND\n"
    waits = head + "SUB 1\nWAITX\nENDSUB\n"
    moves = "HSPD=1000\nLSPD=100\nACC=100\nGOSUB 1\nV1=PX\nEND\nSUB 1\nX1000\nENDSUB\n"
    assert "A301" in codes(head + "SUB 1\nDO1=1\nENDSUB\n", "p.prg")
    assert "A301" not in codes(waits, "p.prg")
    assert "A301" in codes(moves, "p.prg")


def test_mcode_position_read_is_reported_once_per_statement_naming_every_move() -> None:
    text = "PG 1\nLB G1\n  MA 100\n  BR G2, I1=1\n  MR 5\nLB G2\n  PR P, P\n  E\nPG\nS\n' end\n"
    found = [d for d in lint(text) if d.code == "M301"]
    assert len(found) == 1 and "line 3, 5" in found[0].message


# the symbol table and def-use chains ----------------------------------------------------------------

MCODE = """VA Q1=0
VA Q2=0
PG 1
LB G1
  Q1=Q1+1
  IC Q2
  PR Q1
  CL K1
  BR G1, I1=0
  E
LB K1
  RT
LB Z9
  RT
PG
S
' end
"""


def test_symbols_of_an_mcode_file() -> None:
    found = analysis(MCODE, "p.mxt")
    symbols = found.symbols
    assert symbols.variables["Q1"].definition.line == 1
    assert [span.line for span in symbols.variables["Q1"].references] == [5, 5, 7]
    assert symbols.labels["G1"].definition.line == 4 and [s.line for s in symbols.labels["G1"].references] == [9]
    assert symbols.routines["K1"].used and [s.line for s in symbols.routines["K1"].references] == [8]
    assert not symbols.labels["Z9"].used
    assert found.symbols is symbols  # computed once


def test_def_use_of_an_mcode_file() -> None:
    defuse = analysis(MCODE, "p.mxt").defuse
    assert [site.span.line for site in defuse.defs["Q1"]] == [5]
    assert defuse.read("Q1")  # PR Q1
    assert not defuse.read("Q2") and defuse.mentioned("Q2")  # IC Q2 only updates itself
    assert all(use.self_update for use in defuse.uses["Q2"])


def test_registers_without_declaration_are_in_the_table() -> None:
    found = analysis("V1=5\nV2=V1*2\nEND\n", "p.prg")
    assert found.symbols.variables["V1"].count == 2
    assert [site.span.line for site in found.defuse.defs["V2"]] == [2]
    assert [use.site.span.line for use in found.defuse.uses["V1"]] == [2]


def test_a_declaration_inside_a_program_is_a_definition_not_a_use() -> None:
    text = "PG 1\nLB G1\n  VA Q7=3\n  E\nPG\nS\n' end\n"
    defuse = analysis(text, "p.mxt").defuse
    assert defuse.defs["Q7"] and not defuse.uses.get("Q7")
    assert [d.code for d in lint(text) if d.code == "M306"] == ["M306"]


NAMES = st.sampled_from(["V1", "V2", "V3", "V4"])


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(NAMES, st.lists(NAMES, max_size=1), st.sampled_from(string.digits[1:])),
                min_size=1, max_size=12))
def test_def_use_counts_every_write_and_read(program) -> None:
    """Each `Vn=...` line is one definition of Vn and one use per variable on its right."""
    lines = [f"{target}={'+'.join(reads + [digit])}" for target, reads, digit in program]
    defuse = analysis("\n".join(lines + ["END"]) + "\n", "p.prg").defuse
    for name in ("V1", "V2", "V3", "V4"):
        assert len(defuse.defs.get(name, [])) == sum(1 for target, _, _ in program if target == name)
        assert len(defuse.uses.get(name, [])) == sum(reads.count(name) for _, reads, _ in program)
        expect_read = any(name in reads and target != name for target, reads, _ in program)
        assert defuse.read(name) == expect_read


# fixes of the shared rules, end to end ---------------------------------------------------------------

def test_unsafe_fixes_of_shared_rules_delete_the_unused_declaration_and_subroutine(mcc, tmp_path) -> None:
    arcus = tmp_path / "p.prg"
    arcus.write_text("DO1=1\nEND\nSUB 3\nDO2=1\nENDSUB\n", encoding="utf-8")
    mcode = tmp_path / "p.mxt"
    mcode.write_text("VA Q5=0\nPG 1\nLB G1\n  E\nPG\nS\n' end\n", encoding="utf-8")
    result = mcc("lint", "--fix", "--unsafe-fixes", "--select", "A307,M306", str(arcus), str(mcode))
    assert result.returncode == 0, result.stdout + result.stderr
    assert arcus.read_text(encoding="utf-8") == "DO1=1\nEND\n"
    assert mcode.read_text(encoding="utf-8") == "PG 1\nLB G1\n  E\nPG\nS\n' end\n"


def test_the_unused_variable_fix_deletes_every_declaration_at_once(mcc, tmp_path) -> None:
    """A file that declares a variable nine times (the fuzzer's duplicated line; the device refuses
    all but the first, M141) settles in one round instead of one declaration per round (G008)."""
    mcode = tmp_path / "p.mxt"
    mcode.write_text("VA Np=0\n" * 9 + "PG 1\nLB G1\n  E\nPG\nS\n' end\n", encoding="utf-8")
    result = mcc("lint", "--fix", "--unsafe-fixes", "--select", "M306", str(mcode))
    assert "G008" not in result.stdout + result.stderr
    assert mcode.read_text(encoding="utf-8") == "PG 1\nLB G1\n  E\nPG\nS\n' end\n"


def run_rule(code: str, dialect: str, module, text: str = "") -> list:
    """Run one rule on a module built by hand (the neutral operations a lowering may produce)."""
    from mcc.compiler.analysis import Analysis
    from mcc.compiler.config import load_profile
    from mcc.compiler import dialects
    from mcc.compiler.diagnostics import Diagnostics
    from mcc.compiler.lint.rules import Context
    from mcc.compiler.span import SourceFile

    source = SourceFile(f"p{dialects.get(dialect).extensions[0]}", text or "\n" * 5)
    ctx = Context(Analysis(source, None, module, Diagnostics()),
                  load_profile(dialects.get(dialect).default_profile), dialect)
    ctx.code = code
    RULES[code].check(ctx)
    return ctx.diagnostics.items


def neutral_module(dialect: str, *ops):
    from mcc.compiler import ir
    from mcc.compiler.span import Span

    spans = [Span("p", n + 1, 1, n + 1, 2, 0, 0) for n in range(len(ops) + 1)]
    for op, span in zip(ops, spans):
        op.span = span
    block = ir.Block("%1", list(ops), ir.FallOff(spans[-1]))
    return ir.Module(dialect, "", routines=[ir.Routine("SEQ1", ir.RoutineKind.MAIN, [block], number=1)])


def test_x150_homing_does_not_need_a_and_v_but_a_move_does() -> None:
    """GH homes at its own speed with GA (L1701-L1711): a neutral Home is not an X301 move."""
    from mcc.compiler import ir

    home = neutral_module("x150", ir.Home("1", "switch", 1))
    assert run_rule("X301", "x150", home) == []
    move = neutral_module("x150", ir.Move(ir.MoveMode.RELATIVE, (("1", ir.Const(4000, ir.Unit.STEPS)),)))
    assert [d.code for d in run_rule("X301", "x150", move)] == ["X301"]


def test_neutral_stops_end_endless_motion_in_x150_without_its_spellings() -> None:
    """When the X150 lowering writes S as a neutral Stop, X307 needs no change."""
    from mcc.compiler import ir

    jog = ir.Slew("1", None, 1)
    assert [d.code for d in run_rule("X307", "x150", neutral_module("x150", jog))] == ["X307"]
    assert run_rule("X307", "x150", neutral_module("x150", ir.Slew("1", None, 1), ir.Stop("1"))) == []
