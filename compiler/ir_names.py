"""The IR's neutral vocabulary: every name an operation or expression may carry, with its meaning.

The IR means one thing whatever the source dialect, so the names inside it are not any dialect's
spelling: `!=` not MCode's `<>`, `position` not Arcus's `PX` or X150's `POS`. Frontends translate
their spelling into these names and backends translate back (or refuse, naming the construct).
The verifier (`mcc.compiler.ir_verify`) rejects any name not listed here; `Native` operations are
the only place a dialect's own spelling may appear.

Each table maps a neutral name to a one-line meaning; docs/ARCHITECTURE.md prints them.
"""

from __future__ import annotations

from dataclasses import dataclass

from mcc.compiler.ir import Unit

BINARY_OPS: dict[str, str] = {
    "+": "addition",
    "-": "subtraction",
    "*": "multiplication",
    "/": "division; truncates toward zero when both operands are int32 variables or integers",
    "%": "remainder of the truncating division (sign of the dividend)",
    "&": "bitwise and (int32)",
    "|": "bitwise or (int32)",
    "^": "bitwise exclusive or (int32)",
    "<<": "shift left (int32)",
    ">>": "arithmetic shift right (int32)",
}

UNARY_OPS: dict[str, str] = {
    "-": "negation",
    "~": "bitwise not (int32)",
    "!": "logical not: 1 when the operand is 0, else 0",
}

COMPARE_OPS: dict[str, str] = {
    "=": "equal", "!=": "not equal", "<": "less than", "<=": "less than or equal",
    ">": "greater than", ">=": "greater than or equal",
}

LOGIC_OPS: dict[str, str] = {
    "and": "both conditions hold (both are evaluated)",
    "or": "either condition holds (both are evaluated)",
}

FUNCTIONS: dict[str, str] = {
    "abs": "absolute value",
    "sqrt": "square root",
    # the angle unit: degrees, or radians while the setting `trig_radians` is 1 (its power-up value
    # is the module's `device_values`; MCode RA, default radians, lexium-mcode.txt L5107)
    "sin": "sine of an angle (degrees, or radians under `trig_radians`)",
    "cos": "cosine of an angle (degrees, or radians under `trig_radians`)",
    "tan": "tangent of an angle (degrees, or radians under `trig_radians`)",
    "asin": "arc sine (degrees, or radians under `trig_radians`)",
    "acos": "arc cosine (degrees, or radians under `trig_radians`)",
    "atan": "arc tangent (degrees, or radians under `trig_radians`)",
    "log": "natural logarithm",
    "log10": "decimal logarithm",
    "log2": "binary logarithm (base 2)",
    "exp": "e to the power of the argument",
    "pi": "the constant pi (no argument)",
    "int": "the integer part (truncation toward zero)",
}


@dataclass(frozen=True)
class Reading:
    """A device reading (`ir.Status`): what it means, its unit, and whether it takes an index."""

    meaning: str
    unit: Unit = Unit.NONE
    indexed: bool = False  # True: `index` is an input/output/channel number


