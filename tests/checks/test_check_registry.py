"""Every semantic code says where it is reported, and every check is a registered module (issue 26,
docs/decisions/0021).

A whole-program check is `compiler/checks/<dialect>/<code>_<name>.py`: its docstring is its code's
page (read by the code registry without importing it), `@check` registers it under the code of its
module's name for its package's dialect. The other 1xx codes, reported while a statement is read
against the catalog or while the structure is built, are described in compiler/codes/*.toml with
`emitted`, the files that report them. The source is scanned for every code a call reports (`.add("M106",
...)`, `report(..., code="X110")`): a code reported in a file its registry entry does not name, or
named there but no longer reported, fails.
"""

from __future__ import annotations

import ast
import importlib
import re
from pathlib import Path

import pytest
from module_pages import page_of

from mcc.compiler import checks, codes
from mcc.compiler.diagnostics import Kind

ROOT = Path(codes.PACKAGE_ROOT)
SEMANTIC = re.compile(r"[A-Z]1\d\d\Z")  # the semantic checks (docs/ARCHITECTURE.md, "Diagnostics")
MODULES = codes.rule_modules(codes.CHECKS_DIR)
CHECKS = checks.load_all()
# the product's Python: not the tests, benchmarks or editor packages (whose node_modules hold
# third-party Python once the extension's tests are installed), nor a virtual environment
# (build/ and dist/: what `pip install .` leaves, copies of the product, not the product)
SOURCES = [p for p in sorted(ROOT.rglob("*.py"))
           if p.relative_to(ROOT).parts[0] not in ("tests", "bench", "editors", ".venv", "build", "dist")
           and not {".venv", "node_modules"} & set(p.parts)]


def reported_codes(path: Path, own: str | None = None) -> set[str]:
    """The codes a call in `path` reports: the first argument of a call, or its `code=` keyword,
    when that is a code literal (`diags.add("M106", ...)`, `ctx.report(span, msg, code="M129")`);
    in a check module, `ctx.report` without `code=` reports the module's `own` code."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Call):
            if (own and isinstance(node.func, ast.Attribute) and node.func.attr == "report"
                    and not any(k.arg == "code" for k in node.keywords)):
                found.add(own)
            for arg in [*node.args[:1], *(k.value for k in node.keywords if k.arg == "code")]:
                if isinstance(arg, ast.Constant) and isinstance(arg.value, str) and codes.CODE.fullmatch(arg.value):
                    found.add(arg.value)
    return found


def reported_where() -> dict[str, set[str]]:
    where: dict[str, set[str]] = {}
    owner = {path: code for code, path in MODULES.items()}
    for path in SOURCES:
        for code in reported_codes(path, owner.get(path)):
            where.setdefault(code, set()).add(path.relative_to(ROOT).as_posix())
    return where


WHERE = reported_where()


def semantic(info: codes.CodeInfo) -> bool:
    """A dialect's semantic check: a 1xx code of one dialect, or a code of a registered check (M323)."""
    return info.kind is Kind.SEMANTIC and bool(info.dialects) and (SEMANTIC.match(info.code) or info.code in MODULES)


def test_every_semantic_code_reported_is_registered_with_where_it_is_reported() -> None:
    registry = codes.registry()
    for code, files in sorted(WHERE.items()):
        info = registry.get(code)
        assert info is not None, f"{code} is reported in {sorted(files)} but not registered (compiler/codes/*.toml)"
        if semantic(info):
            assert set(info.emitted) == files, (f"{code} is reported in {sorted(files)}; its registry entry says "
                                                f"{sorted(info.emitted)}: correct `emitted`")


def test_every_registered_semantic_code_says_where_it_is_reported() -> None:
    for code in codes.registry().names():
        info = codes.registry().get(code)
        if semantic(info):
            assert info.emitted, f"{code}: `emitted` names no file"
            assert code in WHERE, f"{code} is registered as reported in {info.emitted}, but nothing reports it"


def test_the_scan_finds_what_it_looks_for(tmp_path) -> None:
    sample = tmp_path / "x.py"
    sample.write_text('diags.add("M106", span, "m")\nctx.report(span, "m", code="X110")\n'
                      'BUDGET = frozenset({"M116"})\nmessage = "see M129"\n', encoding="utf-8")
    assert reported_codes(sample) == {"M106", "X110"}
    sample.write_text('ctx.report(span, "m")\n', encoding="utf-8")
    assert reported_codes(sample, "M127") == {"M127"} and reported_codes(sample) == set()


def test_every_check_module_is_a_registered_check_and_every_check_has_a_module() -> None:
    assert sorted(MODULES) == sorted(CHECKS)
    for code, path in MODULES.items():
        assert CHECKS[code].run.__module__.rpartition(".")[2] == path.stem, code
        assert CHECKS[code].dialect == path.parent.name, code


@pytest.mark.parametrize("code", sorted(MODULES))
def test_the_docstring_is_the_page_and_names_the_module(code: str) -> None:
    path = MODULES[code]
    info = page_of(code, path)
    assert info.kind is Kind.SEMANTIC and info.dialects == (path.parent.name,), path.name
    assert codes.registry().get(code).emitted == (path.relative_to(ROOT).as_posix(),)
    module = importlib.import_module(f"mcc.compiler.checks.{path.parent.name}.{path.stem}")
    assert module.__doc__ == info.page()


@pytest.mark.parametrize("code", sorted(CHECKS))
def test_a_check_reports_its_own_code_and_names_the_others(code: str) -> None:
    """The codes a check names in `also` are described in compiler/codes/ (their page is shared
    with the stage that reports them too), and the check reports no other code."""
    found = CHECKS[code]
    path = MODULES[code]
    assert reported_codes(path) <= set(found.codes), f"{path.name} reports a code it does not name in `also`"
    for other in found.also:
        info = codes.registry().get(other)
        assert other not in MODULES and info is not None, other
        assert path.relative_to(ROOT).as_posix() in info.emitted, f"{other}'s `emitted` does not name {path.name}"


def test_needs_are_facts_of_the_dialect() -> None:
    for found in CHECKS.values():
        assert set(found.needs) <= set(checks.FACTS[found.dialect]), found.code


def test_a_check_that_reports_an_unnamed_code_fails() -> None:
    from mcc.compiler.diagnostics import Diagnostics
    from mcc.compiler.span import SourceFile, Span

    program = checks.Program("mcode", SourceFile("t.mxt", ""), None, None, None)
    found = CHECKS["M106"]
    context = checks.Context(program, found, Diagnostics())
    with pytest.raises(ValueError, match="also"):
        context.report(Span("t.mxt", 1, 1, 1, 2, 0, 1), "m", code="M101")


def test_the_check_packages_are_installed() -> None:
    """A wheel (and pre-commit's installation from the repository) holds only the packages
    pyproject.toml lists: a check package left out fails every check there with G001."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib

    listed = set(tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools"]["packages"])
    packages = {"mcc." + ".".join(p.parent.relative_to(ROOT).parts) for p in codes.CHECKS_DIR.rglob("__init__.py")}
    assert packages <= listed, f"add to [tool.setuptools] packages: {sorted(packages - listed)}"
