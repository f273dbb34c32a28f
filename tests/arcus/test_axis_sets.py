"""Per-axis speed settings (HSPDa, LSPDa, ACCa): used only once all three are set for the axis,
otherwise the global HSPD, LSPD and ACC apply (arcus-pmx-4ex-sa.txt L447-L457). One rule, the
module's `axis_sets` fact, followed by the simulator, the values-in-force analysis, the optimizer
and the backends that convert Arcus settings."""

from __future__ import annotations

import pytest

from mcc.compiler import driver, in_force, ir
from conftest import run_mcc
from mcc.sim import simulate

SETS = (ir.MotionParam.INITIAL_SPEED, ir.MotionParam.MAX_SPEED, ir.MotionParam.ACCEL_TIME,
        ir.MotionParam.DECEL_TIME)


def lowered(text: str) -> ir.Module:
    result = driver.check_file("p.prg", "arcus", text=text)
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics]
    return result.analysis.module


def run(text: str):
    return simulate(lowered(text))


GLOBAL = "HSPD=1000\nLSPD=100\nACC=100\n"


def test_the_lowering_declares_the_axis_sets() -> None:
    """L449: "unless, ALL parameters (i.e. high speed, low speed, and acceleration) for a certain
    axis is configured": HSPDa, LSPDa and ACCa (both ramp times) form the set."""
    assert lowered("X0\n").axis_sets == SETS


def test_a_high_speed_of_its_own_alone_is_not_used() -> None:
    """L447-L449: HSPDX=5000 without LSPDX and ACCX leaves X on the global settings.
    By hand: HS 1000, LS 100, ACC 100 ms; each ramp covers (100 + 1000) / 2 * 0.1 = 55 pulses,
    1000 - 110 = 890 pulses at 1000 pps = 0.89 s, total 0.1 + 0.89 + 0.1 = 1.09 s."""
    trace = run(GLOBAL + "HSPDX=5000\nX1000\nWAITX\nEND\n")
    assert trace.time == pytest.approx(1.09)


def test_all_three_of_its_own_are_used() -> None:
    """L451-L457 (the manual's example: HSX, LSX and ACCX all set). By hand: HS 5000, LS 500,
    ACC 200 ms; each ramp covers (500 + 5000) / 2 * 0.2 = 550 pulses, 10000 - 1100 = 8900 pulses
    at 5000 pps = 1.78 s, total 0.2 + 1.78 + 0.2 = 2.18 s. Y, with none of its own, still runs on
    the global settings: 1000 pulses in 1.09 s as above."""
    trace = run(GLOBAL + "HSPDX=5000\nLSPDX=500\nACCX=200\nX10000\nWAITX\nY1000\nWAITY\nEND\n")
    ends = [e.t for e in trace.events if e.kind == "move_end"]
    assert ends == [pytest.approx(2.18), pytest.approx(2.18 + 1.09)]


def test_a_global_setting_does_not_overwrite_a_complete_set_of_its_own() -> None:
    """HSPD and HSPDX are different registers (L443-L445 global, L447 per axis): once X's set is
    complete, HSPD=1000 changes nothing for X (2.18 s as in the test above)."""
    trace = run("HSPDX=5000\nLSPDX=500\nACCX=200\n" + GLOBAL + "X10000\nWAITX\nEND\n")
    assert trace.time == pytest.approx(2.18)


def test_reading_back_gives_each_register() -> None:
    """HSX reads the per-axis high speed, HS the global one (L1552-L1560, the read forms)."""
    trace = run(GLOBAL + "HSPDX=5000\nV1=HSPDX\nV2=HSPD\nV3=ACC\nEND\n")
    assert (trace.variables["V1"], trace.variables["V2"], trace.variables["V3"]) == (5000, 1000, 100)


def state_before_move(text: str) -> in_force.State:
    module = lowered(text)
    analysis = in_force.InForce(module)
    (main,) = [r for r in module.routines if r.kind is ir.RoutineKind.MAIN]
    return next(state for _, _, op, state in analysis.walk(main) if isinstance(op, ir.Move))


def test_the_values_in_force_follow_the_same_rule() -> None:
    """L447-L457 in compiler/in_force.py: an incomplete set reads the global value, a complete one
    its own, and one complete on some paths only is not known."""
    speed = ir.MotionParam.MAX_SPEED
    alone = state_before_move(GLOBAL + "HSPDX=5000\nX1000\n")
    assert in_force.lookup(alone, speed, "X").value == 1000
    full = state_before_move(GLOBAL + "HSPDX=5000\nLSPDX=500\nACCX=200\nHSPD=2000\nX1000\nY1000\n")
    assert in_force.lookup(full, speed, "X").value == 5000 and in_force.lookup(full, speed, "Y").value == 2000
    maybe = state_before_move(GLOBAL + "HSPDX=5000\nLSPDX=500\nIF DI1=1\nACCX=200\nENDIF\nX1000\n")
    assert in_force.lookup(maybe, speed, "X") is None