STATUS: dict[str, Reading] = {r.meaning: r for r in (
    Reading("position", Unit.STEPS),  # commanded position of the axis
    Reading("encoder", Unit.STEPS),  # encoder position, in steps
    Reading("velocity", Unit.STEPS_PER_S),  # current speed, signed
    Reading("moving"),  # 1 while the axis is moving, else 0
    Reading("moving_to_position"),  # 1 while a move to a position (not a slew) runs
    Reading("input", indexed=True),  # digital input n: 1 when active
    Reading("inputs"),  # every digital input as a bit mask, input 1 in bit 0
    Reading("output", indexed=True),  # digital output n: 1 when on
    Reading("outputs"),  # every digital output as a bit mask, output 1 in bit 0
    Reading("analog", indexed=True),  # analog input n, in the device's counts
    Reading("error"),  # the device's error code (0: none)
    Reading("fault"),  # 1 while the axis is in a fault state (limit hit, stall, drive fault)
    Reading("limit_plus"),  # 1 while the positive limit switch is active
    Reading("limit_minus"),  # 1 while the negative limit switch is active
    Reading("home_switch"),  # 1 while the home switch is active
    Reading("stalled"),  # 1 after a stall was detected
    Reading("enabled"),  # 1 while the drive is enabled
    Reading("timer", Unit.S, indexed=True),  # free-running timer n, in seconds
    Reading("max_speed", Unit.STEPS_PER_S),  # the max speed in force
    Reading("initial_speed", Unit.STEPS_PER_S),  # the initial speed in force
    Reading("accel", Unit.STEPS_PER_S2),  # the acceleration in force
    Reading("decel", Unit.STEPS_PER_S2),  # the deceleration in force
    Reading("input_pending"),  # 1 while a value typed for an INPUT statement is waiting (MCode IF)
    Reading("hmt_status"),  # the closed-loop (hMT) status bits (MCode AF)
    Reading("locked_rotor"),  # 1 after a closed-loop drive detected a locked rotor (MCode LR)
    Reading("accel_time", Unit.S),  # the ramp time in force (initial to maximum speed)
    Reading("profile"),  # the velocity profile in force: 0 trapezoidal, 1 S-curve
    Reading("motor_status"),  # status bits: 0 accel, 1 decel, 2 constant speed, 3 alarm in, 4 +limit in, 5 -limit in, 6 home in, 7 +limit error, 8 -limit error, 9 alarm error
    Reading("enable_outputs"),  # every drive-enable output as a bit mask, the first axis in bit 0
    Reading("countdown", Unit.S),  # time left on the countdown timer (it counts down to 0)
    Reading("compare_state"),  # the position-compare output: 0 off, 1 armed, 2 fired
    Reading("aux_input"),  # 1 while the drive's auxiliary (dedicated) input is active (X150 AUX_IN)
    Reading("stop_input"),  # 1 while the dedicated stop input is active
    Reading("enable_input"),  # 1 while the dedicated drive-enable (energise) input is active
    Reading("index_input"),  # 1 while the encoder's index (marker) input is active
    # settings read back (a report of the value in force: X150's 1FOL, 1INL, 1OUTL queries)
    Reading("following_ratio", Unit.PERCENT),  # the `following_ratio` setting in force
    Reading("input_levels"),  # the active level of every input (1 active high), input 1 in bit 0
    Reading("output_levels"),  # the active level of every output (1 active high), output 1 in bit 0
    # drive values the machine model has no cause to change: they read the module's `device_values`
    # (the product's value) unless the simulator models them (docs/SIMULATOR.md, "Drive registers")
    Reading("measured_velocity", Unit.STEPS_PER_S),  # the velocity the encoder measures (closed loop); no slip
    #                                                   is modelled: the velocity
    Reading("position_error", Unit.STEPS),  # closed-loop lead (-) or lag (+) of the rotor: 0, no slip modelled
    Reading("output_fault"),  # over-current fault of the outputs, a bit mask: 0, none modelled
    Reading("captured_position", Unit.STEPS),  # the position captured at the last trip or capture
    Reading("velocity_changing"),  # 1 while the axis accelerates or decelerates
    Reading("last_move"),  # the kind of the last move command: absolute, relative or slew (printed as the
    #                        module's `print_texts` say)
    Reading("part_number"),  # the device's part number (text, from the product profile)
    Reading("firmware_version"),  # the device's firmware and hardware version (text, from the product profile)
    Reading("resolution"),  # steps per motor revolution in force (the resolution setting)
    Reading("switch_levels"),  # the active level of every switch input (1 active high), SWITCH_INPUTS order from bit 0
    Reading("device_address"),  # the address (axis number) of the device that runs the operation
)}

# The dedicated switch inputs a device may have beside its numbered inputs, in the order of the
# `switch_active_high` setting's index (1 first) and of the `switch_levels` reading's bits: each is
# also a reading of its own (STATUS).
SWITCH_INPUTS = ("limit_plus", "limit_minus", "home_switch", "aux_input", "stop_input", "enable_input",
                 "index_input")

