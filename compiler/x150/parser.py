"""Parsing X150 text into the syntax tree, with recovery at line ends.

Two stages (docs/dialects/x150.md, "Tokeniser"):

1. The LALR grammar `grammars/x150.lark` cuts the text into lines of command tokens and comments.
   The common case (no unterminated quote or parenthesis anywhere) is one pass over the file. When
   it fails, the file is parsed again line by line with the `line` start symbol, so each bad line
   costs one X001 diagnostic and every other line is still checked; the commands before the bad
   token on a bad line are kept.
2. Each token is read against the catalog (`tokens.CommandReader`). A command whose argument was
   written after a space (`IF (..)`, `1OUTL XX10X1`, `GOTO 2`, `DTXT "..."`) is re-joined with
   the next token when that token is not a command of its own, with an X103 warning.
"""

from __future__ import annotations

import re
import unicodedata
from functools import lru_cache
from pathlib import Path

from mcc.grammars import x150_tables
from mcc.grammars.lark_runtime import Lark, LarkError, Transformer, UnexpectedInput

from mcc.compiler import limits, recovery
from mcc.compiler.diagnostics import Diagnostics, Edit, Fix
from mcc.compiler.span import SourceFile
from mcc.compiler.x150 import catalog as cat
from mcc.compiler.x150 import syntax as st
from mcc.compiler.x150.tokens import CommandReader, LineSpans, Piece

GRAMMAR = Path(__file__).resolve().parent.parent.parent / "grammars" / "x150.lark"
TOKEN = re.compile(r'(?:[^\s;"(]|"[^"\n]*"|\([^)\n]*\))+|;[^\n]*')
NOT_A_VALUE = ("none", "query")


class Collector(Transformer):
    """Parser callbacks: each line becomes (line number, [CMD tokens], COMMENT token or None)."""

    def __init__(self) -> None:
        super().__init__(visit_tokens=False)
        self.line_delta = 0

    def start(self, children):
        return children

    def line(self, children):
        newline = children[-1]
        comment = None
        tokens = children[:-1]
        if tokens and tokens[-1].type == "COMMENT":
            comment = tokens.pop()
        return newline.line + self.line_delta, tokens, comment


@lru_cache(maxsize=1)
def _parser() -> tuple[Lark, Collector]:
    collector = Collector()
    # generated from the grammar with its newline terminal named NL, so that it stays in the tree
    # (grammars/generate.py RENAMED): the collector reads each line's number from it
    parser = recovery.lalr_parser(x150_tables, collector)
    return parser, collector


def bare_parser():
    """The same grammar with no callbacks, by the `lark` package: the baseline the benchmark
    compares against."""
    return recovery.bare_parser(GRAMMAR.read_text(encoding="utf-8"))


@lru_cache(maxsize=1)
def _scanner() -> re.Pattern:
    """One regular expression of the grammar's own terminals, taken from the Lark parser so that
    grammars/x150.lark stays their one definition: four groups, CMD, COMMENT, NL and the ignored
    blanks, one of which holds each match (no terminal matches an empty text, and no two begin
    with the same character).

    The grammar is regular (a line is command tokens, then an optional comment, then its end), so
    a text in which this expression matches every character, one terminal after the other, is a
    text the LALR parser accepts with the same tokens: the common case is read with one `findall`,
    and Lark's parser runs only for a text it would reject (to report the bad line and recover)."""
    parser, _ = _parser()
    groups: dict[str, list[str]] = {"CMD": [], "COMMENT": [], "NL": [], "IGNORE": []}
    for terminal in parser.terminals:
        if terminal.pattern.flags:  # pragma: no cover - the grammar has no flagged terminal
            raise ValueError(f"x150 terminal {terminal.name} has flags")
        name = terminal.name if terminal.name in ("CMD", "COMMENT", "NL") else "IGNORE"
        if name == "IGNORE" and terminal.name not in parser.lexer_conf.ignore:  # pragma: no cover
            raise ValueError(f"unexpected x150 terminal {terminal.name}")
        groups[name].append(_runs(terminal.pattern.to_regexp()))
    return re.compile("|".join(f"((?:{'|'.join(patterns)}))" for patterns in groups.values()))


