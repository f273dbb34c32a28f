"""The IR verifier: the invariants every module keeps after lowering and after every pass.

Checked, in two groups:

- **structure**: every routine has blocks; block labels are unique in the module; every block ends
  in one terminator; jumps and branches go to blocks of the same routine; calls, transfers and
  handlers name routines that exist.
- **meaning**: constants carry units from the closed set (`ir.IR_UNITS`) that fit where they are
  used (a max speed in steps/s, a delay in seconds, a move target in steps); moves are absolute
  or relative, never "whatever mode is in force"; operators, functions, readings, events and
  settings use the neutral names of `ir_names`; a dialect's own spelling (`DeviceRef`) appears only
  inside a `Native` operation.

`verify(module)` returns the violations; an empty list means the module keeps the contract. The
test suite runs it on every sample and golden program after lowering and after every pass, and
`mcc check --verify-ir` runs it on demand (each violation is a G010 diagnostic).
"""

from __future__ import annotations

from dataclasses import dataclass

from mcc.compiler import ir
from mcc.compiler import ir_names
from mcc.compiler.span import Span


@dataclass(frozen=True)
class Violation:
    group: str  # "structure" | "meaning"
    where: str  # routine/block/op index, for people
    message: str
    span: Span | None = None

    def __str__(self) -> str:
        return f"{self.where}: {self.message}"


# The unit each operand position must carry when it is a constant (NONE is always accepted for
# a plain number written without a unit only where the table says so).
POSITION = frozenset({ir.Unit.STEPS})
TIME = frozenset({ir.Unit.S})
ANGLE = frozenset({ir.Unit.DEGREES})


def verify(module: ir.Module, meaning: bool = True) -> list[Violation]:
    """Every invariant `module` breaks; `meaning=False` checks the structure only."""
    checker = _Checker(module)
    checker.structure()
    if meaning:
        checker.meaning()
    return checker.out


