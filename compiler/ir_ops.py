"""The IR's operations, defined once: one record per operation and terminator, as data.

`compiler/ir.py` keeps the dataclasses (what an operation holds); this table says, for each of
them, what its fields are (their kind and, where a constant must carry one, their unit), what the
operation does that an analysis or a handler must know (its traits) and how it reads in the text
form of `mcc ir` (its syntax, a template in the spirit of MLIR's `assemblyFormat`). The printer
(`ir_print.op_text`, `term_text`), the reader (`ir_read`), the verifier's field checks
(`ir_verify`) and the tests' generator of every operation are derived from it, so an operation is
added here once and the handlers that must know it (backends, the simulator, the optimizer) are
found by the handler-coverage test (tests/ir/test_handlers.py). Decision record 0018.

Syntax templates (docs/IR.md, "The operation table"):

- text is written as it is, spaces included;
- `$field` writes the field, in the form its kind gives (`ir_print.FORMS`; `ir_read` reads it);
- `{...}` is an optional group, written when its anchor field (the one marked `^`, or the only
  field in it) is set: not None, not "" and not its dataclass default; `{...|...}` writes the
  part after `|` when it is not. A flag (a bool whose group's words say it) writes no text of
  its own.

The reader parses a line by the same template: text must match, a group is read when its text is
there, a flag in a read group takes the value that is not its default.
"""

from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass
from enum import Enum

from mcc.compiler import ir
from mcc.compiler import ir_names


class Kind(str, Enum):
    """What a field holds, which says how it is printed, read, generated and checked."""

    EXPR = "expression"  # an ir.Expr (printed infix, fully parenthesised below the top)
    COND = "condition"  # an ir.Cond, or an expression used as one
    ARGS = "arguments"  # a tuple of expressions or conditions, ", "-separated
    ITEMS = "print items"  # a tuple of expressions, each followed by " as <format>" from `formats`
    FORMATS = "print formats"  # the formats of ITEMS, by position (written by ITEMS)
    EXPR_PAIR = "expression pair"  # two expressions, ", "-separated (an arc's centre)
    AXIS = "axis"  # a logical axis name, "*" for every axis
    AXIS_PAIR = "axis pair"  # two axes, "X,Y"
    AXIS_EXPRS = "list of (axis, expression)"  # "X=e1 Y=e2"
    VAR = "variable"  # the ir.Var an assignment writes (its name)
    ENUM = "enum"  # a value of `Field.enum`, printed as its value
    NAME = "name"  # one word: a neutral name (setting, event), a method, a dialect, a mnemonic
    ROUTINE = "routine"  # the name of a routine of the module (or of Module.externals)
    LABEL = "label"  # the label of a block of the same routine
    SIGN = "sign"  # an int printed "+" when >= 0, "-" otherwise (a jog's direction)
    SIGNED = "signed int"  # an int printed with its sign: +1, -1, +0
    INT = "int"  # an int
    BOOL = "bool"  # printed as `Field.words[0]` when true, `words[1]` when false
    FLAG = "flag"  # a bool written only by its optional group's words
    QUOTED = "quoted text"  # a string printed as a JSON string


# The kinds whose value is a string ("" counts as not set for an optional group).
TEXTS = frozenset({Kind.AXIS, Kind.NAME, Kind.ROUTINE, Kind.LABEL, Kind.QUOTED})


class Trait(str, Enum):
    """What an operation does that an analysis or a handler must know about."""

    MOVES_AXIS = "moves an axis"  # starts, changes or stops the motion of an axis
    TAKES_TIME = "takes time"  # the program waits here: virtual time passes before the next operation
    READS_INPUTS = "reads inputs"  # reads the device's inputs itself (beyond its expressions)
    WRITES_OUTPUTS = "writes outputs"
    ENDS_BLOCK = "ends a block"  # a terminator
    CLOBBERS_SETTINGS = "clobbers settings"  # changes a setting, a motion parameter or the position counter
    PRINTS = "prints"  # sends text to the host
    CALLS = "calls"  # runs another routine, now or on an event


