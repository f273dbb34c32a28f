"""The table of dialects: the one registered object through which shared code reaches a dialect.

A dialect's facts and the modules that are its own (frontend, backend, migration, preprocessor,
host protocol, virtual device, editor support) are declared by the dialect itself, in its
`compiler/<dialect>/dialect.py` (one `Dialect` named `DIALECT`); `REGISTERED` below lists those
modules, one line per dialect, and is the only place that knows which dialects exist. Shared code
never names a dialect: it asks the `Dialect` (tests/test_dialect_neutral.py). The modules a
dialect names are imported lazily so that `mcc --version` and the CLI's help stay fast.
docs/decisions/0022-dialect-plugin-interface.md says why the interface is this one.
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
    # The neutral settings (ir_names.SETTINGS) the dialect has a statement for: a drive-only setting
    # outside them may be left out of a conversion to it (backends/drive_setup.py, G051).
    settings: frozenset[str] = frozenset()
    # Every marker a comment may start with (the profile directive `mcc: profile=` is read in any of
    # them, compiler/selection.py), and the ones a `noqa` comment is recognised after ("": `comment`).
    comment_markers: str = ""
    noqa_markers: str = ""
    # The dialect has no initial speed: every move starts from standstill, so a program written for
    # it runs with an initial speed of 0 (compiler/in_force.py FIXED).
    moves_from_standstill: bool = False
    # the module with directive_lines(source) -> [(line, directive)] when the dialect has a
    # preprocessor whose source is checked whole and never formatted ("" when none)
    preprocessor: str = ""
    # The link: the module of the host protocol (`Protocol`, `explain_code`, `describe`, `upload`:
    # link/protocols.py), the module of the virtual device (`make(faults, options)`:
    # link/device/virtual.py), and the extensions of a device memory image, when the device is
    # downloaded an image rather than the compiled listing (empty: the listing).
    link: str = ""
    device: str = ""
    image_extensions: tuple[str, ...] = ()
    # the editor support: a module with `EDITOR`, an lsp.editor.Editor (completion, hover, rename,
    # program memory and the indexer of the editor model; lsp/editor.py loads it)
    editor: str = ""

    def load_frontend(self):
        return importlib.import_module(self.frontend)

    def load_backend(self):
        return importlib.import_module(self.backend)

    def load_migration(self):
        """The migration module, imported only when a compile names a source profile."""
        return importlib.import_module(self.migration) if self.migration else None

    def load_preprocessor(self):
        """The preprocessor module, or None when the dialect has none."""
        return importlib.import_module(self.preprocessor) if self.preprocessor else None

    def load_link(self):
        return importlib.import_module(self.link)

    def load_device(self):
        return importlib.import_module(self.device)

    def noqa_comment_markers(self) -> str:
        return self.noqa_markers or self.comment


# The dialects, in the order the CLI and the documentation list them: one registration line each,
# the module that declares the dialect's `DIALECT`.
REGISTERED = (
    "mcc.compiler.mcode.dialect",
    "mcc.compiler.x150.dialect",
    "mcc.compiler.arcus.dialect",
)

DIALECTS: dict[str, Dialect] = {}
for _module in REGISTERED:
    _dialect = importlib.import_module(_module).DIALECT
    DIALECTS[_dialect.name] = _dialect


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


def from_image(path: str) -> Dialect | None:
    """The dialect whose device memory image `path` is (by its extension), or None."""
    lower = path.lower()
    return next((d for d in DIALECTS.values() if d.image_extensions and lower.endswith(d.image_extensions)), None)


def all_extensions() -> tuple[str, ...]:
    return tuple(ext for d in DIALECTS.values() for ext in d.extensions)
