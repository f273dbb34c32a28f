"""The table of dialects: extensions, frontend and backend modules, default profile.

This is the one place that knows which dialects exist. Frontends and backends are imported lazily
so that `mcc --version` and the CLI's help stay fast.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass


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

    def load_frontend(self):
        return importlib.import_module(self.frontend)

    def load_backend(self):
        return importlib.import_module(self.backend)


DIALECTS: dict[str, Dialect] = {
    "mcode": Dialect("mcode", "Lexium MCode", (".mxt", ".ixt", ".mcode"),
                     "mcc.compiler.mcode.frontend", "mcc.backends.mcode", "lmd-c", ".mxt", "'"),
    "x150": Dialect("x150", "Parker/Digiplan X150/X150E", (".x150",),
                    "mcc.compiler.x150.frontend", "mcc.backends.x150", "x150-pdhx", ".x150", ";", 8000),
    "arcus": Dialect("arcus", "Arcus Performax PMX-4EX-SA", (".prg",),
                     "mcc.compiler.arcus.frontend", "mcc.backends.arcus", "pmx-4ex-sa", ".prg", ";"),
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
