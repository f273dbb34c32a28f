"""Each dialect's homing as its manual describes it, with the home switch at a known machine
position (docs/SIMULATOR.md, "Homing"). Every expected time, position and machine zero is worked
out by hand in the test from the manual's description; the home_end event reports the program's
position, the machine position and the machine coordinate of program position 0 ("zero")."""

from __future__ import annotations

import pytest

from mcc.compiler import driver, ir
from mcc.sim.interpreter import Options, simulate
from mcc.sim.scenario import AxisSwitches, Scenario
from mcc.sim.verify import compare
from sim_helpers import c, kinds, module

U = ir.Unit


def run(text: str, dialect: str, axis: str, home: float, path: str = "h"):
    result = driver.check_file(f"{path}.{ {'mcode': 'mxt', 'arcus': 'prg', 'x150': 'x150'}[dialect]}", dialect,
                               None, text)
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics]
    trace = simulate(result.analysis.module, Scenario(axes={axis: AxisSwitches(home=home)}),
                     Options(until=30, samples=False))
    assert trace.stopped == "end", trace.reason
    (end,) = kinds(trace, "home_end")
    return trace, end


MCODE_SETUP = "IS=1,1,0\nVI=400\nVM=4000\nA=20000\nD=20000\n"  # input 1 is home (L3512)


def test_mcode_hm1_creeps_back_off_the_switch_at_vi_and_leaves_the_counter_alone():
    """lexium-mcode.txt L3198: HM seeks at VM "until it reaches the home switch. It then creeps away
    from the switch in the direction specified at VI ... Motion ceases as soon as the switch
    deactivates"; type 1 seeks in minus and creeps in plus (L3206-L3210). The manual never says HM
    changes P (its example sets P=0 after HM and H, L8084-L8086), so the counter keeps counting.

    Switch at machine -3000, the axis at machine 0 with P=1000 (offset -1000):
    seek: 400 -> 4000 steps/s at A=20000: (4000² - 400²) / 40000 = 396 steps in 0.18 s, cruise
    3000 - 396 = 2604 steps / 4000 = 0.651 s: the switch at 0.831 s at 4000 steps/s;
    brake at D=20000 to VI: 0.18 s, 396 steps past: machine -3396;
    creep + at VI=400 back to the switch edge: 396 / 400 = 0.99 s; ends at 2.001 s, machine
    -3000; P = -3000 - (-1000) = -2000; the machine zero stays at -1000."""
    trace, end = run(MCODE_SETUP + "PG 100\nP=1000\nHM 1\nH\nPR P\nE\nPG\n", "mcode", "1", -3000)
    assert end.t == pytest.approx(2.001, abs=1e-6)
    assert (end.data["machine"], end.data["zero"], end.data["position"]) == (-3000, -1000, -2000)
    assert trace.prints[-1][1].strip() == "-2000"


def test_mcode_hm3_seeks_plus_and_creeps_minus():
    """lexium-mcode.txt L3208: type 3 seeks in plus at VM and creeps in minus at VI (L3198).
    Switch at machine +1000, from 0: seek 396 steps in 0.18 s, then 604 / 4000 = 0.151 s
    (0.331 s); brake 0.18 s to machine 1396; creep back 396 / 400 = 0.99 s: 1.501 s, machine
    1000, P 1000 (the counter was not zeroed), zero at 0."""
    _, end = run(MCODE_SETUP + "PG 100\nHM 3\nH\nE\nPG\n", "mcode", "1", 1000)
    assert end.t == pytest.approx(1.501, abs=1e-6)
    assert (end.data["machine"], end.data["zero"], end.data["position"]) == (1000, 0, 1000)


