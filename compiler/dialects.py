"""The table of dialects: extensions, frontend and backend modules, default profile.

This is the one place that knows which dialects exist. Frontends and backends are imported lazily
so that `mcc --version` and the CLI's help stay fast.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass


@dataclass(frozen=True)
class RoutineNumbers:
    """How a target numbers the routines it writes, so the optimizer knows how many new ones
    (outlined subroutines) fit: the numbers are the profile's `range_key` range (else `default`),
    new routines take them from `first_key` (else the range's start) upward, `reserved` ones are
    never given, and `every_routine` says the main program takes a number too. None of these: the
    target names its routines (MCode labels) and takes at most `named` new ones."""

    range_key: str = ""
    default: tuple[int, int] = (0, 0)
    first_key: str = ""
    first: int = 0  # where new numbers start when the profile has no `first_key`
    reserved: tuple[int, ...] = ()
    every_routine: bool = False
    named: int = 0


@dataclass(frozen=True)
class Resolution:
    """How finely a dialect's writer states what decides a run's timing, in its own units (the
    validation's time tolerance comes from it, sim/verify.py).

    The writer rounds a converted speed or acceleration to `rate` (steps/s, or rev/s with
    `per_rev`), a delay or ramp time to `tick` seconds; `ramp_times` means accelerations are written
    as a ramp time (Arcus ACC), so each ramp of a move may be off by one tick. A product profile may
    override them (`[sim] rate_resolution`, `time_resolution`)."""

    rate: float = 1.0
    per_rev: bool = False
    tick: float = 0.001
    ramp_times: bool = False


@dataclass(frozen=True)
class Dialect:
    name: str
    title: str
    extensions: tuple[str, ...]
    frontend: str  # module with analyze(source, profile) -> Analysis
    backend: str  # module with emit(module, profile) -> Listing
    default_profile: str
    output_extension: str
    comment: str  # the comment marker used in generated text and suppressions
    # A line longer than this is reported (G007) and not analysed: far past anything the device
    # reads (64-character MCode lines and Arcus commands, an X150 store of 8000 bytes), and a
    # megabyte line would otherwise take the parser many seconds and hundreds of megabytes.
    longest_line: int = 4096
    # What the dialect's programs are made of, for the passes that must not name a dialect
    # (compiler/opt, sim/): the type of a variable used without a declaration (an ir.VarType value),
    # whether its backend writes jumps as jumps (labels) rather than rebuilding structure, whether
    # its routines are reached only through the calls written in the program (a host cannot start
    # one), whether its routines are laid out in numbered program regions (MCode PG), whether the
    # text after a transfer to another routine (X150 XG) is kept as written, how it numbers routines,
    # and its line-cost table in the profile (the key, and whether a move costs a line per axis).
    variable_type: str = "int32"
    writes_jumps: bool = False
    private_routines: bool = False
    program_regions: bool = False
    keeps_code_after_transfer: bool = False
    routine_numbers: RoutineNumbers = RoutineNumbers(named=32)
    cost_key: str = ""
    resolution: Resolution = Resolution()
    # the module that moves a program between two product families of this dialect (differs() and
    # migrate(), e.g. MDrivePlus -> Lexium MCode), or "" when the dialect has one family
    migration: str = ""

    def load_frontend(self):
        return importlib.import_module(self.frontend)

    def load_backend(self):
        return importlib.import_module(self.backend)

    def load_migration(self):
        """The migration module, imported only when a compile names a source profile."""
        return importlib.import_module(self.migration) if self.migration else None


DIALECTS: dict[str, Dialect] = {
    # MCode: user variables are 32-bit integers (VA, L6036); labels name routines in PG regions, and
    # a host may run any label with EX, so no routine is private; labels share the 192-name table,
    # so outlining stays modest (32 new labels at most)
    "mcode": Dialect("mcode", "Lexium MCode", (".mxt", ".ixt", ".mcode"),
                     "mcc.compiler.mcode.frontend", "mcc.backends.mcode", "lmd-c", ".mxt", "'",
                     writes_jumps=True, program_regions=True, migration="mcc.compiler.mcode.migrate",
                     # VM/VI/A/D in whole steps/s (steps/s^2) when converted, H in ms
                     resolution=Resolution(1.0, False, 0.001)),
    # X150: VARn hold decimals (parker-x150.md VAR); a host may start any sequence with XR/XG; the
    # sequence text after XG is stored as written; every routine but the stream is a sequence
    "x150": Dialect("x150", "Parker/Digiplan X150/X150E", (".x150",),
                    "mcc.compiler.x150.frontend", "mcc.backends.x150", "x150-pdhx", ".x150", ";", 8000,
                    variable_type="decimal", keeps_code_after_transfer=True,
                    routine_numbers=RoutineNumbers("limits.sequences", (1, 64), every_routine=True),
                    # V and A in rev/s to four decimals (parker-x150.md L4542, L199), T in s from 0.001 (L4104)
                    resolution=Resolution(0.0001, True, 0.001)),
    # Arcus: V1-V64 are 32-bit integers; a SUB runs only by GOSUB (or as SUB 31 on an error, which
    # is never given to a new routine); program memory is priced per statement and per axis
    "arcus": Dialect("arcus", "Arcus Performax PMX-4EX-SA", (".prg",),
                     "mcc.compiler.arcus.frontend", "mcc.backends.arcus", "pmx-4ex-sa", ".prg", ";",
                     private_routines=True,
                     routine_numbers=RoutineNumbers("arcus.subroutines", (0, 31), "arcus.allocate_subroutines_from",
                                                    first=1, reserved=(31,)),
                     cost_key="arcus.cost",
                     # HSPD/LSPD in pulses/s, ACC a ramp time in ms, DELAY in ms (L1198, L1735)
                     resolution=Resolution(1.0, False, 0.001, ramp_times=True)),
}


def names() -> list[str]:
    return list(DIALECTS)


def get(name: str) -> Dialect:
    return DIALECTS[name]


def from_path(path: str) -> Dialect | None:
    lower = path.lower()
    for dialect in DIALECTS.values():
        if lower.endswith(dialect.extensions):
            return dialect
    return None


def all_extensions() -> tuple[str, ...]:
    return tuple(ext for d in DIALECTS.values() for ext in d.extensions)
