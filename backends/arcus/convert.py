"""From the IR's units and neutral names to the PMX-4EX-SA's, for programs of any source dialect.

The IR counts positions in steps of the source's `steps_per_rev`, speeds in steps/s, ramp times
and delays in seconds, and names readings and settings neutrally (docs/IR.md). The Arcus counts
pulses, pulses/s and milliseconds, and spells registers its own way. This module holds what the
legaliser needs to go from one to the other:

- `Scale`: positions scaled by target/source steps per revolution (refused between two pulses,
  never rounded), speeds scaled and rounded to whole pulses/s, times to whole milliseconds;
- `Axes`: the source's logical axes mapped to the target's axis letters in order;
- the neutral readings (`ir.Status`) as Arcus registers (`position` X is `PX`, `moving` X is
  `MSTX&7`), and the neutral settings as Arcus statements (`clear_error` X is `ECLEARX`).

A reading or setting with no Arcus counterpart is None here; the legaliser refuses it by name.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from fractions import Fraction

from mcc.compiler import ir, units

DIALECT = "arcus"

# Neutral reading -> (Arcus catalog name, per axis?) read as the register itself.
REGISTERS = {"position": ("P", True), "encoder": ("E", True), "velocity": ("PS", True),
             "motor_status": ("MST", True), "inputs": ("DI", False), "outputs": ("DO", False),
             "enable_outputs": ("EO", False), "max_speed": ("HSPD", True), "initial_speed": ("LSPD", True),
             "profile": ("SCV", True), "compare_state": ("SYNS", True)}
INDEXED = {"input": "DI", "output": "DO"}
# Readings computed from the motor status bits (L718-L734): (mask, shift).
STATUS_BITS = {"moving": (7, 0), "limit_plus": (1, 4), "limit_minus": (1, 5), "home_switch": (1, 6)}
# Readings the source keeps in ms as `reading * 1000` (an Arcus `TR` or `ACC` read).
MS_REGISTERS = {"countdown": "TR", "accel_time": "ACC"}
# Neutral setting -> (Arcus catalog name, the value's kind): "steps", "rate", "ms" or "plain".
SETTINGS = {"encoder_position": ("E", "steps"), "speed_change": ("SSPD", "rate"), "countdown": ("TR", "ms"),
            "compare_condition": ("SYNC", "plain"), "compare_position": ("SYNP", "steps"),
            "compare_pulse": ("SYNT", "ms"), "enable_outputs": ("EO", "plain")}


class Refused(Exception):
    """A value or name the target cannot express; the message says why."""


@dataclass
class Scale:
    """Unit conversions from the source module to the target profile."""

    source: int  # steps per revolution of the IR (0: unknown)
    target: int  # pulses per revolution of the target (0: unknown)

    @cached_property
    def factor(self) -> Fraction:  # asked once per position and speed: computed once
        return units.ratio(self.source, self.target)

    def steps(self, value: ir.Expr) -> ir.Expr:
        """A position or distance in target pulses; refused when it falls between two pulses."""
        if isinstance(value, ir.Const):
            scaled = units.scale_steps(value.value, self.factor)
            if not scaled.exact:
                raise Refused(f"the position {value.value} steps is {float(value.value * self.factor):g} pulses at "
                              f"{self.target} pulses per revolution (the source counts {self.source} steps per "
                              "revolution): it falls between two pulses; compile with --profile naming a user "
                              "profile whose steps_per_rev makes it whole")
            return ir.Const(int(scaled.value), ir.Unit.STEPS, value.span)
        if self.factor != 1:
            raise Refused(f"a position computed at run time cannot be rescaled from {self.source} to {self.target} "
                          "steps per revolution; compile with a profile whose steps_per_rev is the source's")
        return value

    def rate(self, value: ir.Expr) -> ir.Expr:
        """A speed in whole pulses/s."""
        if isinstance(value, ir.Const):
            return ir.Const(max(1, round(units.scale_rate(value.value, self.factor))) if value.value else 0,
                            ir.Unit.STEPS_PER_S, value.span)
        if self.factor != 1:
            raise Refused(f"a speed computed at run time cannot be rescaled from {self.source} to {self.target} "
                          "steps per revolution")
        return value


def ms(value: ir.Expr, what: str) -> ir.Expr:
    """A time in seconds as whole milliseconds: a constant converted, `v * 0.001` (an Arcus value
    read back) as `v`; anything else computed at run time is refused (Arcus times are literals or
    a variable in ms)."""
    if isinstance(value, ir.Const):
        if value.unit not in (ir.Unit.S, ir.Unit.NONE):
            raise Refused(f"the {what} is given in {value.unit.value}, not a time in seconds")
        return ir.Const(round(units.s_to_ms(value.value)), ir.Unit.NONE, value.span)
    if isinstance(value, ir.BinOp) and value.op == "*" and isinstance(value.right, ir.Const) \
            and abs(value.right.value * units.MS_PER_S - 1) < 1e-9:
        return value.left
    raise Refused(f"the {what} is computed at run time in seconds and Arcus takes whole milliseconds")


class Axes:
    """The source's logical axes as the target's letters: Arcus letters stay; device addresses
    1..n become the n-th letter; other names (an MCode party name, or no name at all: the one
    axis of a single-axis drive) take the free letters in the order they first appear. "*" is
    every axis."""

    LETTERS = ("X", "Y", "Z", "U")

    def __init__(self, module: ir.Module, letters: tuple[str, ...]):
        self.letters = letters
        self.map: dict[str, str] = {}
        names = _axes_used(module)
        named = [n for n in names if n.upper() not in self.LETTERS and not n.isdigit()]
        named += [n for n in names if n.isdigit() and not 1 <= int(n) <= len(letters)]
        for name in names:
            if name.upper() in self.LETTERS:
                self.map[name] = name.upper()
            elif name.isdigit() and 1 <= int(name) <= len(letters):
                self.map[name] = letters[int(name) - 1]
        free = [letter for letter in letters if letter not in self.map.values()]
        for name in named:
            if free:
                self.map[name] = free.pop(0)
        self.count = len(names)

    def letter(self, axis: str) -> str | None:
        """The target letter, "*" for every axis, or None (no axis of the target is left for it)."""
        if axis == ir.ALL_AXES:
            return ir.ALL_AXES
        if axis == "" and "" not in self.map:
            return ir.ALL_AXES  # a setting of no axis in a program that names none
        return self.map.get(axis) or self.map.get(axis.upper())


LEAVES = (ir.Const, ir.Var)


def _axes_used(module: ir.Module) -> list[str]:
    seen: dict[str, None] = {}

    def add(axis: str) -> None:
        if axis != ir.ALL_AXES:
            seen.setdefault(axis, None)

    for _, block in module.blocks():
        for op in block.ops:
            if isinstance(op, ir.Move):
                for axis, _ in op.targets:
                    add(axis)
            elif isinstance(op, ir.Arc):
                for axis in op.axes:
                    add(axis)
            elif isinstance(op, (ir.Slew, ir.Home, ir.WaitMotion, ir.Stop, ir.SetPosition, ir.DriveEnable)):
                add(op.axis)  # a motion command names its axis; "" is a single-axis drive's one axis
            elif getattr(op, "axis", ""):
                add(op.axis)
            for expr in ir.op_exprs(op):
                if type(expr) in LEAVES:
                    continue  # a leaf, and not a reading: most values are
                for node in ir.walk_expr(expr):
                    if isinstance(node, ir.Status) and node.axis:
                        add(node.axis)
        for expr in ir.term_exprs(block.terminator):  # readings in IF/WHILE conditions (IF MSTX=0)
            for node in ir.walk_expr(expr):
                if isinstance(node, ir.Status) and node.axis:
                    add(node.axis)
    return list(seen)


def reading(status: ir.Status, axis: str) -> ir.Expr | None:
    """An Arcus register (a `DeviceRef` for the writer) or a computation on one for a neutral
    reading on target axis `axis`; None when the PMX-4EX-SA has no such reading."""
    span = status.span
    if status.meaning in INDEXED and status.index is not None:
        return ir.DeviceRef(DIALECT, INDEXED[status.meaning], status.meaning, "", status.index, span)
    if status.meaning == "enabled" and axis in Axes.LETTERS:
        return ir.DeviceRef(DIALECT, "EO", "enabled", "", Axes.LETTERS.index(axis) + 1, span)
    if status.meaning in REGISTERS:
        name, per_axis = REGISTERS[status.meaning]
        if per_axis and axis == ir.ALL_AXES and name not in ("HSPD", "LSPD"):
            return None
        return ir.DeviceRef(DIALECT, name, status.meaning, axis if per_axis else "", None, span)
    if status.meaning in STATUS_BITS and axis in Axes.LETTERS:
        mask, shift = STATUS_BITS[status.meaning]
        word: ir.Expr = ir.DeviceRef(DIALECT, "MST", "motor_status", axis, None, span)
        if shift:
            word = ir.BinOp(">>", word, ir.Const(shift), span)
        return ir.BinOp("&", word, ir.Const(mask), span)
    return None


def ms_register(expr: ir.Expr, axis_of) -> ir.Expr | None:
    """`countdown * 1000` (how an Arcus TR read comes back) as the register TR itself."""
    if isinstance(expr, ir.BinOp) and expr.op == "*" and isinstance(expr.left, ir.Status) \
            and expr.left.meaning in MS_REGISTERS and isinstance(expr.right, ir.Const) \
            and expr.right.value == units.MS_PER_S:
        name = MS_REGISTERS[expr.left.meaning]
        axis = axis_of(expr.left.axis) if expr.left.axis else ""
        return ir.DeviceRef(DIALECT, name, expr.left.meaning, "" if axis == ir.ALL_AXES else axis, None, expr.span)
    return None