def test_mcode_hm2_creeps_on_away_from_a_switch_already_passed():
    """lexium-mcode.txt L3207: type 2 seeks and creeps in minus. mcc's switch is a point (the
    scenario's `home`): once the axis has braked past it, creeping further away leaves nothing to
    deactivate, so the homing ends where the brake ended (docs/SIMULATOR.md, "Homing").
    Switch at -3000: 0.831 s to the switch, 0.18 s brake: 1.011 s, machine -3396."""
    _, end = run(MCODE_SETUP + "PG 100\nHM 2\nH\nE\nPG\n", "mcode", "1", -3000)
    assert end.t == pytest.approx(1.011, abs=1e-6)
    assert (end.data["machine"], end.data["zero"], end.data["position"]) == (-3396, 0, -3396)


ARCUS_SETUP = "HSPD=4000\nLSPD=400\nACC=200\nEO=1\n"


def test_arcus_home_zeroes_the_counter_at_the_switch_and_stops_past_zero():
    """arcus-pmx-4ex-sa.txt L662 (and L1003): "the axis ramps from low speed (Lspd) to high speed
    (Hspd) ... until the home sensor is triggered. At the home sensor trigger, pulse and encoder
    position counters reset to zero and the deceleration is done ... At the end of the home
    routine, actual position may not be exactly zero".

    ACC=200 ms from 400 to 4000 steps/s: 3600 / 0.2 = 18000 steps/s². Switch at machine -3000:
    ramp (4000² - 400²) / 36000 = 440 steps in 0.2 s, cruise 2560 / 4000 = 0.64 s: the switch at
    0.84 s, where the counter becomes 0 (machine zero -3000); brake 0.2 s, 440 steps: ends at
    1.04 s, machine -3440, position -440."""
    trace, end = run(ARCUS_SETUP + "HOMEX-\nWAITX\nEND\n", "arcus", "X", -3000)
    assert end.t == pytest.approx(1.04, abs=1e-6)
    assert (end.data["machine"], end.data["zero"], end.data["position"]) == (-3440, -3000, -440)
    assert trace.axes["X"] == -440


def test_arcus_home_close_to_the_switch_brakes_from_the_speed_it_reached():
    """arcus-pmx-4ex-sa.txt L662: the seek does not know where the switch is, so it is still
    accelerating when the switch 200 steps away trips: v² = 400² + 2 · 18000 · 200 = 7,360,000,
    v = 2712.9 steps/s after (2712.9 - 400) / 18000 = 0.1285 s; braking back to LSPD takes as long
    and as far: 0.257 s, machine -400, position -200, zero -200."""
    _, end = run(ARCUS_SETUP + "HOMEX-\nWAITX\nEND\n", "arcus", "X", -200)
    assert end.t == pytest.approx(2 * (7_360_000 ** 0.5 - 400) / 18000, abs=1e-6)
    assert (end.data["machine"], end.data["zero"], end.data["position"]) == (-400, -200, -200)


def test_arcus_zhome_ramps_down_to_lspd_and_zeroes_where_it_stops_on_the_index():
    """arcus-pmx-4ex-sa.txt L676 (ZHOME = ASCII mode 2, L1000): at the home sensor "deceleration is
    done to ensure smooth ramp down to low speed. Low speed is maintained until the index channel
    of the encoder is triggered at which point the motion stops and pulse and encoder position
    counters are reset to zero". mcc's scenarios have no index mark: it comes as the axis reaches
    LSPD (docs/SIMULATOR.md). Same motion as HOMEX- (1.04 s, machine -3440) but the counter is 0
    where it stops: zero at -3440, position 0."""
    _, end = run(ARCUS_SETUP + "ZHOMEX-\nWAITX\nEND\n", "arcus", "X", -3000)
    assert end.t == pytest.approx(1.04, abs=1e-6)
    assert (end.data["machine"], end.data["zero"], end.data["position"]) == (-3440, -3440, 0)


