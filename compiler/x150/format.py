"""The X150 formatter: one canonical layout for command streams and sequences.

- Commands in upper case, as the manual writes them ("sequences of upper case characters", L116);
  quoted text (`DTXT"..."`, `"..."`) and the free text of `TX` keep their case.
- One space between the commands of a line (the delimiter, L130); a space written inside a
  command (`IF (..)`, `1OUTL XX10X1`, which the frontend re-joins with warning X103) is removed.
- No indentation: the stream is sent to the controller as it is, and the manual never indents
  sequences or constructs, so a leading delimiter is not introduced where none was.
- Trailing comments are aligned to one column per block of lines (lines between blank lines):
  column 25, or further right when the block's code is longer. Comment text is kept word for word;
  runs of blank lines collapse to one; a line that does not parse, or a command the frontend could
  not read, is left as it is.

Formatting never changes what a program does: `mcc fmt` compares the IR before and after.
"""

from __future__ import annotations

from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.profiles import Profile
from mcc.compiler.span import SourceFile
from mcc.compiler.x150 import parser
from mcc.compiler.x150 import syntax as st
from mcc.compiler.x150.checks import canonical_case
from mcc.compiler.lint.layout import Out, align_comments, collapse_blank_lines, render


def format_text(text: str, path: str = "<text>", profile: Profile | None = None, strict: bool = False) -> str:
    """The text in the canonical style; a line that does not parse is kept as written, or, when
    `strict`, the text is refused (`SyntaxErrors`), as `mcc fmt` does."""
    source = SourceFile(path, text)
    parsed = Diagnostics()
    tree = parser.parse(source, parsed)
    if strict:
        parsed.refuse_syntax_errors()
    lines = collapse_blank_lines([layout_line(source, line) for line in tree.lines])
    align_comments(lines)
    return "".join(render(line) + "\n" for line in lines)


def layout_line(source: SourceFile, line: st.Line) -> Out:
    if line.error:
        return Out(verbatim=source.line_text(line.number))
    comment = line.comment.text.rstrip() if line.comment is not None else ""
    if not line.commands:
        return Out(comment=comment) if comment else Out(blank=True)
    return Out(code=" ".join(command_text(c) for c in line.commands), comment=comment)


def command_text(command: st.Command) -> str:
    text = command.text
    if not command.ok or command.host or command.info is None:
        return text
    return canonical_case(command)





