"""The Arcus frontend: lexical traps, recovery, spans, the IR each statement lowers to, the checks."""

from __future__ import annotations

import pytest

from mcc.compiler import driver, ir, profiles
from mcc.compiler.arcus import frontend, parser
from mcc.compiler.arcus import syntax as st
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.span import SourceFile

PROFILE = profiles.load("pmx-4ex-sa")


def analyze(text: str, profile=PROFILE):
    return frontend.analyze(SourceFile("t.prg", text), profile)


def codes(text: str, profile=PROFILE) -> list[str]:
    return [d.code for d in analyze(text, profile).diagnostics.sorted()]


def main_ops(text: str) -> list:
    module = analyze(text).module
    return [op for block in module.routines[0].blocks for op in block.ops]


def single_op(text: str):
    ops = main_ops(text)
    assert len(ops) == 1, ops
    return ops[0]


# --- lexical structure ------------------------------------------------------------------------------

@pytest.mark.parametrize("text,spelled", [
    ("END", "END"), ("ENDIF", "ENDIF"), ("ENDSUB", "ENDSUB"), ("ENDWHILE", "ENDWHILE"), ("ELSE", "ELSE"),
    ("SSPDX=100", "SSPDX"), ("SSPDMX=1", "SSPDMX"), ("PX=0", "PX"), ("EX=0", "EX"), ("EO=1", "EO"),
    ("EO2=1", "EO2"), ("ECLEARX", "ECLEARX"), ("ZHOMEX+", "ZHOMEX+"), ("ZOMEZ-", "ZOMEZ-"), ("DO=5", "DO"),
    ("DO5=1", "DO5"), ("STOP", "STOP"), ("STOPY", "STOPY"), ("ABORT", "ABORT"), ("ABORTU", "ABORTU"),
    ("ACC=5", "ACC"), ("ACCZ=5", "ACCZ"), ("HSPD=5", "HSPD"), ("HSPDU=5", "HSPDU"), ("LSPDX=5", "LSPDX"),
    ("SYNXC=1", "SYNXC"), ("SYNYO", "SYNYO"), ("Delay=1000", "DELAY"), ("jogx+", "JOGX+"), ("WAITU", "WAITU"),
])
def test_longest_match_and_glued_suffixes(text: str, spelled: str) -> None:
    from mcc.compiler.arcus.resolve import Resolver

    tree = parser.parse(SourceFile("t.prg", text + "\n"), Diagnostics())
    resolved = Resolver(PROFILE, Diagnostics()).resolve(tree.lines[0])
    assert resolved.spelled == spelled


def test_moves_glue_axes_numbers_and_variables() -> None:
    for text, targets in [("X1000Y2000", [("X", 1000), ("Y", 2000)]), ("X1000 Y1000", [("X", 1000), ("Y", 1000)]),
                          ("X-1000", [("X", -1000)]), ("Y1000Z2000U3000", [("Y", 1000), ("Z", 2000), ("U", 3000)]),
                          ("x5y-6", [("X", 5), ("Y", -6)])]:
        move = single_op(text)
        assert isinstance(move, ir.Move)
        assert [(a, v.value) for a, v in move.targets] == targets
        assert all(v.unit is ir.Unit.STEPS for _, v in move.targets)
    move = single_op("XV10YV11")
    assert [(a, v.name) for a, v in move.targets] == [("X", "V10"), ("Y", "V11")]


def test_comments_are_kept_in_the_tree_with_spans() -> None:
    tree = analyze("; own line\nJOGX+ ;***Jogs X\n").tree
    assert [c.text for c in tree.comments()] == ["; own line", ";***Jogs X"]
    comment = tree.lines[1].comment
    assert (comment.span.line, comment.span.column) == (2, 7)


def test_every_node_has_a_span_pointing_at_its_text() -> None:
    source = SourceFile("t.prg", "V1 = V2+~DI3\nIF MSTX != 0\nARCP0:100:30000\n")
    tree = parser.parse(source, Diagnostics())
    assign = tree.lines[0].statement
    assert isinstance(assign, st.Assignment)
    assert source.text[assign.span.start:assign.span.end] == "V1 = V2+~DI3"
    assert source.text[assign.value.span.start:assign.value.span.end] == "V2+~DI3"
    cond = tree.lines[1].statement
    assert source.text[cond.condition.span.start:cond.condition.span.end] == "MSTX != 0"
    arc = tree.lines[2].statement
    assert [source.text[n.span.start:n.span.end] for n in arc.colon] == ["100", "30000"]


