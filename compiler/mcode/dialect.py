"""The MCode dialect's registration: what shared code asks of Lexium MCode (compiler/dialects.py)."""

from __future__ import annotations

from mcc.compiler.dialects import Dialect, Resolution

# The neutral settings (compiler/ir_names.py SETTINGS) this dialect has a statement for.
SETTINGS = frozenset({
    "run_current", "hold_current", "hold_delay", "settle_time", "encoder_enable", "error_code",
    "handler_enable", "input_debounce", "input_function", "input_active_high", "output_function",
    "output_active_high", "io_sourcing", "position_maintenance", "trip_pulse_width", "analog_filter",
    "decel_jerk", "echo_mode", "clock_input_filter", "jog_enable", "lead_limit", "lag_limit", "program_lock",
    "limit_response", "locked_rotor_timeout", "makeup_frequency", "makeup_mode", "numeric_move_enable",
    "float_format", "trig_radians", "direction_reversed", "step_angle", "stall_factor", "continue_on_stall",
    "torque_direction", "torque_percent", "torque_speed", "velocity_filter", "soft_limit_position",
    "soft_limit_enable", "warning_temperature",
})

DIALECT = Dialect(
    "mcode", "Lexium MCode", (".mxt", ".ixt", ".mcode"),
    "mcc.compiler.mcode.frontend", "mcc.backends.mcode", "lmd-c", ".mxt", "'",
    # user variables are 32-bit integers (VA, L6036); labels name routines in PG regions, and a host
    # may run any label with EX, so no routine is private; labels share the 192-name table, so
    # outlining stays modest (32 new labels at most)
    writes_jumps=True, program_regions=True, migration="mcc.compiler.mcode.migrate",
    # VM/VI/A/D in whole steps/s (steps/s^2) when converted, H in ms
    resolution=Resolution(1.0, False, 0.001),
    settings=SETTINGS,
    # MCode listings use the backtick as well as the apostrophe the manual documents (spec §1.5)
    comment_markers="'`", noqa_markers="'`",
    preprocessor="mcc.compiler.mcode.preprocessor",
    link="mcc.link.mcode", device="mcc.link.device.mcode", editor="mcc.lsp.mcode_editor",
)
