"""The editor model of an Arcus file, from its syntax tree and the catalog.

Subroutines are numbers (`SUB 1` … `ENDSUB`, called by `GOSUB 1`); variables are `V0`…`V63`,
with no declaration: every assignment counts as a definition. The main program runs from the
first line to `END`; `IF`/`WHILE` blocks and subroutines fold.
"""

from __future__ import annotations

from mcc.compiler import cancel
from mcc.compiler.arcus import catalog as acat
from mcc.compiler.arcus import syntax as st
from mcc.compiler.arcus.resolve import VARIABLE, sub_span
from mcc.compiler.span import SourceFile
from mcc.lsp import model as m
from mcc.lsp.model import comment_folds, span_lines

OPENERS = {"IF": "ENDIF", "WHILE": "ENDWHILE", "SUB": "ENDSUB"}


def build(tree: st.SyntaxTree, source: SourceFile, profile, analysis=None) -> m.Index:
    """The editor model of the file (`analysis`, the frontend's result, is not needed here)."""
    index = m.Index("arcus")
    cat = acat.load(getattr(profile, "product", acat.DEFAULT_PRODUCT))  # the product's statements (PRG on the siblings)
    for line in tree.lines:
        stmt = line.statement
        if isinstance(stmt, st.Command) and stmt.parts and stmt.parts[0].word.upper() == "SUB" \
                and stmt.parts[0].number:
            index.symbol(f"subroutine:{int(stmt.parts[0].number)}", m.SYMBOL_SUBROUTINE,
                         str(int(stmt.parts[0].number)))
    for line in tree.lines:
        cancel.every(line.number)  # a newer keystroke abandons this model (compiler/cancel.py)
        if line.comment is not None:
            index.add(line.comment.span, m.COMMENT)
        stmt = line.statement
        if isinstance(stmt, st.Command):
            for part in stmt.parts:
                add_part(index, cat, part, head=True)
            for node in stmt.colon:
                add_node(index, cat, node, None)
        elif isinstance(stmt, st.Assignment):
            target = add_part(index, cat, stmt.target, head=False, written=True)
            add_node(index, cat, stmt.value, target.entry if target is not None else None)
        elif isinstance(stmt, st.Conditional):
            found = cat.match(stmt.keyword)
            index.add(stmt.keyword_span, m.CONTROL, entry=found.keyword.entry if found else None)
            comparisons = [stmt.condition.first, *(c for _, c in stmt.condition.more)]
            for comparison in comparisons:
                for node in (comparison.left, comparison.right, *(n for _, n in comparison.chained)):
                    add_node(index, cat, node, None)
    structure(index, tree, source)
    return index.finish()


def add_part(index: m.Index, cat, part: st.Part, head: bool, written: bool = False) -> m.Token | None:
    word = part.word.upper()
    found = cat.match(word + (part.number if word in ("V", "DI", "DO") or not head else ""))
    if found is None:
        found = cat.match(word)
    if found is None:
        return None
    keyword = found.keyword
    if head and keyword.form == "glued" and VARIABLE.match(part.key[found.end:]):
        # a variable as a move target: `XV21` moves X to the value of V21 (arcus-pmx-4ex-sa.txt L2759)
        token = index.add(sub_span(part, 0, found.end), m.COMMAND, entry=keyword.entry)
        number = int(part.key[found.end + 1:])
        key = f"variable:V{number}"
        index.symbol(key, m.SYMBOL_VARIABLE, f"V{number}")
        index.add(sub_span(part, found.end, len(part.key)), m.VARIABLE, entry=keyword.entry, symbol=key)
        return token
    if keyword.name == "V" and part.number:
        key = f"variable:V{int(part.number)}"
        index.symbol(key, m.SYMBOL_VARIABLE, f"V{int(part.number)}")
        return index.add(part.span, m.VARIABLE, entry=keyword.entry, symbol=key, definition=written)
    kind = m.CONTROL if keyword.kind == "control" else (m.COMMAND if head else m.REGISTER)
    token = index.add(part.word_span, kind, entry=keyword.entry)
    if part.number_span is not None:
        if keyword.name in ("SUB", "GOSUB"):
            key = f"subroutine:{int(part.number)}"
            index.symbol(key, m.SYMBOL_SUBROUTINE, str(int(part.number)))
            index.add(part.number_span, m.SUBROUTINE, symbol=key, definition=keyword.name == "SUB")
        elif found.end <= len(word):  # the number is a value (X1000), not part of the name (DO7)
            value = float(int(part.number)) * (-1 if part.sign == "-" else 1)
            span = part.sign_span.to(part.number_span) if part.sign_span else part.number_span
            index.add(span, m.NUMBER, command=keyword.entry, value=value)
    return token


def add_node(index: m.Index, cat, node: st.Node, command) -> None:
    for item in st.walk(node):
        if isinstance(item, st.Number):
            index.add(item.span, m.NUMBER, command=command, value=float(item.value))
        elif isinstance(item, st.Ref):
            add_part(index, cat, item.part, head=False)


def structure(index: m.Index, tree: st.SyntaxTree, source: SourceFile) -> None:
    stack: list[tuple[str, int, m.Routine | None]] = []
    main: m.Routine | None = None
    first_code = next((line.number for line in tree.lines if line.statement is not None), None)
    for line in tree.lines:
        stmt = line.statement
        word = ""
        if isinstance(stmt, st.Conditional):
            word = stmt.keyword
        elif isinstance(stmt, st.Command) and stmt.parts:
            word = stmt.parts[0].word.upper()
        if word in OPENERS:
            routine = None
            if word == "SUB" and isinstance(stmt, st.Command) and stmt.parts[0].number:
                number = int(stmt.parts[0].number)
                routine = m.Routine(f"SUB {number}", "subroutine", stmt.span, stmt.parts[0].span,
                                    symbol=f"subroutine:{number}")
                index.routines.append(routine)
            stack.append((word, line.number, routine))
        elif word in OPENERS.values():
            for depth in range(len(stack) - 1, -1, -1):
                if OPENERS[stack[depth][0]] == word:
                    _, start, routine = stack[depth]
                    del stack[depth:]
                    if line.number > start:
                        index.folds.append((start, line.number, "region"))
                    if routine is not None:
                        routine.span = span_lines(source, start, line.number)
                    break
        elif word == "END" and main is None and first_code is not None:
            main = m.Routine("main program", "program", span_lines(source, first_code, line.number),
                             stmt.span)
            index.routines.insert(0, main)
    comment_folds(index, tree)
