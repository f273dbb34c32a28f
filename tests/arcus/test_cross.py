"""Compiling other dialects' programs into Arcus: units, ramps, move modes, axes, readings and
settings converted with the target profile, or refused with the construct and its line.

The IR modules here are written as the MCode and X150 frontends produce them under the issue 8
contract (steps, steps/s, steps/s^2, seconds, neutral names); the last tests run every sample
and golden program of the other dialects through `mcc compile --target arcus`.
"""

from __future__ import annotations

import pytest

from conftest import EXTENSIONS, GOLDEN, run_mcc, sample_files
from mcc.backends import arcus as backend
from mcc.compiler import driver, ir, profiles

from sim_behaviour import same_behaviour

PROFILE = profiles.load("pmx-4ex-sa")
S, SPS, SPS2, STEPS = ir.Unit.S, ir.Unit.STEPS_PER_S, ir.Unit.STEPS_PER_S2, ir.Unit.STEPS


def target_profile(**fields) -> profiles.Profile:
    data = {**PROFILE.data, **fields}
    return profiles.Profile(PROFILE.name, "arcus", PROFILE.product, PROFILE.title, PROFILE.firmware,
                            PROFILE.axes, int(fields.get("steps_per_rev", 0)), data)


def module(dialect: str, *ops, steps_per_rev: int = 0, subs=()) -> ir.Module:
    main = ir.Routine("main", ir.RoutineKind.MAIN, [ir.Block("b0", list(ops), ir.End())])
    return ir.Module(dialect, "src", routines=[main, *subs], path=f"src.{dialect}", steps_per_rev=steps_per_rev)


def setm(param, value, unit, axis="1"):
    return ir.SetMotion(param, axis, ir.Const(value, unit))


def move(mode, *targets):
    return ir.Move(mode, tuple((axis, ir.Const(v, STEPS)) for axis, v in targets))


def code_lines(listing) -> list[str]:
    return [line for line in listing.text.splitlines() if not line.startswith(";")]


def errors(listing) -> list[str]:
    return [d.message for d in listing.diagnostics if d.severity.value == "error"]


def read_back(listing) -> ir.Module:
    result = driver.check_file("out.prg", "arcus", text=listing.text)
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics] + [listing.text]
    return result.analysis.module


def test_an_acceleration_becomes_a_ramp_time_with_the_speeds_in_force() -> None:
    listing = backend.emit(module(
        "mcode", setm(ir.MotionParam.INITIAL_SPEED, 1000, SPS), setm(ir.MotionParam.MAX_SPEED, 5000, SPS),
        setm(ir.MotionParam.ACCEL, 20000, SPS2), setm(ir.MotionParam.DECEL, 20000, SPS2),
        move(ir.MoveMode.ABSOLUTE, ("1", 1000)),
        setm(ir.MotionParam.MAX_SPEED, 9000, SPS),  # a new speed: the same acceleration is a longer ramp
        move(ir.MoveMode.ABSOLUTE, ("1", 2000))), PROFILE)
    assert errors(listing) == []
    # (5000-1000)/20000 = 0.2 s; the deceleration ramps in the same time, so no second ACC
    assert code_lines(listing) == ["LSPDX=1000", "HSPDX=5000", "ACCX=200", "X1000", "HSPDX=9000", "ACCX=400",
                                   "X2000", "END"]
    again = read_back(listing)
    assert backend.emit(again, PROFILE).text == "\n".join(code_lines(listing)) + "\n"


def test_an_acceleration_set_before_the_speeds_is_written_when_they_are_known() -> None:
    listing = backend.emit(module(
        "mcode", setm(ir.MotionParam.ACCEL, 10000, SPS2), setm(ir.MotionParam.INITIAL_SPEED, 500, SPS),
        setm(ir.MotionParam.MAX_SPEED, 2500, SPS), move(ir.MoveMode.ABSOLUTE, ("1", 10))), PROFILE)
    assert code_lines(listing) == ["LSPDX=500", "HSPDX=2500", "ACCX=200", "X10", "END"]


def test_a_ramp_that_cannot_be_computed_is_refused_at_the_move() -> None:
    listing = backend.emit(module("mcode", setm(ir.MotionParam.ACCEL, 10000, SPS2),
                                  move(ir.MoveMode.ABSOLUTE, ("1", 10))), PROFILE)
    # reported where the acceleration is set (nothing follows that would make it a ramp time) and at
    # the move; and at the move once more: an axis's own acceleration is used only with its own
    # speeds (arcus-pmx-4ex-sa.txt L447-L457), which are not known there
    found = errors(listing)
    assert len(found) == 3
    assert sum("speeds that are not known" in e for e in found) == 2
    assert sum("speed axis 1 runs with here is not known" in e for e in found) == 1