@pytest.mark.parametrize("level", ["O1", "O2", "Os"])
def test_an_own_setting_equal_to_the_global_one_is_not_removed(level: str) -> None:
    """HSPDX=1000 after HSPD=1000 is not redundant (L449): without it X's set is incomplete and X
    runs with the global LSPD and ACC instead of LSPDX=50 and ACCX=300. Before the fix, -O2
    removed it across the block boundary (wrong code)."""
    text = GLOBAL + "IF DI1=1\nV1=1\nENDIF\nHSPDX=1000\nLSPDX=50\nACCX=300\nX1000\nWAITX\nEND\n"
    result = driver.compile_file("p.prg", "arcus", text=text, opt_level=level)
    assert "HSPDX=1000" in result.listing.text.splitlines()


def test_o2_removes_a_global_setting_already_in_force_across_blocks_and_calls() -> None:
    """A global HSPD already in force on every path (L443-L445) is redundant at -O2 across blocks
    and a call that sets nothing; one that a subroutine changes is kept."""
    text = ("HSPD=1000\nIF DI1=1\nV1=1\nENDIF\nGOSUB 1\nHSPD=1000\nX1000\nWAITX\nGOSUB 2\nHSPD=1000\n"
            "X0\nWAITX\nEND\nSUB 1\nV2=1\nENDSUB\nSUB 2\nHSPD=3000\nENDSUB\n")
    result = driver.compile_file("p.prg", "arcus", text=text, opt_level="O2")
    assert result.listing.text.splitlines().count("HSPD=1000") == 2  # the first, and the one after SUB 2


def test_into_mcode_an_incomplete_set_of_its_own_is_not_written() -> None:
    """HSPDX=5000 alone is not used (L447-L449): the MCode drive runs at the global HSPD."""
    text = "LSPD=100\nHSPD=1000\nACC=100\nHSPDX=5000\nX1000\nWAITX\nEND\n"
    result = driver.compile_file("p.prg", "arcus", target="mcode", text=text)
    code = [line for line in result.listing.text.splitlines() if not line.startswith("'")]
    assert "VM=5000" not in code and "VM=1000" in code


def test_into_mcode_a_complete_set_applies_and_survives_a_global_setting(tmp_path) -> None:
    """Once HSPDX, LSPDX and ACCX are all set, X runs with them (L451-L457) and a later HSPD=2000
    changes only the global register: the MCode drive keeps VM=5000 for the next move. By hand:
    ACCX=200 ms from 500 to 5000 pps is A = 4500 / 0.2 = 22500 steps/s²; --verify agrees."""
    source = tmp_path / "p.prg"
    source.write_text("LSPD=100\nHSPD=1000\nACC=100\nHSPDX=5000\nLSPDX=500\nACCX=200\nX1000\nWAITX\n"
                      "HSPD=2000\nX0\nWAITX\nEND\n")
    out = tmp_path / "p.mxt"
    result = run_mcc("compile", str(source), "--target", "mcode", "--verify", "-o", str(out))
    assert result.returncode == 0, result.stdout + result.stderr
    code = [line for line in out.read_text().splitlines() if not line.startswith("'")]
    assert code.index("VM=5000") < code.index("A=22500") < code.index("MA 1000")
    assert code[code.index("MA 0") - 1] == "VM=5000"  # X's own speed back after the global HSPD=2000


def test_into_mcode_a_set_complete_on_some_paths_only_is_refused_at_its_line() -> None:
    """Whether HSPDX applies depends on the path (L449): no MCode program can say it; refused."""
    text = "LSPD=100\nHSPD=1000\nACC=100\nIF DI1=1\nACCX=200\nENDIF\nLSPDX=500\nHSPDX=5000\nX1000\nWAITX\nEND\n"
    result = driver.compile_file("p.prg", "arcus", target="mcode", text=text)
    errors = [d for d in result.diagnostics if d.severity.value == "error"]
    assert errors and errors[0].code == "G003" and errors[0].span.line == 8  # HSPDX=5000: LSPDX before it left the set incomplete on every path


