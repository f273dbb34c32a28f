"""The layers of the toolchain, kept by reading every module's imports (an import-linter contract
in test form, so it needs nothing installed):

- backends depend on the IR and its vocabulary, the profiles (and the homing model read from them,
  compiler/homing.py), diagnostics and spans, and their own
  modules; each backend may read its own dialect's command catalog, routine naming and neutral-name tables (pure data). They never
  import a frontend's parser, syntax tree, lowering or checks, nor the driver.
- frontends (compiler/<dialect>/) never import the driver, the CLI or a backend.
- the compiler never imports the CLI.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DIALECTS = ("mcode", "arcus", "x150")

# What every backend may import from mcc.compiler.
BACKEND_ALLOWED = {
    "mcc.compiler", "mcc.compiler.ir", "mcc.compiler.ir_names", "mcc.compiler.units",
    "mcc.compiler.in_force", "mcc.compiler.profiles", "mcc.compiler.diagnostics",
    "mcc.compiler.span", "mcc.compiler.codes", "mcc.compiler.catalog", "mcc.compiler.homing",
}

# Imports that break a layer today and are being moved (issue 8); the list may only shrink.
KNOWN_EXCEPTIONS: set[tuple[str, str]] = {
}


def imports(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module:
            found.add(node.module)
            found.update(f"{node.module}.{alias.name}" for alias in node.names)
        elif isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
    return {name for name in found if name.startswith("mcc.")}


def modules(folder: str) -> list[Path]:
    return sorted((ROOT / folder).rglob("*.py"))


def is_module(name: str) -> bool:
    """`mcc.compiler.x150.catalog` names a module; `mcc.compiler.ir.Module` a name inside one."""
    parts = name.split(".")[1:]
    path = ROOT.joinpath(*parts)
    return path.with_suffix(".py").exists() or (path / "__init__.py").exists()


def own_tables(dialect: str) -> set[str]:
    """A backend may read its own dialect's tables: the command catalog (spellings), the routine
    naming convention and the spellings of neutral names (`neutral`: input patterns, settings)
    (pure data, no syntax tree): one definition for both sides."""
    return {f"mcc.compiler.{dialect}.catalog", f"mcc.compiler.{dialect}.naming",
            f"mcc.compiler.{dialect}.neutral"}


def backend_violations(path: Path) -> list[str]:
    rel = path.relative_to(ROOT).as_posix()
    own = path.relative_to(ROOT / "backends").parts[0].removesuffix(".py")
    bad = []
    for name in imports(path):
        if not is_module(name) or name.startswith("mcc.backends"):
            continue
        if name in BACKEND_ALLOWED or name in own_tables(own) or name == f"mcc.compiler.{own}":
            continue
        if (rel, name) in KNOWN_EXCEPTIONS:
            continue
        bad.append(f"{rel} imports {name}")
    return bad


@pytest.mark.parametrize("path", modules("backends"), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_backends_depend_only_on_the_ir_and_profiles(path):
    assert backend_violations(path) == []


@pytest.mark.parametrize("dialect", DIALECTS)
def test_frontends_do_not_import_the_driver_cli_or_backends(dialect):
    bad = [f"{p.relative_to(ROOT)} imports {name}"
           for p in modules(f"compiler/{dialect}") for name in imports(p)
           if name.startswith(("mcc.compiler.driver", "mcc.cli", "mcc.backends"))]
    assert bad == []


def test_compiler_does_not_import_the_cli():
    bad = [f"{p.relative_to(ROOT)} imports {name}" for p in modules("compiler") for name in imports(p)
           if name.startswith("mcc.cli")]
    assert bad == []


def test_known_exceptions_still_exist():
    """An exception that no longer happens must leave the list, so the list only shrinks."""
    stale = [pair for pair in KNOWN_EXCEPTIONS if pair[1] not in imports(ROOT / pair[0])]
    assert stale == []
