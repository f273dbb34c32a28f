"""The Lexium MCode machine as its manual describes it (issue 22): power-up settings, float
registers, inputs and integer arithmetic. Each expected value is worked out by hand from the manual
line cited in the test's docstring."""

from __future__ import annotations

import math

import pytest

from mcc.compiler import driver, in_force, ir, profiles
from mcc.sim.files import simulate_file
from mcc.sim.scenario import Scenario


def run(text: str, scenario: Scenario | None = None, profile: str | None = None):
    prof = profiles.load(profile) if profile else None
    simulated = simulate_file("prog.mxt", "mcode", prof, scenario, text=text)
    errors = [d for d in simulated.result.diagnostics if d.severity.value == "error"]
    assert not errors, errors
    assert simulated.trace is not None
    return simulated.trace


def program(*lines: str) -> str:
    return "\n".join(("PG 100",) + lines + ("E", "PG", ""))


def triangle_time(distance: float, start: float, accel: float) -> float:
    """A move too short to reach VM: ramp from `start` up to the peak and back down (A = D)."""
    peak = math.sqrt(start * start + accel * distance)  # v² = VI² + 2·A·(distance/2)
    return 2 * (peak - start) / accel


# -- 1. power-up settings ------------------------------------------------------------------------

def test_a_move_with_nothing_set_runs_at_the_factory_defaults():
    """lexium-mcode.txt L662-L687: VI 1000 steps/s, VM 768000 steps/s, A = D 1,000,000 steps/s².
    MA 51200 from 0: half the distance (25600) is reached before VM (reaching VM takes
    (768000² - 1000²) / 2e6 = 294,911 steps), so the profile is a triangle with peak
    sqrt(1000² + 1e6·51200) = 226,276.8 steps/s: t = 2·(226276.8 - 1000) / 1e6 = 0.4506 s."""
    trace = run(program("MA 51200", "H"))
    assert trace.axes["1"] == 51200
    assert trace.time == pytest.approx(triangle_time(51200, 1000, 1e6), abs=1e-3)
    assert trace.time == pytest.approx(0.4506, abs=1e-3)


def test_the_defaults_are_read_as_the_program_reads_them():
    """L666, L673, L680, L687: PR VI, VM, A, D answer the defaults when nothing was set."""
    trace = run(program("PR VI", "PR VM", "PR A", "PR D"))
    assert [text.strip() for _, text in trace.prints] == ["1000", "768000", "1000000", "1000000"]


def test_the_defaults_come_from_the_profile():
    """docs/PROFILES.md `[machine.defaults]`: the power-up values are the product's data, in the
    product's steps (MCode, L673) or revolutions (X150 V default 1 rev/s, parker-x150.md L4542)."""
    mcode = profiles.power_up(profiles.load("lmd-c"), 51200)
    assert mcode == {"initial_speed": 1000.0, "max_speed": 768000.0, "accel": 1e6, "decel": 1e6, "profile": 0}
    x150 = profiles.power_up(profiles.load("x150-blhx"), 4000)
    assert x150["max_speed"] == 4000.0  # 1 rev/s at 4000 steps/rev
    assert x150["accel"] == 40000.0  # no default in the manual (L197): mcc's fallback 10 rev/s²


def test_a_conversion_writes_the_sources_power_up_settings_where_the_target_differs():
    """A program that sets nothing moves at the MCode defaults (L662-L687); on an X150 (V 1 rev/s,
    parker-x150.md L4542) the same program would run 15 times slower, so the conversion writes VM,
    A and D explicitly before the program's first line, in a block of its own (a jump back to the
    first label does not set them again)."""
    result = driver.check_file("prog.mxt", "mcode", None, program("LB K1", "MA 51200", "H", "BR K1"))
    module = result.analysis.module
    converted = in_force.with_power_up(module, profiles.load("lmd-c"), profiles.load("x150-blhx"))
    main = next(r for r in converted.routines if r.kind is ir.RoutineKind.MAIN)
    first = main.blocks[0]
    assert isinstance(first.terminator, ir.Jump) and first.terminator.target == "K1"
    written = {op.param: op.value.value for op in first.ops}
    assert written[ir.MotionParam.MAX_SPEED] == 768000
    assert written[ir.MotionParam.ACCEL] == 1000000
    assert written[ir.MotionParam.DECEL] == 1000000
    # the source module is left as it was
    assert module.routines[0].blocks[0].label == "K1"


