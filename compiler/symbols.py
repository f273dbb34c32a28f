"""Symbol tables and def-use chains of one lowered module, computed once per analysis.

Lint rules (an unused variable, label or subroutine; a variable read before it is written), the
language server (definition, references, "used N times") and later passes all ask "where is this
name defined, and where is it used?". `Analysis.symbols` and `Analysis.defuse` answer from the IR,
once per file (lazily, then cached), in one linear walk over the module.

What counts, in the IR's neutral terms:

- a **variable** is defined by its declaration (`Module.variables`, with the declaration's span),
  by an `Assign` to it, and by the operation at its declaration's span (a declaration inside a
  program, kept `Native` because only its own dialect declares there: its first argument is the
  name being declared, not a use); it is used by every `Var` an operation or terminator reads;
- a **label** is a named block; it is referenced by a `Jump` or `Branch` to it (not by the jump a
  lowering adds where one label's code runs on into the next), by a `LabelRef`, and by a call,
  transfer or handler naming the routine it starts;
- a **routine** is referenced by a `Call`, a `GotoRoutine` transfer, a `SetHandler` that installs
  it, or a `LabelRef` naming it.

A reference's span is the span of the operation that makes it (the IR keeps one span per
operation; a `Var` or `LabelRef` has its own). The module must not change after the tables are
built: passes that rewrite the IR work on `ir.copy_module`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mcc.compiler import ir
from mcc.compiler.span import Span


@dataclass
class Symbol:
    """One name of the file: where it is defined and every place that refers to it."""

    name: str
    kind: str  # "variable" | "label" | "routine"
    definition: Span | None = None
    references: list[Span] = field(default_factory=list)  # the spans of the references that have one
    count: int = 0  # every reference, with or without a span

    @property
    def used(self) -> bool:
        return self.count > 0


@dataclass
class Symbols:
    """The file's names by kind. A routine's name is also the label of its entry block where the
    dialect writes one (MCode `LB K1`), so the same name may be in `labels` and `routines`."""

    variables: dict[str, Symbol] = field(default_factory=dict)
    labels: dict[str, Symbol] = field(default_factory=dict)
    routines: dict[str, Symbol] = field(default_factory=dict)

    def lookup(self, name: str) -> Symbol | None:
        return self.variables.get(name) or self.routines.get(name) or self.labels.get(name)


@dataclass(frozen=True)
class Site:
    """One operation (or terminator: `index == -1`) of a routine's block."""

    routine: str
    block: str
    index: int
    item: object

    @property
    def span(self) -> Span | None:
        return getattr(self.item, "span", None)


@dataclass(frozen=True)
class Use:
    site: Site
    var: ir.Var
    self_update: bool = False  # read only to compute the variable itself (`IC Q1`, `V1=V1+1`)


@dataclass
class DefUse:
    """For each variable: the operations that define it and the reads that use it, in module order."""

    defs: dict[str, list[Site]] = field(default_factory=dict)
    uses: dict[str, list[Use]] = field(default_factory=dict)

    def read(self, name: str) -> bool:
        """The value is read for something other than updating the variable itself."""
        return any(not use.self_update for use in self.uses.get(name, ()))

    def mentioned(self, name: str) -> bool:
        """Written or read anywhere in the program (its declaration alone does not count)."""
        return bool(self.defs.get(name)) or bool(self.uses.get(name))


def _is_declaration(op, module: ir.Module) -> bool:
    """A declaration kept as an operation: the op at a declared variable's span naming it first."""
    if not isinstance(op, ir.Native) or not op.args or not isinstance(op.args[0], ir.Var):
        return False
    var = module.variables.get(op.args[0].name)
    return var is not None and var.span is not None and var.span == op.span


def _is_fallthrough(term, target: ir.Block | None) -> bool:
    """The jump a lowering adds where one label's code runs on into the next: it carries the span
    of the label it falls into (a written jump has its own statement's span)."""
    return isinstance(term, ir.Jump) and target is not None and term.span is not None and term.span == target.span


def build(module: ir.Module) -> tuple[Symbols, DefUse]:
    """Both tables in one walk over the module."""
    symbols = Symbols()
    defuse = DefUse()
    for name, var in module.variables.items():
        symbols.variables[name] = Symbol(name, "variable", var.span)
    blocks: dict[str, ir.Block] = {}
    for routine in module.routines:
        symbols.routines.setdefault(routine.name, Symbol(routine.name, "routine", routine.span))
        for block in routine.blocks:
            blocks.setdefault(block.label, block)
            if block.named:
                symbols.labels.setdefault(block.label, Symbol(block.label, "label", block.span))

    def note(symbol: Symbol, span: Span | None) -> None:
        symbol.count += 1
        if span is not None:
            symbol.references.append(span)

    def refer(name: str, span: Span | None) -> None:
        for table in (symbols.labels, symbols.routines):
            if name in table:
                note(table[name], span)

    def variable(name: str) -> Symbol:
        if name not in symbols.variables:  # a register the dialect does not declare (Arcus V1, X150 VAR1)
            symbols.variables[name] = Symbol(name, "variable", None)
        return symbols.variables[name]

    def reads(exprs, site: Site | None, own: str | None, where: tuple) -> None:
        for expr in exprs:
            for node in ir.walk_expr(expr):
                if isinstance(node, ir.Var):
                    site = site or Site(*where)
                    defuse.uses.setdefault(node.name, []).append(Use(site, node, node.name == own))
                    note(variable(node.name), node.span or site.span)
                elif isinstance(node, ir.LabelRef):
                    refer(node.name, node.span or getattr(where[3], "span", None))

    for routine in module.routines:
        for block in routine.blocks:
            for index, op in enumerate(block.ops):
                where = (routine.name, block.label, index, op)
                if isinstance(op, ir.Assign):
                    site = Site(*where)
                    own = op.target.name
                    defuse.defs.setdefault(own, []).append(site)
                    note(variable(own), op.target.span or op.span)
                    reads((op.value,), site, own, where)
                elif isinstance(op, ir.Native) and _is_declaration(op, module):
                    site = Site(*where)
                    defuse.defs.setdefault(op.args[0].name, []).append(site)
                    reads(op.args[1:], site, None, where)
                else:
                    if isinstance(op, ir.Call) or isinstance(op, ir.SetHandler) and op.routine:
                        refer(op.routine, op.span)
                    reads(ir.op_exprs(op), None, None, where)
            term = block.terminator
            if term is None:
                continue
            if isinstance(term, ir.GotoRoutine):
                refer(term.routine, term.span)
            for label in ir.successors(term):
                if label in symbols.labels and not _is_fallthrough(term, blocks.get(label)):
                    note(symbols.labels[label], term.span)
            if isinstance(term, ir.Branch):
                reads((term.cond,), None, None, (routine.name, block.label, -1, term))
    return symbols, defuse