def test_into_arcus_an_axis_speed_of_its_own_becomes_a_complete_set(tmp_path) -> None:
    """X150 `1V8` sets device 1's velocity alone (parker-x150.md L179: an address makes a universal
    command device specific). On the PMX-4EX-SA HSPDX alone would not be used (L447-L449): the
    output completes X's set (LSPDX, ACCX) before X moves, and after the universal `V6` (every
    device) writes X's own HSPDX again, since HSPD no longer reaches an axis with a complete set.
    --verify runs both and finds the same motion."""
    source = tmp_path / "p.x150"
    source.write_text("V5\nA10\n1V8\n1D4000\n1G\nV6\n1D0\n1G\n")
    out = tmp_path / "p.prg"
    result = run_mcc("compile", str(source), "--target", "arcus", "--verify", "-o", str(out))
    assert result.returncode == 0, result.stdout + result.stderr
    code = [line for line in out.read_text().splitlines() if not line.startswith(";")]
    first, second = code.index("X4000"), code.index("X0")
    assert {"HSPDX=32000", "LSPDX=1"} <= set(code[:first]) and any(c.startswith("ACCX=") for c in code[:first])
    assert "HSPD=24000" in code[first:second] and "HSPDX=24000" in code[first:second]


def test_settings_sent_before_the_program_are_in_force_in_it() -> None:
    """MCode settings sent before `PG` run at once and hold when the program runs (lexium-mcode.txt
    L510-L512); the simulator runs them first. The values in force carry them into the program, so
    MCode -> Arcus, which must write axis 1's complete set (HSPDX, LSPDX, ACCX, L447-L457) before its
    first move, knows the initial speed there (issue 23: tests/sim/golden/mcode/sub_call.mxt was
    refused, G003 "the initial speed axis 1 runs with here is not known")."""
    text = "VI=500\nVM=5000\nA=50000\nD=50000\nPG 100\nLB MN\n  MR 1000\n  H\n  E\nPG\n"
    module = driver.check_file("p.mxt", "mcode", text=text).analysis.module
    analysis = in_force.InForce(module)
    (main,) = [r for r in module.routines if r.kind is ir.RoutineKind.MAIN]
    state = next(state for _, _, op, state in analysis.walk(main) if isinstance(op, ir.Move))
    assert in_force.lookup(state, ir.MotionParam.INITIAL_SPEED, "1").value == 500
    assert in_force.lookup(state, ir.MotionParam.MAX_SPEED, "1").value == 5000
    result = driver.compile_file("p.mxt", "mcode", target="arcus", text=text, always_verify=True)
    assert not [d for d in result.diagnostics if d.severity.value == "error"], \
        [(d.code, d.message) for d in result.diagnostics]
    code = [line for line in result.listing.text.splitlines() if not line.startswith(";")]
    assert {"LSPDX=500", "HSPDX=5000"} <= set(code[:code.index("X1000")])


def test_commands_that_never_end_carry_nothing_into_the_program() -> None:
    """The program's entry runs after the commands sent before it only when they end (the
    simulator's order, sim/interpreter.py): a stretch that loops for ever leaves nothing known, one
    that ends leaves its settings."""
    speed = ir.SetMotion(ir.MotionParam.INITIAL_SPEED, "1", ir.Const(500, ir.Unit.STEPS_PER_S))
    move = ir.Move(ir.MoveMode.RELATIVE, (("1", ir.Const(1000, ir.Unit.STEPS)),))

    def start_of_main(terminator) -> in_force.State:
        first = ir.Routine("immediate", ir.RoutineKind.IMMEDIATE, [ir.Block("i", [speed], terminator)])
        main = ir.Routine("main", ir.RoutineKind.MAIN, [ir.Block("m", [move], ir.End())])
        analysis = in_force.InForce(ir.Module("mcode", "lmd-c", routines=[first, main]))
        return next(state for _, _, op, state in analysis.walk(main) if isinstance(op, ir.Move))

    assert in_force.lookup(start_of_main(ir.FallOff()), ir.MotionParam.INITIAL_SPEED, "1").value == 500
    assert in_force.lookup(start_of_main(ir.Jump("i")), ir.MotionParam.INITIAL_SPEED, "1") is None


def test_an_axis_acceleration_replaces_its_ramp_time_in_force() -> None:
    """An acceleration and a ramp time give the same thing two ways; the one set last applies
    (docs/SIMULATOR.md, "Motion"). Setting the acceleration of axis 1 alone replaces the ramp time
    it ran with, its own or the one set for every axis: neither may be read for axis 1 afterwards
    (before, only a setting for every axis replaced the other)."""
    span = None
    ops = [ir.SetMotion(ir.MotionParam.ACCEL_TIME, ir.ALL_AXES, ir.Const(0.2, ir.Unit.S), span),
           ir.SetMotion(ir.MotionParam.ACCEL_TIME, "1", ir.Const(0.3, ir.Unit.S), span),
           ir.SetMotion(ir.MotionParam.ACCEL, "1", ir.Const(50000, ir.Unit.STEPS_PER_S2), span)]
    state: in_force.State = {}
    for op in ops:
        in_force.transfer(state, op, {})
    assert in_force.lookup(state, ir.MotionParam.ACCEL_TIME, "1") is None
    assert in_force.lookup(state, ir.MotionParam.ACCEL, "1").value == 50000
