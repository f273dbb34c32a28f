"""A rule's or a check's module is its page (decisions 0016 and 0021): the checks both kinds of
module share, in one place (tests/lint/test_rule_modules.py, tests/checks/test_check_registry.py)."""

from __future__ import annotations

import ast
from pathlib import Path

from mcc.compiler import codes


def page_of(code: str, path: Path) -> codes.CodeInfo:
    """The page of `code` read from its module `path`, after checking that the module's docstring is
    that page in the form `mcc explain` prints, that the module is named for the code, and that the
    registry answers the same page for the code."""
    text = path.read_text(encoding="utf-8")
    page = codes.module_docstring(text)
    assert page == ast.get_docstring(ast.parse(text), clean=False), f"{path.name}: start it with r\"\"\"<the page>"
    info = codes.parse_page(page, path.name)
    assert info.page() == page, f"{path.name}: the page is not in the form `mcc explain` prints (docs/LINT.md)"
    assert path.stem == f"{code.lower()}_{info.name.replace('-', '_')}"
    assert codes.registry().get(code) == info
    return info
