"""The X150 dialect's registration: what shared code asks of Parker/Digiplan X150/X150E
(compiler/dialects.py)."""

from __future__ import annotations

from mcc.compiler.dialects import Dialect, Resolution, RoutineNumbers

# The neutral settings (compiler/ir_names.py SETTINGS) this dialect has a statement for.
SETTINGS = frozenset({
    "input_function", "input_active_high", "output_function", "output_active_high", "switch_active_high",
    "limits_disabled", "position_maintenance", "stop_on_stall", "encoder_resolution", "motor_resolution",
    "position_deadband", "encoder_step_mode", "keep_buffer_on_stop", "home_accel", "home_final_speed",
    "following_mode", "following_ratio", "command_source", "single_step", "trace", "panel_pause_keys",
    "limit_decel", "position_error_limit", "in_position_window", "in_position_time", "servo_proportional_gain",
    "servo_integral_gain", "servo_velocity_gain", "servo_feedforward_gain", "servo_filter_time",
    "following_filter_time", "panel_stop_key",
})

DIALECT = Dialect(
    "x150", "Parker/Digiplan X150/X150E", (".x150",),
    "mcc.compiler.x150.frontend", "mcc.backends.x150", "x150-pdhx", ".x150", ";", 8000,
    # VARn hold decimals (parker-x150.md VAR); a host may start any sequence with XR/XG; the sequence
    # text after XG is stored as written; every routine but the stream is a sequence
    variable_type="decimal", keeps_code_after_transfer=True,
    routine_numbers=RoutineNumbers("limits.sequences", (1, 64), every_routine=True),
    # V and A in rev/s to four decimals (parker-x150.md L4542, L199), T in s from 0.001 (L4104)
    resolution=Resolution(0.0001, True, 0.001),
    settings=SETTINGS,
    comment_markers=";",
    # no initial speed: moves start from standstill (docs/dialects/x150.md)
    moves_from_standstill=True,
    link="mcc.link.x150", device="mcc.link.device.x150", editor="mcc.lsp.x150_editor",
)
