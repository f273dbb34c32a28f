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

The field checks (choices and units) are read from the operation table, `compiler/ir_ops.py`:
a field's `choices` and its units are data there, not a case per operation here.

`verify(module)` returns the violations; an empty list means the module keeps the contract. The
test suite runs it on every sample and golden program after lowering and after every pass, and
`mcc check --verify-ir` runs it on demand (each violation is a G010 diagnostic).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from mcc.compiler import ir
from mcc.compiler import ir_names
from mcc.compiler import ir_ops
from mcc.compiler.span import Span


@dataclass(frozen=True)
class Violation:
    group: str  # "structure" | "meaning"
    where: str  # routine/block/op index, for people
    message: str
    span: Span | None = None

    def __str__(self) -> str:
        return f"{self.where}: {self.message}"


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
                if block.terminator is not None:
                    self._routine_refs(block.terminator, where)
                for index, op in enumerate(block.ops):
                    self._routine_refs(op, f"{where}[{index}]")

    def _routine_refs(self, node, where: str) -> None:
        """Each routine an operation or terminator names (its table's routine fields) exists."""
        definition = ir_ops.definition(node)
        for f in definition.fields if definition is not None else ():
            name = getattr(node, f.name) if f.kind is ir_ops.Kind.ROUTINE else None
            if name is not None:
                self._routine_ref(name, where, node.span)

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
        definition = ir_ops.definition(op)
        if definition is not None:
            self._fields(op, definition, where)
        if isinstance(op, ir.Print) and op.formats:
            if len(op.formats) > len(op.items):
                self.add("meaning", where, "a print has more formats than items", op.span)
            for spec in op.formats:
                problem = ir_names.print_format_error(spec)
                if problem is not None:
                    self.add("meaning", where, problem, op.span)

    def _fields(self, op: ir.Op, definition: ir_ops.OpDef, where: str) -> None:
        """The field checks the operation table states: a value among the field's choices (a move's
        mode, a neutral event or setting name, a homing's creep and zero), and the unit of each
        constant where the table gives one (a position in steps, a delay in seconds, ...)."""
        for f in definition.fields:
            value = getattr(op, f.name)
            if f.choices is not None and value not in f.choices:
                shown = value.value if isinstance(value, Enum) else value
                self.add("meaning", where, f.invalid.format(value=shown), op.span)
                continue
            units = ir_ops.units_of(op, f)
            if units is None or value is None:
                continue
            allowed, what = units
            if f.kind is ir_ops.Kind.AXIS_EXPRS:
                for axis, target in value:
                    self._unit(target, allowed, where, what.format(axis=axis), op.span)
            elif f.kind is ir_ops.Kind.EXPR_PAIR:
                for item in value:
                    self._unit(item, allowed, where, what, op.span)
            else:
                self._unit(value, allowed, where, what, op.span)

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