def test_three_bad_lines_give_three_syntax_errors_and_the_rest_is_checked() -> None:
    text = "X1000\nV1=(V2+1)\nDELAY=\nHSPD=1000\nIF V1=1 X1000 ENDIF\nV99=1\nX2000\n"
    diags = analyze(text).diagnostics.sorted()
    assert [(d.code, d.span.line) for d in diags] == [("A001", 2), ("A001", 3), ("A001", 5), ("A103", 6)]
    assert all(d.kind.value == "syntax" for d in diags[:3])
    module = analyze(text).module
    moves = [op for op in module.routines[0].blocks[0].ops if isinstance(op, ir.Move)]
    assert len(moves) == 2


def test_apostrophe_comments_are_read_with_one_warning() -> None:
    diags = analyze("GOSUB 1 '***Pen Up\nX0Y0 '***Go\nEND\nSUB 1\nENDSUB\n").diagnostics.sorted()
    assert [(d.code, d.severity.value, d.span.line) for d in diags] == [("A127", "warning", 1)]
    assert "1 more" in diags[0].notes[0]


# --- lowering ---------------------------------------------------------------------------------------

def test_speed_settings_lower_to_set_motion_with_units_and_global_axis() -> None:
    hspd, lspdx, acc, dec, accv, decv = main_ops("HSPD=1000\nLSPDX=100\nACC=300\nACCY=V3\n")
    assert (hspd.param, hspd.axis, hspd.value.value, hspd.value.unit) == \
        (ir.MotionParam.MAX_SPEED, "*", 1000, ir.Unit.STEPS_PER_S)
    assert (lspdx.param, lspdx.axis) == (ir.MotionParam.INITIAL_SPEED, "X")
    # ACC is one ramp time (ms) for both ramps: accel_time and decel_time in seconds
    assert [(op.param, op.value.value, op.value.unit) for op in (acc, dec)] == [
        (ir.MotionParam.ACCEL_TIME, 0.3, ir.Unit.S), (ir.MotionParam.DECEL_TIME, 0.3, ir.Unit.S)]
    # a variable holds milliseconds: scaled to seconds in the IR
    assert (accv.axis, accv.value.op, accv.value.left.name, accv.value.right.value) == ("Y", "*", "V3", 0.001)
    assert decv.param is ir.MotionParam.DECEL_TIME


def test_motion_statements_lower_to_neutral_operations() -> None:
    arc, cir, jog, home, zhome, zome, stop, abort, wait, delay = main_ops(
        "ARCP0:100:30000\nCIRN0:2000\nJOGX-\nHOMEZ+\nZHOMEX+\nZOMEY-\nSTOPX\nABORT\nWAITY\nDELAY=1000\n")
    assert (arc.axes, arc.clockwise, arc.angle.value, arc.angle.unit) == (("X", "Y"), True, 30,
                                                                         ir.Unit.DEGREES)
    assert [c.value for c in arc.center] == [0, 100]
    assert (cir.clockwise, cir.angle) == (False, None)
    assert (jog.axis, jog.direction, jog.velocity) == ("X", -1, None)
    assert [(h.axis, h.method, h.direction) for h in (home, zhome, zome)] == \
        [("Z", "switch", 1), ("X", "switch+index", 1), ("Y", "index", -1)]
    assert (stop.axis, stop.ramp, abort.axis, abort.ramp) == ("X", True, "*", False)
    assert wait.axis == "Y"
    assert (delay.duration.value, delay.duration.unit) == (1, ir.Unit.S)


def test_io_positions_variables_and_registers() -> None:
    do7, do, px, v1, v2, v3, v4 = main_ops("DO7=1\nDO=V2\nPX=0\nV1=V2+1\nV2=~EO\nV3=PSX\nV4=DI1\n")
    assert (do7.index, do7.value.value, do.index) == (7, 1, None)
    assert (px.axis, px.value.value) == ("X", 0)
    assert isinstance(v1.value, ir.BinOp) and v1.value.op == "+"
    assert isinstance(v2.value, ir.UnOp) and v2.value.op == "~"
    assert v2.value.operand == ir.Status("enable_outputs", "", None, v2.value.operand.span)
    assert (v3.value.meaning, v3.value.axis) == ("velocity", "X")
    assert (v4.value.meaning, v4.value.index) == ("input", 1)
    assert set(analyze("V1=V2+1\n").module.variables) == {"V1", "V2"}