def test_a_validated_conversion_keeps_the_power_up_speeds():
    """L671-L687 against parker-x150.md L4542 (V 1 rev/s): `MA 51200` with nothing set but VI runs
    at VM 768000 steps/s = 15 rev/s and A 1e6 steps/s² = 19.53125 rev/s² at 51200 steps/rev; the X150
    output states them, and the validation that runs both agrees (no S010). On the Arcus the same
    speeds are HSPD=768000 and (the axis's own) LSPDX=400. VI=400: at the power-up VI of 1000 steps/s (L662-L666)
    the move, which X150 starts from standstill, would end 2 ms later, more than
    `[x150] start_speed_drift`: refused (X216, tests/test_cross_from_mcode.py)."""
    text = "VI=400\n" + program("MA 51200", "H")
    x150 = driver.compile_file("prog.mxt", "mcode", target="x150", text=text)
    assert not x150.has_errors, [(d.code, d.message) for d in x150.diagnostics]
    assert "V15" in x150.listing.text.splitlines() and "A19.5312" in x150.listing.text.splitlines()
    arcus = driver.compile_file("prog.mxt", "mcode", target="arcus", text=text)
    assert not arcus.has_errors, [(d.code, d.message) for d in arcus.diagnostics]
    assert {"HSPD=768000", "LSPDX=400"} <= set(arcus.listing.text.splitlines())


def test_a_conversion_between_equal_products_adds_nothing():
    """L662-L687: every MCode product powers up alike, so lmd-c -> lmm writes no setting."""
    result = driver.check_file("prog.mxt", "mcode", None, program("MA 51200", "H"))
    module = result.analysis.module
    assert in_force.with_source_power_up(module, profiles.load("lmm")) is module


# -- 2. float registers ----------------------------------------------------------------------------

def test_a_quotient_stored_in_a_float_register_keeps_its_fraction():
    """lexium-mcode.txt L2830-L2834: `VA Q1=25 VA Q2=30`, `F1=Q2/Q1`, `PR F1` answers 1.200000
    (the PF default 10,6,0,0 prints six decimals, L4760-L4775)."""
    trace = run("VA Q1=25\nVA Q2=30\n" + program("F1=Q2/Q1", "PR F1"))
    assert [text.strip() for _, text in trace.prints] == ["1.200000"]
    assert trace.variables["F1"] == pytest.approx(1.2)


def test_the_lowering_declares_the_registers_types():
    """L2802-L2811: F1-F8 are double-precision registers; R1-R4 are integers (their catalog
    defaults 0.0 and 0)."""
    module = driver.check_file("prog.mxt", "mcode", None, program("F1=R1/3", "R2=F1")).analysis.module
    assert module.type_of("F1") is ir.VarType.FLOAT64
    assert module.type_of("R1") is ir.VarType.INT32 and module.type_of("R2") is ir.VarType.INT32
    assert "F1" not in module.variables  # a register is never declared with VA by a backend


def test_a_float_copied_to_an_integer_drops_its_fraction_and_a_move_rounds_it_down():
    """L2813: a float transferred to a user variable or R1-R4 loses its fraction (toward zero:
    -142.2 -> -142); L2815: `MA F5` moves to the value rounded down (-142.2 -> -143)."""
    trace = run("VA RV=0\n" + program("F3=-51200/360", "RV=F3", "PR RV", "MA F3", "H", "PR P"))
    assert [text.strip() for _, text in trace.prints] == ["-142", "-143"]


