"""Programs written for mcontrol's MCode preprocessor (`#include`, `#define`, `#if` ... `#endif`).

mcontrol (an open-source MDrive host) keeps its MCode as source files with C-like directives that
its own tool (`mcodepp.py`) expands before download: `#include "../brake.mxt"` pastes another file
once, `#define NAME value` sets a name that only `#if NAME == ...` tests, `#if`/`#elseif`/`#else`/
`#endif` keep or drop lines. The device never sees a `#`: MCode has no such character
(lexium-mcode.txt knows only `'` and the backquote as comment markers).

Decision (docs/dialects/mcode.md, "mcontrol's preprocessor"): mcc does not expand them. A file
with directives gets one diagnostic, M142, on its first directive, with every directive line as a
note, instead of "unexpected character '#'" on each of them; the rest of the file is still read
(the directive lines blanked, so every other line keeps its number and columns) for the editor's
outline and hover, but its errors are not reported: a label of an included file or a line of an
`#if` branch is not there to check. Check the preprocessor's output, the program the device gets.
"""

from __future__ import annotations

import re

from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.span import SourceFile

DIRECTIVE = re.compile(r"^[ \t]*#[ \t]*(include|define|undef|ifdef|ifndef|if|elseif|elif|else|endif)\b",
                       re.IGNORECASE | re.MULTILINE)


def directive_lines(source: SourceFile) -> list[tuple[int, str]]:
    """(line number, directive keyword) of every preprocessor line, in file order."""
    if "#" not in source.text:
        return []
    return [(source.text.count("\n", 0, m.start()) + 1, m.group(1).lower()) for m in DIRECTIVE.finditer(source.text)]


def blanked(source: SourceFile, lines: list[tuple[int, str]]) -> SourceFile:
    """The source with each directive line's text replaced by spaces: same length, same offsets."""
    text = source.text
    pieces = []
    start = 0
    for number, _ in lines:
        begin = source.line_starts[number - 1]
        end = text.find("\n", begin)
        end = len(text) if end < 0 else end
        pieces += [text[start:begin], " " * (end - begin)]
        start = end
    pieces.append(text[start:])
    return SourceFile(source.path, "".join(pieces))


def report(source: SourceFile, lines: list[tuple[int, str]], diags: Diagnostics) -> None:
    """The one M142 that replaces the file's errors."""
    kinds = sorted({kind for _, kind in lines}, key=lambda k: next(n for n, kk in lines if kk == k))
    shown = ", ".join(f"#{k}" for k in kinds)
    first = lines[0][0]
    diags.add("M142", source.line_span(first),
              f"this file is source for mcontrol's MCode preprocessor ({shown}, {len(lines)} "
              f"line{'s' if len(lines) != 1 else ''}), not a program the device reads: mcc does not expand "
              "directives. Run the preprocessor (mcontrol's mcodepp.py) and check its output",
              notes=tuple(f"{source.path}:{n}: {source.line_text(n).strip()}" for n, _ in lines[:8]))