@dataclass(frozen=True)
class Field:
    """One field of an operation. `units`: the units a constant in it must carry (empty: any unit
    of the closed set); `unit_by`: the units come from another field's value instead ("param":
    `ir.PARAM_UNITS`, "setting": `ir_names.SETTINGS`); `what`: how the verifier names the field
    ("{axis}" is the axis of an AXIS_EXPRS entry); `choices`: the values the contract allows,
    `invalid` the verifier's message for another one ("{value}"); `words`: a BOOL's spelling when true
    and when false."""

    name: str
    kind: Kind
    units: frozenset = frozenset()
    unit_by: str = ""
    what: str = ""
    enum: type | None = None
    choices: object = None
    invalid: str = ""
    words: tuple[str, str] = ("", "")
    optional: bool = False  # None is a value (written by leaving its optional group out)


@dataclass(frozen=True)
class OpDef:
    """One operation or terminator: its class, fields (every dataclass field but `span`, in
    declaration order), traits and syntax template."""

    cls: type
    summary: str
    syntax: str
    fields: tuple[Field, ...]
    traits: frozenset[Trait]
    terminator: bool = False

    @property
    def name(self) -> str:
        return self.cls.__name__

    def field(self, name: str) -> Field:
        return next(f for f in self.fields if f.name == name)

    def default(self, name: str):
        """The dataclass default of field `name`, or MISSING."""
        for f in dataclasses.fields(self.cls):
            if f.name == name:
                if f.default is not dataclasses.MISSING:
                    return f.default
                if f.default_factory is not dataclasses.MISSING:  # type: ignore[misc]
                    return f.default_factory()  # type: ignore[misc]
        return dataclasses.MISSING


T = Trait
K = Kind
POSITION = frozenset({ir.Unit.STEPS})
SPEED = frozenset({ir.Unit.STEPS_PER_S})
ACCELERATION = frozenset({ir.Unit.STEPS_PER_S2})
TIME = frozenset({ir.Unit.S})
ANGLE = frozenset({ir.Unit.DEGREES})
PLAIN = frozenset({ir.Unit.NONE})
# A native command may do anything its dialect's command does.
ANYTHING = frozenset(set(Trait) - {Trait.ENDS_BLOCK})


def _f(name: str, kind: Kind, **facts) -> Field:
    return Field(name, kind, **facts)


