"""Shared code never names a dialect (issue 26, "a dialect has one home and one plugin interface").

The simulator, the optimizer and the virtual device's machine never ask which dialect a module came
from: what a program means is in the IR and the product profile (issue 22, "one model of each
product"). Everything else that is one dialect's (its facts, its preprocessor, host protocol,
virtual device and editor support) is reached through its registered `Dialect`
(compiler/dialects.py; each dialect declares its own in compiler/<dialect>/dialect.py), so no
product file outside the dialects' own folders and files names one.

A dialect's name may appear in prose and as a label (a trace says which dialect it ran), but not
as a value the code compares with or looks up: no string literal that is a dialect's name, and no
comparison of a `.dialect` with a literal or a table (`module.dialect in PRIVATE`). Comparing two
`.dialect`s (is this profile for this file's dialect?) is matching, not deciding, and allowed.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from mcc.compiler import dialects, ir_names

ROOT = Path(__file__).resolve().parent.parent
# the test suite, benchmarks, environments, and the editor packages (TypeScript; their node_modules
# hold third-party Python once the extension's tests are installed)
NOT_PRODUCT = ("tests", "bench", ".venv", "build", "dist", "editors")


def own(path: Path) -> bool:
    """Whether `path` is one dialect's own: a folder or file named after it (compiler/mcode/,
    backends/arcus/, link/x150.py, lsp/mcode_editor.py, compiler/x150/dialect.py, ...)."""
    parts = path.relative_to(ROOT).parts
    return any(name in part for part in parts for name in dialects.names())


def product_files() -> list[Path]:
    """Every Python file of the product outside the dialects' own folders and files."""
    found = []
    for path in ROOT.rglob("*.py"):
        parts = path.relative_to(ROOT).parts
        if parts[0] in NOT_PRODUCT or "__pycache__" in parts or "node_modules" in parts or parts[0].endswith(".egg-info") or own(path):
            continue
        found.append(path)
    return sorted(found)


# The registration needs no exemption: compiler/dialects.py lists the modules that declare the
# dialects (REGISTERED, module paths), and each declaration is in its dialect's own folder.
REGISTRATION = ROOT / "compiler/dialects.py"
NEUTRAL = product_files()


def findings(path: Path) -> list[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    names = set(dialects.names())
    bad = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and node.value in names:
            bad.append(f"line {node.lineno}: the dialect name {node.value!r}")
        if isinstance(node, ast.Compare):
            sides = [node.left, *node.comparators]
            if any(isinstance(s, ast.Attribute) and s.attr == "dialect" for s in sides) and any(
                    isinstance(s, (ast.Constant, ast.Set, ast.Tuple, ast.List, ast.Dict))
                    or isinstance(s, ast.Name) and s.id.isupper() for s in sides):
                bad.append(f"line {node.lineno}: a comparison of `.dialect` with a name or a table")
    return sorted(bad, key=lambda line: int(line.split(":")[0].split()[1]))


@pytest.mark.parametrize("path", NEUTRAL, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_no_dialect_name_decides_anything(path):
    assert findings(path) == []


def test_the_scan_covers_the_shared_code():
    """The files issue 26 counted dialect names in, and the registration, are scanned; a dialect's
    own files are not."""
    scanned = {p.relative_to(ROOT).as_posix() for p in NEUTRAL}
    assert {"compiler/ir_names.py", "lsp/completion.py", "cli/link.py", "link/protocols.py", "compiler/selection.py",
            "sim/interpreter.py", "compiler/opt/outline.py", REGISTRATION.relative_to(ROOT).as_posix()} <= scanned
    assert not {"compiler/mcode/dialect.py", "lsp/x150_editor.py", "link/arcus.py", "backends/mcode.py"} & scanned


@pytest.mark.parametrize("name", dialects.names())
def test_every_dialect_provides_the_plugin_interface(name):
    """What shared code asks of a dialect's modules is there (compiler/dialects.py documents it)."""
    from mcc.lsp.editor import Editor, editor_of

    dialect = dialects.get(name)
    link = dialect.load_link()
    assert all(callable(getattr(link, hook, None)) for hook in ("Protocol", "explain_code", "describe", "upload"))
    assert callable(getattr(dialect.load_device(), "make", None))
    assert isinstance(editor_of(name), Editor) and editor_of(name).indexer
    preprocessor = dialect.load_preprocessor()
    assert preprocessor is None or callable(preprocessor.directive_lines)
    for ext in dialect.image_extensions:
        assert dialects.from_image(f"machine{ext.upper()}") is dialect
    assert dialect.settings and dialect.settings <= set(ir_names.SETTINGS)


def test_every_setting_belongs_to_a_dialect():
    """Each neutral setting is some dialect's (ir_names.SETTINGS; the dialects declare which)."""
    assert all(info.dialects for info in ir_names.SETTINGS.values())


def test_the_check_finds_what_it_forbids(tmp_path):
    sample = tmp_path / "x.py"
    sample.write_text('TYPES = {"mcode": 1}\nif module.dialect in PRIVATE:\n    pass\n'
                      'if profile.dialect == module.dialect:\n    pass\n')
    assert findings(sample) == ["line 1: the dialect name 'mcode'",
                                "line 2: a comparison of `.dialect` with a name or a table"]
