"""A lint rule is one module whose docstring is its page (issue 26), found by its package.

compiler/lint/rules/<package>/<code>_<name>.py: the registry reads the code's facts from the
docstring without importing the module (compiler/codes.py), `@rule` takes the code from the
module's name, and `rules.load(dialect)` imports only that dialect's package and the rules of every
dialect (envelope), so a check of MCode files never imports the Arcus or X150 rules.
"""

from __future__ import annotations

import importlib
import json
import subprocess
import sys

import pytest
from module_pages import page_of

from mcc.compiler import codes
from mcc.compiler.lint.rules import RULES, load_all

MODULES = codes.rule_modules()
load_all()


def test_every_rule_module_is_a_registered_rule_and_every_rule_has_a_module() -> None:
    assert sorted(MODULES) == sorted(RULES)
    for code, path in MODULES.items():
        assert RULES[code].check.__module__.rpartition(".")[2] == path.stem or RULES[code].voice is not None, code


@pytest.mark.parametrize("code", sorted(MODULES))
def test_the_docstring_is_the_page_and_names_the_module(code: str) -> None:
    path = MODULES[code]
    info = page_of(code, path)
    package = path.parent.name
    assert info.kind.value == "lint" and info.dialects
    assert package == "envelope" or info.dialects == (package,), f"{path.name} is in the {package} package"
    module = importlib.import_module(f"mcc.compiler.lint.rules.{package}.{path.stem}")
    assert module.__doc__ == info.page()


def test_a_page_is_described_once(tmp_path) -> None:
    """A code described in compiler/codes/*.toml and by a rule module is refused."""
    package = tmp_path / "mcode"
    package.mkdir()
    page = codes.registry().get("M301").page()
    (package / "m301_position_read_while_moving.py").write_text(f'r"""{page}"""\n', encoding="utf-8")
    found = codes.rule_modules(tmp_path)
    assert list(found) == ["M301"]
    assert codes.read_rule_page(found["M301"]) == codes.registry().get("M301")
    (package / "m302_position_read_while_moving.py").write_text(f'r"""{page}"""\n', encoding="utf-8")
    with pytest.raises(ValueError, match="file name"):
        codes.read_rule_page(codes.rule_modules(tmp_path)["M302"])


LOADED = """
import json, sys
from mcc.compiler.codes import registry
from mcc.compiler import driver
driver.check_file("clean.mxt", text="VA Q1\\nPR Q1\\n")
checked = sorted(m for m in sys.modules if m.startswith("mcc.compiler.lint.rules."))
pages_read = len(registry().codes) - {toml_codes}
from mcc.compiler.config import Settings
from mcc.compiler.lint import engine
engine.lint_text("p.mxt", "VA Q1\\nPR Q1\\n", Settings())
linted = sorted(m for m in sys.modules if m.startswith("mcc.compiler.lint.rules."))
print(json.dumps([checked, pages_read, linted]))
"""


def test_a_check_imports_no_rule_and_a_lint_of_mcode_only_the_mcode_rules() -> None:
    toml_codes = len(codes.registry().names()) - len(MODULES) - len(codes.rule_modules(codes.CHECKS_DIR))
    out = subprocess.run([sys.executable, "-c", LOADED.format(toml_codes=toml_codes)], capture_output=True,
                         text=True, check=True).stdout
    checked, pages_read, linted = json.loads(out)
    assert checked == [] and pages_read == 0, (checked, pages_read)
    packages = {name.split(".")[4] for name in linted}
    assert packages == {"mcode", "envelope", "shared"}, packages
    assert not [name for name in linted if ".arcus" in name or ".x150" in name]


def test_every_rule_package_is_shipped() -> None:
    """pyproject.toml lists the packages explicitly: a rule package missing there is missing from
    an installed mcc."""
    from conftest import ROOT
    from mcc.compiler import toml

    project = toml.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    listed = set(project["tool"]["setuptools"]["packages"])
    packages = {"mcc.compiler.lint.rules"} | {f"mcc.compiler.lint.rules.{p.parent.name}"
                                              for p in (ROOT / "compiler" / "lint" / "rules").glob("*/__init__.py")}
    assert packages <= listed, sorted(packages - listed)
