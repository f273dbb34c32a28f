"""What a frontend returns for one source file: the text, the syntax tree, the IR and diagnostics.

It lives apart from the driver so that frontends depend on it without depending on the driver
(the layers are kept by tests/test_layers.py). The file's symbol table and def-use chains
(`compiler/symbols.py`) are computed from the IR on first use and kept, so the lint rules, the
language server and later passes share one walk instead of each redoing it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from mcc.compiler import ir
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.span import SourceFile
from mcc.compiler.symbols import DefUse, Symbols, build


@dataclass
class Analysis:
    source: SourceFile
    tree: Any
    module: ir.Module | None
    diagnostics: Diagnostics
    # program memory against the target's budget, from the same model as the backend's listing
    # (X150 sequence bytes, Arcus assembly lines); filled by the frontend or by `measure_memory`
    memory: dict = field(default_factory=dict)
    # the frontend's reading of each statement, in order, where the editor's model needs it (MCode:
    # (line, Resolved) pairs, read once with the names the whole file declares), so the language
    # server builds its model from the same reading instead of resolving every statement again
    statements: list = field(default_factory=list)
    _tables: tuple[Symbols, DefUse] | None = field(default=None, repr=False, compare=False)

    def _built(self) -> tuple[Symbols, DefUse]:
        if self._tables is None:
            module = self.module if self.module is not None else ir.Module("", "")
            self._tables = build(module)
        return self._tables

    @property
    def symbols(self) -> Symbols:
        """Variables, labels and routines: definition span and reference spans (computed once)."""
        return self._built()[0]

    @property
    def defuse(self) -> DefUse:
        """For each variable, the operations that define it and those that read it (computed once)."""
        return self._built()[1]