def test_a_float_expression_feeds_a_move_with_its_full_precision():
    """issue 23: F3=51200/360 is 142.2222 (L2834), F4=F3*90 is 12800.0, `MA F4` ends at 12800,
    not 12780 (142 * 90) as integer arithmetic would give."""
    trace = run(program("F3=51200/360", "F4=F3*90", "MA F4", "H"))
    assert trace.axes["1"] == 12800


@pytest.mark.parametrize("level", ["O1", "O2", "Os"])
def test_the_optimizer_keeps_float_registers_float(level):
    """issue 23 (L2813, L2815, L2834): folding must not take F3 for the integer 142, and copy
    propagation must not rewrite `MA RV` (RV=F3 drops the fraction) as `MA F3` (rounds down)."""
    from mcc.compiler.opt import optimize
    from mcc.sim import simulate

    text = "VA RV=0\n" + program("F3=-51200/360", "F4=F3*90", "MA F4", "H", "RV=F3", "MA RV", "H", "PR F3",
                                 "F5=2", "PR F5")
    source = driver.check_file("prog.mxt", "mcode", None, text).analysis.module
    work = ir.copy_module(source)
    optimize(work, level, profiles.load("lmd-c"))
    moves = [op for _, b in work.blocks() for op in b.ops if isinstance(op, ir.Move)]
    assert isinstance(moves[1].targets[0][1], ir.Var) and moves[1].targets[0][1].name == "RV"
    before, after = simulate(source), simulate(work)
    assert [t for _, t in after.prints] == [t for _, t in before.prints]
    assert [t.strip() for _, t in before.prints] == ["-142.222222", "2.000000"]
    assert after.axes == before.axes == {"1": -142}


# -- 3. inputs -------------------------------------------------------------------------------------

def levels(*events: tuple[float, int, int], inputs: dict[int, int] | None = None) -> Scenario:
    from mcc.sim.scenario import InputEvent

    return Scenario(inputs=dict(inputs or {}), events=[InputEvent(n, v, at=t) for t, n, v in events])


def test_an_input_reads_its_logic_state_low_active_by_default():
    """lexium-mcode.txt L3273 (I1-I4 read the logic state, "dependent on active (low/high)
    setting"), L3500 (IS default: LOW active): a low level reads 1, a high level 0. The scenario
    gives levels (docs/SIMULATOR.md, "Inputs")."""
    trace = run(program("PR I1", "PR I2"), levels(inputs={1: 0, 2: 1}))
    assert [text.strip() for _, text in trace.prints] == ["1", "0"]


def test_is_sets_the_polarity_and_in_reads_the_raw_levels():
    """L3488-L3542: `IS=2,0,1` makes input 2 HIGH active; L3433-L3435: IN is the binary state of the
    inputs, 1 = input voltage, whatever their polarity. Levels 1,1,0,0: I1 (low-active) 0, I2
    (high-active) 1, IN = 0b0011 = 3."""
    trace = run("IS=2,0,1\n" + program("PR I1", "PR I2", "PR IN"), levels(inputs={1: 1, 2: 1, 3: 0, 4: 0}))
    assert [text.strip() for _, text in trace.prints] == ["0", "1", "3"]


def test_an_input_no_scenario_drives_is_inactive():
    """An idle input reads inactive whichever way it is wired (L3500 low-active: its line sits
    high, IN reads 1 for it): `BR K1, I1=0` polls until the line is pulled low at 1 s."""
    text = program("LB K1", "BR K1, I1=0", "PR IN")
    trace = run(text, levels((1.0, 1, 0)))
    assert trace.prints[0][0] == pytest.approx(1.0, abs=0.01)
    assert trace.prints[0][1].strip() == "14"  # input 1 low, inputs 2-4 idle high: 0b1110