def test_a_deceleration_other_than_the_acceleration_is_refused() -> None:
    listing = backend.emit(module(
        "x150", setm(ir.MotionParam.INITIAL_SPEED, 0, SPS), setm(ir.MotionParam.MAX_SPEED, 4000, SPS),
        setm(ir.MotionParam.ACCEL, 40000, SPS2), setm(ir.MotionParam.DECEL, 10000, SPS2)), PROFILE)
    assert len(errors(listing)) == 1 and "ramps down in the same time" in errors(listing)[0]


def test_ramp_times_and_delays_are_written_in_milliseconds() -> None:
    listing = backend.emit(module(
        "x150", setm(ir.MotionParam.ACCEL_TIME, 0.25, S), setm(ir.MotionParam.DECEL_TIME, 0.25, S),
        ir.Delay(ir.Const(1.5, S))), PROFILE)
    # an X150 program starts every move from standstill: LSPD at its lowest first (in_force.FIXED)
    assert code_lines(listing) == ["LSPD=1", "ACCX=250", "DELAY=1500", "END"]


def test_relative_moves_get_inc_and_absolute_ones_abs() -> None:
    listing = backend.emit(module(
        "x150", move(ir.MoveMode.RELATIVE, ("1", 4000)), move(ir.MoveMode.RELATIVE, ("1", 4000)),
        move(ir.MoveMode.ABSOLUTE, ("1", 0))), PROFILE)
    assert code_lines(listing) == ["LSPD=1", "INC", "X4000", "X4000", "ABS", "X0", "END"]
    modes = [op.mode for op in read_back(listing).routines[0].blocks[0].ops if isinstance(op, ir.Move)]
    assert modes == [ir.MoveMode.RELATIVE, ir.MoveMode.RELATIVE, ir.MoveMode.ABSOLUTE]


def test_the_same_moves_in_the_same_order_after_the_round_trip() -> None:
    # the speed for every axis: an axis's own HSPDX alone would not be used (arcus-pmx-4ex-sa.txt L449)
    source = module("mcode", setm(ir.MotionParam.MAX_SPEED, 4000, SPS, "*"), move(ir.MoveMode.RELATIVE, ("1", 50)),
                    ir.SetOutput(2, ir.Const(1)), ir.Delay(ir.Const(0.1, S)), move(ir.MoveMode.ABSOLUTE, ("1", 7)),
                    ir.WaitMotion("1"))
    compiled = read_back(backend.emit(source, PROFILE))
    # the same moves (axis 1 is X), output, delay and wait, in the same order and at the same times
    same_behaviour(source, compiled)
    moves = [op for _, b in compiled.blocks() for op in b.ops if isinstance(op, ir.Move)]
    assert [(m.mode, m.targets[0][0]) for m in moves] == [(ir.MoveMode.RELATIVE, "X"), (ir.MoveMode.ABSOLUTE, "X")]


def test_a_module_that_starts_unknown_writes_the_mode_first() -> None:
    profile = target_profile(arcus={**PROFILE.data["arcus"], "boot_move_mode": "unknown"})
    listing = backend.emit(module("mcode", move(ir.MoveMode.ABSOLUTE, ("1", 5))), profile)
    assert code_lines(listing) == ["ABS", "X5", "END"]


def test_a_profile_can_ask_for_the_first_mode_to_be_written_once_before_any_loop() -> None:
    profile = target_profile(arcus={**PROFILE.data["arcus"], "write_initial_move_mode": True})
    loop = ir.Routine("main", ir.RoutineKind.MAIN, [
        ir.Block("h", [], ir.Branch(ir.Compare("<", ir.Var("V1"), ir.Const(3)), "b", "x")),
        ir.Block("b", [move(ir.MoveMode.ABSOLUTE, ("X", 5)), ir.Assign(ir.Var("V1"), ir.Const(4))], ir.Jump("h")),
        ir.Block("x", [move(ir.MoveMode.ABSOLUTE, ("X", 0))], ir.End())])
    source = ir.Module("arcus", "src", routines=[loop])
    assert code_lines(backend.emit(source, profile)) == ["ABS", "WHILE V1<3", "X5", "V1=4", "ENDWHILE", "X0", "END"]
    assert code_lines(backend.emit(source, PROFILE)) == ["WHILE V1<3", "X5", "V1=4", "ENDWHILE", "X0", "END"]


