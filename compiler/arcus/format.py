"""The Arcus formatter: one canonical layout for standalone programs.

- Keywords, axis letters and variables in upper case (the language ignores case, spec §2.1).
- The canonical spellings of the spec (§2.2): `V1=V2+1`, `HSPDX=1000`, `IF V1=1`, `WHILE V1!=2`,
  `GOSUB 1`, `SUB 1`, `X1000Y2000` (the axes of one move written together, as the DXF converter
  writes them), `ARCP0:100:30000`; no spaces around `=`, operators and comparisons.
- The bodies of IF/ELSEIF/ELSE, WHILE and SUB are indented two spaces per level; ELSEIF, ELSE
  and the closing keyword line up with their opener. A comment on its own line takes the
  indentation of the code it precedes.
- Trailing comments are aligned to one column per block of lines (lines between blank lines),
  column 25 or further right when the block's code is longer. Comment text is kept word for word
  (";" and "'" alike); runs of blank lines collapse to one; a line that does not parse is left as
  it is.

Formatting never changes what a program does: `mcc fmt` compares the IR before and after.
"""

from __future__ import annotations

from functools import lru_cache

from mcc.compiler.arcus import catalog as acat
from mcc.compiler.arcus import parser
from mcc.compiler.arcus import syntax as st
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.profiles import Profile
from mcc.compiler.span import SourceFile
from mcc.compiler.lint.layout import Out, align_comments, collapse_blank_lines, render

INDENT = "  "
OPENERS = {"IF", "WHILE", "SUB"}
MIDDLES = {"ELSEIF", "ELSE"}
CLOSERS = {"ENDIF", "ENDWHILE", "ENDSUB"}




@lru_cache(maxsize=1)
def catalog() -> acat.ArcusCatalog:
    return acat.load()


def format_text(text: str, path: str = "<text>", profile: Profile | None = None, strict: bool = False) -> str:
    """The text in the canonical style; a line that does not parse is kept as written, or, when
    `strict`, the text is refused (`SyntaxErrors`), as `mcc fmt` does."""
    source = SourceFile(path, text)
    parsed = Diagnostics()
    tree = parser.parse(source, parsed)
    if strict:
        parsed.refuse_syntax_errors()
    limit = int(profile.get("limits.line_length", 0)) if profile else 0
    lines = collapse_blank_lines(layout(source, tree))
    align_comments(lines, limit)
    return "".join(render(line) + "\n" for line in lines)


# layout --------------------------------------------------------------------------------------------

def keyword_of(stmt: st.Statement) -> str:
    """The block keyword a statement is, if any (IF, ELSE, ENDWHILE, SUB, ...)."""
    if isinstance(stmt, st.Conditional):
        return stmt.keyword
    if isinstance(stmt, st.Command) and len(stmt.parts) == 1 and not stmt.colon:
        word = stmt.parts[0].word.upper()
        if word in MIDDLES | CLOSERS or word == "SUB" and stmt.parts[0].number:
            return word
    return ""


def layout(source: SourceFile, tree: st.SyntaxTree) -> list[Out]:
    out: list[Out] = []
    depth = 0
    waiting: list[Out] = []

    def place(indent: str) -> None:
        for item in waiting:
            item.indent = indent
        waiting.clear()

    for line in tree.lines:
        if line.error:
            place(INDENT * depth)
            out.append(Out(verbatim=source.line_text(line.number)))
            continue
        comment = line.comment.text.rstrip() if line.comment is not None else ""
        stmt = line.statement
        if stmt is None:
            if comment:
                waiting.append(Out(comment=comment))
                out.append(waiting[-1])
            else:
                place(INDENT * depth)
                out.append(Out(blank=True))
            continue
        word = keyword_of(stmt)
        if word in MIDDLES or word in CLOSERS:
            depth = max(0, depth - 1)
        place(INDENT * depth)
        out.append(Out(INDENT * depth, statement(stmt), comment))
        if word in OPENERS or word in MIDDLES:
            depth += 1
    place(INDENT * depth)
    return out


# statements ----------------------------------------------------------------------------------------

def statement(stmt: st.Statement) -> str:
    if isinstance(stmt, st.Assignment):
        return part(stmt.target) + "=" + node(stmt.value)
    if isinstance(stmt, st.Conditional):
        return f"{stmt.keyword} {condition(stmt.condition)}"
    text = ""
    for i, p in enumerate(stmt.parts):
        piece = part(p, numbered=len(stmt.parts) == 1)
        if i and not (text[-1].isdigit() or text[-1] in "+-"):
            text += " "  # two words must not run together into one
        text += piece
    for operand in stmt.colon:
        text += ":" + node(operand)
    return text


def part(p: st.Part, numbered: bool = False) -> str:
    word = p.word.upper()
    if numbered and p.number and not p.sign and takes_number(word):
        return f"{word} {p.number}"  # GOSUB 1, SUB 1
    return word + p.sign + p.number


@lru_cache(maxsize=None)
def takes_number(word: str) -> bool:
    """Keywords written with a space before their number (the catalog's form "number")."""
    found = catalog().match(word) or catalog().match_elsewhere(word)  # PRG n of the family's other products
    return found is not None and found.end == len(word) and found.keyword.form == "number"


def condition(cond: st.Condition) -> str:
    text = comparison(cond.first)
    for logic, comp in cond.more:
        text += f" {logic.upper()} {comparison(comp)}"
    return text


def comparison(comp: st.Comparison) -> str:
    text = node(comp.left) + comp.op + node(comp.right)
    for op, operand in comp.chained:
        text += op + node(operand)
    return text


def node(n: st.Node) -> str:
    if isinstance(n, st.Number):
        return n.text
    if isinstance(n, st.Ref):
        return part(n.part)
    if isinstance(n, st.Unary):
        return n.op + node(n.operand)
    if isinstance(n, st.Binary):
        return node(n.left) + n.op + node(n.right)
    raise TypeError(f"unexpected syntax node {type(n).__name__}")


# blank lines and comments ---------------------------------------------------------------------------