def test_arcus_zome_zeroes_at_the_index_and_stops_past_it():
    """arcus-pmx-4ex-sa.txt L678-L680 (ZOME = mode 3, L1005): the axis "maintains the high speed
    until the index channel of the encoder is triggered at which point the motion stops and ...
    counters are reset to zero". The scenario's home position stands for the index; the counter
    becomes 0 there and the stop ramps down as HOME's (mcc's decision): 1.04 s, machine -3440,
    zero -3000, position -440."""
    _, end = run(ARCUS_SETUP + "ZOMEX-\nWAITX\nEND\n", "arcus", "X", -3000)
    assert end.t == pytest.approx(1.04, abs=1e-6)
    assert (end.data["machine"], end.data["zero"], end.data["position"]) == (-3440, -3000, -440)


def test_x150_gh_reverses_onto_the_switch_edge_at_ghf_and_zeroes_there():
    """parker-x150.md L1711-L1722: GH-1 turns negatively at 1 rev/s, at the home input "It will then
    stop, reverse and finally stop completely when the home switch is hit for the second time";
    the final move runs at GHF (default 0.1 rev/s, L1726-L1734); "the GH command will reset the
    absolute position counter to zero" (L1715); GH ramps at GA, default 10 rev/s² (L1686-L1695),
    not at the move acceleration A.

    4000 steps/rev (CUR default); GA 10 = 40000 steps/s², GH-1 = 4000 steps/s. Switch at -3000:
    ramp 4000² / 80000 = 200 steps in 0.1 s, cruise 2800 / 4000 = 0.7 s: the switch at 0.8 s;
    brake 0.1 s, 200 steps past (-3200); creep back at 400 steps/s: 0.5 s. Ends at 1.4 s on the
    switch edge, machine -3000, position 0, zero -3000."""
    _, end = run("1XE10\n1XD10\n1A20\n1GH-1\n1XT\n", "x150", "1", -3000)
    assert end.t == pytest.approx(1.4, abs=1e-6)
    assert (end.data["machine"], end.data["zero"], end.data["position"]) == (-3000, -3000, 0)


def test_x150_ga_and_ghf_set_the_homing_ramp_and_the_final_speed():
    """parker-x150.md L1695 (GA: the acceleration of GH, replacing the default 10 rev/s²) and
    L1726-L1734 (GHF: the final move's speed). GA20 = 80000 steps/s², GHF0.5 = 2000 steps/s.
    Switch at +3000, GH2 = 8000 steps/s: ramp 8000² / 160000 = 400 steps in 0.1 s, cruise
    2600 / 8000 = 0.325 s (0.425 s); brake 0.1 s, 400 steps past (3400); creep back
    400 / 2000 = 0.2 s: 0.725 s, machine 3000, zero 3000."""
    _, end = run("1XE10\n1XD10\n1GA20\n1GHF0.5\n1GH2\n1XT\n", "x150", "1", 3000)
    assert end.t == pytest.approx(0.725, abs=1e-6)
    assert (end.data["machine"], end.data["zero"], end.data["position"]) == (3000, 3000, 0)


def test_the_homing_ir_carries_each_products_homing():
    """The lowering writes the profile's [homing] table into ir.Home: the simulator reads no
    dialect name (lexium-mcode.txt L3198, arcus-pmx-4ex-sa.txt L662, parker-x150.md L1715)."""
    def home_of(text, dialect, ext):
        result = driver.check_file(f"h.{ext}", dialect, None, text)
        return next(op for _, b in result.analysis.module.blocks() for op in b.ops if isinstance(op, ir.Home))

    mcode = home_of("PG 100\nHM 4\nH\nE\nPG\n", "mcode", "mxt")
    assert (mcode.direction, mcode.creep, mcode.creep_speed, mcode.zero, mcode.needs_input) == (1, 1, None, "none", True)
    arcus = home_of("HOMEY+\nEND\n", "arcus", "prg")
    assert (arcus.direction, arcus.creep, arcus.zero) == (1, 0, "switch")
    x150 = home_of("1XE10\n1XD10\n1GH-2\n1XT\n", "x150", "x150")
    assert (x150.direction, x150.creep, x150.creep_speed.value, x150.zero) == (-1, 1, 400, "end")
    assert x150.accel.value == 40000 and mcode.accel is None and arcus.accel is None