def test_a_subroutine_called_in_its_mode_costs_no_switch() -> None:
    sub = ir.Routine("K", ir.RoutineKind.SUBROUTINE,
                     [ir.Block("k", [move(ir.MoveMode.RELATIVE, ("1", 1))], ir.Return())])
    source = module("mcode", move(ir.MoveMode.RELATIVE, ("1", 2)), ir.Call("K"), ir.Call("K"),
                    move(ir.MoveMode.RELATIVE, ("1", 3)), subs=(sub,))
    listing = backend.emit(source, PROFILE)
    assert code_lines(listing) == ["INC", "X2", "GOSUB 1", "GOSUB 1", "X3", "END", "SUB 1", "X1", "ENDSUB"]
    assert backend.emit(read_back(listing), PROFILE).text == "\n".join(code_lines(listing)) + "\n"


def test_positions_scale_to_the_target_resolution_or_are_refused() -> None:
    target = target_profile(steps_per_rev=4000)
    listing = backend.emit(module("mcode", move(ir.MoveMode.ABSOLUTE, ("1", 51200)),
                                  setm(ir.MotionParam.MAX_SPEED, 25600, SPS), steps_per_rev=51200), target)
    assert code_lines(listing) == ["X4000", "HSPDX=2000", "END"]
    listing = backend.emit(module("mcode", move(ir.MoveMode.ABSOLUTE, ("1", 100)), steps_per_rev=51200), target)
    [message] = errors(listing)
    assert "100 steps" in message and "51200" in message and "4000" in message and "--profile" in message


def test_the_header_states_the_assumptions_and_the_output_checks_clean() -> None:
    listing = backend.emit(module("x150", move(ir.MoveMode.ABSOLUTE, ("1", 1)), steps_per_rev=4000), PROFILE)
    header = [line for line in listing.text.splitlines() if line.startswith(";")]
    assert header[0].startswith("; compiled by mcc from x150")
    assert "source 4000" in header[1] and "target not set" in header[1] and "the target's is unknown" in header[1]
    assert "1->X" in header[2] and "ABS" in header[2]
    read_back(listing)
    assert not backend.emit(module("arcus", move(ir.MoveMode.ABSOLUTE, ("X", 1))), PROFILE).text.startswith(";")


def test_axes_map_in_order_and_a_fifth_axis_is_refused() -> None:
    listing = backend.emit(module("x150", move(ir.MoveMode.ABSOLUTE, ("2", 1)), move(ir.MoveMode.ABSOLUTE, ("1", 2))),
                           PROFILE)
    assert code_lines(listing) == ["LSPD=1", "Y1", "X2", "END"]  # device addresses 1..4 are X..U
    named = module("mcode", *[move(ir.MoveMode.ABSOLUTE, (name, 1)) for name in "ABCDE"])
    listing = backend.emit(named, PROFILE)
    assert code_lines(listing)[:4] == ["X1", "Y1", "Z1", "U1"]
    [message] = errors(listing)
    assert "axis 'E'" in message and "5 axes" in message


def test_the_one_unnamed_axis_of_a_single_axis_drive_is_x() -> None:
    listing = backend.emit(module("mcode", move(ir.MoveMode.RELATIVE, ("", 20000)), ir.WaitMotion(""),
                                  setm(ir.MotionParam.MAX_SPEED, 800, SPS, axis="")), PROFILE)
    assert code_lines(listing) == ["INC", "X20000", "WAITX", "HSPDX=800", "END"]
    assert "(unnamed)->X" in listing.text.splitlines()[2]


def test_neutral_readings_become_arcus_registers() -> None:
    v1 = ir.Var("V1")
    source = module("mcode",
                    ir.Assign(v1, ir.Status("position", "1")),
                    ir.WaitInput(ir.Compare("=", ir.Status("moving", "1"), ir.Const(0))),
                    ir.Assign(v1, ir.Status("input", "", 3)))
    listing = backend.emit(source, PROFILE)
    assert errors(listing) == []
    assert code_lines(listing) == ["V1=PX", "V60=MSTX&7", "WHILE V60!=0", "V60=MSTX&7", "ENDWHILE", "V1=DI3",
                                   "END"]


def test_what_the_pmx_has_no_counterpart_for_is_refused_by_name() -> None:
    source = module("mcode", ir.Setting("run_current", "1", ir.Const(50, ir.Unit.PERCENT)),
                    ir.Assign(ir.Var("V1"), ir.Status("fault", "1")),
                    ir.SetMotion(ir.MotionParam.ACCEL_TIME, "1", ir.BinOp("+", ir.Var("V2"), ir.Const(1))),
                    ir.SetOutput(1, ir.Const(1)))
    listing = backend.emit(source, PROFILE)
    messages = errors(listing)
    assert len(messages) == 3
    assert "run_current" in messages[0] and "'fault'" in messages[1] and "milliseconds" in messages[2]
    assert all(d.span is not None for d in listing.diagnostics)
    assert code_lines(listing) == ["DO1=1", "END"]


