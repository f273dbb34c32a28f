"""The generated parsers of the grammars (grammars/generate.py, decision 0023): they are what the
grammars and the installed Lark generate, they parse as Lark's own parser of the grammar does, and
the check path never imports the `lark` package (issue 26: a small `mcc check` is a whole process)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import lark
import pytest

from mcc.grammars import generate, lark_runtime

ROOT = Path(__file__).resolve().parent.parent
PROGRAMS = sorted(p for p in (ROOT / "samples").rglob("*") if p.suffix in (".mxt", ".prg", ".x150"))
GRAMMAR_OF = {".mxt": "mcode", ".prg": "arcus", ".x150": "x150"}


def test_regenerating_gives_the_committed_files() -> None:
    """Each generated file is exactly what `python -m mcc.grammars.generate` writes from the grammars
    and the installed Lark (the state numbering is canonical, so this holds in every process)."""
    for name, text in generate.expected_files().items():
        committed = (generate.HERE / name).read_text(encoding="utf-8")
        assert committed == text, f"grammars/{name} is out of date: run `python -m mcc.grammars.generate`"


def test_every_grammar_has_its_tables() -> None:
    assert generate.grammar_names() == ["arcus", "mcode", "x150"]
    for name in generate.grammar_names():
        assert (generate.HERE / f"{name}_tables.py").is_file()


def shape(node):
    """A tree as nested tuples: (rule name, children) and (token type, text, line, column). A
    grammar's own parser names rules by tokens, the loaded one by strings: the names are compared."""
    if hasattr(node, "children"):
        return str(node.data), tuple(shape(child) for child in node.children)
    return node.type, str(node), node.line, node.column


def outcome(parse, text: str, start: str):
    """What a parse gives: the tree's shape or the exception's class name, line and column."""
    try:
        return shape(parse(text, start=start))
    except Exception as exc:  # both parsers raise their own copies of Lark's exception classes
        return type(exc).__name__, getattr(exc, "line", None), getattr(exc, "column", None)


@pytest.mark.parametrize("path", PROGRAMS, ids=lambda p: p.name)
def test_the_generated_parser_parses_as_lark_does(path: Path) -> None:
    """The samples, and each of their lines with a stray character in it, give the same tree or the
    same error from the generated parser as from the `lark` package's parser of the same grammar."""
    name = GRAMMAR_OF[path.suffix]
    tables = __import__(f"mcc.grammars.{name}_tables", fromlist=["DATA"])
    generated = lark_runtime.load(tables.DATA, tables.MEMO)
    reference = lark.Lark(generate.grammar_text(name), **generate.OPTIONS)
    text = path.read_text(encoding="utf-8")
    assert outcome(generated.parse, text, "start") == outcome(reference.parse, text, "start")
    for number, line in enumerate(text.splitlines()[:60]):
        for variant in (line, line[: len(line) // 2] + "(" + line[len(line) // 2:], line + " ="):
            line_text = variant + "\n"
            assert outcome(generated.parse, line_text, "line") == outcome(reference.parse, line_text, "line"), \
                (number, variant)


def test_the_check_path_does_not_import_lark(tmp_path: Path) -> None:
    """A check of each dialect, with and without a syntax error (recovery line by line), loads the
    generated parser and never the `lark` package."""
    programs = {"ok.mxt": "VM=20000\nMR 2000\n", "bad.mxt": "VM=20000\nMR 2000 (\n",
                "ok.prg": "HSPD=20000\nX1000\nEND\n", "bad.prg": "V1=(2\nX1000\nEND\n",
                "ok.x150": "1V5\n1G\n", "bad.x150": "1V5\n1G (\n"}
    for name, text in programs.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    probe = ("import sys, json\nfrom mcc.compiler import driver\ncodes = {}\n"
             f"for name in {sorted(programs)!r}:\n"
             f"    result = driver.check_file({str(tmp_path)!r} + '/' + name, None, None)\n"
             "    codes[name] = sorted({d.code for d in result.diagnostics if d.code[1:] == '001'})\n"
             "print(json.dumps([codes, sorted(sys.modules)]))")
    codes, loaded = json.loads(subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                                              check=True, timeout=120).stdout)
    assert codes == {"ok.mxt": [], "bad.mxt": ["M001"], "ok.prg": [], "bad.prg": ["A001"],
                     "ok.x150": [], "bad.x150": ["X001"]}
    assert "mcc.grammars.lark_runtime" in loaded
    assert not [module for module in loaded if module == "lark" or module.startswith("lark.")]