def test_the_oracle_reports_a_homing_that_moves_the_machine_zero():
    """A conversion that homes to the same place but zeroes the counter elsewhere is a different
    program (issue 22): program position 0 is at another machine position afterwards. Zero at
    the switch (Arcus, L662) vs where the homing stops: the same motion, different zeros."""
    ops = [ir.SetMotion(ir.MotionParam.MAX_SPEED, "X", c(1000, U.STEPS_PER_S)),
           ir.SetMotion(ir.MotionParam.ACCEL, "X", c(10000, U.STEPS_PER_S2)),
           ir.SetMotion(ir.MotionParam.DECEL, "X", c(10000, U.STEPS_PER_S2))]
    at_switch = module(ops + [ir.Home("X", "switch", -1, zero="switch"), ir.WaitMotion("X")])
    at_stop = module(ops + [ir.Home("X", "switch", -1, zero="end"), ir.WaitMotion("X")])
    found = compare(at_switch, at_stop, [Scenario(axes={"X": AxisSwitches(home=-2000)})])
    assert found is not None and "homing" in found.message and "zero" in found.message
    assert compare(at_switch, module(ops + [ir.Home("X", "switch", -1, zero="switch"), ir.WaitMotion("X")]),
                   [Scenario(axes={"X": AxisSwitches(home=-2000)})]) is None


@pytest.mark.parametrize("source, dialect, target, line", [
    ("HSPD=4000\nLSPD=400\nACC=200\nHOMEX-\nWAITX\nEND\n", "arcus", "mcode", 4),
    ("HSPD=4000\nLSPD=400\nACC=200\nHOMEX-\nWAITX\nEND\n", "arcus", "x150", 4),
    ("1XE10\n1XD10\n1V2\n1GH-1\n1XT\n", "x150", "arcus", 4),
    ("1XE10\n1XD10\n1V2\n1GH-1\n1XT\n", "x150", "mcode", 4),
    ("IS=1,1,0\nPG 100\nVM=4000\nHM 1\nH\nE\nPG\n", "mcode", "arcus", 4),
    ("IS=1,1,0\nPG 100\nVM=4000\nHM 1\nH\nE\nPG\n", "mcode", "x150", 4),
])
def test_a_cross_compiled_homing_that_would_move_the_zero_is_refused_on_its_line(source, dialect, target, line):
    """MCode HM leaves the counter alone (lexium-mcode.txt L3198), Arcus HOME zeroes it at the
    switch and stops past it (arcus-pmx-4ex-sa.txt L662), X150 GH zeroes it on the switch edge
    after creeping back (parker-x150.md L1715, L1722): no dialect's homing keeps another's machine
    zero and stop, so each conversion is refused (G003) on the homing line."""
    ext = {"mcode": "mxt", "arcus": "prg", "x150": "x150"}[dialect]
    result = driver.compile_file(f"h.{ext}", dialect, target, text=source)
    refusals = [d for d in result.diagnostics if d.code == "G003" and d.span.line == line]
    assert refusals, [(d.code, d.message) for d in result.diagnostics]
    if dialect != "x150":  # GH's speed of its own is refused first (MCode has no homing speed but VM)
        assert any("zero" in refusal.message for refusal in refusals), [r.message for r in refusals]