OPERATIONS: tuple[OpDef, ...] = (
    OpDef(ir.Assign, "a variable takes the value of an expression", "$target = $value",
          (_f("target", K.VAR), _f("value", K.EXPR)), frozenset()),
    OpDef(ir.SetMotion, "set a motion parameter of an axis (or of every axis, *)", "set $param $axis = $value",
          (_f("param", K.ENUM, enum=ir.MotionParam), _f("axis", K.AXIS),
           _f("value", K.EXPR, unit_by="param")), frozenset({T.CLOBBERS_SETTINGS})),
    OpDef(ir.Move, "move to targets on one or more axes (several: linear interpolation)",
          "move $mode $targets{ with $options}",
          (_f("mode", K.ENUM, enum=ir.MoveMode, choices=(ir.MoveMode.ABSOLUTE, ir.MoveMode.RELATIVE),
              invalid="move mode '{value}': moves are absolute or relative"),
           _f("targets", K.AXIS_EXPRS, units=POSITION, what="move target on axis {axis}"),
           _f("options", K.AXIS_EXPRS)), frozenset({T.MOVES_AXIS})),
    OpDef(ir.Arc, "circular or arc interpolation about a centre (docs/IR.md, \"Arcs\")",
          "arc $clockwise $axes centre ($center){ angle $angle| full circle}",
          (_f("axes", K.AXIS_PAIR), _f("center", K.EXPR_PAIR, units=POSITION, what="arc centre"),
           _f("clockwise", K.BOOL, words=("cw", "ccw")),
           _f("angle", K.EXPR, optional=True, units=ANGLE, what="arc angle")),
          frozenset({T.MOVES_AXIS})),
    OpDef(ir.Slew, "run at a constant signed velocity, or jog in a direction at the maximum speed",
          "{slew $axis velocity $velocity^|jog $axis $direction}",
          (_f("axis", K.AXIS), _f("velocity", K.EXPR, optional=True, units=SPEED, what="slew velocity"),
           _f("direction", K.SIGN)), frozenset({T.MOVES_AXIS})),
    OpDef(ir.Home, "seek the home switch (docs/IR.md, \"Neutral names\"; docs/SIMULATOR.md, \"Homing\")",
          "home $axis $method direction $direction{ speed $speed}{ accel $accel}"
          "{ creep $creep^{ at $creep_speed}} zero $zero{$needs_input^ needs home input}{ mode $mode}",
          (_f("axis", K.AXIS), _f("method", K.NAME), _f("direction", K.SIGNED), _f("mode", K.EXPR, optional=True),
           _f("creep", K.SIGNED, choices=(-1, 0, 1), invalid="homing creep direction {value} is not +1, -1 or 0"),
           _f("speed", K.EXPR, optional=True, units=SPEED, what="homing speed"),
           _f("creep_speed", K.EXPR, optional=True, units=SPEED, what="homing creep speed"),
           _f("zero", K.NAME, choices=ir.HOME_ZEROS,
              invalid="homing zero '{value}' is not one of " + ", ".join(ir.HOME_ZEROS)),
           _f("accel", K.EXPR, optional=True, units=ACCELERATION, what="homing acceleration"),
           _f("needs_input", K.FLAG)),
          frozenset({T.MOVES_AXIS, T.READS_INPUTS})),
    OpDef(ir.Stop, "stop an axis, ramping down or at once", "stop $axis $ramp",
          (_f("axis", K.AXIS), _f("ramp", K.BOOL, words=("ramp", "abort"))), frozenset({T.MOVES_AXIS})),
    OpDef(ir.SetPosition, "set an axis's position counter", "set position $axis = $value",
          (_f("axis", K.AXIS), _f("value", K.EXPR, units=POSITION, what="position")),
          frozenset({T.CLOBBERS_SETTINGS})),
    OpDef(ir.WaitMotion, "wait until an axis (every axis, *) stands still", "wait motion $axis",
          (_f("axis", K.AXIS),), frozenset({T.TAKES_TIME})),
    OpDef(ir.Delay, "wait for a time", "delay $duration",
          (_f("duration", K.EXPR, units=TIME, what="delay"),), frozenset({T.TAKES_TIME})),
    OpDef(ir.SetOutput, "set one output, or every output to a bit mask or pattern",
          "{output $index^|outputs} = $value",
          (_f("index", K.INT, optional=True), _f("value", K.EXPR)), frozenset({T.WRITES_OUTPUTS})),
    OpDef(ir.WaitInput, "wait until a condition on the inputs holds", "wait until $cond",
          (_f("cond", K.COND),), frozenset({T.TAKES_TIME, T.READS_INPUTS})),
    OpDef(ir.Print, "send text and values to the host (docs/IR.md, \"Print formats\")",
          "print{ on $axis} $items{$newline^ no-newline}{$signed^ signed}{$traced^ if tracing}",
          (_f("items", K.ITEMS), _f("newline", K.FLAG), _f("axis", K.AXIS), _f("signed", K.FLAG),
           _f("formats", K.FORMATS), _f("traced", K.FLAG)), frozenset({T.PRINTS})),
    OpDef(ir.DriveEnable, "enable or disable an axis's drive", "enable $axis = $on",
          (_f("axis", K.AXIS), _f("on", K.EXPR)), frozenset({T.CLOBBERS_SETTINGS})),
    OpDef(ir.Call, "call a routine, when a condition holds if it has one", "call $routine{ if $cond}",
          (_f("routine", K.ROUTINE), _f("cond", K.COND, optional=True)), frozenset({T.CALLS})),
    OpDef(ir.SetHandler, "install (or, without a routine, remove) an event handler (docs/IR.md, \"Handlers\")",
          "on $event($args){ -> $routine^| off}{$once^ once}{$gated^ gated}{$takes_over^ takes-over}",
          (_f("event", K.NAME, choices=ir_names.EVENTS, invalid="event '{value}' is not a neutral event name"),
           _f("routine", K.ROUTINE, optional=True), _f("args", K.ARGS), _f("once", K.FLAG), _f("gated", K.FLAG),
           _f("takes_over", K.FLAG)), frozenset({T.CALLS})),
    OpDef(ir.Setting, "set a device setting named in ir_names.SETTINGS (of one input or output: index)",
          "setting $name{[$index]} $axis = $value",
          (_f("name", K.NAME, choices=ir_names.SETTINGS, invalid="setting '{value}' is not in ir_names.SETTINGS"),
           _f("axis", K.AXIS), _f("value", K.EXPR, unit_by="setting"), _f("index", K.INT, optional=True)),
          frozenset({T.CLOBBERS_SETTINGS})),
    OpDef(ir.Save, "store the settings and program in non-volatile memory", "save", (), frozenset()),
    OpDef(ir.Pause, "wait here until the host resumes (docs/IR.md, \"Host control\")",
          "pause $axis{$stop_motion^ stop motion}",
          (_f("axis", K.AXIS), _f("stop_motion", K.FLAG)),
          # the host may send any command while the program waits
          frozenset({T.TAKES_TIME, T.CLOBBERS_SETTINGS, T.MOVES_AXIS})),
    OpDef(ir.Resume, "the host ends a pause", "resume $axis", (_f("axis", K.AXIS),), frozenset()),
    OpDef(ir.Step, "in single-step mode, the host lets the next commands run", "step $axis $count",
          (_f("axis", K.AXIS), _f("count", K.EXPR, units=PLAIN, what="step count")), frozenset()),
    OpDef(ir.Native, "a command with no neutral meaning, kept for its own backend (decision 0004)",
          "native $dialect $mnemonic{ axis=$axis}{ form=$form} ($args)",
          (_f("dialect", K.NAME), _f("mnemonic", K.NAME), _f("args", K.ARGS), _f("form", K.QUOTED),
           _f("axis", K.AXIS)), ANYTHING),
)