# Print formats (`Print.formats`, one per item; docs/IR.md, "Print formats"): a word and a number,
# then options.
PRINT_FORMATS: dict[str, str] = {
    "fixed": "`fixed p`: the number with p digits after the decimal point, the further digits dropped "
             "(truncated toward zero), no point when p is 0; option `magnitude`: without its sign",
    "bits": "`bits n`: n binary digits of an integer, bit 0 first (leftmost)",
    "pad": "`pad n`: an integer with leading zeros to n digits",
}


def print_format_error(spec: str) -> str | None:
    """Why `spec` is not a print format (PRINT_FORMATS), or None when it is one ("" included)."""
    if spec == "":
        return None
    words = spec.split()
    if len(words) < 2 or words[0] not in PRINT_FORMATS or not words[1].isdigit() or int(words[1]) > 64:
        return f"'{spec}' is not a print format (a word of {sorted(PRINT_FORMATS)} and a number up to 64)"
    extra = words[2:]
    if extra and (words[0] != "fixed" or extra != ["magnitude"]):
        return f"'{spec}' has an option its format does not take"
    return None

# SetHandler events: what makes the handler run.
EVENTS: dict[str, str] = {
    "input": "a digital input reaches a level or edge (args: input number, level)",
    "position": "the axis passes a position (args: position in steps)",
    "capture": "a capture input latches the position",
    "time": "a timer expires (args: seconds)",
    "relative": "the axis has moved a distance since the handler was armed (args: steps)",
    "hmt": "a closed-loop (hMT) event such as a lost position",
    "power": "power-up: the handler runs when the device starts",
    "power_loss": "the main power is lost (the logic supply stays on)",
    "error": "an error occurs while the program runs",
    "fault": "the device enters a fault state",
    "when": "a condition becomes true (args: the condition)",
    "stall": "a stall is detected",
}

# The bits of the `handler_enable` setting (MCode TE, L5657-L5696): the events they let fire.
HANDLER_ENABLE_BITS: dict[int, str] = {1: "input", 2: "position", 4: "capture", 8: "time", 16: "relative",
                                       32: "hmt", 64: "power_loss"}


@dataclass(frozen=True)
class SettingInfo:
    """A device setting (`ir.Setting`): meaning and unit. Which dialects have it is the dialects'
    own fact (each `Dialect.settings`, compiler/<dialect>/dialect.py): `dialects` asks them."""

    name: str
    unit: Unit
    meaning: str
    # how the value is held: "int" (a whole number), "float" (printed in the product's float format),
    # "text" (a text the device keeps, e.g. a format); every setting can be read back as a reading
    # `Status(name)`: the value the run set, else the module's `device_values` (the product's default)
    value_type: str = "int"
    # drive set-up only (docs/decisions/0016): its one effect is on drive hardware that another
    # product configures outside the program or does not have; it cannot change motion, outputs,
    # prints, variables or timing, so a conversion to a dialect without it may leave it out with a
    # warning (backends/drive_setup.py, G051)
    drive_only: bool = False

    @property
    def dialects(self) -> tuple[str, ...]:
        """The dialects that have a statement for the setting, in the order of the table of dialects."""
        from mcc.compiler import dialects

        return tuple(d.name for d in dialects.DIALECTS.values() if self.name in d.settings)