def _runs(pattern: str) -> str:
    """A terminal `(?:[class]|rest)+` as `(?:[class]+|rest)+`: the same tokens (a run of the
    class's characters is the first alternative taken once per character; nothing follows the
    group, so the engine never backtracks into it), but the engine loops inside the class over a
    run instead of around the whole alternation once per character. The CMD terminal: about a
    fifth of the scan."""
    match = re.fullmatch(r"\(\?:(\[[^\]]*\])\|(.*)\)\+", pattern, re.S)
    return f"(?:{match.group(1)}+|{match.group(2)})+" if match is not None else pattern


def _scan(text: str) -> list | None:
    """The lines of `text` (which ends with a line end) as (number, [(token, offset)], comment)
    with comment (text, start, end) or None; None when a character matches no terminal.

    `findall` gives the matches' texts only (which costs much less than a match object each):
    they follow one another, so each one's offset is the sum of the lengths before it, and a
    character no terminal matches is skipped by the search, which the total length shows."""
    out: list = []
    tokens: list[tuple[str, int]] = []
    comment = None
    number = 1
    pos = 0
    for command, remark, newline, blank in _scanner().findall(text):
        if command:
            tokens.append((command, pos))
            pos += len(command)
        elif newline:
            out.append((number, tokens, comment))
            number += 1
            tokens = []
            comment = None
            pos += len(newline)
        elif blank:
            pos += len(blank)
        else:
            comment = (remark, pos, pos + len(remark))
            pos += len(remark)
    if pos != len(text):
        return None
    return out


@lru_cache(maxsize=1)
def _reader() -> CommandReader:
    return CommandReader(cat.load())


def describe_error(exc: UnexpectedInput, text: str, column: int) -> str:
    char = text[column - 1] if 0 < column <= len(text) else ""
    if char == '"':
        return "unterminated text: add the closing '\"' on the same line (DTXT\"TEXT\")"
    if char == "(":
        return "unclosed '(': the condition or (VARn) must end with ')' on the same line"
    if char:
        name = unicodedata.name(char, "")
        shown = f"U+{ord(char):04X}" + (f" ({name.lower()})" if name else "")
        return f"unexpected character {shown}: X150 commands are separated by spaces or line ends"
    return str(exc).splitlines()[0]


def parse(original: SourceFile, diags: Diagnostics) -> st.SyntaxTree:
    parser, collector = _parser()
    source, refused = limits.readable(original, ";", diags)
    text = source.text if source.text.endswith("\n") or not source.text else source.text + "\n"
    collector.line_delta = 0
    tree = st.SyntaxTree(source.path)
    raw_lines = _scan(text)
    if raw_lines is None:
        raw_lines = _parse_by_line(source, parser, collector, diags)
    starts = source.line_starts
    reader = _reader()
    path = source.path
    lines = tree.lines
    # One LineSpans for every line, moved to each in turn: what is read from a line keeps its own
    # spans, not this object (making one per line cost about 2 % of a check).
    spans = LineSpans(path, 0, 0)
    readings: dict = {}  # token text -> its first reading, copied for the next ones (`read_again`)
    for number, tokens, comment in raw_lines:
        if isinstance(tokens, st.Line):  # a line that failed, already built
            lines.append(tokens)
            continue
        if tokens or comment is not None:
            spans.line = number
            spans.line_start = starts[number - 1]
            line = st.Line(number, read_commands(reader, spans, tokens, diags, readings) if tokens else [])
            if comment is not None:
                line.comment = st.Comment(comment[0], spans.at(comment[1], comment[2]))
        else:
            line = st.Line(number)
        lines.append(line)
    limits.refuse_deep(original, tree.lines, refused, diags, bounded=(st.Condition,))
    return tree


