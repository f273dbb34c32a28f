"""Cutting the command stream into units: sequence definitions and the immediate stretches between.

`XDn` starts storing commands as sequence n and `XT` ends it (L4904, L5382); everything else is
sent to the controllers as it comes. A unit is either one `XDn ... XT` definition or one stretch of
commands outside any definition, in stream order. This pass also reports the definition errors:
XD inside a definition (X106), XT outside one (X107), a definition never closed (X105), and takes
the `XEn` sent just before `XDn` into the definition (the backend always writes `XEn XDn`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.x150 import syntax as st


@dataclass
class Unit:
    kind: str  # "sequence" | "immediate"
    commands: list[st.Command] = field(default_factory=list)  # the body (XD, XT and the erase excluded)
    number: int | None = None  # sequence number
    address: int | None = None  # the XD's device address
    start: st.Command | None = None  # XDn
    end: st.Command | None = None  # XT (None: not closed)
    erase: st.Command | None = None  # the XEn sent just before XDn
    name: str = ""  # routine name, given by the lowering
    nested: bool = False  # the XD came inside another definition (X106): nothing can be sent before it

    @property
    def is_sequence(self) -> bool:
        return self.kind == "sequence"

    def device(self) -> int | None:
        """The device every command of the unit is for, or None when it is written per command."""
        if self.is_sequence:
            return self.address
        addresses = {c.address for c in self.commands if c.ok}
        if len(addresses) == 1:
            return next(iter(addresses))
        return None


def sequence_number(command: st.Command) -> int | None:
    arg = command.arg
    return arg.value if isinstance(arg, st.Number) and isinstance(arg.value, int) else None


UNIT_MARKS = ("XD", "XT")


def split_units(tree: st.SyntaxTree, diags: Diagnostics) -> list[Unit]:
    units: list[Unit] = []
    stream: Unit | None = None
    sequence: Unit | None = None
    commands = list(tree.commands())
    # Only XD and XT start or end a unit: the commands between two of them go to the unit in
    # force as one slice (a file has tens of thousands of commands and a few hundred of these).
    marks = [index for index, command in enumerate(commands)
             if command.mnemonic in UNIT_MARKS and command.info is not None]
    marks.append(len(commands))  # the end: the commands after the last mark
    done = 0
    for index in marks:
        if index > done:
            between = commands[done:index]
            if sequence is not None:
                sequence.commands += between
            else:
                if stream is None:
                    stream = Unit("immediate")
                    units.append(stream)
                stream.commands += between
        done = index + 1
        if index == len(commands):
            break
        command = commands[index]
        name = command.mnemonic
        if name == "XD":
            if sequence is not None:
                diags.add("X106", command.span,
                          f"XD inside the definition of sequence {sequence.number} (line {sequence.start.span.line}): "
                          "XD clears the download and starts again, so that definition is lost; end it with XT "
                          "first")
                sequence.end = None
            nested = sequence is not None
            sequence = Unit("sequence", number=sequence_number(command), address=command.address, start=command,
                            nested=nested)
            if sequence.number is None and command.ok:
                diags.add("X104", command.span, "XD needs the number of the sequence it defines: XD1 to XD64 (L4899)")
            if stream is not None and stream.commands and _erases(stream.commands[-1], command):
                sequence.erase = stream.commands.pop()
                if not stream.commands:
                    units.remove(stream)
            units.append(sequence)
            stream = None
        elif name == "XT":
            if sequence is None:
                diags.add("X107", command.span, "XT ends a sequence definition, but no XD opened one: remove it "
                                                "or add XDn before the sequence's commands")
            else:
                sequence.end = command
                sequence = None
    if sequence is not None:
        start = sequence.start
        diags.add("X105", start.span, f"sequence {sequence.number} is never closed: add XT after its last command "
                                      "(until XT the controller stores everything it receives)")
    return units


def _erases(previous: st.Command, define: st.Command) -> bool:
    return (previous.ok and previous.mnemonic == "XE" and previous.address == define.address
            and sequence_number(previous) is not None and sequence_number(previous) == sequence_number(define))
