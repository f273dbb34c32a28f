"""docs/rules/ is generated from the code registry: the committed pages must equal the generated
ones (regenerate with `python -m mcc.compiler.codes docs/rules`)."""

from __future__ import annotations

from pathlib import Path

from conftest import ROOT
from mcc.compiler.codes import registry, write_docs

RULES_DIR = ROOT / "docs" / "rules"


def test_committed_rule_pages_equal_the_generated_ones(tmp_path: Path) -> None:
    write_docs(tmp_path)
    generated = {p.name: p.read_text(encoding="utf-8") for p in tmp_path.glob("*.md")}
    committed = {p.name: p.read_text(encoding="utf-8") for p in RULES_DIR.glob("*.md")}
    hint = "docs/rules/ is stale: run `python -m mcc.compiler.codes docs/rules` and commit the result"
    assert sorted(committed) == sorted(generated), hint
    stale = [name for name in generated if committed[name] != generated[name]]
    assert not stale, f"{hint} (changed: {', '.join(stale[:10])})"


def test_every_code_has_a_page_and_the_index_links_it() -> None:
    index = (RULES_DIR / "README.md").read_text(encoding="utf-8")
    for info in registry():
        assert (RULES_DIR / f"{info.code}.md").is_file()
        assert f"[{info.code}]({info.code}.md)" in index


def test_explain_prints_the_page(mcc) -> None:
    result = mcc("explain", "M301")
    assert result.returncode == 0
    assert result.stdout == (RULES_DIR / "M301.md").read_text(encoding="utf-8")