def _parse_by_line(source: SourceFile, parser: Lark, collector: Collector, diags: Diagnostics) -> list:
    out: list = []
    starts = source.line_starts
    reader = _reader()
    for number in range(1, source.line_count + 1):
        text = source.line_text(number)
        if number == source.line_count and not text:
            break  # the empty remainder after the final newline
        collector.line_delta = number - 1
        try:
            _, tokens, comment = parser.parse(text + "\n", start="line")
        except UnexpectedInput as exc:
            column = max(1, min(getattr(exc, "column", 1) or 1, len(text) + 1))
            out.append((number, _bad_line(source, reader, number, text, column, exc, diags), None))
            continue
        except LarkError as exc:  # pragma: no cover - any other parser failure is still a syntax error
            diags.add("X001", source.line_span(number), str(exc).splitlines()[0])
            out.append((number, st.Line(number, error=True), None))
            continue
        shift = starts[number - 1]
        out.append((number, [(str(t), t.start_pos + shift) for t in tokens],
                    (str(comment), comment.start_pos + shift, comment.end_pos + shift) if comment is not None
                    else None))
    collector.line_delta = 0
    return out


def _bad_line(source: SourceFile, reader: CommandReader, number: int, text: str, column: int,
              exc: UnexpectedInput, diags: Diagnostics) -> st.Line:
    """Report the line's first unreadable character and keep the commands before its token."""
    line_start = source.line_starts[number - 1]
    spans = LineSpans(source.path, number, line_start)
    start = line_start + column - 1
    end = start + (1 if column <= len(text) else 0)
    diags.add("X001", spans.at(start, end), describe_error(exc, text, column))
    token_start = column - 1
    while token_start > 0 and not text[token_start - 1].isspace():
        token_start -= 1
    line = st.Line(number, error=True)
    pieces = []
    for match in TOKEN.finditer(text, 0, token_start):
        if match.group().startswith(";"):
            break
        pieces.append((match.group(), line_start + match.start()))
    line.commands = read_commands(reader, spans, pieces, diags, {})
    return line


def read_commands(reader: CommandReader, spans: LineSpans, pieces: list[tuple[str, int]],
                  diags: Diagnostics, readings: dict) -> list[st.Command]:
    """Read the command tokens of one line, re-joining an argument written after a space.
    `readings`: the tokens read so far in the file (`CommandReader.read_again`)."""
    count = len(pieces)
    if count == 1:  # most lines: one command, which takes no next word
        command = reader.read_again(pieces[0][0], pieces[0][1], spans, readings)
        for problem in command.problems:
            diags.add(problem.code, problem.span, problem.message)
        return [command]
    commands: list[st.Command] = []
    index = 0
    while index < count:
        text, start = pieces[index]
        command = reader.read_again(text, start, spans, readings)
        # A command with a value (most: `arg` set, and not a bare VARn) takes no next word.
        if index + 1 < count and (command.arg is None or type(command.arg) is st.VarStatement) \
                and _may_take_next(command):
            following = reader.read_again(*pieces[index + 1], spans, readings)
            joined = _rejoin(reader, spans, command, following, pieces[index], pieces[index + 1])
            if joined is not None:
                gap = spans.at(start + len(text), pieces[index + 1][1])
                diags.add("X103", gap, f"a space separates {joined.mnemonic} from its argument: the controller "
                                       f"reads a space as the end of a command (L130); write {joined.text}",
                          fix=Fix("remove the space", (Edit(gap, ""),)))
                command = joined
                index += 1
        commands.append(command)
        index += 1
    for command in commands:
        if command.problems:
            for problem in command.problems:
                diags.add(problem.code, problem.span, problem.message)
    return commands


def _has_value(command: st.Command) -> bool:
    arg = command.arg
    return arg is not None and not (isinstance(arg, st.VarStatement) and arg.value is None)


def _may_take_next(command: st.Command) -> bool:
    """A command written without its value (`1OUTL`, `IF`, `GOTO`, `VAR2`) may take the next word."""
    info = command.info
    return (info is not None and not _has_value(command) and info.arg not in NOT_A_VALUE
            and not (command.problems and not info.value_required))


def _rejoin(reader: CommandReader, spans: LineSpans, command: st.Command, following: st.Command,
            first: tuple[str, int], second: tuple[str, int]) -> st.Command | None:
    if following.ok and not command.problems:
        return None  # the next token is a command of its own: `1OUTL 1A10` is a report then a setting
    joined = reader.read(Piece(first[0] + second[0], first[1], len(first[0]), second[1]), spans)
    if joined.mnemonic != command.mnemonic or not _has_value(joined):
        return None
    if joined.problems and not command.problems:
        return None
    joined.rejoined = True
    return joined

