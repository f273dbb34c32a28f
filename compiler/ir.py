"""The shared intermediate representation.

One IR for all three dialects: every check, optimisation and backend works on it, whatever the
source. The shapes follow docs/ARCHITECTURE.md:

- a `Module` holds the declared variables and the routines, in source order;
- a `Routine` is a named control-flow graph of `Block`s (main program, subroutine, event handler,
  power-up entry, or the immediate stream of commands sent outside any program);
- a `Block` holds dialect-neutral `Op`s and ends in exactly one terminator;
- expressions and conditions are small trees; numbers carry units;
- what has no neutral meaning is a `Native` operation that keeps dialect, mnemonic and arguments.

Every operation keeps the `Span` of the source text it came from.

Axes are logical names: "X" "Y" "Z" "U" for Arcus, the device address ("1".."32") for X150, the
party device name or "1" for MCode; "*" means every axis (a broadcast or a global setting).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum
from typing import Callable, Union

from mcc.compiler.span import Span

ALL_AXES = "*"


class Unit(str, Enum):
    """The closed set of quantities the IR knows (docs/ARCHITECTURE.md, "Units").

    A step is 1/`Module.steps_per_rev` of a motor revolution: the frontend converts the dialect's
    own units (X150 revolutions, Arcus milliseconds, ...) into these with `mcc.compiler.units`,
    and each backend converts back with its target profile.
    """

    NONE = ""  # a plain number: a count, a flag, a bit mask, an index
    STEPS = "steps"  # position or distance
    STEPS_PER_S = "steps/s"  # speed
    STEPS_PER_S2 = "steps/s^2"  # acceleration or deceleration
    S = "s"  # time: a delay, a timeout, a ramp time
    DEGREES = "deg"  # an angle (arc interpolation)
    PERCENT = "%"  # a share of a maximum (motor current)
    # Legacy spellings of the dialects' own units. The verifier rejects them: a frontend that
    # still produces one has not been converted yet (issue 8 migration).
    COUNTS = "counts"
    REVS = "revs"
    REVS_PER_S = "revs/s"
    REVS_PER_S2 = "revs/s^2"
    MS = "ms"
    MILLIDEGREES = "mdeg"


IR_UNITS = frozenset({Unit.NONE, Unit.STEPS, Unit.STEPS_PER_S, Unit.STEPS_PER_S2, Unit.S, Unit.DEGREES,
                      Unit.PERCENT})


class VarType(str, Enum):
    INT32 = "int32"
    FLOAT64 = "float64"
    DECIMAL = "decimal"


# ---------------------------------------------------------------------------------------------
# Expressions
#
# Expressions are values: never changed once made, so they are shared (by operations, by the mode
# states of a frontend, by a backend's copies of a program). They are not declared `frozen` for the
# same reason as `Span`: a frozen dataclass sets each field through `object.__setattr__`, which made
# making one about four times as slow, and a check makes one or more per command
# (docs/PERFORMANCE.md). `unsafe_hash` keeps them hashable, as they were.


@dataclass(slots=True, unsafe_hash=True)
class Const:
    value: int | float
    unit: Unit = Unit.NONE
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class Var:
    """A program variable: a user variable or a general-purpose register (R1, F1, V10, VAR3)."""

    name: str
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class DeviceRef:
    """A device register in the dialect's own spelling (MCode `P`, Arcus `MSTX`, X150 `POS`).

    Allowed only inside a `Native` operation (a register no other dialect has). Everywhere else a
    reading is a neutral `Status`; the verifier enforces it.
    """

    dialect: str
    name: str
    meaning: str = ""
    axis: str = ""
    index: int | None = None
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class Status:
    """A neutral device reading: `meaning` is one of `ir_names.STATUS` (position, velocity,
    moving, input, output, error, ...), `axis` the logical axis, `index` an input/output number or
    a bit. The dialect's spelling (MCode `P`, Arcus `MSTX`, X150 `IN`) lives only in frontends and
    backends."""

    meaning: str
    axis: str = ""
    index: int | None = None
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class LabelRef:
    """A reference to a code location by name or address (MCode `BR K1`, `TP=100,K2`, `EX 100`)."""

    name: str
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class Text:
    value: str
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class BinOp:
    op: str  # + - * / % & | ^ << >>
    left: "Expr"
    right: "Expr"
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class UnOp:
    op: str  # - (negate)  ! or ~ (bitwise not)
    operand: "Expr"
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class Func:
    name: str  # abs cos sin tan acos asin atan sqrt log log10 pi (neutral names)
    args: tuple["Expr", ...]
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class Pattern:
    """An input/output bit pattern over 0, 1 and X (don't care), most significant last."""

    bits: str
    span: Span | None = None


Expr = Union[Const, Var, Status, DeviceRef, LabelRef, Text, BinOp, UnOp, Func, Pattern]


@dataclass(slots=True, unsafe_hash=True)
class Compare:
    op: str  # = != < <= > >=
    left: Expr
    right: Expr
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class Logic:
    op: str  # and | or
    left: "Cond"
    right: "Cond"
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class Truth:
    """An expression used as a condition: true when non-zero (MCode `BR Q1, AF&2`)."""

    expr: Expr
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class InputMatch:
    """Inputs match a pattern (X150 `IN_XX1`)."""

    pattern: Pattern
    span: Span | None = None


@dataclass(slots=True, unsafe_hash=True)
class Not:
    cond: "Cond"
    span: Span | None = None


Cond = Union[Compare, Logic, Truth, InputMatch, Not]


# ---------------------------------------------------------------------------------------------
# Operations


class MotionParam(str, Enum):
    """A motion setting of one axis, and the unit its value carries (PARAM_UNITS)."""

    INITIAL_SPEED = "initial_speed"  # steps/s: the speed a move starts from and stops at
    MAX_SPEED = "max_speed"  # steps/s: the slew speed of a move
    ACCEL = "accel"  # steps/s^2
    DECEL = "decel"  # steps/s^2
    ACCEL_TIME = "accel_time"  # s: the time to ramp from initial to maximum speed (Arcus ACC)
    DECEL_TIME = "decel_time"  # s: the time to ramp down from maximum to initial speed
    PROFILE = "profile"  # 0 trapezoidal, 1 S-curve (a plain number)
    RESOLUTION = "resolution"  # motor steps per revolution (a plain number)


PARAM_UNITS = {
    MotionParam.INITIAL_SPEED: Unit.STEPS_PER_S, MotionParam.MAX_SPEED: Unit.STEPS_PER_S,
    MotionParam.ACCEL: Unit.STEPS_PER_S2, MotionParam.DECEL: Unit.STEPS_PER_S2,
    MotionParam.ACCEL_TIME: Unit.S, MotionParam.DECEL_TIME: Unit.S,
    MotionParam.PROFILE: Unit.NONE, MotionParam.RESOLUTION: Unit.NONE,
}


class MoveMode(str, Enum):
    ABSOLUTE = "absolute"
    RELATIVE = "relative"
    # Legacy: "whatever ABS/INC is in force". The verifier rejects it: frontends resolve the
    # dialect's modes by data flow (mcc.compiler.move_modes) and write ABSOLUTE or RELATIVE.
    MODAL = "modal"


@dataclass(slots=True)
class Assign:
    target: Var
    value: Expr
    span: Span | None = None


@dataclass(slots=True)
class SetMotion:
    param: MotionParam
    axis: str
    value: Expr
    span: Span | None = None


@dataclass(slots=True)
class Move:
    """A move to targets on one or more axes (several axes: linear interpolation)."""

    mode: MoveMode
    targets: tuple[tuple[str, Expr], ...]
    options: tuple[tuple[str, Expr], ...] = ()  # dialect options (MCode MA p2/p3)
    span: Span | None = None


@dataclass(slots=True)
class Arc:
    """Circular (angle None: full circle) or arc interpolation around a centre. `angle` (degrees)
    is the end point's direction from the centre, measured clockwise from the negative first
    axis, not a sweep (docs/IR.md, "Arcs")."""

    axes: tuple[str, str]
    center: tuple[Expr, Expr]
    clockwise: bool
    angle: Expr | None = None  # degrees: the end point's direction (docs/IR.md, "Arcs")
    span: Span | None = None


@dataclass(slots=True)
class Slew:
    """Run at a constant signed velocity (MCode SL) or in a direction at max speed (jog)."""

    axis: str
    velocity: Expr | None = None
    direction: int = 0  # +1 / -1 for a jog without an explicit velocity
    span: Span | None = None


@dataclass(slots=True)
class Home:
    """Seek the home switch (`method`: switch | index | switch+index | offset | limit) moving in
    `direction` (+1/-1) at `speed` (steps/s; None: the max speed in force) until the switch trips,
    then decelerate to a stop past it (ramping at `accel` when given, else at the acceleration and
    deceleration in force); then, when `creep` is +1/-1, creep in that direction at
    `creep_speed` (steps/s; None: the initial speed in force) and stop as the switch is left (its
    edge). `zero` says where the counter becomes 0: "switch" (at the trip, so the axis stops past
    0), "end" (where the homing stops) or "none" (the counter keeps counting). docs/SIMULATOR.md,
    "Homing", has each dialect's homing with the manuals' lines; the lowering fills these fields
    from the product profile's `[homing]` table (compiler/homing.py). With `needs_input` the
    homing fails unless an input has been set up as the home switch (`input_function` "home")."""

    axis: str
    method: str  # switch | index | switch+index | offset | limit
    direction: int = 0
    mode: Expr | None = None  # legacy: a dialect homing type; the contract uses direction/creep
    span: Span | None = None
    creep: int = 0  # 0: no creep off the switch
    speed: Expr | None = None  # X150 GH n homes at a speed of its own, not at V
    creep_speed: Expr | None = None  # X150 GHF; None: the initial speed in force (MCode VI)
    zero: str = "end"  # HOME_ZEROS
    accel: Expr | None = None  # steps/s², the seek's and brake's ramp (X150 GA's default); None: the move ramps
    needs_input: bool = False  # fails, without moving, unless an input is set up as the home switch (MCode Error 80)


HOME_ZEROS = ("switch", "end", "none")


@dataclass(slots=True)
class Stop:
    axis: str
    ramp: bool = True  # False: abort without deceleration
    span: Span | None = None


@dataclass(slots=True)
class SetPosition:
    axis: str
    value: Expr
    span: Span | None = None


@dataclass(slots=True)
class WaitMotion:
    axis: str
    span: Span | None = None


@dataclass(slots=True)
class Delay:
    duration: Expr  # carries its unit (ms or s)
    span: Span | None = None


@dataclass(slots=True)
class SetOutput:
    index: int | None  # None: every output, value is a bit mask or a Pattern
    value: Expr
    span: Span | None = None


@dataclass(slots=True)
class WaitInput:
    cond: Cond
    span: Span | None = None


@dataclass(slots=True)
class Print:
    """Send text and values to the host. `axis` names the device that sends them when the line is
    addressed to one (an MCode party address); empty for the device the program runs on. `signed`:
    every value is sent with its sign, `+` for zero and positive numbers too (the X150's position
    report `*+4000`, L3141); a backend that cannot write the sign refuses the print. `formats`: the
    format of each item, by position ("" or missing: as the value prints), from
    `ir_names.PRINT_FORMATS` (`fixed 3`, `fixed 0 magnitude`, `bits 10`, `pad 2`): data the
    simulator applies and a backend writes or refuses (docs/IR.md, "Print formats"). `traced`: the
    device's own report of the command it runs, sent only while its `trace` setting is on (X150
    XTR, parker-x150.md L5384-L5433; docs/IR.md, "Trace reports")."""

    items: tuple[Expr, ...]
    newline: bool = True
    span: Span | None = None
    axis: str = ""
    signed: bool = False
    formats: tuple[str, ...] = ()
    traced: bool = False


@dataclass(slots=True)
class DriveEnable:
    axis: str
    on: Expr
    span: Span | None = None


@dataclass(slots=True)
class Call:
    routine: str
    cond: Cond | None = None  # MCode `CL K1, I2=1` is a predicated call
    span: Span | None = None


@dataclass(slots=True)
class SetHandler:
    """Install an event handler: MCode trips and OE, X150 XWHEN/XFK.

    `event` is a neutral name (input, position, capture, time, relative, hmt, power, error, fault,
    when); `args` are the event's parameters.

    How the handler behaves is a fact of the operation, set by the frontend from its manual, so the
    simulator runs every dialect's handlers from the IR alone (docs/IR.md, "Handlers"):
    `once`: it fires once and is disarmed until installed again (MCode trips, L5657); `gated`: it
    fires only while its bit of the `handler_enable` setting is set (MCode TE); `takes_over`: a fault
    handler replaces the program instead of interrupting it (X150 XFK, "program control will pass
    to a fault sequence", L2305). Time and position handlers fire once whatever `once` says.
    """

    event: str
    routine: str | None
    args: tuple[Expr, ...] = ()
    span: Span | None = None
    once: bool = False
    gated: bool = False
    takes_over: bool = False


@dataclass(slots=True)
class Setting:
    """A device setting with a neutral name from `ir_names.SETTINGS` (run current, hold current,
    encoder enable, ...): each entry documents its meaning, its unit and the dialects that have it,
    so a backend either writes its own spelling or refuses the setting by name."""

    name: str
    axis: str
    value: Expr
    span: Span | None = None
    index: int | None = None  # an input or output number, for settings of one line


@dataclass(slots=True)
class Save:
    span: Span | None = None


@dataclass(slots=True)
class Pause:
    """Suspend the program here until the host resumes it (X150 `PS` until `C`, MCode `PS` until
    `RS`). With `stop_motion` a move in progress ramps down at the pause and restarts when the
    program resumes (MCode, L4931-L4959); without it the move runs on while the program waits
    (X150's PS pauses command execution only, L3146-L3159)."""

    axis: str
    stop_motion: bool = False
    span: Span | None = None


@dataclass(slots=True)
class Resume:
    """The host ends a pause (X150 `C`, L291-L300; MCode `RS`, L5193-L5222); no effect when the
    program is not paused."""

    axis: str
    span: Span | None = None


@dataclass(slots=True)
class Step:
    """The host lets the next `count` commands run while single-step mode (the `single_step`
    setting) holds the program (X150 `#n`, L5548-L5560; MCode steps a line per space typed in its
    single-step mode, which a listing cannot send). No effect when single-step mode is off."""

    axis: str
    count: Expr
    span: Span | None = None


@dataclass(slots=True)
class Native:
    """A construct with no neutral meaning, kept verbatim for its own backend."""

    dialect: str
    mnemonic: str
    args: tuple[Expr, ...] = ()
    form: str = ""  # how it was written, when the dialect cares: "=", " ", "" ...
    axis: str = ""
    span: Span | None = None


Op = Union[Assign, SetMotion, Move, Arc, Slew, Home, Stop, SetPosition, WaitMotion, Delay,
           SetOutput, WaitInput, Print, DriveEnable, Call, SetHandler, Setting, Save, Pause, Resume, Step,
           Native]


# ---------------------------------------------------------------------------------------------
# Terminators


@dataclass(slots=True)
class Jump:
    target: str  # block label (module-unique)
    span: Span | None = None


@dataclass(slots=True)
class Branch:
    cond: Cond
    then: str
    otherwise: str
    span: Span | None = None


@dataclass(slots=True)
class Return:
    span: Span | None = None


@dataclass(slots=True)
class End:
    """End of the program: execution stops (MCode E, Arcus END)."""

    span: Span | None = None


@dataclass(slots=True)
class GotoRoutine:
    """Transfer to another routine without return (X150 XG/GOTO)."""

    routine: str
    span: Span | None = None


@dataclass(slots=True)
class FallOff:
    """Control runs past the last statement of the region with no explicit end."""

    span: Span | None = None


Terminator = Union[Jump, Branch, Return, End, GotoRoutine, FallOff]


# ---------------------------------------------------------------------------------------------
# Structure


class RoutineKind(str, Enum):
    MAIN = "main"
    SUBROUTINE = "subroutine"
    HANDLER = "handler"
    POWERUP = "powerup"
    IMMEDIATE = "immediate"
    PROGRAM = "program"  # a program that runs at the same time as the main one (Arcus PRG n, n >= 1)


@dataclass(slots=True, eq=False)
class Block:
    label: str
    ops: list[Op] = field(default_factory=list)
    terminator: Terminator | None = None
    span: Span | None = None
    named: bool = False  # the label was written in the source (not generated)


@dataclass(slots=True, eq=False)
class Routine:
    name: str
    kind: RoutineKind
    blocks: list[Block] = field(default_factory=list)
    span: Span | None = None
    number: int | None = None  # Arcus SUB n, X150 sequence n
    origin: int | None = None  # MCode: PG address where this routine's program region starts

    @property
    def entry(self) -> Block | None:
        return self.blocks[0] if self.blocks else None

    def block(self, label: str) -> Block | None:
        for block in self.blocks:
            if block.label == label:
                return block
        return None


@dataclass(slots=True)
class Variable:
    name: str
    type: VarType = VarType.INT32
    init: Expr | None = None
    scope: str = "global"  # global | local
    span: Span | None = None


@dataclass(slots=True, eq=False)
class Module:
    dialect: str
    profile: str
    variables: dict[str, Variable] = field(default_factory=dict)
    routines: list[Routine] = field(default_factory=list)
    path: str = ""
    # The size of the IR's step: steps per motor revolution in the source's terms (its profile,
    # or the resolution the program sets). Backends scale positions by target/source.
    steps_per_rev: int = 0
    # Routines called but defined outside this file (an X150 sequence already stored on the
    # controller): calls to them are resolved, and backends write the call without a body.
    externals: list[str] = field(default_factory=list)
    # The type of each device register the program uses without declaring it (MCode F1..F8 hold
    # float64, R1..R4 int32): declared by the lowering, never written as a declaration by a backend.
    registers: dict[str, VarType] = field(default_factory=dict)
    # The type of a variable the program uses without declaring it: the dialect's (compiler/dialects.py,
    # `variable_type`: MCode and Arcus int32, X150 decimal) unless the module says otherwise.
    default_type: VarType | None = None

    def __post_init__(self) -> None:
        if self.default_type is None:
            from mcc.compiler import dialects

            known = dialects.DIALECTS.get(self.dialect)
            self.default_type = VarType(known.variable_type) if known is not None else VarType.FLOAT64

    def type_of(self, name: str) -> VarType | None:
        """The type of a variable or register, or None when the module does not say."""
        variable = self.variables.get(name)
        if variable is not None:
            return variable.type
        return self.registers.get(name)
    # Facts about the source's machine that its operations alone do not say (docs/IR.md, "Module
    # facts"); the lowering declares them, the simulator and the backends follow them.
    # Whether every move's mode is stated by the program itself, so that none relies on the
    # absolute/incremental mode the controller powered up in or a host left it in (Arcus ABS before
    # the first move, L1569): "start" (the program's first statement is the switch),
    # "paths" (a switch precedes each path's first move), "" (not stated). A backend whose
    # target keeps a modal ABS/INC then states the mode as the program did.
    modes_stated: str = ""
    # The motion parameters that form an axis's own set of settings, used by that axis only once all
    # of them have been written for it (Arcus HSPDa, LSPDa and ACCa, L447-L457); until then the
    # axis runs with the settings for every axis (`*`), which are a separate set that a `*` write
    # never copies into the axes. Empty (the default): an axis's own setting applies at once, and a
    # `*` setting is written into every axis (an unaddressed X150 command, L177).
    axis_sets: tuple[MotionParam, ...] = ()
    # The product's value of each setting or reading the program uses that the simulator does not
    # cause (a drive register's factory default, the device's identity), in the IR's units: what a
    # reading of it gives before the program sets it (docs/IR.md, "Module facts"). A setting not
    # listed reads 0.
    device_values: dict[str, object] = field(default_factory=dict)
    # How the values of a text-like reading print: reading -> {value: text} (MCode `PR MD` prints
    # the last move's kind as MA, MR or SL, lexium-mcode.txt L4145-L4153).
    print_texts: dict[str, dict[str, str]] = field(default_factory=dict)

    def routine(self, name: str) -> Routine | None:
        for routine in self.routines:
            if routine.name == name:
                return routine
        return None

    def blocks(self):
        """Every (routine, block) pair in module order."""
        for routine in self.routines:
            for block in routine.blocks:
                yield routine, block

    def block_index(self) -> dict[str, tuple[Routine, Block]]:
        """Each block label's (routine, block), built in one walk. The module is mutable (the
        optimizer rewrites it), so the index is a snapshot: build it where the module no longer
        changes (a backend's writer, the simulator) and look blocks up in it, never by scanning
        the module per lookup, which made a 500-deep nest quadratic (issue 26)."""
        return {block.label: (routine, block) for routine, block in self.blocks()}


def successors(term: Terminator | None) -> tuple[str, ...]:
    """Block labels a terminator can transfer to (within the module)."""
    if isinstance(term, Jump):
        return (term.target,)
    if isinstance(term, Branch):
        return (term.then, term.otherwise)
    return ()


def callers_of(seeds: set[str], calls: dict[str, set[str]]) -> set[str]:
    """`seeds` and every routine that calls one of them, directly or through other routines
    (`calls`: routine name -> the names it calls)."""
    result = set(seeds)
    changed = True
    while changed:
        changed = False
        for name, callees in calls.items():
            if name not in result and callees & result:
                result.add(name)
                changed = True
    return result


def settled_ops(module: Module) -> set[int]:
    """The operations (by id) before which no move can still be running: in a program's entry
    block until its first motion (nothing ran before it), and after a wait for the axes that moved.
    Conservative: a block other than the entry, a call or a native command may leave anything
    running. Backends use it where their dialects differ only for a move in progress (a pause
    that stops motion or lets it run on)."""
    found: set[int] = set()
    starts = (RoutineKind.MAIN, RoutineKind.IMMEDIATE, RoutineKind.POWERUP)
    for routine in module.routines:
        for index, block in enumerate(routine.blocks):
            moving: set[str] = set() if index == 0 and routine.kind in starts else {ALL_AXES}
            for op in block.ops:
                if not moving:
                    found.add(id(op))
                if isinstance(op, WaitMotion):
                    moving = set() if op.axis == ALL_AXES else moving - {op.axis}
                elif isinstance(op, Move):
                    moving |= {axis for axis, _ in op.targets}
                elif isinstance(op, (Slew, Home)):
                    moving.add(op.axis)
                elif isinstance(op, (Arc, Call, Native)):
                    moving.add(ALL_AXES)
    return found


def retarget(term: Terminator | None, old: str, new: str) -> None:
    """Point a terminator's transfers to block `old` at block `new` instead."""
    if isinstance(term, Jump) and term.target == old:
        term.target = new
    elif isinstance(term, Branch):
        if term.then == old:
            term.then = new
        if term.otherwise == old:
            term.otherwise = new


def walk_expr(expr):
    """Yield an expression or condition and all of its sub-expressions, depth first."""
    stack = [expr]
    pop, extend, children = stack.pop, stack.extend, _EXPR_CHILDREN.get
    while stack:
        node = pop()
        if node is None:
            continue
        yield node
        get = children(type(node))
        if get is None:
            get = _EXPR_CHILDREN[type(node)] = _first_rule(type(node), _EXPR_RULES)
        if get is not _NOTHING:
            extend(get(node))


def _nothing(_node) -> tuple:
    return ()


_NOTHING = _nothing


def _first_rule(cls: type, rules: tuple) -> Callable:
    """The function of the first rule whose types `cls` is (isinstance order), or _NOTHING."""
    return next((get for types, get in rules if issubclass(cls, types)), _NOTHING)


# The sub-expressions of a node, pushed so that they come out left first. Dispatched on the node's
# type through a dictionary filled from these rules (walking expressions is most of what the lint
# rules' data flow does: a chain of isinstance tests per node cost a tenth of an editor's analysis).
_EXPR_RULES: tuple = (
    ((BinOp, Compare, Logic), lambda n: (n.right, n.left)),
    (UnOp, lambda n: (n.operand,)),
    (Func, lambda n: reversed(n.args)),
    (Truth, lambda n: (n.expr,)),
    (InputMatch, lambda n: (n.pattern,)),
    (Not, lambda n: (n.cond,)),
)
_EXPR_CHILDREN: dict[type, Callable] = {}


def op_exprs(op: Op) -> tuple:
    """The expressions and conditions an operation reads."""
    get = _OP_EXPRS.get(type(op))
    if get is None:
        get = _OP_EXPRS[type(op)] = _first_rule(type(op), _OP_RULES)
    return get(op)


_OP_RULES: tuple = (
    (Assign, lambda op: (op.value,)),
    ((SetMotion, SetPosition, Setting), lambda op: (op.value,)),
    (Move, lambda op: tuple(e for _, e in op.targets) + tuple(e for _, e in op.options)),
    (Arc, lambda op: op.center + ((op.angle,) if op.angle is not None else ())),
    (Slew, lambda op: (op.velocity,) if op.velocity is not None else ()),
    (Home, lambda op: tuple(e for e in (op.mode, op.speed, op.creep_speed, op.accel) if e is not None)),
    (Delay, lambda op: (op.duration,)),
    (SetOutput, lambda op: (op.value,)),
    (WaitInput, lambda op: (op.cond,)),
    (Print, lambda op: op.items),
    (DriveEnable, lambda op: (op.on,)),
    (Step, lambda op: (op.count,)),
    (Call, lambda op: (op.cond,) if op.cond is not None else ()),
    ((SetHandler, Native), lambda op: op.args),
)
_OP_EXPRS: dict[type, Callable] = {}


def term_exprs(term: Terminator | None) -> tuple:
    if isinstance(term, Branch):
        return (term.cond,)
    return ()


def copy_module(module: Module) -> Module:
    """A copy of `module` that passes may change freely: new routines, blocks, operation and
    terminator objects; expressions are immutable and shared (so a deep expression costs nothing
    and needs no recursion)."""
    import copy
    import dataclasses

    routines = []
    for routine in module.routines:
        blocks = [dataclasses.replace(b, ops=[copy.copy(op) for op in b.ops], terminator=copy.copy(b.terminator))
                  for b in routine.blocks]
        routines.append(dataclasses.replace(routine, blocks=blocks))
    variables = {name: copy.copy(v) for name, v in module.variables.items()}
    return dataclasses.replace(module, variables=variables, routines=routines, externals=list(module.externals),
                               registers=dict(module.registers), device_values=dict(module.device_values),
                               print_texts={k: dict(v) for k, v in module.print_texts.items()})
