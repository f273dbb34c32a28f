"""Bounds on one line of input, so that no input can exhaust mcc (shared by the three parsers).

No controller reads a number of more than about 20 digits, or a statement nested more than a few
levels deep (MCode lines hold 64 characters, an Arcus statement has one operator, an X150
condition two terms). mcc is more generous, but not unbounded: Python refuses to convert more than
4,300 digits to an integer, and the walks over expressions (lowering, resolution, the formatters,
the backends) are recursive. So each parser passes its text through `readable` (a number of more
than `MAX_DIGITS` digits outside comments and strings is reported as G030 and read as a shorter
one) and its lines through `refuse_deep` (a statement nested more than `MAX_DEPTH` levels is
reported as G031). A refused line is marked as an error line: it is not lowered and the formatter
keeps it as written, like a line that does not parse.
"""

from __future__ import annotations

import bisect
import dataclasses
import re
from typing import Iterable

from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.span import SourceFile, Span

MAX_DIGITS = 40
MAX_DEPTH = 100  # nesting of one statement; a list of n items counts n levels (X150 reads terms in a row)
LONG_NUMBER = re.compile(r"\d{%d,}" % (MAX_DIGITS + 1))
LONG_LINE = re.compile(r"[^\n]{%d,}" % (MAX_DEPTH // 2 + 1))  # a line that may nest too deep (refuse_deep)


def outside_text(line: str, position: int, comment_chars: str) -> bool:
    """Position `position` of `line` is code: not after a comment character, not inside quotes."""
    quoted = False
    for char in line[:position]:
        if char == '"':
            quoted = not quoted
        elif char in comment_chars and not quoted:
            return False
    return not quoted


def readable(source: SourceFile, comment_chars: str, diags: Diagnostics) -> tuple[SourceFile, set[int]]:
    """The text the parser may read, and the numbers of the lines that hold a number too long.

    Each digit run longer than MAX_DIGITS in code is reported (G030) and, in the returned text only,
    replaced by MAX_DIGITS nines and spaces, so positions do not move and no conversion fails."""
    text = source.text
    if LONG_NUMBER.search(text) is None:
        return source, set()
    starts = source.line_starts
    pieces: list[str] = []
    done = 0
    refused: set[int] = set()
    for match in LONG_NUMBER.finditer(text):
        line_start = text.rfind("\n", 0, match.start()) + 1
        line_end = text.find("\n", match.start())
        line = text[line_start:line_end if line_end >= 0 else len(text)]
        if not outside_text(line, match.start() - line_start, comment_chars):
            continue
        number = bisect.bisect_right(starts, match.start())
        column = match.start() - line_start + 1
        length = match.end() - match.start()
        span = Span(source.path, number, column, number, column + length, match.start(), match.end())
        diags.add("G030", span, f"this number has {length:,} digits: no controller reads more than about 20, and "
                                f"mcc reads at most {MAX_DIGITS}; write the value the device can hold")
        refused.add(number)
        pieces += [text[done:match.start()], "9" * MAX_DIGITS, " " * (length - MAX_DIGITS)]
        done = match.end()
    if not refused:
        return source, set()
    pieces.append(text[done:])
    return SourceFile(source.path, "".join(pieces)), refused


def depth(node, limit: int = MAX_DEPTH, bounded: tuple[type, ...] = ()) -> int:
    """How deep a syntax node nests (stops counting past `limit`), without recursion: a dataclass
    adds one level, a list or tuple of n items adds n (a flat run of terms is evaluated as a chain),
    except the lists of a `bounded` node, whose length the dialect's own checks limit (one level)."""
    deepest = 0
    work = [(node, 0)]
    while work:
        current, level = work.pop()
        if level > deepest:
            deepest = level
            if deepest > limit:
                return deepest
        if isinstance(current, (list, tuple)):
            step = len(current)
            work += [(item, level + step) for item in current if _nested(item)]
        elif dataclasses.is_dataclass(current) and not isinstance(current, (Span, type)):
            flat = isinstance(current, bounded)
            for f in dataclasses.fields(current):
                value = getattr(current, f.name)
                if flat and isinstance(value, (list, tuple)):
                    work += [(item, level + 1) for item in value if _nested(item)]
                elif _nested(value):
                    work.append((value, level + 1))
    return deepest


def _nested(value) -> bool:
    return isinstance(value, (list, tuple)) or (dataclasses.is_dataclass(value) and not isinstance(value, (Span, type)))


def statements(line) -> Iterable:
    statement = getattr(line, "statement", None)
    if statement is not None:
        yield statement
    yield from getattr(line, "commands", None) or ()


def refuse_deep(source: SourceFile, lines: list, refused: set[int], diags: Diagnostics,
                bounded: tuple[type, ...] = ()) -> None:
    """Mark as error lines those in `refused` and those holding a statement nested too deep (G031).

    `bounded` are node types whose lists the dialect limits itself (X150 conditions: two terms,
    reported as X111 by its checks), so the manual's rule is reported rather than G031. Only lines longer than MAX_DEPTH // 2 characters are measured: a shorter line cannot nest that
    deep, so a normal file costs one length test per line."""
    short = MAX_DEPTH // 2
    starts = source.line_starts
    # The lines to look at, found by one search: those refused and those longer than `short`.
    candidates = refused | {bisect.bisect_right(starts, match.start()) for match in LONG_LINE.finditer(source.text)}
    if not candidates:
        return
    for line in lines:
        number = line.number
        if number not in candidates:
            continue
        if line.error or number < 1 or number > len(starts):
            continue
        end = starts[number] - 1 if number < len(starts) else len(source.text)
        if number not in refused:
            if end - starts[number - 1] <= short:
                continue
            deepest = max((depth(s, MAX_DEPTH, bounded) for s in statements(line)), default=0)
            if deepest <= MAX_DEPTH:
                continue
            diags.add("G031", source.line_span(number),
                      f"this statement nests more than {MAX_DEPTH} levels deep (operators, parentheses or terms "
                      "in a row): no controller reads it; compute it in several statements with variables")
        refuse(line, source)


def refuse(line, source: SourceFile) -> None:
    """Make `line` an error line: kept as written, not lowered (an IF or WHILE still opens its block)."""
    statement = getattr(line, "statement", None)
    if hasattr(line, "keyword") and statement is not None:
        keyword = getattr(statement, "keyword", "")
        if keyword in ("IF", "ELSEIF", "WHILE"):
            line.keyword = keyword
    if hasattr(line, "statement"):
        line.statement = None
    if hasattr(line, "commands"):
        line.commands = []
    if hasattr(line, "span"):
        line.span = source.line_span(line.number)
    line.error = True