SETTINGS: dict[str, SettingInfo] = {s.name: s for s in (
    # RC and HC set the motor's current only (lexium-mcode.txt L5134, L3077); HT (hold_delay) is not
    # drive-only: MP and MV stay active through the HT and MT delays (L4207, L4429)
    SettingInfo("run_current", Unit.PERCENT, "motor current while moving, % of the maximum",
                drive_only=True),
    SettingInfo("hold_current", Unit.PERCENT, "motor current at rest, % of the maximum",
                drive_only=True),
    SettingInfo("hold_delay", Unit.S, "time after a move before the hold current applies"),
    SettingInfo("settle_time", Unit.S, "time the motor settles after a move before the next starts"),
    SettingInfo("encoder_enable", Unit.NONE, "1: the encoder is used (closed loop), 0: open loop"),
    SettingInfo("error_code", Unit.NONE, "the device's error code: writing 0 clears the error"),
    SettingInfo("handler_enable", Unit.NONE, "which installed handlers may fire: a bit mask in "
                "HANDLER_ENABLE_BITS order; a handler that fires clears its bit (MCode TE)"),
    SettingInfo("input_debounce", Unit.S, "time input `index` must hold a new level before it counts"),
    SettingInfo("input_function", Unit.NONE, "what input `index` does: a name of INPUT_FUNCTIONS"),
    SettingInfo("input_active_high", Unit.NONE, "1: input `index` is active at a high level, 0: low"),
    SettingInfo("output_function", Unit.NONE, "what output `index` shows: a name of OUTPUT_FUNCTIONS"),
    SettingInfo("output_active_high", Unit.NONE, "1: output `index` is on at a high level, 0: low"),
    SettingInfo("io_sourcing", Unit.NONE, "1: I/O point `index` sources current, 0: it sinks (MDrivePlus S1-S4; "
                "wiring on Lexium drives)"),
    SettingInfo("switch_active_high", Unit.NONE, "1: switch input `index` (SWITCH_INPUTS, 1 first) is active at a "
                "high level, 0: low"),
    SettingInfo("encoder_position", Unit.STEPS, "sets the encoder counter of the axis"),
    SettingInfo("clear_error", Unit.NONE, "1 clears the axis's limit/alarm error so that it accepts moves again"),
    SettingInfo("enable_outputs", Unit.NONE, "every drive-enable output as a bit mask, the first axis in bit 0"),
    SettingInfo("countdown", Unit.S, "loads the countdown timer, which then counts down to 0"),
    SettingInfo("speed_change", Unit.STEPS_PER_S, "changes the speed of the move in progress on the fly"),
    SettingInfo("compare_condition", Unit.NONE, "when the position-compare output fires: 1 encoder = position, "
                "2 encoder > position, 3 encoder < position"),
    SettingInfo("compare_position", Unit.STEPS, "the encoder position the position-compare output tests"),
    SettingInfo("compare_pulse", Unit.S, "pulse width of the compare output at equality (0: while equal)"),
    SettingInfo("compare_output", Unit.NONE, "1 arms the position-compare output, 0 turns it off (its digital "
                "output is then the program's again)"),
    SettingInfo("limits_disabled", Unit.NONE, "limit switches ignored, a bit mask: 1 the + limit, 2 the - limit "
                "(0: both active)"),
    SettingInfo("position_maintenance", Unit.NONE, "1: a stepper is servoed back to its encoder position at rest, "
                "0: off"),
    SettingInfo("stop_on_stall", Unit.NONE, "1: a move stops (at its deceleration) when a stall is detected, 0: "
                "it goes on"),
    SettingInfo("encoder_resolution", Unit.NONE, "encoder counts per motor revolution (after quadrature)"),
    SettingInfo("motor_resolution", Unit.NONE, "motor steps per revolution of the drive (not the IR's step)"),
    SettingInfo("position_deadband", Unit.NONE, "position error, in motor steps, that position maintenance "
                "leaves uncorrected"),
    SettingInfo("encoder_step_mode", Unit.NONE, "1: distances count encoder steps, 0: motor steps"),
    SettingInfo("keep_buffer_on_stop", Unit.NONE, "1: a stop keeps the commands waiting in the buffer, 0: clears "
                "them"),
    SettingInfo("home_accel", Unit.STEPS_PER_S2, "acceleration of a homing move; 0: the largest the drive makes"),
    SettingInfo("home_final_speed", Unit.STEPS_PER_S, "speed of a homing move's final approach to the home edge"),
    SettingInfo("following_mode", Unit.NONE, "0: the axis is an indexer that runs its own moves; 1-6: it "
                "follows a step/encoder input in one of the device's following modes"),
    SettingInfo("following_ratio", Unit.PERCENT, "speed of a following axis as a percentage of its input"),
    SettingInfo("command_source", Unit.NONE, "how the following input is counted: 0 quadrature x4, 1 x2, 2 x1, "
                "3 step and direction"),
    SettingInfo("single_step", Unit.NONE, "1: a stored program runs one command per step request from the host, "
                "0: it runs freely"),
    SettingInfo("trace", Unit.NONE, "1: the device reports each program command to the host as it runs it, 0: off"),
    # the RP240 panel's keys (parker-x150.md L860-L885, L1237-L1253): on a target without the panel
    # no key can be pressed, so enabling one changes nothing the program does (drive-only, G051)
    SettingInfo("panel_pause_keys", Unit.NONE, "1: the operator panel's PAUSE and CONTINUE keys pause and resume "
                "the program, 0: they are ignored", drive_only=True),
    SettingInfo("limit_decel", Unit.STEPS_PER_S2, "deceleration of a stop at a limit switch"),
    SettingInfo("position_error_limit", Unit.NONE, "position error, in motor steps, beyond which a servo faults; "
                "0: no limit"),
    SettingInfo("in_position_window", Unit.NONE, "position error, in motor steps, within which a move counts as "
                "in position"),
    SettingInfo("in_position_time", Unit.S, "time the position error must stay within the in-position window"),
    SettingInfo("servo_proportional_gain", Unit.NONE, "the servo loop's proportional gain (device units)"),
    SettingInfo("servo_integral_gain", Unit.NONE, "the servo loop's integral gain (device units)"),
    SettingInfo("servo_velocity_gain", Unit.NONE, "the servo loop's velocity feedback gain (device units)"),
    SettingInfo("servo_feedforward_gain", Unit.NONE, "the servo loop's velocity feedforward gain (device units)"),
    SettingInfo("servo_filter_time", Unit.S, "time constant of the servo loop's output filter"),
    SettingInfo("following_filter_time", Unit.S, "time constant of the filter on a following input"),
    SettingInfo("panel_stop_key", Unit.NONE, "1: the operator panel's STOP key stops motion and ends every loop "
                "and program, 0: it is ignored", drive_only=True),
    # Drive registers the program may set and read back, whose effect the simulator does not model
    # (it keeps their value: docs/SIMULATOR.md, "Drive registers"); MCode's spelling in the catalog's
    # `setting` key (compiler/catalogs/mcode.toml)
    SettingInfo("trip_pulse_width", Unit.NONE, "pulse width of the trip (clock) output, in 50 ns units"),
    SettingInfo("analog_filter", Unit.NONE, "samples of the analog input's running-average filter"),
    SettingInfo("decel_jerk", Unit.NONE, "samples of the deceleration ramp held at constant deceleration "
                "(S-curve jerk)"),
    SettingInfo("echo_mode", Unit.NONE, "how the device echoes the host's commands (0 all, 1 none, 2 no prompt, "
                "3 queued)"),
    SettingInfo("clock_input_filter", Unit.NONE, "digital filter of the clock inputs (a code of the filter time)"),
    SettingInfo("jog_enable", Unit.NONE, "1: the jog inputs move the axis, 0: they are ignored"),
    SettingInfo("lead_limit", Unit.NONE, "closed loop: the largest lead of the rotor, in motor steps, before a "
                "fault"),
    SettingInfo("lag_limit", Unit.NONE, "closed loop: the largest lag of the rotor, in motor steps, before a fault"),
    SettingInfo("program_lock", Unit.NONE, "1: the stored program cannot be listed, changed or uploaded"),
    SettingInfo("limit_response", Unit.NONE, "how the axis responds to a limit switch (a mode number)"),
    SettingInfo("locked_rotor_timeout", Unit.S, "closed loop: time at the lag limit without rotor movement before "
                "a locked rotor is declared"),
    SettingInfo("makeup_frequency", Unit.STEPS_PER_S, "closed loop: speed at which missed steps are made up"),
    SettingInfo("makeup_mode", Unit.NONE, "closed loop: how missed steps are made up (a mode number)"),
    SettingInfo("numeric_move_enable", Unit.NONE, "1: a number typed alone repeats the last move kind with it"),
    SettingInfo("float_format", Unit.NONE, "how floating-point values print: width, decimals, notation "
                "(1 scientific), justification (1 left), as text `w,d,n,j`", "text"),
    SettingInfo("trig_radians", Unit.NONE, "1: the trigonometric functions work in radians, 0: in degrees"),
    SettingInfo("direction_reversed", Unit.NONE, "1: the motor's plus and minus directions are swapped"),
    SettingInfo("step_angle", Unit.NONE, "the motor's full-step angle in degrees", "float"),
    SettingInfo("stall_factor", Unit.NONE, "following error, in encoder counts, above which a stall is declared"),
    SettingInfo("continue_on_stall", Unit.NONE, "1: a move goes on after a stall, 0: it stops"),
    SettingInfo("torque_direction", Unit.NONE, "closed-loop torque mode: 1 plus, 0 minus"),
    SettingInfo("torque_percent", Unit.PERCENT, "closed-loop torque mode: the largest torque"),
    SettingInfo("torque_speed", Unit.STEPS_PER_S, "closed-loop torque mode: the speed"),
    SettingInfo("velocity_filter", Unit.NONE, "closed loop: filtering of the measured velocity (0 none)"),
    SettingInfo("soft_limit_position", Unit.STEPS, "the position of software limit `index` (0 the minus limit, "
                "1 the plus limit)"),
    SettingInfo("soft_limit_enable", Unit.NONE, "1: software limit `index` (0 minus, 1 plus) stops the axis, 0: off"),
    SettingInfo("warning_temperature", Unit.NONE, "temperature, in °C, above which the device raises a warning"),
)}