TERMINATORS: tuple[OpDef, ...] = (
    OpDef(ir.Jump, "go to a block", "jump $target", (_f("target", K.LABEL),),
          frozenset({T.ENDS_BLOCK}), terminator=True),
    OpDef(ir.Branch, "go to one of two blocks by a condition", "branch $cond ? $then : $otherwise",
          (_f("cond", K.COND), _f("then", K.LABEL), _f("otherwise", K.LABEL)),
          frozenset({T.ENDS_BLOCK}), terminator=True),
    OpDef(ir.Return, "return from a routine", "return", (), frozenset({T.ENDS_BLOCK}), terminator=True),
    OpDef(ir.End, "end the program", "end", (), frozenset({T.ENDS_BLOCK}), terminator=True),
    OpDef(ir.GotoRoutine, "transfer to another routine without return", "goto routine $routine",
          (_f("routine", K.ROUTINE),), frozenset({T.ENDS_BLOCK, T.CALLS}), terminator=True),
    OpDef(ir.FallOff, "control runs past the last statement with no explicit end", "fall off", (),
          frozenset({T.ENDS_BLOCK}), terminator=True),
)

TABLE: dict[type, OpDef] = {d.cls: d for d in OPERATIONS + TERMINATORS}
BY_NAME: dict[str, OpDef] = {d.name: d for d in TABLE.values()}