def test_settings_with_a_neutral_meaning_are_neutral_and_the_rest_native() -> None:
    ops = main_ops("SCVX=1\nSSPDMX=1\nSSPDX=V1\nSYNXC=1\nSYNXO\nSYNXF\nTR=100\nECLEARU\nEO1=1\nEO=3\nEY=0\n"
                   "ABS\nINC\n")
    assert (ops[0].param, ops[0].axis) == (ir.MotionParam.PROFILE, "X")
    assert (ops[1].mnemonic, ops[1].form, ops[1].axis) == ("SSPDMX", "=", "X")  # no other dialect has it
    settings = [(op.name, op.axis, getattr(op.value, "value", None)) for op in ops[2:8]]
    assert settings == [("speed_change", "X", None), ("compare_condition", "X", 1), ("compare_output", "X", 1),
                        ("compare_output", "X", 0), ("countdown", "", 0.1), ("clear_error", "U", 1)]
    assert (ops[8].axis, ops[8].on.value) == ("X", 1)  # EO1 enables the X drive
    assert (ops[9].name, ops[9].axis, ops[10].name) == ("enable_outputs", "*", "encoder_position")
    assert len(ops) == 11  # ABS and INC leave the IR: their effect is in the moves


def test_registers_read_as_neutral_readings() -> None:
    ops = main_ops("V1=MSTX\nV2=TR\nV3=EO2\nV4=DO\nV5=EX\n")
    assert [op.value.meaning for op in (ops[0], ops[2], ops[3], ops[4])] == \
        ["motor_status", "enabled", "outputs", "encoder"]
    assert (ops[1].value.op, ops[1].value.left.meaning, ops[1].value.right.value) == ("*", "countdown", 1000)
    assert ops[2].value.axis == "Y"


def test_control_flow_lowers_to_blocks_routines_and_calls() -> None:
    module = analyze("IF V1=1\nX1\nELSEIF V1=2\nX2\nELSE\nX3\nENDIF\nWHILE V2<5\nGOSUB 3\nENDWHILE\nEND\n"
                     "SUB 3\nY1\nENDSUB\n").module
    main, sub = module.routines
    assert (main.kind, sub.kind, sub.name, sub.number) == (ir.RoutineKind.MAIN, ir.RoutineKind.SUBROUTINE,
                                                           "SUB3", 3)
    terms = [b.terminator for b in main.blocks]
    branches = [t for t in terms if isinstance(t, ir.Branch)]
    assert [b.cond.op for b in branches] == ["=", "=", "<"]
    assert any(isinstance(t, ir.End) for t in terms)
    calls = [op for b in main.blocks for op in b.ops if isinstance(op, ir.Call)]
    assert [c.routine for c in calls] == ["SUB3"]
    assert isinstance(sub.blocks[-1].terminator, ir.Return)


def profile_with(**arcus) -> profiles.Profile:
    data = {**PROFILE.data, "arcus": {**PROFILE.data["arcus"], **arcus}}
    return profiles.Profile("p", "arcus", "pmx-4ex-sa", data=data)


def move_modes(module: ir.Module, routine: int = 0) -> list[ir.MoveMode]:
    return [op.mode for b in module.routines[routine].blocks for op in b.ops if isinstance(op, ir.Move)]


def test_move_modes_follow_abs_and_inc_from_the_boot_mode() -> None:
    result = analyze("X1\nABS\nX2\nINC\nX3\nIF V1=1\nABS\nELSE\nABS\nENDIF\nX4\n")
    assert move_modes(result.module) == [ir.MoveMode.ABSOLUTE, ir.MoveMode.ABSOLUTE, ir.MoveMode.RELATIVE,
                                         ir.MoveMode.ABSOLUTE]
    assert codes("X1\n") == []
    assert move_modes(analyze("X1\n", profile_with(boot_move_mode="inc")).module) == [ir.MoveMode.RELATIVE]
    assert codes("X1\nINC\nX2\n", profile_with(boot_move_mode="unknown")) == ["A128"]