def test_arcus_settings_round_trip_through_their_neutral_names() -> None:
    text = ("SCVX=1\nECLEARY\nEO=3\nEO2=0\nSYNXC=1\nSYNXP=3000\nSYNXT=10\nSYNXO\nTR=1000\nV1=TR\nSYNXF\nSSPDMX=1\n"
            "SSPDX=3000\nEX=0\nACC=V3\nV2=SYNXS\nEND\n")
    result = driver.compile_file("t.prg", "arcus", text=text)
    assert not result.has_errors, result.diagnostics
    assert result.listing.text == text


def arcus_programs() -> list[str]:
    files = sample_files("arcus") + sorted(GOLDEN.joinpath("arcus").glob("*/*.prg"))
    return [str(path) for path in files]


@pytest.mark.parametrize("path", arcus_programs(), ids=lambda v: v.split("/")[-2] + "/" + v.split("/")[-1])
def test_arcus_programs_do_the_same_after_compiling(path: str) -> None:
    """The same moves, outputs, native commands and handlers, in the same order and at the same times."""
    checked = driver.check_file(path, "arcus")
    if checked.has_errors:
        return
    result = driver.compile_file(path, "arcus")
    compiled = read_back(result.listing)
    same_behaviour(checked.analysis.module, compiled)


# --- every sample and golden program of the other dialects ------------------------------------

def other_programs() -> list[tuple[str, str]]:
    found = []
    for dialect in ("mcode", "x150"):
        files = sample_files(dialect) + sorted(GOLDEN.joinpath(dialect).glob(f"*/*{EXTENSIONS[dialect]}"))
        found += [(dialect, str(path)) for path in files]
    return found


@pytest.mark.parametrize("dialect,path", other_programs(), ids=lambda v: v.split("/tests/")[-1])
def test_other_dialects_compile_into_arcus_or_are_refused_with_a_line(dialect: str, path: str) -> None:
    checked = driver.check_file(path, dialect)
    if checked.has_errors:
        return  # only a program that checks clean reaches a backend
    result = driver.compile_file(path, dialect, target="arcus")
    assert not [d for d in result.diagnostics if d.kind.value == "internal"]
    refusals = [d for d in result.diagnostics if d.severity.value == "error"]
    if refusals:
        assert all(d.span is not None and d.span.line >= 1 and d.message for d in refusals)
        return
    written = result.listing.text
    back = driver.compile_file("out.prg", "arcus", text=written)
    assert not back.has_errors, [(d.code, d.message) for d in back.diagnostics]
    code = "".join(line + "\n" for line in written.splitlines() if not line.startswith(";"))
    assert back.listing.text == code


def test_compile_into_arcus_from_the_command_line(tmp_path) -> None:
    source = tmp_path / "feed.x150"
    source.write_text("1A10\n1V2\n1D4000\n1G\n")
    result = run_mcc("compile", str(source), "--target", "arcus")
    assert "Traceback" not in result.stdout + result.stderr
    if result.returncode == 1:  # a refusal names the file and line
        assert f"{source}:" in result.stdout + result.stderr
    else:
        assert result.returncode == 0 and "X" in result.stdout


def test_an_mcode_initial_value_is_written_and_the_conversion_verifies(tmp_path) -> None:
    """`VA Q1=25` creates Q1 and sets it to 25 (lexium-mcode.txt L6031-L6036); Arcus declares no
    variables (arcus-pmx-4ex-sa.txt L2671-L2675: V0-V63 are assigned), so the output
    assigns it before the program runs, and `--verify` finds both programs move to 25."""
    source = tmp_path / "va.mxt"
    source.write_text("VA Q1=25\nPG 100\nMA Q1\nH\nE\nPG\n")
    result = run_mcc("compile", str(source), "--target", "arcus", "--verify", "-o", str(tmp_path / "va.prg"))
    assert result.returncode == 0, result.stdout + result.stderr
    lines = [line for line in (tmp_path / "va.prg").read_text().splitlines() if not line.startswith(";")]
    # the value is set first; the MCode drive's power-up speeds it moves with follow (VI, VM, A, D:
    # lexium-mcode.txt L662-L687), then the move to it
    assert lines[0] == "V0=25" and "XV0" in lines and lines.index("XV0") > 0