@pytest.mark.parametrize("source, dialect, ext, axis", [
    (ARCUS_SETUP + "HOMEX-\nWAITX\nX100\nWAITX\nEND\n", "arcus", "prg", "X"),
    (ARCUS_SETUP + "ZHOMEX-\nWAITX\nX100\nWAITX\nEND\n", "arcus", "prg", "X"),
    ("1XE10\n1XD10\n1A20\n1V2\n1GH-1\n1D100\n1G\n1XT\n", "x150", "x150", "1"),
    (MCODE_SETUP + "PG 100\nHM 1\nH\nMA 100\nH\nE\nPG\n", "mcode", "mxt", "1"),
])
def test_a_homing_compiled_to_its_own_dialect_verifies(source, dialect, ext, axis):
    """The same product's homing keeps the zero and the stop (L3198 / L662 / L1715): compiling to
    the source's dialect with --verify writes the program."""
    from mcc.sim.verify import check_translation

    result = driver.compile_file(f"h.{ext}", dialect, dialect, text=source)
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics]
    checked = driver.check_file(f"h.{ext}", dialect, None, source)
    problem = check_translation(f"h.{ext}", dialect, checked.analysis.module, result.listing.text, dialect,
                                scenarios=[Scenario(axes={axis: AxisSwitches(home=-3000)})])
    assert problem == ""


def test_the_virtual_device_runs_an_immediate_hm_through_its_creep():
    """An immediate `HM 1` on the virtual MCode device (its machine has the home switch at machine
    0): the seek, the brake past the switch and the creep back at VI follow one another before the
    machine is frozen (lexium-mcode.txt L3198), and P keeps counting: P=500 at machine 0, MR 1000
    (P 1500, machine 1000), HM 1 ends on the switch at machine 0, where P reads 500."""
    from mcc.link.device.mcode import MCodeDevice

    device = MCodeDevice()
    for command in ("IS=1,1,0", "VI=400", "VM=4000", "A=20000", "D=20000", "P=500", "MR 1000", "HM 1"):
        device.command(f"{command}\r".encode())
    assert device.command(b"PR P\r").split(b"\r\n")[1] == b"500"


def test_the_printer_and_the_verifier_know_the_homing_fields():
    """docs/IR.md, "Home": the printer shows the creep and the zero; the verifier rejects a zero or
    a creep direction outside the contract (the simulator would otherwise guess)."""
    from mcc.compiler import ir_print, ir_verify

    op = ir.Home("1", "switch", -1, creep=1, zero="none")
    assert ir_print.op_text(op) == "home 1 switch direction -1 creep +1 zero none"
    assert ir_print.op_text(ir.Home("1", "switch", -1, creep=1, zero="none", needs_input=True)).endswith("needs home input")
    x150 = ir.Home("1", "switch", 1, creep=-1, creep_speed=c(400, U.STEPS_PER_S), zero="end",
                   speed=c(8000, U.STEPS_PER_S), accel=c(40000, U.STEPS_PER_S2))
    assert ir_print.op_text(x150) == \
        "home 1 switch direction +1 speed 8000 steps/s accel 40000 steps/s^2 creep -1 at 400 steps/s zero end"
    bad = module([ir.Home("X", "switch", -1, creep=2, zero="somewhere")])
    messages = [v.message for v in ir_verify.verify(bad)]
    assert any("creep direction 2" in m for m in messages) and any("'somewhere'" in m for m in messages)


def test_mcode_hm_without_a_home_input_stops_with_error_80_s016():
    """lexium-mcode.txt L3200: HM needs "a switch connected to an input defined as home using the IS
    (Input Setup) command" (type 1 in the IS table, L3512); without one the drive answers Error 80
    "HOME Sw. not defined" (L8515): the homing does not move and the run stops with S016."""
    result = driver.check_file("h.mxt", "mcode", None, "VM=4000\nPG 100\nHM 1\nH\nE\nPG\n")
    trace = simulate(result.analysis.module, Scenario(axes={"1": AxisSwitches(home=-3000)}))
    assert trace.stopped == "error" and [d.code for d in trace.diagnostics] == ["S016"]
    assert trace.diagnostics[0].span.line == 3 and kinds(trace, "home") == []
    set_up = driver.check_file("h.mxt", "mcode", None, "IS=2,1,0\nVI=400\nVM=4000\nPG 100\nHM 1\nH\nE\nPG\n")
    assert simulate(set_up.analysis.module, Scenario(axes={"1": AxisSwitches(home=-3000)})).stopped == "end"