def test_a_move_whose_mode_depends_on_the_path_is_reported() -> None:
    assert codes("IF V1=1\nINC\nENDIF\nX3\n") == ["A128"]
    assert codes("WHILE V1=1\nX1\nINC\nX2\nENDWHILE\n") == ["A128"]  # the second pass runs in INC
    assert codes("WHILE V1=1\nABS\nX1\nINC\nX2\nENDWHILE\n") == []


def test_subroutines_start_in_the_mode_of_their_calls_and_return_theirs() -> None:
    module = analyze("INC\nGOSUB 1\nX1\nGOSUB 2\nX2\nEND\nSUB 1\nX5\nABS\nENDSUB\nSUB 2\nDO1=1\nENDSUB\n").module
    assert move_modes(module) == [ir.MoveMode.ABSOLUTE, ir.MoveMode.ABSOLUTE]
    assert move_modes(module, 1) == [ir.MoveMode.RELATIVE]  # SUB 1 is called in INC
    assert codes("GOSUB 1\nINC\nGOSUB 1\nEND\nSUB 1\nX1\nENDSUB\n") == ["A128"]
    assert codes("END\nSUB 4\nX1\nENDSUB\n") == []  # never called: it starts like the program


# --- checks -------------------------------------------------------------------------------------------

@pytest.mark.parametrize("text,expected", [
    ("HSPED=1000\n", ["A101"]),
    ("HS=5000\nJX+\nSTORE\nGS1\n", ["A102"] * 4),
    ("V64=1\nXV100\n", ["A103", "A103"]),
    ("GOSUB 32\n", ["A104"]),
    ("GOSUB 0\nEND\nSUB 0\nENDSUB\n", ["A105"]),
    ("GOSUB 1\nEND\n", ["A106"]),
    ("END\nSUB 1\nENDSUB\nSUB 1\nENDSUB\n", ["A107"]),
    ("SUB 1\nENDSUB\nGOSUB 1\nEND\n", ["A108"]),
    ("GOSUB 1\nSUB 1\nENDSUB\n", ["A109"]),
    ("END\nX1000\nSUB 1\nENDSUB\n", ["A110"]),
    ("WHILE V1=1\nX0\n", ["A111"]),
    ("X1000\nENDIF\n", ["A112"]),
    ("WHILE V1=1\nIF V2=1\nENDWHILE\nENDIF\n", ["A113", "A112"]),
    ("IF V1=1\nELSE\nELSE\nENDIF\n", ["A114"]),
    ("IF V1=1\nELSE\nELSEIF V1=2\nENDIF\n", ["A114"]),
    ("END\nSUB 1\nSUB 2\nENDSUB\nENDSUB\n", ["A115", "A112"]),
    ("IF V1=1 AND V2=2\nENDIF\n", ["A116"]),
    ("IF V1=1=2\nENDIF\n", ["A116"]),
    ("V1=V2*3+V4\n", ["A117"]),
    ("HSPD=V1+100\n", ["A117"]),
    ("IF V1+1=5\nENDIF\n", ["A117"]),
    ("DELAY=V1\nTR=V2\nSYNXT=V3\n", ["A118"] * 3),
    ("ARCP0:V1:9000\n", ["A118"]),
    ("GOSUB V2\n", ["A118"]),
    ("EO1=31\nDO9=1\nHSPD=7000000\nSCVX=2\n", ["A119"] * 4),
    ("ACC=20000\nX200000000\n", ["A120", "A120"]),
    ("PRG 0\nX1\nEND\n", ["A121"]),
    ("JOGX\nHSPD 1000\nX=1000\nARCP0:100\nGOSUB\nELSE 5\n", ["A122"] * 6),
    ("DI1=1\nMSTX=0\n", ["A123", "A123"]),
    ("V1=TR+100\nIF SYNXS=2\nENDIF\nV2=SSPDX\n", ["A124"] * 3),
    ("X1000 WAITX\nGOSUB 1 X0\nEND\nSUB 1\nENDSUB\n", ["A125", "A125"]),
    ("X1000Y200X3000\n", ["A126"]),
])
def test_each_check(text: str, expected: list[str]) -> None:
    assert codes(text) == expected


