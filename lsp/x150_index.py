"""The editor model of an X150 file, from its syntax tree (the tokeniser already attached each
command's catalog entry).

Sequences are numbers: `XDn` … `XT` defines sequence n, every command whose catalog argument is a
sequence (`XR`, `XG`, `XRP`, `XE`, `GOSUB`, `GOTO`, ...) refers to one. A sequence is identified by
its number alone, whatever device address is written in front. Variables are `VAR1`…`VAR50`.
"""

from __future__ import annotations

from mcc.compiler import cancel
from mcc.compiler.span import SourceFile
from mcc.compiler.x150 import syntax as st
from mcc.lsp import model as m
from mcc.lsp.model import comment_folds, span_lines

BLOCKS = {"XD": "XT", "IF": "NIF", "WHILE": "NWHILE", "REPEAT": "UNTIL", "L": "N"}


def build(tree: st.SyntaxTree, source: SourceFile, profile, analysis=None) -> m.Index:
    """The editor model of the file (`analysis`, the frontend's result, is not needed here)."""
    index = m.Index("x150")
    for command in tree.commands():
        if command.mnemonic == "XD" and isinstance(command.arg, st.Number):
            number = int(command.arg.value)
            index.symbol(f"sequence:{number}", m.SYMBOL_SEQUENCE, str(number))
    for line in tree.lines:
        cancel.every(line.number)  # a newer keystroke abandons this model (compiler/cancel.py)
        if line.comment is not None:
            index.add(line.comment.span, m.COMMENT)
        for command in line.commands:
            add_command(index, command)
    structure(index, tree, source)
    return index.finish()


def variable(index: m.Index, ref: st.VarRef, written: bool, entry=None, span=None) -> None:
    key = f"variable:VAR{ref.number}"
    index.symbol(key, m.SYMBOL_VARIABLE, f"VAR{ref.number}")
    index.add(span or ref.span, m.VARIABLE, symbol=key, definition=written, entry=entry)


def add_command(index: m.Index, command: st.Command) -> None:
    index.add(command.address_span, m.ADDRESS)
    info = command.info
    entry = info.entry if info is not None else None
    arg = command.arg
    if command.mnemonic_span is not None and not isinstance(arg, st.VarStatement):
        kind = m.CONTROL if entry is not None and entry.kind in ("control", "sequence") else m.COMMAND
        index.add(command.mnemonic_span, kind, entry=entry)
    if info is not None and info.arg == "sequence" and isinstance(arg, st.Number):
        number = int(arg.value)
        key = f"sequence:{number}"
        index.symbol(key, m.SYMBOL_SEQUENCE, str(number))
        index.add(arg.span, m.SUBROUTINE, symbol=key, definition=command.mnemonic == "XD")
        return
    name = None
    if isinstance(arg, st.VarStatement) and command.mnemonic_span is not None:
        # `VAR1=5`, `VAR1`: the whole name is the variable (the parser's span is its number)
        name = command.mnemonic_span.to(arg.var.span)
    operands(index, arg, entry, name)


def operands(index: m.Index, arg, entry, statement_name=None) -> None:
    if arg is None:
        return
    if isinstance(arg, st.Number):
        index.add(arg.span, m.NUMBER, command=entry, value=float(arg.value))
    elif isinstance(arg, st.VarRef):
        variable(index, arg, False, entry)
    elif isinstance(arg, st.Source):
        index.add(arg.span, m.REGISTER)
    elif isinstance(arg, st.Text):
        index.add(arg.span, m.STRING)
    elif isinstance(arg, st.VarStatement):
        variable(index, arg.var, arg.value is not None, entry, span=statement_name)
        if arg.value is not None:
            operands(index, arg.value, None)
    elif isinstance(arg, st.Chain):
        operands(index, arg.first, entry)
        for _, operand in arg.rest:
            operands(index, operand, entry)
    elif isinstance(arg, st.Condition):
        for term in arg.terms:
            if isinstance(term, st.Comparison):
                operands(index, term.left, None)
                operands(index, term.right, None)


def structure(index: m.Index, tree: st.SyntaxTree, source: SourceFile) -> None:
    stack: list[tuple[str, int, m.Routine | None]] = []
    closers = {v: k for k, v in BLOCKS.items()}
    for line in tree.lines:
        for command in line.commands:
            name = command.mnemonic
            if name in BLOCKS:
                routine = None
                if name == "XD" and isinstance(command.arg, st.Number):
                    number = int(command.arg.value)
                    device = f" (device {command.address})" if command.address is not None else ""
                    routine = m.Routine(f"sequence {number}{device}", "sequence", command.span, command.span,
                                        symbol=f"sequence:{number}")
                    index.routines.append(routine)
                stack.append((name, line.number, routine))
            elif name in closers:
                for depth in range(len(stack) - 1, -1, -1):
                    if stack[depth][0] == closers[name]:
                        _, start, routine = stack[depth]
                        del stack[depth:]
                        if line.number > start:
                            index.folds.append((start, line.number, "region"))
                        if routine is not None:
                            routine.span = span_lines(source, start, line.number)
                        break
    comment_folds(index, tree)
