"""The editor model of an MCode file, from its syntax tree and the catalog.

Labels (`LB`) and variables (`VA`) share one name table (L537); a name is a label if some `LB`
defines it, a variable if some `VA` declares it or it is assigned, otherwise a catalog name.
Program regions (`PG n` … `PG`) and label bodies make the outline and the folding ranges.
"""

from __future__ import annotations

from mcc.compiler import cancel
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.mcode import catalog as mcat
from mcc.compiler.mcode import syntax as st
from mcc.compiler.mcode.resolve import Resolver
from mcc.compiler.span import SourceFile
from mcc.lsp import model as m
from mcc.lsp.model import comment_folds, span_lines


def children(node: st.Node):
    if isinstance(node, (st.Binary, st.Comparison)):
        return (node.left, node.right)
    if isinstance(node, st.Unary):
        return (node.operand,)
    if isinstance(node, st.FuncCall):
        return (node.operand,)
    if isinstance(node, st.Juxtaposed):
        return (node.first, node.second)
    return ()


def walk(node: st.Node):
    stack = [node]
    while stack:
        item = stack.pop()
        yield item
        stack.extend(reversed(children(item)))


def build(tree: st.SyntaxTree, source: SourceFile, profile, analysis=None) -> m.Index:
    """The editor model of the file, from the frontend's reading of its statements (`analysis`,
    `Analysis.statements`) when it read this tree; read again only without one."""
    index = m.Index("mcode")
    cat = mcat.load()
    for line in tree.lines:
        cancel.every(line.number)  # a newer keystroke abandons this model (compiler/cancel.py)
        if line.comment is not None:
            index.add(line.comment.span, m.COMMENT)
    if analysis is not None and analysis.tree is tree:
        resolved = analysis.statements
    else:
        resolved = resolve_again(tree, profile)
    # pass 1: definitions
    for _line, res in resolved:
        name = res.command.name if res.command else ""
        if name in ("LB", "VA") and res.args:
            arg = res.args[0]
            target = arg.left if isinstance(arg, st.Comparison) else arg
            if isinstance(target, st.Name):
                kind = m.SYMBOL_LABEL if name == "LB" else m.SYMBOL_VARIABLE
                index.symbol(f"{kind}:{target.key}", kind, target.text)
        elif res.user:
            index.symbol(f"variable:{res.user}", m.SYMBOL_VARIABLE, res.stmt.head.text)
    # pass 2: tokens
    for _line, res in resolved:
        add_statement(index, cat, res)
    structure(index, tree, resolved, source)
    return index.finish()


def resolve_again(tree: st.SyntaxTree, profile) -> list:
    """Each statement's reading, for a tree no frontend analysis came with."""
    resolver = Resolver(profile, Diagnostics())
    resolved = []
    for line in tree.lines:
        if line.statement is not None:
            try:
                resolved.append((line, resolver.resolve(line.statement)))
            except Exception:  # noqa: BLE001 - a line the resolver cannot read is just not indexed
                continue
    return resolved


def name_symbol(index: m.Index, key: str) -> str:
    for kind in (m.SYMBOL_LABEL, m.SYMBOL_VARIABLE):
        if f"{kind}:{key}" in index.symbols:
            return f"{kind}:{key}"
    return ""


def add_statement(index: m.Index, cat: mcat.McodeCatalog, res) -> None:
    stmt = res.stmt
    command = res.command
    head = stmt.head
    if command is not None:
        kind = m.COMMAND if command.kind == mcat.INSTRUCTION else m.REGISTER
        index.add(head.span, kind, entry=command.entry)
        if command.name == "MS" and res.args and isinstance(res.args[0], st.Number):
            index.settings["MS"] = float(res.args[0].value)
    elif res.user:
        index.add(head.span, m.VARIABLE, symbol=f"variable:{res.user}")
    defining = command is not None and command.name in ("LB", "VA")
    for position, arg in enumerate(res.args):
        for node in walk(arg):
            if isinstance(node, st.Name):
                symbol = name_symbol(index, node.key)
                if symbol:
                    definition = defining and position == 0 and node is (arg.left if isinstance(arg, st.Comparison)
                                                                         else arg)
                    kind = m.LABEL if symbol.startswith("label") else m.VARIABLE
                    index.add(node.span, kind, symbol=symbol, definition=definition)
                else:
                    known = cat.lookup(node.key) or cat.functions.get(node.key)
                    index.add(node.span, m.REGISTER, entry=known.entry if known else None)
            elif isinstance(node, st.Number):
                index.add(node.span, m.NUMBER, command=command.entry if command else None,
                          value=float(node.value))
            elif isinstance(node, st.String):
                index.add(node.span, m.STRING)


def structure(index: m.Index, tree: st.SyntaxTree, resolved, source: SourceFile) -> None:
    """Programs (PG n … PG), label bodies, comment blocks."""
    last_line = max(1, source.line_count)
    program: m.Routine | None = None
    label: m.Routine | None = None

    def close_label(end_line: int) -> None:
        nonlocal label
        if label is not None:
            label.span = span_lines(source, label.span.line, max(label.span.line, end_line))
            if label.span.end_line > label.span.line:
                index.folds.append((label.span.line, label.span.end_line, "region"))
            label = None

    for line, res in resolved:
        name = res.command.name if res.command else ""
        if name == "PG":
            close_label(line.number - 1)
            if res.args:  # PG <address>: a program starts
                if program is not None:
                    finish_program(index, program, source, line.number - 1)
                address = res.args[0]
                text = getattr(address, "text", "?")
                program = m.Routine(f"PG {text}", "program", line.statement.span, line.statement.span)
                index.routines.append(program)
            elif program is not None:
                finish_program(index, program, source, line.number)
                program = None
        elif name == "LB" and res.args and isinstance(res.args[0], st.Name):
            close_label(line.number - 1)
            target = res.args[0]
            label = m.Routine(target.text, "label", line.statement.span, target.span,
                              symbol=f"label:{target.key}")
            (program.children if program is not None else index.routines).append(label)
    close_label(last_line if program is None else last_line)
    if program is not None:
        finish_program(index, program, source, last_line)
    comment_folds(index, tree)


def finish_program(index: m.Index, program: m.Routine, source: SourceFile, end_line: int) -> None:
    program.span = span_lines(source, program.span.line, max(program.span.line, end_line))
    for child in program.children:
        if child.span.end_line > program.span.end_line:
            child.span = span_lines(source, child.span.line, program.span.end_line)
    if program.span.end_line > program.span.line:
        index.folds.append((program.span.line, program.span.end_line, "region"))