@pytest.mark.parametrize("text", [
    "HSPD=1000\nLSPD=100\nACC=300\nX1000Y2000\nWAITX\nEND\n",
    "V1=12345\nV2=V1+1\nV3=DI\nV4=DO\nV5=~EO\nV6=V1>>2\nV7=V1<<1\nV8=V1%3\nV9=V1|V2\nV10=V1&V2\n",
    "IF MSTX=0\nDO=6\nELSEIF MSTY=0\nDO=3\nENDIF\n",
    "WHILE 1=1\nIF TR>8000\nX0\nELSE\nX8000\nENDIF\nENDWHILE\n",
    "V1=SYNXS\nWHILE V1 != 2\nV1=SYNXS\nENDWHILE\n",
    "GOSUB 31\nEND\nSUB 31\nENDSUB\n",
    "ACC=10000\nX134217727\nEO1=1\nDO8=1\nHSPD=6000000\n",
])
def test_valid_programs_have_no_diagnostics(text: str) -> None:
    assert codes(text) == []


def test_block_diagnostics_name_both_ends() -> None:
    diags = analyze("WHILE V1=1\nIF V2=1\nX1\nENDWHILE\n").diagnostics.sorted()
    misnested = next(d for d in diags if d.code == "A113")
    assert misnested.span.line == 4
    assert "line 2" in misnested.message and "line 1" in misnested.message
    assert any("t.prg:2:1" in note for note in misnested.notes)
    unclosed = analyze("IF V1=1\nX1\n").diagnostics.sorted()[0]
    assert (unclosed.code, unclosed.span.line) == ("A111", 1)
    assert "t.prg:2:" in unclosed.notes[0]


def test_subroutine_range_and_gosub_zero_follow_the_profile() -> None:
    data = {**PROFILE.data, "arcus": {**PROFILE.data["arcus"], "subroutines": [1, 32], "gosub_zero": "error"}}
    manual = profiles.Profile("p", "arcus", "pmx-4ex-sa", data=data)
    assert codes("GOSUB 32\nEND\nSUB 32\nENDSUB\n", manual) == []
    assert codes("GOSUB 0\n", manual) == ["A104"]
    data["arcus"] = {**data["arcus"], "subroutines": [0, 31]}
    strict = analyze("GOSUB 0\nEND\nSUB 0\nENDSUB\n", profiles.Profile("p", "arcus", "x", data=data))
    assert [(d.code, d.severity.value) for d in strict.diagnostics] == [("A105", "error")]


def test_undefined_subroutines_are_one_semantic_diagnostic_per_number() -> None:
    diags = analyze("GOSUB 1\nX0\nGOSUB 2\nGOSUB 1\nGOSUB 1\n").diagnostics.sorted()
    assert [(d.code, d.kind.value, d.span.line) for d in diags] == [("A106", "semantic", 1), ("A106", "semantic", 3)]
    assert "lines 4, 5" in diags[0].notes[0]


def test_host_commands_name_their_standalone_twin() -> None:
    messages = [d.message for d in analyze("HSX=5\nCLRY\nJX+\nSLOAD=1\n").diagnostics.sorted()]
    assert "HSPD" in messages[0] and "ECLEARY" in messages[1] and "JOG" in messages[2]
    assert "no equivalent" in messages[3]


def test_multi_operator_assignments_keep_their_meaning_in_the_ir() -> None:
    result = analyze("V1=V2+V3*4-V5\n")
    assert [d.code for d in result.diagnostics] == ["A117"]
    value = result.module.routines[0].blocks[0].ops[0].value
    assert value.op == "-" and value.left.op == "+" and value.left.right.op == "*"


def test_no_input_raises(tmp_path) -> None:
    for text in ["", "\n\n", "IF", "ELSEIF\n", "V", "X", ":", "~", "SUB\nSUB 1\nSUB 1", "ENDSUB\nENDIF\nENDWHILE",
                 "ARCP::", "X--1", "V1=~~~", "GOSUB 99999999999999999999", "\x00\x01", "é", "END\nEND\nELSE"]:
        result = driver.compile_file("f.prg", "arcus", text=text)
        assert not [d for d in result.diagnostics if d.kind.value == "internal"], text


def test_a_bad_opener_line_still_opens_its_block() -> None:
    text = "WHILE V1=\nIF V2 == 3\nX1\nELSEIF V2=(3)\nX2\nENDIF\nENDWHILE\nSUB x\nENDSUB\nEND\n"
    assert codes(text) == ["A001", "A001", "A001", "A122"]
