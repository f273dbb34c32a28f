"""The layers of the toolchain, kept by import-linter contracts (pyproject.toml,
`[tool.importlinter]`; docs/ARCHITECTURE.md, "Layers"). This test runs `lint-imports`, so CI does:

- backends depend on the IR and its vocabulary, the profiles (and the homing model read from them,
  compiler/homing.py), diagnostics and spans, and their own modules; each backend may read its own
  dialect's command catalog, routine naming and neutral-name tables (pure data). They never import
  a frontend's parser, syntax tree, lowering or checks, nor the driver, the simulator, the CLI, the
  language server, the link or the debugger (direct imports, inside functions too);
- frontends (compiler/<dialect>/) never import the driver, the CLI or a backend, not even through
  another module;
- the compiler never imports the CLI, not even through another module.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent.parent


def contracts() -> dict[str, dict]:
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    return {c["id"]: c for c in config["tool"]["importlinter"]["contracts"]}


def test_the_import_contracts_are_kept():
    exe = Path(sys.executable).parent / "lint-imports"
    done = subprocess.run([str(exe), "--no-cache"], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]
    assert "0 broken" in done.stdout


def test_the_backend_contract_forbids_every_other_top_level_package():
    """A new top-level package is outside the backends' layer until the contract says otherwise, as
    the hand-written allow-list of mcc.compiler modules that this contract replaced was."""
    packages = {f"mcc.{p.parent.name}" for p in ROOT.glob("*/__init__.py")} - {"mcc.backends"}
    forbidden = set(contracts()["backends-on-the-ir"]["forbidden_modules"])
    assert packages <= forbidden


def test_the_contracts_cover_every_frontend():
    from mcc.compiler import dialects

    frontends = {f"mcc.compiler.{name}" for name in dialects.DIALECTS}
    assert frontends <= set(contracts()["frontends-not-driver"]["source_modules"])
