"""What the editor features ask of a dialect: one `Editor` per dialect, in its own module
(lsp/<dialect>_editor.py, named by `Dialect.editor` in compiler/<dialect>/dialect.py).

The features (completion.py, hover.py, memory.py, navigation.py, analysis.py) are written once and
never name a dialect; where a dialect differs they ask its Editor: the places of a line where a kind
of name is typed (a label after `BR`, a subroutine number after `GOSUB`), where a statement starts,
which catalog commands fit a place, how a command's syntax becomes a snippet, how a rename is
checked, how program memory is priced, and which module builds the editor model. The defaults here
are those of a dialect with no such knowledge: a dialect registered without an editor module gets
them (completion of its variables and values, hover, no memory figures).
"""

from __future__ import annotations

import importlib
import re
from dataclasses import dataclass


@dataclass(frozen=True)
class Place:
    """A place on a line where a kind of name is typed: when `pattern` is found in the text before
    the cursor (outside a comment if `outside_comment`), completion offers the symbols of `symbols`
    (model.SYMBOL_*), the readable values too with `values`, replacing from the start of group
    `start_group` (None: the word being typed)."""

    pattern: re.Pattern
    symbols: tuple[str, ...]
    values: bool = False
    outside_comment: bool = False
    start_group: int | None = None


class Editor:
    """A dialect's editor support, with the defaults of a dialect that has none of its own."""

    # the module with build(tree, source, profile) -> model.Index, the editor model; "" none
    indexer: str = ""
    # the places where a name is typed (Place), tried in order before a statement's start
    places: tuple[Place, ...] = ()
    # the text before the cursor at the start of a statement (a command is typed there), or None;
    # `statement_group`: the group where the command starts (after a device address), else the word
    statement_start: re.Pattern | None = None
    statement_group: int | None = None
    statement_symbols: bool = True  # variables are offered at a statement's start too
    # the catalog kinds offered as values (None: what the catalog marks readable, operands, variables)
    value_kinds: tuple[str, ...] | None = None
    # Variables are declared (a definition is the declaration), else every assignment defines one.
    variables_declared: bool = False
    # the setting of the editor model that scales the profile's steps per revolution (a microstep
    # resolution given at `microstep_reference`), or "" when the profile's figure holds
    microstep_setting: str = ""
    microstep_reference: float = 1.0
    # whether program memory is priced for the code lenses (memory.py)
    prices_memory: bool = False

    def word_start(self, before: str, start: int) -> int:
        """The column where the word being typed starts, given the start of its trailing word."""
        return start

    def command_place(self, snap, line: int) -> str:
        """The kind of place at `line` that decides which commands fit there ("" everywhere alike)."""
        return ""

    def allows(self, entry, place: str) -> bool:
        """Whether the catalog command `entry` may be written at a place of kind `place`."""
        return True

    def snippet(self, entry) -> tuple[str, str]:
        """(insert text as an LSP snippet, the syntax it came from) for a command."""
        from mcc.lsp import catalog_info

        return catalog_info.snippet(entry)

    def command_before(self, before: str) -> tuple[object | None, str]:
        """(the catalog entry of the command whose arguments are being typed, the arguments typed)."""
        return None, ""

    def validate_rename(self, snap, symbol, new: str):
        """(the renamed symbol's key, a function from an occurrence's old text to its new text), or
        navigation.RenameError with the reason."""
        from mcc.lsp.navigation import RenameError

        raise RenameError(f"{snap.dialect} names cannot be renamed")

    def memory(self, snap, listing, errors: tuple[int, ...]):
        """Program memory per routine (a memory.Usage) from the backend's listing, or None."""
        return None


def editor_of(dialect: str) -> Editor:
    """The editor support of the registered dialect `dialect` (the defaults when it has none)."""
    from mcc.compiler import dialects

    found = dialects.DIALECTS.get(dialect)
    if found is None or not found.editor:
        return DEFAULT
    return _load(found.editor)


_LOADED: dict[str, Editor] = {}


def _load(module: str) -> Editor:
    editor = _LOADED.get(module)
    if editor is None:
        editor = _LOADED[module] = importlib.import_module(module).EDITOR
    return editor


DEFAULT = Editor()
