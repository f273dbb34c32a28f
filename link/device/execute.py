"""The one seam between a virtual device and program execution.

`run_program` takes the compiled IR module of what the device stores and runs it as far as the
host protocol can observe without a motion simulator: assignments to variables (with the
arithmetic of constants and variables), calls and returns, branches on those variables. The first
operation that needs the machine (a move, a wait, an input, a delay, a device register) ends the
run with the program "running", because on a real controller it would still be running there.
When the IR simulator (`mcc.sim`) is merged, this function hands the module to it instead and
returns what the simulator reports (docs/LINK.md, "Running a program").
"""

from __future__ import annotations

import operator
from dataclasses import dataclass, field

from mcc.compiler import ir

OPS = {"+": operator.add, "-": operator.sub, "*": operator.mul, "/": lambda a, b: a / b if b else 0,
       "%": lambda a, b: a % b if b else 0, "&": lambda a, b: int(a) & int(b), "|": lambda a, b: int(a) | int(b),
       "^": lambda a, b: int(a) ^ int(b)}
RELOPS = {"=": operator.eq, "==": operator.eq, "<>": operator.ne, "!=": operator.ne, "<": operator.lt,
          "<=": operator.le, ">": operator.gt, ">=": operator.ge}
STEP_BUDGET = 100_000
# Dialect commands kept Native in the IR that only select a mode and never wait: running past them
# changes nothing the host protocol can observe without a motion simulator.
MODE_ONLY = {("arcus", "ABS"), ("arcus", "INC"), ("x150", "MPA"), ("x150", "MPI"), ("x150", "MN"),
             ("x150", "MC"), ("mcode", "EE"), ("mcode", "MS")}


class NeedsMachine(Exception):
    """The program reached something only the motion/I-O simulator can run."""


@dataclass
class Outcome:
    status: str                      # "idle" (ran to its end) | "running" (still running on a device)
    variables: dict[str, float] = field(default_factory=dict)
    reason: str = ""
    output: list[str] = field(default_factory=list)


def value(expr, variables: dict[str, float]) -> float:
    if isinstance(expr, ir.Const):
        return expr.value
    if isinstance(expr, ir.Var):
        return variables.get(expr.name.upper(), 0)
    if isinstance(expr, ir.BinOp) and expr.op in OPS:
        return OPS[expr.op](value(expr.left, variables), value(expr.right, variables))
    if isinstance(expr, ir.UnOp) and expr.op == "-":
        return -value(expr.operand, variables)
    raise NeedsMachine(type(expr).__name__)


def truth(cond, variables: dict[str, float]) -> bool:
    if isinstance(cond, ir.Compare) and cond.op in RELOPS:
        return RELOPS[cond.op](value(cond.left, variables), value(cond.right, variables))
    if isinstance(cond, ir.Logic):
        left, right = truth(cond.left, variables), truth(cond.right, variables)
        return (left and right) if cond.op.lower() == "and" else (left or right)
    if isinstance(cond, ir.Not):
        return not truth(cond.cond, variables)
    if isinstance(cond, ir.Truth):
        return bool(value(cond.expr, variables))
    raise NeedsMachine(type(cond).__name__)


def entry_routine(module: ir.Module, entry: str | int | None) -> ir.Routine | None:
    for routine in module.routines:
        if entry is None and routine.kind == ir.RoutineKind.MAIN:
            return routine
        if entry is not None and (routine.name.upper() == str(entry).upper() or routine.number == entry
                                  or routine.origin == entry
                                  or any(b.named and b.label.upper() == str(entry).upper() for b in routine.blocks)):
            return routine
    return None


def run_program(module: ir.Module, variables: dict[str, float], entry: str | int | None = None) -> Outcome:
    """Run `module` from `entry` (a routine or label name, a number, an origin; None: the main
    routine) on `variables` (updated in place) and say where it ended."""
    routine = entry_routine(module, entry)
    if routine is None or routine.entry is None:
        return Outcome("idle", variables, f"nothing to run at {entry!r}")
    blocks = {b.label: (r, b) for r in module.routines for b in r.blocks}
    label = routine.entry.label
    if entry is not None and not isinstance(entry, int):
        named = [b for b in routine.blocks if b.named and b.label.upper() == str(entry).upper()]
        label = named[0].label if named else label
    stack: list[tuple[str, int]] = []   # where each call returns to: (block label, next op)
    out: list[str] = []
    steps, index = 0, 0
    try:
        while True:
            steps += 1
            if steps > STEP_BUDGET:
                return Outcome("running", variables, f"still running after {STEP_BUDGET} steps (a loop)", out)
            _routine, block = blocks[label]
            called = False
            while index < len(block.ops):
                op = block.ops[index]
                index += 1
                if isinstance(op, ir.Assign):
                    variables[op.target.name.upper()] = value(op.value, variables)
                elif isinstance(op, ir.Call):
                    target = module.routine(op.routine)
                    if target is None or target.entry is None:
                        raise NeedsMachine(f"a call of {op.routine}")
                    if op.cond is None or truth(op.cond, variables):
                        stack.append((label, index))
                        label, index, called = target.entry.label, 0, True
                        break
                elif isinstance(op, (ir.Save, ir.SetHandler, ir.SetMotion, ir.DriveEnable, ir.Print)):
                    continue
                elif isinstance(op, ir.Native) and (op.dialect, op.mnemonic.upper()) in MODE_ONLY:
                    continue
                else:
                    raise NeedsMachine(type(op).__name__)
            if called:
                continue
            term = block.terminator
            index = 0
            if isinstance(term, ir.Jump):
                label = term.target
            elif isinstance(term, ir.Branch):
                label = term.then if truth(term.cond, variables) else term.otherwise
            elif isinstance(term, ir.Return) and stack:
                label, index = stack.pop()
            elif isinstance(term, (ir.End, ir.FallOff, ir.Return)) or term is None:
                return Outcome("idle", variables, "ran to its end", out)
            elif isinstance(term, ir.GotoRoutine):
                target = module.routine(term.routine)
                if target is None or target.entry is None:
                    return Outcome("idle", variables, f"jumps to missing {term.routine}", out)
                label = target.entry.label
            else:
                raise NeedsMachine(type(term).__name__)
    except NeedsMachine as exc:
        return Outcome("running", variables, f"waits on {exc} (motion and I/O are the simulator's work)", out)
