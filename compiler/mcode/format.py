"""The MCode formatter: one canonical layout, the one every sample of the manual uses (L7617-L7658).

- Commands, factory variables, flags and functions in upper case (MCode ignores case, L6871);
  user labels and variables, party device names and text in quotes exactly as written.
- No spaces around `=`, `,` and operators; one space between a command and its first argument
  (`MA 2000`, `BR G1,I1=0`, `F1=CS F2`). Whether a statement is written `O2=0` or `O2 0` is kept:
  both are accepted (L530) and the choice is the author's.
- Outside a program everything starts at column 0. Between `PG <address>` and `PG` labels (`LB`)
  start at column 0 and the body is indented two spaces. A comment on its own line takes the
  indentation of the code it precedes.
- Trailing comments are aligned to one column per block of lines (lines between blank lines):
  column 25, or further right when the block's code is longer. A line that alignment would push
  past the device's 64-character buffer (comments count, L626) keeps one space instead.
- Comments are kept word for word; runs of blank lines collapse to one; no blank lines at the start
  or end; every line ends with a newline. A line that does not parse is left exactly as it is.

Formatting never changes what a program does: `mcc fmt` compares the IR of the file before and
after and refuses to write when they differ (and the property tests check the same).
"""

from __future__ import annotations

import re

from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.mcode import catalog as mcat
from mcc.compiler.mcode import parser
from mcc.compiler.mcode import syntax as st
from mcc.compiler.profiles import Profile
from mcc.compiler.span import SourceFile
from mcc.compiler.lint.layout import Out, align_comments, collapse_blank_lines, render

INDENT = "  "
DEFAULT_LINE_LENGTH = 64
GLUED = re.compile(r"([A-Za-z]{1,2})([0-9]+)\Z")
CANONICAL_OPERATORS = {"=<": "<="}




def format_text(text: str, path: str = "<text>", profile: Profile | None = None, strict: bool = False) -> str:
    """The text in the canonical style; a line that does not parse is kept as written, or, when
    `strict`, the text is refused (`SyntaxErrors`), as `mcc fmt` does."""
    source = SourceFile(path, text)
    parsed = Diagnostics()
    tree = parser.parse(source, parsed)
    if strict:
        parsed.refuse_syntax_errors()
    limit = int(profile.get("limits.line_length", DEFAULT_LINE_LENGTH)) if profile else DEFAULT_LINE_LENGTH
    return Formatter(source, tree, limit).run()


class Formatter:
    def __init__(self, source: SourceFile, tree: st.SyntaxTree, limit: int):
        self.source = source
        self.tree = tree
        self.limit = limit
        self.cat = mcat.load()
        self.user = user_names(tree)

    def run(self) -> str:
        lines = self.layout()
        lines = collapse_blank_lines(lines)
        align_comments(lines, self.limit, indent_counts=False)
        return "".join(render(line) + "\n" for line in lines)

    # layout ------------------------------------------------------------------------------------
    def layout(self) -> list[Out]:
        out: list[Out] = []
        in_program = False
        waiting: list[Out] = []  # comment lines that take the indentation of the code after them
        for line in self.tree.lines:
            body = INDENT if in_program else ""
            if line.error:
                self.place(waiting, body)
                waiting = []
                out.append(Out(verbatim=self.source.line_text(line.number)))
                continue
            stmt = line.statement
            comment = line.comment.text.rstrip() if line.comment is not None else ""
            if stmt is None:
                if comment:
                    waiting.append(Out(comment=comment))
                    out.append(waiting[-1])
                else:
                    self.place(waiting, body)
                    waiting = []
                    out.append(Out(blank=True))
                continue
            head = stmt.head.key
            if head == "PG":
                in_program = bool(stmt.args)
                indent = ""
            else:
                indent = "" if head == "LB" else body
            self.place(waiting, indent)
            waiting = []
            out.append(Out(indent, self.statement(stmt), comment))
        self.place(waiting, INDENT if in_program else "")
        return out

    @staticmethod
    def place(comments: list[Out], indent: str) -> None:
        for item in comments:
            item.indent = indent

    # statements and expressions ----------------------------------------------------------------
    def statement(self, stmt: st.Statement) -> str:
        party = stmt.party
        if stmt.form == "number":
            return party + self.node(stmt.args[0])
        head = self.head(stmt.head.text)
        if stmt.form == "bare":
            return party + head + stmt.suffix
        separator = "=" if stmt.form == "assign" else " "
        return party + head + separator + ",".join(self.node(arg) for arg in stmt.args) + stmt.suffix

    def head(self, word: str) -> str:
        upper = word.upper()
        commands = self.cat.commands
        if upper in self.user:
            return word
        if upper in commands:
            return upper
        if len(upper) == 3 and upper[1:] in commands and word[0].isalnum():
            return word[0] + upper[1:]  # party device name (case-sensitive) + command
        glued = GLUED.match(word)
        if glued and glued.group(1).upper() in commands:
            return upper
        return word

    def name(self, word: str) -> str:
        upper = word.upper()
        if upper in self.user:
            return word
        if upper in self.cat.commands or upper in self.cat.functions or upper == "PI":
            return upper
        return word

    def node(self, node: st.Node) -> str:
        if isinstance(node, st.Name):
            return self.name(node.text)
        if isinstance(node, st.Number):
            return node.text
        if isinstance(node, st.String):
            return f'"{node.text}"'
        if isinstance(node, st.Unary):
            return node.op + self.node(node.operand)
        if isinstance(node, st.Binary):
            return self.node(node.left) + node.op + self.node(node.right)
        if isinstance(node, st.FuncCall):
            return f"{node.name} {self.node(node.operand)}"
        if isinstance(node, st.Comparison):
            op = CANONICAL_OPERATORS.get(node.op, node.op)
            return self.node(node.left) + op + self.node(node.right)
        if isinstance(node, st.Juxtaposed):
            return f"{self.node(node.first)} {self.node(node.second)}"
        raise TypeError(f"unexpected syntax node {type(node).__name__}")


def user_names(tree: st.SyntaxTree) -> set[str]:
    """Labels and variables the program declares (kept as written)."""
    names = set()
    for stmt in tree.statements():
        if stmt.head.key in ("LB", "VA") and stmt.args:
            arg = stmt.args[0]
            arg = arg.left if isinstance(arg, st.Comparison) else arg
            if isinstance(arg, st.Name):
                names.add(arg.key)
    return names





