"""The Arcus dialect's registration: what shared code asks of the Arcus Performax PMX-4EX-SA
(compiler/dialects.py)."""

from __future__ import annotations

from mcc.compiler.dialects import Dialect, Resolution, RoutineNumbers

# The neutral settings (compiler/ir_names.py SETTINGS) this dialect has a statement for.
SETTINGS = frozenset({
    "encoder_position", "clear_error", "enable_outputs", "countdown", "speed_change", "compare_condition",
    "compare_position", "compare_pulse", "compare_output",
})

DIALECT = Dialect(
    "arcus", "Arcus Performax PMX-4EX-SA", (".prg",),
    "mcc.compiler.arcus.frontend", "mcc.backends.arcus", "pmx-4ex-sa", ".prg", ";",
    # V1-V64 are 32-bit integers; a SUB runs only by GOSUB (or as SUB 31 on an error, which is never
    # given to a new routine); program memory is priced per statement and per axis
    private_routines=True,
    routine_numbers=RoutineNumbers("arcus.subroutines", (0, 31), "arcus.allocate_subroutines_from",
                                   first=1, reserved=(31,)),
    cost_key="arcus.cost",
    # HSPD/LSPD in pulses/s, ACC a ramp time in ms, DELAY in ms (L1198, L1735)
    resolution=Resolution(1.0, False, 0.001, ramp_times=True),
    settings=SETTINGS,
    # ';' is the language's comment (L1721); "'" is what the DXF converter writes (L1201); noqa is
    # recognised after ';' only
    comment_markers=";'", noqa_markers=";",
    # the device is downloaded a memory image (.sa) saved by the vendor's tool, not the listing
    link="mcc.link.arcus", device="mcc.link.device.arcus", editor="mcc.lsp.arcus_editor",
    image_extensions=(".sa",),
)
