"""Every operation of the table (compiler/ir_ops.py) is handled or refused by each backend, the
simulator and every optimizer pass: none is dropped silently (issue 26).

Each operation is exercised through a tiny module stated as IR text (one example per operation,
`EXAMPLES`; a new operation fails `test_every_operation_has_an_example` until it has one), from a
module of each source dialect:

- a backend (mcode, x150, arcus: `emit`) writes it (an output line maps back to its line) or
  refuses it with an error at its line; never an internal error or an exception. Terminators are
  rebuilt into the target's structure (a jump to the next block writes nothing), so for them only
  the absence of an internal error is checked;
- the simulator has a handler registered for it (`sim.interpreter.OP_METHODS`; terminators by its
  `_terminator`) and runs the module without an exception, any error at the operation's line;
- each optimizer pass keeps the verifier's contract and the simulated behaviour.
"""

from __future__ import annotations

import pytest

from ir_text import ir_from_text
from mcc.compiler import dialects, ir, ir_ops, profiles
from mcc.compiler.ir_verify import verify
from mcc.compiler.opt import PASSES, optimize

DIALECTS = ("mcode", "arcus", "x150")
PROFILES = {"arcus": "pmx-4ex-sa", "mcode": "lmd-c", "x150": "x150-pdhx"}
# The axes each dialect's lowering writes: MCode "" (this drive), X150 the device address.
AXES = {"arcus": ("X", "Y"), "mcode": ("", ""), "x150": ("1", "2")}

EXAMPLES = {
    "Assign": "V1 = V1 + 1",
    "SetMotion": "set max_speed {a} = 2000 steps/s",
    "Move": "move absolute {a}=400 steps",
    "Arc": "arc cw {a2},{b2} centre (100 steps, 0 steps) angle 90 deg",
    "Slew": "slew {a} velocity 1000 steps/s",
    "Home": "home {a} switch direction +1 zero switch",
    "Stop": "stop {a} ramp",
    "SetPosition": "set position {a} = 0 steps",
    "WaitMotion": "wait motion {a}",
    "Delay": "delay 0.5 s",
    "SetOutput": "output 1 = 1",
    "WaitInput": "wait until input[1] = 0",
    "Print": 'print "done ", V1',
    "DriveEnable": "enable {a} = 1",
    "Call": "call S1",
    "SetHandler": "on input(1, 1) -> S1",
    "Setting": "setting run_current {a} = 50 %",
    "Save": "save",
    "Pause": "pause {a}",
    "Resume": "resume {a}",
    "Step": "step {a} 1",
    "Native": "native {d} XYZ (1)",
    # terminators: the last line of block %1
    "Jump": "jump %1",
    "Branch": "branch V1 = 1 ? %1 : %2",
    "Return": "return",
    "End": "end",
    "GotoRoutine": "goto routine S1",
    "FallOff": "fall off",
}
# Other forms of some operations, which the handlers write another way.
VARIANTS = {
    "Move": ["move relative {a2}=400 steps {b2}=V1", "move absolute {a}=400 steps with p2=1"],
    "Arc": ["arc ccw {a2},{b2} centre (100 steps, 0 steps) full circle"],
    "Slew": ["jog {a} -"],
    "Home": ["home {a} switch direction -1 speed 500 steps/s creep +1 zero none needs home input"],
    "Stop": ["stop {a} abort"],
    "SetOutput": ["outputs = pattern 1X0"],
    "Print": ['print on {a} V1 as fixed 2 signed', 'print "tick" no-newline if tracing'],
    "Call": ["call S1 if input[2] = 1"],
    "SetHandler": ["on input(1, 1) off", "on time(1 s) -> S1 once gated"],
    "Setting": ["setting input_function[4] {a} = 0"],
    "Pause": ["pause {a} stop motion"],
    "Step": ["step {a} V1"],  # a count known only at run time (X150's #n takes a constant, L5548)
}
# A backend that handles an operation by writing nothing for it, and why.
WRITES_NOTHING = {
    ("x150", "Print", 2): "a trace report (Print.traced): an X150 in trace mode sends it by itself "
                          "(parker-x150.md L5384-L5433; docs/IR.md, \"Trace reports\")",
    # the example's abort is the module's first operation: no move can run there, so it stops nothing
    # (arcus-pmx-4ex-sa.txt L694) and a target without a stored abort writes nothing for it
    # (docs/CROSS.md, "Abort"; refused while a move may run: tests/test_cross_arcus.py)
    ("mcode", "Stop", 1): "an abort where no move can run (MCode stops at once only with ESC, from the host)",
    ("x150", "Stop", 1): "an abort where no move can run (X150 never saves K in a sequence)",
}
OP_LINE, TERM_LINE = 10, 11
CASES = [(name, 0) for name in EXAMPLES] + [(name, n) for name, more in VARIANTS.items() for n in range(1, len(more) + 1)]


