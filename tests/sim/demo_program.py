"""A demonstration run for the documentation's plot: a small pick-and-place cycle in hand-built IR.

    python tests/sim/demo_program.py run.png

X homes against its switch, then three cycles: an interpolated X/Y move to the pick point,
output 1 (the gripper) on, a relative move back while Y runs an S-curve, and a wait for the
"part taken" input 2, which the scenario sets when X passes 2000 steps (and clears at 5000).
"""

from __future__ import annotations

import sys

from mcc.compiler import ir
from mcc.sim import Options, simulate
from mcc.sim.scenario import AxisSwitches, InputEvent, Scenario

U = ir.Unit


def program() -> ir.Module:
    def k(v, unit=U.NONE):
        return ir.Const(v, unit)

    setup = [ir.SetMotion(ir.MotionParam.MAX_SPEED, "*", k(8000, U.STEPS_PER_S)),
             ir.SetMotion(ir.MotionParam.INITIAL_SPEED, "*", k(400, U.STEPS_PER_S)),
             ir.SetMotion(ir.MotionParam.ACCEL, "*", k(20000, U.STEPS_PER_S2)),
             ir.SetMotion(ir.MotionParam.DECEL, "*", k(20000, U.STEPS_PER_S2)),
             ir.SetMotion(ir.MotionParam.PROFILE, "Y", k(1)),
             ir.Home("X", "switch", -1, zero="switch"), ir.WaitMotion("X"),  # 0 at the switch, no creep
             ir.Assign(ir.Var("V1"), k(0))]
    cycle = [ir.Move(ir.MoveMode.ABSOLUTE, (("X", k(6000, U.STEPS)), ("Y", k(3000, U.STEPS)))),
             ir.WaitMotion("*"),
             ir.SetOutput(1, k(1)), ir.Delay(k(0.3, U.S)),
             ir.Move(ir.MoveMode.RELATIVE, (("X", k(-6000, U.STEPS)),)),
             ir.Move(ir.MoveMode.ABSOLUTE, (("Y", k(0, U.STEPS)),)),
             ir.WaitInput(ir.Compare("=", ir.Status("input", index=2), k(1))),
             ir.SetOutput(1, k(0)), ir.WaitMotion("*"),
             ir.Assign(ir.Var("V1"), ir.BinOp("+", ir.Var("V1"), k(1)))]
    main = ir.Routine("main", ir.RoutineKind.MAIN, [
        ir.Block("setup", setup, ir.Jump("cycle")),
        ir.Block("cycle", cycle, ir.Branch(ir.Compare("<", ir.Var("V1"), k(3)), "cycle", "done")),
        ir.Block("done", [ir.Print((ir.Text("cycles: "), ir.Var("V1")))], ir.End())])
    return ir.Module("arcus", "pmx-4ex-sa", {"V1": ir.Variable("V1")}, [main], path="demo (hand-built IR)",
                     steps_per_rev=4000)


def scenario() -> Scenario:
    return Scenario(events=[InputEvent(2, 1, axis="X", passes=2000), InputEvent(2, 0, axis="X", passes=5000)], axes={"X": AxisSwitches(home=-2500)})


def main(argv: list[str]) -> int:
    from mcc.sim.plot import PlotUnavailable, plot

    out = argv[0] if argv else "sim-sample.png"
    trace = simulate(program(), scenario(), Options(until=30))
    trace.path = "pick-and-place demo (hand-built IR)"
    try:
        plot(trace, out)
    except PlotUnavailable as exc:
        print(exc, file=sys.stderr)
        return 2
    print(f"{out}: stopped: {trace.stopped} at {trace.time:.3f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
