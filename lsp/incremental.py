"""Incremental checking for the editor: re-parse only the lines an edit changed.

The three dialects are line-oriented: each physical line parses on its own (the parsers' recovery
mode already parses one line at a time, compiler/recovery.py), so the syntax node of a line and
the diagnostics its parsing reports depend only on the line's text and where it stands. Parsing
is the larger part of `mcc check` on a long file, and an edit changes one line or a few, so the
server keeps, per document, the parsed lines of the previous version and:

- reuses a line's node as it is when the same text stands at the same place (line number and
  offset);
- moves it (a copy with its spans and number shifted) when the same text moved: an edit above it
  changed the length of a line or added or removed lines;
- parses the lines it has not seen, all in one call of the dialect's own `parser.parse` on a text
  made of those lines, and moves the results to their places.

The tree is then lowered and checked by the frontend's `analyze_tree` exactly as `mcc check` does
(the lowering and the checks look at the whole program, so they run again in full), and the rest
of `driver.check_file` (long lines, neighbour languages, program memory) is followed step by step.
tests/lsp/test_incremental.py compares the result with a from-scratch check after random edits.
Anything unexpected (a parse that does not give one node per line) falls back to a full parse.
"""

from __future__ import annotations

import dataclasses
import importlib
from typing import Any, Callable

from mcc.compiler import cancel, dialects, driver
from mcc.compiler import selection
from mcc.compiler.config import Settings, load_profile
from mcc.compiler.diagnostics import Diagnostic, Diagnostics, Edit, Fix
from mcc.compiler.lint import engine
from mcc.compiler.span import SourceFile, Span

Entry = tuple[Any, list[Diagnostic]]  # a line's node and the diagnostics its parsing reported


class Mover:
    """Copies of syntax nodes and diagnostics with every span moved by a number of lines and
    characters. Only the dialect's syntax nodes (and diagnostics, fixes, edits) are copied; what
    they point to otherwise (catalog entries, strings) is shared. Each node type gets a small
    generated function (moving is done for every line below an edit that changed a line's length,
    so it must cost much less than parsing the line again)."""

    def __init__(self, syntax) -> None:
        self.movers: dict[type, Callable] = {Span: _move_span, list: self._move_list, tuple: self._move_tuple}
        types = [cls for cls in vars(syntax).values()
                 if isinstance(cls, type) and dataclasses.is_dataclass(cls) and cls.__module__ == syntax.__name__]
        for cls in types + [Diagnostic, Fix, Edit]:
            self.movers[cls] = self._compile(cls, renumber=cls is syntax.Line)

    def move(self, value, lines: int, chars: int):
        mover = self.movers.get(type(value))
        return value if mover is None else mover(value, lines, chars)

    def _move_list(self, value: list, lines: int, chars: int) -> list:
        get = self.movers.get
        return [item if (mover := get(type(item))) is None else mover(item, lines, chars) for item in value]

    def _move_tuple(self, value: tuple, lines: int, chars: int) -> tuple:
        return tuple(self._move_list(list(value), lines, chars))

    def _compile(self, cls: type, renumber: bool) -> Callable:
        frozen = cls.__dataclass_params__.frozen  # type: ignore[attr-defined]
        body = ["def move(value, lines, chars):", "    copy = new(cls)"]
        for f in dataclasses.fields(cls):
            name = f.name
            if renumber and name == "number":
                moved = "value.number + lines"
            else:
                body.append(f"    item = value.{name}")
                body.append("    mover = get(type(item))")
                moved = "item if mover is None else mover(item, lines, chars)"
            body.append(f"    put(copy, {name!r}, {moved})" if frozen else f"    copy.{name} = {moved}")
        body.append("    return copy")
        scope = {"new": object.__new__, "cls": cls, "get": self.movers.get, "put": object.__setattr__}
        exec("\n".join(body), scope)  # noqa: S102 - generated from the dataclass's own field names
        return scope["move"]


def _span_mover() -> Callable:
    """A moved copy of a span, its slots filled directly: twice as fast as the frozen dataclass's
    generated __init__, which does the same through object.__setattr__ (spans are most of what
    is moved)."""
    slots = {name: getattr(Span, name).__set__ for name in ("file", "line", "column", "end_line", "end_column",
                                                            "start", "end")}
    file, line, column, end_line, end_column, start, end = slots.values()
    new = object.__new__

    def move(span: Span, lines: int, chars: int) -> Span:
        copy = new(Span)
        file(copy, span.file)
        line(copy, span.line + lines)
        column(copy, span.column)
        end_line(copy, span.end_line + lines)
        end_column(copy, span.end_column)
        start(copy, span.start + chars)
        end(copy, span.end + chars)
        return copy

    return move


_move_span = _span_mover()