def example(name: str, dialect: str, variant: int = 0) -> ir.Module:
    a, b = AXES[dialect]
    line = (EXAMPLES[name] if variant == 0 else VARIANTS[name][variant - 1]).format(a=a, b=b, a2=a or "X", b2=b or "Y", d=dialect)
    op, term = (line, "jump %2") if not ir_ops.BY_NAME[name].terminator else ("V1 = 1", line)
    return ir_from_text(f"""
        var V1: int32
        routine main (main)
        %1:
          {op}  ; L{OP_LINE}
          {term}  ; L{TERM_LINE}
        %2:
          end  ; L12

        routine S1 (subroutine) number=1
        S1:
          return  ; L20
    """, dialect)


NAMES = [d.name for d in ir_ops.TABLE.values()]


def test_every_operation_has_an_example():
    assert sorted(EXAMPLES) == sorted(NAMES)


@pytest.mark.parametrize("name, variant", CASES)
@pytest.mark.parametrize("source", DIALECTS)
def test_the_examples_keep_the_contract(name, variant, source):
    assert verify(example(name, source, variant)) == []


def outcome(listing, line: int) -> str:
    errors = [d for d in listing.diagnostics if d.severity.value == "error"]
    if any(d.code == "G001" for d in listing.diagnostics):
        return "internal error: " + "; ".join(d.message for d in listing.diagnostics if d.code == "G001")
    if any(d.span is not None and d.span.line == line for d in errors):
        return "refused"
    if any(s.line == line for out in listing.lines for s in out.sources):
        return "written"
    return "dropped: " + "; ".join(f"{d.code} line {d.span.line if d.span else '?'}" for d in errors)


@pytest.mark.parametrize("name, variant", CASES)
def test_every_backend_writes_or_refuses_each_operation(name, variant):
    found = []
    terminator = ir_ops.BY_NAME[name].terminator
    for target in DIALECTS:
        backend = dialects.get(target).load_backend()
        profile = profiles.load(PROFILES[target])
        for source in DIALECTS:
            try:
                result = outcome(backend.emit(example(name, source, variant), profile), TERM_LINE if terminator else OP_LINE)
            except Exception as exc:  # noqa: BLE001 - an exception is the finding
                result = f"raised {type(exc).__name__}: {exc}"
            if result.startswith("dropped") and (terminator or (target, name, variant) in WRITES_NOTHING):
                continue
            if result not in ("written", "refused"):
                found.append(f"{source} -> {target}: {result}")
    assert found == []


def test_the_simulator_registers_a_handler_for_every_operation():
    from mcc.sim.interpreter import OP_METHODS

    assert set(OP_METHODS) == {d.cls for d in ir_ops.OPERATIONS}


@pytest.mark.parametrize("name, variant", CASES)
@pytest.mark.parametrize("source", DIALECTS)
def test_the_simulator_runs_each_operation(name, variant, source):
    from mcc.sim.interpreter import Options, Simulator

    sim = Simulator(example(name, source, variant), options=Options(until=5.0))
    sim.run()
    misplaced = [d for d in sim.diags if d.severity.value == "error" and (d.span is None or d.span.line < OP_LINE)]
    assert misplaced == []


@pytest.mark.parametrize("name, variant", CASES)
def test_every_optimizer_pass_keeps_each_operation_s_behaviour(name, variant):
    from sim_behaviour import same_behaviour

    for source in DIALECTS:
        module = example(name, source, variant)
        profile = profiles.load(module.profile)
        for one in PASSES:
            work = ir.copy_module(module)
            optimize(work, "O2", profile, one, verify=True)
            assert verify(work) == [], (source, one)
            same_behaviour(module, work)