def test_a_trip_on_input_fires_when_the_input_becomes_active():
    """L5716: `TI 1,Q1 TE=1` executes Q1 when input 1 is active; low-active by default (L3500), so
    the trip fires when the level falls."""
    text = "VA N1=0\n" + program("TI 1,K1", "TE=1", "LB G2", "H 100", "BR G2,N1<1", "E", "LB K1", "IC N1", "RT")
    trace = run(text, levels((1.0, 1, 1), (2.0, 1, 0)))
    assert [round(e.t, 3) for e in trace.events if e.kind == "handler"] == [2.0]


def test_a_conversion_to_a_product_of_the_other_polarity_inverts_the_reads():
    """An MCode I2 is low-active (L3500); an Arcus DI2 reads the level (arcus-pmx-4ex-sa.txt
    L1900-L1905: `IF DI=255` is "no inputs triggered"). `BR K1, I2=0` (loop while input 2 is
    inactive, its line high) becomes a loop while DI2=1, and the validation agrees."""
    source = "PG 1\nLB K1\nBR K1, I2=0\nO1=1\nE\nPG\n"
    result = driver.compile_file("prog.mxt", "mcode", target="arcus", text=source)
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics]
    assert "WHILE DI2=1" in result.listing.text


def test_an_arcus_input_read_becomes_the_inverted_mcode_input():
    """arcus L1900-L1905 (DI reads the level) against lexium-mcode.txt L3500 (I1 low-active): `IF
    DI1=1` (the line is high) is `I1=0` in MCode, written as the branch around the IF body."""
    result = driver.compile_file("prog.prg", "arcus", target="mcode", text="IF DI1=1\nDO1=1\nENDIF\nEND\n")
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics]
    assert "BR Z0,I1<>0" in result.listing.text


# -- 4. integer division ---------------------------------------------------------------------------

def test_integer_division_rounds_down_also_below_zero():
    """lexium-mcode.txt L1249: math outside F1-F8 is "rounded down to the nearest integer": 7/2 is
    3, -7/2 is -4 (toward minus infinity, not toward zero), 7/-2 is -4."""
    trace = run("VA Q1=-7\nVA Q2=7\nVA Q3=-2\n" + program("R1=Q2/2", "R2=Q1/2", "R3=Q2/Q3", "PR R1", "PR R2",
                                                          "PR R3"))
    assert [text.strip() for _, text in trace.prints] == ["3", "-4", "-4"]


def test_the_other_products_keep_their_truncating_division():
    """Only a profile with `integer_division = "floor"` rounds down (docs/SIMULATOR.md,
    "Arithmetic"): the shared arithmetic truncates toward zero by default."""
    from mcc.sim import values

    assert values.binary("/", -7, 2) == -3 and values.binary("/", -7, 2, "floor") == -4
    assert values.binary("%", -7, 2) == -1 and values.binary("%", -7, 2, "floor") == 1


def test_a_malformed_machine_table_in_a_users_profile_falls_back_without_a_traceback(tmp_path):
    """docs/PROFILES.md `[machine.*]`: values of the wrong kind are ignored (mcc's fallback applies):
    the run still ends, the float prints in Python's plain form, the speed is 1 rev/s."""
    path = tmp_path / "bad.toml"
    path.write_text('extends = "lmd-c"\nname = "bad"\n[machine.arithmetic]\nfloat_print = "abc"\n'
                    '[machine.inputs]\ncount = "x"\n[machine.defaults]\nunit = 5\n', encoding="utf-8")
    profile = profiles.load(str(path))
    assert profiles.power_up(profile, 51200)["max_speed"] == 51200.0  # 1 rev/s: the table is not read
    simulated = simulate_file("prog.mxt", "mcode", profile, None, text=program("F1=6/5", "PR F1", "PR IN"))
    assert simulated.trace is not None and simulated.trace.stopped == "end"
    assert [text.strip() for _, text in simulated.trace.prints] == ["1.2", "0"]