class _Checker:
    def __init__(self, module: ir.Module):
        self.module = module
        self.out: list[Violation] = []
        self.routines = {r.name: r for r in module.routines}
        self.externals = set(module.externals)

    def add(self, group: str, where: str, message: str, span: Span | None = None) -> None:
        self.out.append(Violation(group, where, message, span))

    # -- structure -----------------------------------------------------------------------------

    def structure(self) -> None:
        seen: dict[str, str] = {}
        for routine in self.module.routines:
            if not routine.blocks:
                self.add("structure", routine.name, "routine has no blocks", routine.span)
            labels = {b.label for b in routine.blocks}
            for block in routine.blocks:
                where = f"{routine.name}/{block.label}"
                if block.label in seen:
                    self.add("structure", where, f"block label also used in routine {seen[block.label]}",
                             block.span)
                seen[block.label] = routine.name
                if block.terminator is None:
                    self.add("structure", where, "block has no terminator", block.span)
                for target in ir.successors(block.terminator):
                    if target not in labels:
                        self.add("structure", where, f"jump to '{target}', not a block of this routine",
                                 block.span)
                if isinstance(block.terminator, ir.GotoRoutine):
                    self._routine_ref(block.terminator.routine, where, block.terminator.span)
                for index, op in enumerate(block.ops):
                    if isinstance(op, ir.Call):
                        self._routine_ref(op.routine, f"{where}[{index}]", op.span)
                    elif isinstance(op, ir.SetHandler) and op.routine is not None:
                        self._routine_ref(op.routine, f"{where}[{index}]", op.span)

    def _routine_ref(self, name: str, where: str, span: Span | None) -> None:
        if name not in self.routines and name not in self.externals:
            self.add("structure", where, f"routine '{name}' does not exist", span)

    # -- meaning -------------------------------------------------------------------------------

    def meaning(self) -> None:
        for name, variable in self.module.variables.items():
            if variable.init is not None:
                self._expr(variable.init, f"variable {name}")
        for routine in self.module.routines:
            for block in routine.blocks:
                where = f"{routine.name}/{block.label}"
                for index, op in enumerate(block.ops):
                    self._op(op, f"{where}[{index}]")
                for expr in ir.term_exprs(block.terminator):
                    self._expr(expr, f"{where}/terminator", getattr(block.terminator, "span", None))

    def _op(self, op: ir.Op, where: str) -> None:
        if isinstance(op, ir.Native):
            return  # the one place a dialect's spelling may live
        for expr in ir.op_exprs(op):
            self._expr(expr, where, getattr(op, "span", None))
        if isinstance(op, ir.Move):
            if op.mode not in (ir.MoveMode.ABSOLUTE, ir.MoveMode.RELATIVE):
                self.add("meaning", where, f"move mode '{op.mode.value}': moves are absolute or relative",
                         op.span)
            for axis, target in op.targets:
                self._unit(target, POSITION, where, f"move target on axis {axis}", op.span)
        elif isinstance(op, ir.SetMotion):
            self._unit(op.value, frozenset({ir.PARAM_UNITS[op.param]}), where, op.param.value, op.span)
        elif isinstance(op, ir.SetPosition):
            self._unit(op.value, POSITION, where, "position", op.span)
        elif isinstance(op, ir.Delay):
            self._unit(op.duration, TIME, where, "delay", op.span)
        elif isinstance(op, ir.Arc):
            for value in op.center:
                self._unit(value, POSITION, where, "arc centre", op.span)
            if op.angle is not None:
                self._unit(op.angle, ANGLE, where, "arc angle", op.span)
        elif isinstance(op, ir.Home):
            self._home(op, where)
        elif isinstance(op, ir.Print) and op.formats:
            if len(op.formats) > len(op.items):
                self.add("meaning", where, "a print has more formats than items", op.span)
            for spec in op.formats:
                problem = ir_names.print_format_error(spec)
                if problem is not None:
                    self.add("meaning", where, problem, op.span)
        elif isinstance(op, ir.Step):
            self._unit(op.count, frozenset({ir.Unit.NONE}), where, "step count", op.span)
        elif isinstance(op, ir.Slew) and op.velocity is not None:
            self._unit(op.velocity, frozenset({ir.Unit.STEPS_PER_S}), where, "slew velocity", op.span)
        elif isinstance(op, ir.SetHandler) and op.event not in ir_names.EVENTS:
            self.add("meaning", where, f"event '{op.event}' is not a neutral event name", op.span)
        elif isinstance(op, ir.Setting):
            info = ir_names.SETTINGS.get(op.name)
            if info is None:
                self.add("meaning", where, f"setting '{op.name}' is not in ir_names.SETTINGS", op.span)
            else:
                self._unit(op.value, frozenset({info.unit}), where, op.name, op.span)

    def _home(self, op: ir.Home, where: str) -> None:
        """A homing operation says what it does after the switch (docs/IR.md, "Home")."""
        speeds = frozenset({ir.Unit.STEPS_PER_S})
        if op.speed is not None:
            self._unit(op.speed, speeds, where, "homing speed", op.span)
        if op.creep_speed is not None:
            self._unit(op.creep_speed, speeds, where, "homing creep speed", op.span)
        if op.accel is not None:
            self._unit(op.accel, frozenset({ir.Unit.STEPS_PER_S2}), where, "homing acceleration", op.span)
        if op.creep not in (-1, 0, 1):
            self.add("meaning", where, f"homing creep direction {op.creep} is not +1, -1 or 0", op.span)
        if op.zero not in ir.HOME_ZEROS:
            self.add("meaning", where, f"homing zero '{op.zero}' is not one of {', '.join(ir.HOME_ZEROS)}",
                     op.span)

    def _unit(self, expr, allowed: frozenset, where: str, what: str, span) -> None:
        if isinstance(expr, ir.Const) and expr.unit not in allowed:
            expected = " or ".join(repr(u.value or "plain number") for u in sorted(allowed))
            self.add("meaning", where, f"{what} is {expr.value} {expr.unit.value or '(no unit)'}, "
                                       f"expected {expected}", span or expr.span)

    def _expr(self, expr, where: str, span=None) -> None:
        """Report each node of `expr` spelt in a dialect's terms, at the node's span or else at the
        span of the operation holding it (`span`), so the refusal names a line."""
        for node in ir.walk_expr(expr):
            problem = _spelling_problem(node)
            if problem:
                self.add("meaning", where, problem, getattr(node, "span", None) or span)


def _spelling_problem(node) -> str:
    if isinstance(node, ir.Const) and node.unit not in ir.IR_UNITS:
        return f"constant {node.value} carries the dialect unit '{node.unit.value}'"
    if isinstance(node, ir.BinOp) and node.op not in ir_names.BINARY_OPS:
        return f"operator '{node.op}' is not a neutral operator"
    if isinstance(node, ir.UnOp) and node.op not in ir_names.UNARY_OPS:
        return f"unary operator '{node.op}' is not a neutral operator"
    if isinstance(node, ir.Compare) and node.op not in ir_names.COMPARE_OPS:
        return f"comparison '{node.op}' is not a neutral comparison"
    if isinstance(node, ir.Logic) and node.op not in ir_names.LOGIC_OPS:
        return f"logic operator '{node.op}' is not neutral"
    if isinstance(node, ir.Func) and node.name not in ir_names.FUNCTIONS:
        return f"function '{node.name}' is not a neutral function"
    if isinstance(node, ir.Status) and node.meaning not in ir_names.STATUS and node.meaning not in ir_names.SETTINGS:
        return f"reading '{node.meaning}' is not a neutral reading"
    if isinstance(node, ir.DeviceRef):
        return f"device register '{node.name}' in {node.dialect} spelling outside a Native operation"
    return ""
