"""X150 spellings of neutral IR names, shared by the frontend and the X150 backend (pure data and
IR, no syntax tree).

Input patterns.

An X150 input pattern is `ddddddd_uuuuuuuuuu` (L3774-L3791): seven dedicated inputs, `_`, then the
ten user inputs IN1-IN10, each `0`, `1` or `X` (don't care), trailing X omissible per group; a
pattern without `_` is the dedicated group only (L3796). The IR's `Pattern` means "input n is the
n-th character" (docs/IR.md), so only the user group becomes a `Pattern`; each dedicated input with
a fixed level becomes a comparison of its neutral reading (`limit_plus`, `home_switch`, ...), the
terms joined by `and`. The backend merges such a conjunction back into one X150 pattern.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.span import Span

# The dedicated group, left to right (L3778): LMT+ LMT- HOME AUX_IN STOP ENERGISE INDEX.
DEDICATED = ("limit_plus", "limit_minus", "home_switch", "aux_input", "stop_input", "enable_input",
             "index_input")
USER_INPUTS = 10


def split(bits: str) -> tuple[str, str]:
    """(dedicated group, user group) of an X150 pattern, trailing X removed from each."""
    dedicated, _, user = bits.upper().partition("_") if "_" in bits else (bits.upper(), "", "")
    return dedicated.rstrip("X"), user.rstrip("X")


def to_cond(bits: str, axis: str, span=None) -> ir.Cond:
    """The neutral condition an X150 input pattern tests (always true when every input is X)."""
    dedicated, user = split(bits)
    terms: list[ir.Cond] = []
    for index, bit in enumerate(dedicated):
        if bit in "01" and index < len(DEDICATED):
            terms.append(ir.Compare("=", ir.Status(DEDICATED[index], axis, None, span), ir.Const(int(bit)), span))
    if user:
        terms.append(ir.InputMatch(ir.Pattern(user, span), span))
    if not terms:
        return ir.InputMatch(ir.Pattern("", span), span)  # every input "don't care": always true
    cond = terms[0]
    for term in terms[1:]:
        cond = ir.Logic("and", cond, term, span)
    return cond


def from_cond(cond) -> str | None:
    """The X150 pattern (`ddd_uuu`) that tests the same as `cond`, or None when it is not a
    conjunction of input levels an X150 pattern can express (one level per input)."""
    levels: dict[tuple[str, int], str] = {}
    if not _collect(cond, levels):
        return None
    dedicated = ["X"] * len(DEDICATED)
    user = ["X"] * USER_INPUTS
    for (kind, index), bit in levels.items():
        if kind == "user":
            user[index - 1] = bit
        else:
            dedicated[index] = bit
    # always with the `_`: a pattern without one tests the dedicated inputs only, which X131 asks
    # to make explicit
    return "".join(dedicated).rstrip("X") + "_" + "".join(user).rstrip("X")


def _collect(cond, levels: dict) -> bool:
    if isinstance(cond, ir.Logic) and cond.op == "and":
        return _collect(cond.left, levels) and _collect(cond.right, levels)
    found: list[tuple[tuple[str, int], str]] = []
    if isinstance(cond, ir.InputMatch):
        if len(cond.pattern.bits) > USER_INPUTS or any(b not in "01X" for b in cond.pattern.bits.upper()):
            return False
        found = [(("user", n), b) for n, b in enumerate(cond.pattern.bits.upper(), 1) if b in "01"]
    else:
        one = level(cond)
        if one is None:
            return False
        found = [one]
    for key, bit in found:
        if levels.get(key, bit) != bit:
            return False  # the same input at two levels: never true, not a pattern
        levels[key] = bit
    return True


def level(cond) -> tuple[tuple[str, int], str] | None:
    """`reading = 0/1` (or `!= 0/1`) of a user input or a dedicated input."""
    if not (isinstance(cond, ir.Compare) and cond.op in ("=", "!=") and isinstance(cond.left, ir.Status)
            and isinstance(cond.right, ir.Const) and cond.right.value in (0, 1)):
        return None
    on = (cond.right.value == 1) == (cond.op == "=")
    bit = "1" if on else "0"
    status = cond.left
    if status.meaning == "input" and status.index is not None and 1 <= status.index <= USER_INPUTS:
        return ("user", status.index), bit
    if status.meaning in DEDICATED and status.index is None:
        return ("dedicated", DEDICATED.index(status.meaning)), bit
    return None


# Settings: X150 command -> the neutral setting it writes (ir_names.SETTINGS); each takes a plain
# number, written back as the command with that number. A setting whose neutral unit is a speed or an
# acceleration (IV, GHF in rev/s; GA in rev/s^2) is converted with the resolution.
SETTINGS = {
    "LD": "limits_disabled",  # L2388: 0 both limits enabled, 1 + disabled, 2 - disabled, 3 both
    "FSC": "position_maintenance",  # L1603
    "FSD": "stop_on_stall",  # L1630
    "CER": "encoder_resolution",  # L419
    "CMR": "motor_resolution",  # L596
    "DW": "position_deadband",  # L1347
    "FSB": "encoder_step_mode",  # L1595
    "SSH": "keep_buffer_on_stop",  # L3960
    "IV": "speed_change",  # L2192: the speed of the move in progress (immediate only)
    "GA": "home_accel",  # L1695: rev/s^2, 0 = no acceleration period
    "GHF": "home_final_speed",  # L1726: rev/s
    "SIM": "following_mode",  # L3727-L3741
    "FOL": "following_ratio",  # L1461: percent
    "CCS": "command_source",  # L378-L383
    "XST": "single_step",  # L5330
    "XTR": "trace",  # L5384
    "DCNT": "panel_pause_keys",  # L860
    "DSTP": "panel_stop_key",  # L1237
    "LA": "limit_decel",  # L2371: rev/s^2
    "CPE": "position_error_limit",  # L669: motor steps
    "CEW": "in_position_window",  # L440: motor steps
    "CIT": "in_position_time",  # L500: ms
    "CPG": "servo_proportional_gain",  # L693
    "CIG": "servo_integral_gain",  # L489
    "CVG": "servo_velocity_gain",  # L770
    "CFG": "servo_feedforward_gain",  # L459
    "CTG": "servo_filter_time",  # L705: ms
    "CAG": "following_filter_time",  # L320-L330: ms, the SIM3/4 input filter
}
# Settings written in ms on the X150 and in seconds in the IR: IR units per X150 unit.
SCALES = {"CIT": 0.001, "CTG": 0.001, "CAG": 0.001}
SETTING_COMMANDS = {name: mnemonic for mnemonic, name in SETTINGS.items()}

# Input and output functions (IN<n><letter>, OUT<n><letter>, L2058-L2114, L2974-L3013): the letters
# with a neutral meaning (ir_names.INPUT_FUNCTIONS / OUTPUT_FUNCTIONS); the others stay Native.
INPUT_FUNCTIONS = {"A": "general", "B": "sequence_strobe", "C": "kill", "E": "drive_enable", "F": "pause",
                   "G": "go", "H": "direction_toggle", "J": "jog_plus", "K": "jog_minus", "M": "end_loop",
                   "N": "data", "O": "sequence_select", "P": "memory_lock", "Q": "continue", "R": "reset",
                   "T": "position_zero", "W": "data_sign"}
OUTPUT_FUNCTIONS = {"A": "general", "B": "moving", "C": "program_running", "F": "no_fault", "G": "busy",
                    "H": "energised", "J": "data_strobe", "T": "in_position", "Z": "registration_pulse"}
INPUT_LETTERS = {name: letter for letter, name in INPUT_FUNCTIONS.items()}
OUTPUT_LETTERS = {name: letter for letter, name in OUTPUT_FUNCTIONS.items()}
OUTPUTS = 6


# The position report, defined once. `aPR` answers "a number preceded by a sign and followed by a
# carriage return *(s)n[CR]" (L3141), e.g. `*-25600` (L3143). mcc's decisions (docs/dialects/x150.md,
# "Decisions"): the sign is always sent, `+` for zero and positive positions (`*+4000`, `*+0`): the
# manual says "preceded by a sign", and "the sign indicates which side of the absolute zero position
# the motor is on"; no spaces (the `* - 140000` of the IV example, L2216, is the typesetting of the
# same report, whose own definition and example have none). The lowering makes `aPR` this print,
# the X150 writer writes it back as `PR` (and refuses a position printed any other way), and the
# virtual device answers `PR` by running it on the simulator: the text is the IR's alone.
REPORT_PREFIX = "*"  # every X150 report starts with it (L3141; `*R` L235, `*122` L289, `*0000000_...` L2134)


def position_report(axis: str, span: Span | None, sender: str = "") -> ir.Print:
    """`aPR`: the prefix, then the position counter with its sign, then a line end."""
    return ir.Print((ir.Text(REPORT_PREFIX, span), ir.Status("position", axis, None, span)), True, span, sender,
                    signed=True)


def report_axis(op: ir.Print) -> str | None:
    """The axis whose position `op` reports in the PR format, or None when it is another print."""
    items = op.items
    if op.signed and op.newline and len(items) == 2 and isinstance(items[0], ir.Text) \
            and items[0].value == REPORT_PREFIX and isinstance(items[1], ir.Status) \
            and items[1].meaning == "position" and items[1].index is None:
        return items[1].axis
    return None


# The reports of the active levels (INL L2131-L2141, OUTL L3034-L3051), defined once: the lowering
# makes `aINL` / `aOUTL` these prints, the X150 writer writes them back, the simulator and the
# virtual device print them (the text is the IR's alone). Decision (docs/dialects/x150.md,
# "Decisions"): the reply is always the header lines and the levels; the manual's first samples
# (L2133, L3040) show the levels alone in the description column, its re-samples the whole reply
# (L2138-L2141, L3047-L3051), as every report of levels does (TRS, L4353-L4356).
INPUT_LEVELS_HEADER = ("Input active levels are:\n"
                       "LMT+ LMT- HOME AUX-IN STOP ENG INDEX_I1 I2 I3 I4 I5 I6 I7 I8 I9 I10\n")   # L2138-L2140
OUTPUT_LEVELS_HEADER = ";Output active levels are:\n;01 02 03 04 05 06\n"   # L3049-L3050


def levels_report(kind: str, axis: str, span: Span | None, sender: str = "") -> ir.Print:
    """`aINL` (kind "INL": `*` the seven dedicated inputs' levels `_` the ten user inputs') or
    `aOUTL` (kind "OUTL": `*` the six outputs'), after the header lines."""
    if kind == "INL":
        return ir.Print((ir.Text(INPUT_LEVELS_HEADER + REPORT_PREFIX, span), ir.Status("switch_levels", axis, None, span),
                         ir.Text("_", span), ir.Status("input_levels", axis, None, span)), True, span, sender,
                        formats=("", f"bits {len(DEDICATED)}", "", f"bits {USER_INPUTS}"))
    return ir.Print((ir.Text(OUTPUT_LEVELS_HEADER + REPORT_PREFIX, span), ir.Status("output_levels", axis, None, span)),
                    True, span, sender, formats=("", f"bits {OUTPUTS}"))


def levels_report_of(op: ir.Print) -> tuple[str, str] | None:
    """(kind, axis) when `op` is a report `levels_report` makes, else None."""
    for kind in ("INL", "OUTL"):
        shape = levels_report(kind, "", None)
        if op.newline and not op.signed and op.formats == shape.formats and len(op.items) == len(shape.items) \
                and all(_same_item(a, b) for a, b in zip(op.items, shape.items)):
            axes = {item.axis for item in op.items if isinstance(item, ir.Status)}
            if len(axes) == 1:
                return kind, axes.pop()
    return None


def _same_item(item, shape) -> bool:
    if isinstance(shape, ir.Text):
        return isinstance(item, ir.Text) and item.value == shape.value
    return isinstance(item, ir.Status) and item.meaning == shape.meaning and item.index is None


# TX: "transmits via the serial port (RS-232C) the value of a user variable and a string" (L4463-
# L4483): `aTXn,m,p,x` sends x, then VARn with p digits after the point, with its sign when m is 1
# (`2D+987`) and without it when m is 0 (`3V987.123`). Decisions (docs/dialects/x150.md): the
# digits past p are dropped (the manual's examples round and truncate alike); a line end follows,
# as after every report; m = 0 sends no sign, a negative value included ("0 if the sign is not to
# be transmitted").
def transmit(variable: ir.Var, sign: bool, decimals: int, text: str, span: Span | None,
             sender: str = "") -> ir.Print:
    spec = f"fixed {decimals}" + ("" if sign else " magnitude")
    return ir.Print((ir.Text(text, span), variable), True, span, sender, signed=sign, formats=("", spec))


def transmit_of(op: ir.Print) -> tuple[str, bool, int, str] | None:
    """(variable name, sign, decimals, text) when `op` is a `transmit`, else None."""
    if not (op.newline and len(op.items) == 2 and isinstance(op.items[0], ir.Text)
            and isinstance(op.items[1], ir.Var) and len(op.formats) == 2 and op.formats[0] == ""):
        return None
    words = op.formats[1].split()
    if len(words) < 2 or words[0] != "fixed" or not words[1].isdigit():
        return None
    magnitude = words[2:] == ["magnitude"]
    if magnitude == op.signed or words[2:] not in ([], ["magnitude"]):
        return None   # m is 0 (no sign) or 1 (the sign always): nothing else has a TX
    return op.items[1].name, op.signed, int(words[1]), op.items[0].value


# QS: "Responds with the identity of the echoing device ... an asterisk, a two digit device
# address, an exclamation mark" (L3209-L3217); run by axis 1 the host receives `;*01!` (L3217).
def identity_report(axis: str, span: Span | None, sender: str = "") -> ir.Print:
    return ir.Print((ir.Text(";" + REPORT_PREFIX, span), ir.Status("device_address", axis, None, span),
                     ir.Text("!", span)), True, span, sender, formats=("", "pad 2", ""))


def identity_report_of(op: ir.Print) -> str | None:
    """The axis whose identity `op` reports (`identity_report`), else None."""
    shape = identity_report("", None)
    if op.newline and not op.signed and op.formats == shape.formats and len(op.items) == 3 \
            and all(_same_item(a, b) for a, b in zip(op.items, shape.items)):
        return op.items[1].axis
    return None


# S and STOP act "as soon as S is entered" (parker-x150.md L3649-L3675, STOP L4050-L4070): the
# motor decelerates at A, the buffer is cleared unless SSH1, a T delay ends, an XD download is
# aborted. SB does the same stop in its turn in the buffer (L3694): the IR's `Stop` with a ramp.
# The two are one where nothing sent before the S can still be waiting in the buffer: the stream so
# far (every stretch sent before it) is straight-line code none of whose operations waits (a delay,
# a wait, a call, a homing, a pause, the end of an MN move, a loop or a branch, a move queued behind
# another, a command of the X150's own whose timing the IR does not know). Then there is nothing to
# clear or end, and S is that `Stop`; anywhere else it stays the X150's own command, which the other
# dialects refuse at its line. S is never in a sequence (not saveable, L3656).
RECEIPT_STOPS = ("S", "STOP")
# IV changes the speed of the move in progress "during motion" (L2192-L2216: `G` then `IV20`, "speed
# up during move"): lowered to `speed_change` in its turn, exact only where receipt is the turn.
ON_RECEIPT = ("IV",)
WAITING_OPS = (ir.WaitMotion, ir.Delay, ir.WaitInput, ir.Call, ir.Home, ir.Pause, ir.Step, ir.Native)
MOTION_OPS = (ir.Move, ir.Slew, ir.Arc)


def stops_in_turn(module: ir.Module, on_receipt: dict | None = None) -> None:
    """Each `S`/`STOP` of the stream that nothing before can delay becomes `Stop(axis, ramp)`; each
    immediate setting lowered in its turn (`IV`, in `on_receipt`: its op's id -> the command as
    written) that something before may delay goes back to the X150's own command (see above)."""
    on_receipt = on_receipt or {}
    in_turn, moved = True, False
    for routine in module.routines:
        if routine.kind is not ir.RoutineKind.IMMEDIATE:
            continue
        if len(routine.blocks) != 1:
            in_turn = False  # a loop or a branch: what runs before a later command depends on time
            if not on_receipt:
                return  # nothing later is in its turn, and no setting waits to go back
        for block in routine.blocks:
            for index, op in enumerate(block.ops):
                if isinstance(op, ir.Native) and op.dialect == "x150" and op.mnemonic in RECEIPT_STOPS \
                        and not op.args and in_turn:
                    block.ops[index] = ir.Stop(op.axis, True, op.span)
                    continue
                if id(op) in on_receipt:
                    if not in_turn:
                        block.ops[index] = on_receipt[id(op)]
                    continue
                if isinstance(op, WAITING_OPS) or isinstance(op, MOTION_OPS) and moved:
                    in_turn = False
                    if not on_receipt:
                        return  # nothing later is in its turn, and no setting waits to go back
                moved = moved or isinstance(op, MOTION_OPS)


# Y "terminates a loop at end of the current pass" (parker-x150.md L5484-L5506); it is immediate, so
# it acts when it is received, not in its turn. Its example: `L A10 V10 D8000 T2 G N Y`: the loop
# runs "continuously", and Y, sent right after N, ends it "at the end of the pass during which the Y
# command is entered": the first pass. That is the IR's counted loop run once, and the Y nothing
# more, when the pass is surely under way when Y arrives: the loop is in the stream and everything
# sent before it is straight-line code that never waits (as for S, `stops_in_turn`), its pass is one
# block that waits (a delay, the end of a move, an input: a pass that never waits would spin through
# passes while the Y is on its way), its count is a constant, and the Y is the first thing sent after
# its N. Anywhere else Y stays the X150's own command, refused by the other dialects at its line.
LOOP_ENDS = ("Y",)
PASS_WAITS = (ir.WaitMotion, ir.Delay, ir.WaitInput)


def loops_ended_on_receipt(module: ir.Module, counter_prefix: str) -> None:
    """Each stream loop that a `Y` sent after it ends in its first pass runs once (see above)."""
    for routine in module.routines:
        if routine.kind is not ir.RoutineKind.IMMEDIATE:
            continue
        blocks = routine.blocks
        if len(blocks) == 3 and _loop_ended_by_y(blocks, counter_prefix):
            start, _, after = blocks
            init = start.ops[-1]
            start.ops[-1] = ir.Assign(init.target, ir.Const(1, ir.Unit.NONE, init.value.span), init.span)
            del after.ops[0]
        if len(blocks) != 1 or any(isinstance(op, WAITING_OPS) for op in blocks[0].ops):
            return  # what follows may be received before its turn: left as it is


def _loop_ended_by_y(blocks: list, counter_prefix: str) -> bool:
    start, head, after = blocks
    if not start.ops or not isinstance(start.terminator, ir.Jump) or start.terminator.target != head.label:
        return False
    init = start.ops[-1]
    if not (isinstance(init, ir.Assign) and init.target.name.startswith(counter_prefix)
            and isinstance(init.value, ir.Const) and init.value.value >= 0):
        return False
    if any(isinstance(op, WAITING_OPS) for op in start.ops) or sum(isinstance(op, MOTION_OPS) for op in start.ops) > 1:
        return False
    term = head.terminator
    if not (isinstance(term, ir.Branch) and term.then == head.label and term.otherwise == after.label
            and any(isinstance(op, PASS_WAITS) for op in head.ops)
            and not any(isinstance(op, (ir.Call, ir.Native)) for op in head.ops)
            and any(isinstance(node, ir.Var) and node.name == init.target.name for node in ir.walk_expr(term.cond))):
        return False
    first = after.ops[0] if after.ops else None
    return isinstance(first, ir.Native) and first.dialect == "x150" and first.mnemonic in LOOP_ENDS and not first.args