class LineCache:
    """The parsed lines of one document's previous version (see the module's docstring)."""

    def __init__(self, dialect: dialects.Dialect) -> None:
        package = dialect.frontend.rsplit(".", 1)[0]
        self.dialect = dialect
        self.parser = importlib.import_module(package + ".parser")
        self.syntax = importlib.import_module(package + ".syntax")
        self.mover = Mover(self.syntax)
        self.path = ""
        self.placed: dict[tuple[str, int, int], Entry] = {}  # (text, number, offset) -> entry there
        self.relative: dict[str, Entry] = {}  # text -> entry as if at line 1, offset 0
        self.parsed = 0  # lines parsed by the last call (for tests and the benchmark)

    def parse(self, source: SourceFile, diags: Diagnostics):
        """The syntax tree of `source`, as the dialect's `parser.parse` builds it, with the parse
        diagnostics added to `diags`."""
        if source.path != self.path:
            self.path, self.placed, self.relative = source.path, {}, {}
        text = source.text
        texts = text.split("\n")
        if texts and texts[-1] == "":
            texts.pop()  # the empty remainder after the final newline is no line
        starts = source.line_starts
        placed: dict[tuple[str, int, int], Entry] = {}
        relative: dict[str, Entry] = {}
        missing: list[int] = []  # 0-based indices of the lines to parse
        entries: list[Entry | None] = [None] * len(texts)
        for index, line_text in enumerate(texts):
            key = (line_text, index + 1, starts[index])
            found = self.placed.get(key)
            moved = self.relative.get(line_text)
            if moved is not None:
                relative[line_text] = moved  # kept while the text is in the file
            if found is None:
                if moved is None:
                    missing.append(index)
                    continue
                found = (self.mover.move(moved[0], index, starts[index]),
                         [self.mover.move(d, index, starts[index]) for d in moved[1]])
            entries[index] = placed[key] = found
        fresh = list(dict.fromkeys(texts[i] for i in missing))  # each new text parsed once
        self.parsed = len(fresh)
        if fresh and not self.parse_texts(source, fresh, relative):
            self.placed, self.relative = {}, {}
            return self.parser.parse(source, diags)
        for index in missing:
            node, found = relative[texts[index]]
            entries[index] = placed[(texts[index], index + 1, starts[index])] = (
                self.mover.move(node, index, starts[index]), [self.mover.move(d, index, starts[index]) for d in found])
        self.placed, self.relative = placed, relative
        # the cached diagnostics are copied: settling them sets their severity in place
        diags.extend([dataclasses.replace(d) for _, found in entries if found for d in found])
        return self.syntax.SyntaxTree(source.path, [node for node, _ in entries])

    def parse_texts(self, source: SourceFile, fresh: list[str], relative: dict[str, Entry]) -> bool:
        """Parse the lines `fresh` in one call, store them in `relative`, and answer whether that
        went as expected (one node per line, every diagnostic on one of them)."""
        part = SourceFile(source.path, "\n".join(fresh) + "\n")
        found = Diagnostics()
        tree = self.parser.parse(part, found)
        if len(tree.lines) != len(fresh) or any(line.number != k for k, line in enumerate(tree.lines, 1)):
            return False
        by_line: list[list[Diagnostic]] = [[] for _ in fresh]
        for diag in found.items:
            span = diag.span
            if not 1 <= span.line <= len(fresh) or span.end_line != span.line or span.file != source.path:
                return False
            by_line[span.line - 1].append(diag)
        starts = part.line_starts
        for k, line_text in enumerate(fresh):
            lines, chars = -k, -starts[k]
            relative[line_text] = (self.mover.move(tree.lines[k], lines, chars),
                                   [self.mover.move(d, lines, chars) for d in by_line[k]])
        return True


def check_text(path: str, text: str, settings: Settings, dialect: str | None, cache: LineCache | None,
               stop: Callable[[], bool] | None = None) -> tuple[engine.Checked | None, LineCache | None]:
    """`engine.check_text` (the work of `mcc check`), parsing through `cache` (made or replaced
    when the document's dialect is new); the cache to keep for the next version. The check is
    None when `stop` answered True at a checkpoint (after parsing, in the lowering, between the
    checks, before the memory: compiler/cancel.py); the cache then holds the new text's lines."""
    found = driver.resolve_dialect(path, dialect, settings)
    if found is None or found.name not in dialects.DIALECTS:
        return engine.check_text(path, text, settings, dialect), None
    if cache is None or cache.dialect.name != found.name:
        cache = LineCache(found)
    source = SourceFile(path, text)
    # the profile as `mcc check` chooses it (compiler/selection.py: --profile, directive, per-file-profiles, target)
    choice = selection.choose(path, found.name, source, settings)
    profile = choice.profile
    diags = Diagnostics(list(choice.diagnostics))
    result = driver.FileResult(path, found.name, source=source, profile=profile, profile_source=choice.source)
    with driver.fewer_collections():  # over every step, as `driver.check_file`
        try:
            with cancel.stopping_when(stop):
                result.analysis = analyze_source(source, found, profile, diags, cache)
        except cancel.Cancelled:
            return None, cache
        if result.analysis is not None and not diags.has_errors:
            if stop is not None and stop():
                return None, cache
            driver.measure_memory(result.analysis, found, profile, diags)
        if not choice.chosen and diags.has_errors:
            driver.suggest_profile(result, found, diags)  # G021, as `mcc check` does
    result.diagnostics = diags.items
    return engine.Checked(path, result.dialect, result, profile), cache


def analyze_source(source: SourceFile, dialect: dialects.Dialect, profile, diags: Diagnostics, cache: LineCache):
    """`driver.analyze_source` with the parse going through the cache (cancel.Cancelled goes
    through: the cache is complete for the new text once the parse is done)."""
    preprocessor = dialect.load_preprocessor()
    if preprocessor is not None and preprocessor.directive_lines(source):
        return driver.analyze_source(source, dialect, profile, diags)  # preprocessor source, as `mcc check` (M142)
    source = driver.without_long_lines(source, dialect.longest_line, diags)
    try:
        frontend = dialect.load_frontend()
        with driver.fewer_collections():
            found = Diagnostics()
            tree = cache.parse(source, found)
            cancel.checkpoint()
            analysis = frontend.analyze_tree(source, tree, driver.profile_for(dialect, profile), found)
    except Exception as exc:  # noqa: BLE001 - the no-traceback guarantee
        driver.internal_error(diags, source.path, exc, "checking")
        cache.placed, cache.relative = {}, {}
        return None
    if analysis.diagnostics.has_errors:
        analysis = driver.neighbour_language(analysis, dialect)
    diags.extend(analysis.diagnostics)
    return analysis
