"""The simulator, the optimizer and the virtual device's machine never ask which dialect a module
came from: what a program means is in the IR and the product profile (issue 22, "one model of each
product"), and what a target can write is in the table of dialects (compiler/dialects.py).

A dialect's name may appear in prose and as a label (a trace says which dialect it ran), but not
as a value the code compares with or looks up: no string literal that is a dialect's name, and no
comparison of a `.dialect` with a literal or a table (`module.dialect in PRIVATE`). Comparing two
`.dialect`s (is this profile for this file's dialect?) is matching, not deciding, and allowed.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from mcc.compiler import dialects

ROOT = Path(__file__).resolve().parent.parent
NEUTRAL = sorted([*ROOT.glob("sim/*.py"), *ROOT.glob("compiler/opt/*.py"), ROOT / "link/device/machine.py"])


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


def test_the_check_finds_what_it_forbids(tmp_path):
    sample = tmp_path / "x.py"
    sample.write_text('TYPES = {"mcode": 1}\nif module.dialect in PRIVATE:\n    pass\n'
                      'if profile.dialect == module.dialect:\n    pass\n')
    assert findings(sample) == ["line 1: the dialect name 'mcode'",
                                "line 2: a comparison of `.dialect` with a name or a table"]