def definition(node) -> OpDef | None:
    """The table's record of an operation or terminator object (None for anything else)."""
    return TABLE.get(type(node))


def with_trait(trait: Trait) -> tuple[type, ...]:
    """The operation and terminator classes that have `trait`."""
    return tuple(d.cls for d in TABLE.values() if trait in d.traits)


def units_of(node, f: Field) -> tuple[frozenset, str] | None:
    """The units a constant in field `f` of `node` must carry and how the verifier names the field,
    or None when the field's units are not checked (or are unknown: an unknown setting's name is
    its own violation)."""
    if f.unit_by == "param":
        return frozenset({ir.PARAM_UNITS[node.param]}), node.param.value
    if f.unit_by == "setting":
        info = ir_names.SETTINGS.get(node.name)
        return (frozenset({info.unit}), node.name) if info is not None else None
    if f.units:
        return f.units, f.what
    return None


# ---------------------------------------------------------------------------------------------
# Templates, parsed once into pieces that the printer and the reader walk


@dataclass(frozen=True)
class Text:
    text: str


@dataclass(frozen=True)
class Ref:
    field: str


@dataclass(frozen=True)
class Group:
    anchor: str
    then: tuple
    otherwise: tuple


_TOKEN = re.compile(r"\$([a-z_]+)(\^?)|([{}|])|([^${}|]+)")


def pieces(syntax: str) -> tuple:
    """A template as a tuple of Text, Ref and Group pieces (see the module's docstring)."""
    stack: list[list] = [[]]
    anchors: list[list[str]] = [[]]  # per open group: [marked anchor, fields seen]
    for match in _TOKEN.finditer(syntax):
        name, mark, brace, text = match.groups()
        if text is not None:
            stack[-1].append(Text(text))
        elif name is not None:
            stack[-1].append(Ref(name))
            if mark:
                anchors[-1].insert(0, "^" + name)
            anchors[-1].append(name)
        elif brace == "{":
            stack.append([])
            anchors.append([])
        elif brace == "|":
            stack[-1].append("|")
        else:
            body = stack.pop()
            seen = anchors.pop()
            marked = [a[1:] for a in seen if a.startswith("^")]
            names = [a for a in seen if not a.startswith("^")]
            anchor = marked[0] if marked else names[0]
            split = body.index("|") if "|" in body else len(body)
            stack[-1].append(Group(anchor, tuple(body[:split]), tuple(body[split + 1:])))
            anchors[-1].extend(names)
    return tuple(stack[0])


def referenced(parts: tuple) -> list[str]:
    """Every field a template writes, in order."""
    found: list[str] = []
    for part in parts:
        if isinstance(part, Ref):
            found.append(part.field)
        elif isinstance(part, Group):
            found += referenced(part.then) + referenced(part.otherwise)
    return found


PIECES: dict[type, tuple] = {d.cls: pieces(d.syntax) for d in TABLE.values()}


def markdown() -> str:
    """The table as docs/IR.md prints it (tests/ir/test_ir_ops.py keeps the page equal to it)."""

    def field_text(f: Field) -> str:
        units = " ".join(sorted(repr(u.value or "plain") for u in f.units)).replace("'", "")
        unit = f" [{units}]" if units else " [by param]" if f.unit_by == "param" else \
            " [by setting]" if f.unit_by == "setting" else ""
        return f"`{f.name}` {f.kind.value}{'?' if f.optional else ''}{unit}"

    rows = ["| operation | syntax | fields (kind, `?` optional, [unit]) | traits |", "|---|---|---|---|"]
    for d in OPERATIONS + TERMINATORS:
        syntax = d.syntax.replace("|", "\\|")
        traits = ", ".join(t.value for t in Trait if t in d.traits)
        rows.append(f"| `{d.name}` | `{syntax}` | {'; '.join(field_text(f) for f in d.fields)} | {traits} |")
    return "\n".join(rows) + "\n"
