"""Dead stores and unused variables.

What it does: at -O2, an assignment overwritten later in the same block before anything reads the
variable is removed (`V1 = 0` then `V1 = 5` keeps only `V1 = 5`); a hidden variable of mcc's own
(a name starting with `%`, such as an X150 loop counter) that nothing reads loses its assignments;
at -O2, a declared variable that no operation reads or assigns loses its declaration (a name-table
entry on MCode).

Why it is safe: a store whose value may fault (a division by a variable, `may_fault`) is kept,
since removing it would remove the runtime error; any other value removed is never read by the program: not by the operations between the
two stores, not by a call or a native command (the removal stops at either), not by an event
handler (variables a handler reads are left alone). A host can read variables over the serial
line, so the removal also stops at every operation that takes time (a move, a wait, a delay, a
print): between two stores with no such operation in between, a host has little moment to read
the first value. Controllers answer a host's queries between any two statements, so this removal
of stores to the program's own variables is left to -O2; -O1 removes only mcc's hidden ones. The -O2 removal of unused declarations assumes no host reads a variable the program
never uses (say so with -O1 when one does).

Needs: nothing beyond the module.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.opt.common import clobbers_everything

NAME = "dead_stores"
NEEDS = ()
TAKES_TIME = (ir.Move, ir.Arc, ir.Slew, ir.Home, ir.WaitMotion, ir.WaitInput, ir.Delay, ir.Print)


def run(module: ir.Module, context) -> int:
    handler_reads = reads_in_handlers(module)
    changed = 0
    for _, block in module.blocks() if context.global_scope else ():
        keep = [True] * len(block.ops)
        pending: dict[str, int] = {}  # variable -> index of a store nothing has read yet
        for index, op in enumerate(block.ops):
            if clobbers_everything(op) or isinstance(op, TAKES_TIME):
                pending.clear()
            for name in reads_of(op):
                pending.pop(name, None)
            if isinstance(op, ir.Assign):
                name = op.target.name
                if name in pending:
                    keep[pending[name]] = False
                if name not in handler_reads and not may_fault(op.value):
                    pending[name] = index
        if not all(keep):
            changed += keep.count(False)
            block.ops[:] = [op for op, kept in zip(block.ops, keep) if kept]
    changed += drop_hidden(module)
    if context.global_scope:
        changed += drop_unused_declarations(module)
    return changed


def reads_of(op) -> set[str]:
    names = set()
    for expr in ir.op_exprs(op):
        for node in ir.walk_expr(expr):
            if isinstance(node, ir.Var):
                names.add(node.name)
    return names


def all_reads(module: ir.Module) -> set[str]:
    names: set[str] = set()
    for _, block in module.blocks():
        for op in block.ops:
            names |= reads_of(op)
            if isinstance(op, ir.Native):  # a native command may read its variable arguments
                names |= {a.name for a in op.args if isinstance(a, ir.Var)}
        for expr in ir.term_exprs(block.terminator):
            names |= {n.name for n in ir.walk_expr(expr) if isinstance(n, ir.Var)}
    for variable in module.variables.values():
        if variable.init is not None:
            names |= {n.name for n in ir.walk_expr(variable.init) if isinstance(n, ir.Var)}
    return names


def reads_in_handlers(module: ir.Module) -> set[str]:
    names: set[str] = set()
    for routine in module.routines:
        if routine.kind is ir.RoutineKind.HANDLER:
            for block in routine.blocks:
                for op in block.ops:
                    names |= reads_of(op)
                for expr in ir.term_exprs(block.terminator):
                    names |= {n.name for n in ir.walk_expr(expr) if isinstance(n, ir.Var)}
    return names


def may_fault(expr) -> bool:
    """Whether computing `expr` may stop the program with a runtime error (a division or remainder
    by a divisor that is not a non-zero constant, a function outside its domain): such a store is
    kept, since removing it would remove the error."""
    for node in ir.walk_expr(expr):
        if isinstance(node, ir.BinOp) and node.op in ("/", "%") and \
                not (isinstance(node.right, ir.Const) and node.right.value != 0):
            return True
        if isinstance(node, ir.Func) and node.name not in ("abs", "pi"):
            return True
    return False


def drop_hidden(module: ir.Module) -> int:
    """mcc's own declared temporaries (an X150 loop counter) that nothing reads. A hidden name that
    is not a declared variable is device state (the X150 distance register `%D`, which a later `G`
    or the host uses), never removed."""
    read = all_reads(module)
    hidden = {n for n in module.variables if n.startswith("%")}
    removed = 0
    for _, block in module.blocks():
        kept = [op for op in block.ops if not (isinstance(op, ir.Assign) and op.target.name in hidden
                                               and op.target.name not in read and not may_fault(op.value))]
        removed += len(block.ops) - len(kept)
        block.ops[:] = kept
    for name in [n for n in module.variables if n.startswith("%") and n not in read]:
        del module.variables[name]
    return removed


def drop_unused_declarations(module: ir.Module) -> int:
    used = all_reads(module)
    for _, block in module.blocks():
        used |= {op.target.name for op in block.ops if isinstance(op, ir.Assign)}
    unused = [n for n, v in module.variables.items() if n not in used and v.scope == "global"]
    for name in unused:
        del module.variables[name]
    return len(unused)
