"""Columns between mcc (characters) and the editor (the position encoding agreed at `initialize`).

mcc's spans count columns in characters (Unicode code points) of the normalised text. LSP counts
them in the units of the position encoding the server announced: UTF-16 code units unless the
client offered another (pygls picks the first of the client's `general.positionEncodings` it
supports; Neovim offers UTF-8 first). A column differs between the two as soon as a line holds a
non-ASCII character before it (`PR "Température °C: ",Np`: `Np` starts at character 21, UTF-8
byte 23), so every position that crosses the protocol is converted here, both ways, with the text
of the line it is on. A rename that skipped this wrote `NqNp` into the user's file.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import attrs
from lsprotocol import types as t

LineText = Callable[[int], str]  # the text of a 0-based line ("" past the end)


def _width(char: str, encoding: str) -> int:
    code = ord(char)
    if encoding == "utf-8":
        return 1 if code < 0x80 else 2 if code < 0x800 else 3 if code < 0x10000 else 4
    return 2 if code > 0xFFFF else 1  # utf-16


@dataclass(frozen=True)
class Units:
    """The client's column unit: "utf-8", "utf-16" or "utf-32" (characters: no conversion)."""

    encoding: str = "utf-16"

    @property
    def characters(self) -> bool:
        return self.encoding == "utf-32"

    def to_client(self, line: str, column: int) -> int:
        """A 0-based character column of `line` in the client's units."""
        if self.characters or line.isascii():
            return column
        head = line[:column]
        return sum(_width(ch, self.encoding) for ch in head) + max(column - len(line), 0)

    def from_client(self, line: str, units: int) -> int:
        """A column in the client's units as a 0-based character column of `line` (a column inside
        a character counts as that character; past the end, as the end)."""
        if self.characters or line.isascii():
            return units
        seen = 0
        for index, ch in enumerate(line):
            if seen >= units:
                return index
            seen += _width(ch, self.encoding)
        return len(line)

    def position_to_client(self, position: t.Position, text_of: LineText) -> t.Position:
        return t.Position(position.line, self.to_client(text_of(position.line), position.character))

    def position_from_client(self, position: t.Position, text_of: LineText) -> t.Position:
        return t.Position(position.line, self.from_client(text_of(position.line), position.character))

    def range_from_client(self, range_: t.Range, text_of: LineText) -> t.Range:
        return t.Range(self.position_from_client(range_.start, text_of), self.position_from_client(range_.end, text_of))

    def out(self, result, text_of: LineText):
        """`result` (any answer or notification built from lsprotocol types, lists and dicts) with
        every `Position` in it converted to the client's units. Positions are rebuilt, never
        changed in place, so objects shared with a snapshot stay in characters."""
        if self.characters or result is None:
            return result
        return _convert(result, lambda p: self.position_to_client(p, text_of), 0)


def _convert(value, convert: Callable[[t.Position], t.Position], depth: int):
    if depth > 64:  # far deeper than any LSP answer
        return value
    if isinstance(value, t.Position):
        return convert(value)
    if isinstance(value, (str, bytes, int, float, bool)) or value is None:
        return value
    if isinstance(value, list):
        return [_convert(item, convert, depth + 1) for item in value]
    if isinstance(value, tuple):
        return tuple(_convert(item, convert, depth + 1) for item in value)
    if isinstance(value, dict):
        return {key: _convert(item, convert, depth + 1) for key, item in value.items()}
    if attrs.has(type(value)):
        changes = {}
        for field in attrs.fields(type(value)):
            item = getattr(value, field.name)
            new = _convert(item, convert, depth + 1)
            if new is not item:
                changes[field.name.lstrip("_") if field.alias is None else field.alias] = new
        return attrs.evolve(value, **changes) if changes else value
    return value