# The values of the input_function and output_function settings (an `ir.Text`).
INPUT_FUNCTIONS = ("general", "home", "limit_plus", "limit_minus", "run_program", "soft_stop", "pause",
                   "jog_plus", "jog_minus", "reset", "capture", "step_direction", "encoder_ab", "step_up_down",
                   "kill",  # kill: stop at once without a ramp and end the program
                   # X150 only (L2077-L2106):
                   "sequence_strobe",  # a 0->1 edge runs the sequence the select inputs name
                   "sequence_select",  # one bit of the sequence number the strobe runs
                   "drive_enable",  # the drive is energised while the input is active
                   "go",  # a 0->1 edge starts a move, as G
                   "direction_toggle",  # a 0->1 edge reverses the direction of the next move, as H
                   "end_loop",  # ends the running loop after its current pass, as Y
                   "data",  # one bit of the parallel data (thumbwheel) read by the ...RD commands
                   "data_sign",  # the sign of the parallel data
                   "memory_lock",  # while active, the stored programs cannot be changed
                   "continue",  # resumes a program paused by PS
                   "position_zero")  # a 0->1 edge makes the present position 0, as PZ
OUTPUT_FUNCTIONS = ("general", "moving", "error", "stall", "velocity_changing", "locked_rotor",
                    "moving_to_position", "hmt_active", "make_up_active", "encoder_a", "encoder_b", "trip",
                    "attention",
                    # X150 only (L2986-L2995):
                    "program_running",  # on while a sequence runs
                    "no_fault",  # on while there is no fault (fail-safe)
                    "busy",  # on while the controller is busy
                    "energised",  # on while the drive is energised by ON
                    "data_strobe",  # strobes the parallel data inputs (thumbwheels)
                    "in_position",  # on when the motor has settled within the in-position window
                    "registration_pulse")  # a 100 ms pulse after a registration move


def status_unit(meaning: str) -> Unit:
    reading = STATUS.get(meaning)
    if reading is not None:
        return reading.unit
    setting = SETTINGS.get(meaning)  # a setting read back
    return setting.unit if setting is not None else Unit.NONE
