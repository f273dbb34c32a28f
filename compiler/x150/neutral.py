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
# number, written back as the command with that number. `speed_change` (IV, rev/s) is converted.
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
}
SETTING_COMMANDS = {name: mnemonic for mnemonic, name in SETTINGS.items()}

# Input and output functions (IN<n><letter>, OUT<n><letter>, L2058-L2114, L2974-L3013): the letters
# with a neutral meaning (ir_names.INPUT_FUNCTIONS / OUTPUT_FUNCTIONS); the others stay Native.
INPUT_FUNCTIONS = {"A": "general", "C": "kill", "F": "pause", "J": "jog_plus", "K": "jog_minus", "R": "reset"}
OUTPUT_FUNCTIONS = {"A": "general", "B": "moving"}
INPUT_LETTERS = {name: letter for letter, name in INPUT_FUNCTIONS.items()}
OUTPUT_LETTERS = {name: letter for letter, name in OUTPUT_FUNCTIONS.items()}
OUTPUTS = 6