# --- properties ------------------------------------------------------------------------------------

from fractions import Fraction  # noqa: E402

from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as hs  # noqa: E402


@settings(max_examples=60, deadline=None)
@given(position=hs.integers(-10**7, 10**7), source=hs.sampled_from([200, 400, 4000, 25000, 51200]),
       target=hs.sampled_from([200, 1000, 4000, 10000]))
def test_a_position_is_scaled_exactly_or_refused(position: int, source: int, target: int) -> None:
    listing = backend.emit(module("mcode", move(ir.MoveMode.ABSOLUTE, ("1", position)), steps_per_rev=source),
                           target_profile(steps_per_rev=target))
    scaled = Fraction(position * target, source)
    if scaled.denominator == 1:
        assert code_lines(listing) == [f"X{scaled.numerator}", "END"]
    else:
        assert code_lines(listing) == ["END"] and len(errors(listing)) == 1


@settings(max_examples=60, deadline=None)
@given(initial=hs.integers(0, 5000), span=hs.integers(1, 200000), accel=hs.integers(1, 10**6))
def test_an_acceleration_becomes_the_ramp_time_of_the_speeds_in_force(initial: int, span: int, accel: int) -> None:
    listing = backend.emit(module("x150", setm(ir.MotionParam.INITIAL_SPEED, initial, SPS),
                                  setm(ir.MotionParam.MAX_SPEED, initial + span, SPS),
                                  setm(ir.MotionParam.ACCEL, accel, SPS2)), PROFILE)
    lspd = max(initial, 1)  # the LSPD written: the PMX-4EX-SA's minimum is 1 pulse/s (G005 below it)
    ramp = max(1, round((initial + span - lspd) / accel * 1000))
    assert code_lines(listing)[3] == f"ACCX={ramp}"  # after LSPD=1 (X150 starts from standstill), LSPDX, HSPDX


def test_values_outside_the_controllers_ranges_are_clamped_with_a_warning_or_refused() -> None:
    listing = backend.emit(module("x150", setm(ir.MotionParam.INITIAL_SPEED, 0, SPS),
                                  setm(ir.MotionParam.MAX_SPEED, 7_000_000, SPS), ir.SetOutput(3, ir.Const(2)),
                                  ir.Setting("compare_pulse", "1", ir.Const(0.02, S))), PROFILE)
    assert code_lines(listing) == ["LSPD=1", "LSPDX=1", "END"]
    assert [d.code for d in listing.diagnostics] == ["G005", "G003", "G003", "G003"]
    assert "6000000" in errors(listing)[0] and "SYNT" in errors(listing)[2]


def test_input_and_output_patterns_become_bit_tests_and_bit_writes() -> None:
    source = module("x150", ir.WaitInput(ir.InputMatch(ir.Pattern("1X0"))), ir.SetOutput(None, ir.Pattern("X10")))
    listing = backend.emit(source, PROFILE)
    assert errors(listing) == []
    lines = code_lines(listing)
    assert lines.index("DO2=1") + 1 == lines.index("DO3=0")  # X leaves output 1 alone
    assert "IF DI1=1" in lines and "IF DI3=0" in lines  # the AND of both bits, through a flag
    read_back(listing)
    too_wide = backend.emit(module("x150", ir.WaitInput(ir.InputMatch(ir.Pattern("XXXXXXXX1")))), PROFILE)
    assert "beyond DI8" in errors(too_wide)[0]


def test_readings_in_conditions_keep_their_axis() -> None:
    text = "IF MSTX=0\nDO=6\nELSEIF MSTY=0\nDO=3\nENDIF\nWHILE PZ<100\nZ100\nENDWHILE\nEND\n"
    result = driver.compile_file("t.prg", "arcus", text=text)
    assert not result.has_errors, result.diagnostics
    assert result.listing.text == text


def test_an_x150_program_starts_from_standstill_so_its_ramps_need_only_the_max_speed() -> None:
    """X150 has no initial speed (in_force.FIXED): `A10 V10` converts although no initial speed is
    set, with LSPD written at its lowest and the ramp computed from it; the header says so."""
    result = driver.compile_file("a.x150", "x150", target="arcus", text="MN\nA10\nV10\nD8000\nG\n")
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics]
    assert code_lines(result.listing)[:3] == ["LSPD=1", "HSPD=40000", "ACC=1000"]  # (40000 - 1) / 40000 s
    assert any("standstill" in line for line in result.listing.text.splitlines() if line.startswith(";"))
    again = driver.compile_file("a.prg", "arcus", text=result.listing.text)
    assert not again.has_errors
