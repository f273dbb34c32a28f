"""The rule registry and the code registry agree, and every rule's documented bad example is
reported and its good example is not: the pages in docs/rules/ are checked examples."""

from __future__ import annotations

import pytest

from helpers import codes
from mcc.compiler import config, dialects
from mcc.compiler.codes import registry
from mcc.compiler.lint.rules import load_all

EXTENSIONS = {name: d.extensions[0] for name, d in dialects.DIALECTS.items()}
RULE_CODES = sorted(load_all())
# Lint rules own the 3xx numbers of each dialect (docs/ARCHITECTURE.md); a frontend may also emit
# lint-kind codes of its own (X102), which are not rules.
LINT_CODES = sorted(i.code for i in registry() if i.kind.value == "lint" and i.dialects and i.code[1] == "3")


def test_every_lint_code_has_one_rule_and_every_rule_a_code() -> None:
    assert RULE_CODES == LINT_CODES


@pytest.mark.parametrize("code", RULE_CODES)
def test_rule_metadata_comes_from_the_code_registry(code: str) -> None:
    from mcc.compiler.lint.rules import RULES

    rule = RULES[code]
    info = registry().get(code)
    assert info.kind.value == "lint"
    assert set(rule.dialects) == set(info.dialects)
    assert rule.name == info.name
    assert info.summary and info.explanation.strip() and info.bad.strip() and info.good.strip()
    assert info.manual, f"{code} must cite the manual lines it is grounded in"
    assert "L" in info.explanation, f"{code}'s explanation should cite manual lines"


def example_path(code: str) -> str:
    info = registry().get(code)
    return f"example{EXTENSIONS[info.dialects[0]]}"


def example_settings(code: str) -> config.Settings | None:
    """The configuration a rule's examples are checked with (the envelope rules need an envelope)."""
    info = registry().get(code)
    if not info.config:
        return None
    loaded = config.parse(info.config, "pyproject.toml")
    assert not loaded.diagnostics, f"{code}'s example configuration is invalid"
    return loaded.settings


@pytest.mark.parametrize("code", RULE_CODES)
def test_documented_bad_example_is_reported(code: str) -> None:
    info = registry().get(code)
    assert code in codes(info.bad, example_path(code), example_settings(code))


@pytest.mark.parametrize("code", RULE_CODES)
def test_documented_good_example_is_not_reported(code: str) -> None:
    info = registry().get(code)
    assert code not in codes(info.good, example_path(code), example_settings(code))


@pytest.mark.parametrize("code", ["G101", "G104"])
def test_suppression_examples(code: str) -> None:
    info = registry().get(code)
    assert code in codes(info.bad)
    assert code not in codes(info.good)


@pytest.mark.parametrize("code", ["G102", "G103"])
def test_configuration_examples(code: str, tmp_path) -> None:
    info = registry().get(code)
    for which, expected in (("bad", True), ("good", False)):
        path = tmp_path / which / "pyproject.toml"
        path.parent.mkdir()
        path.write_text(getattr(info, which).lstrip(), encoding="utf-8")
        loaded = config.parse(path.read_text(), str(path))
        assert (code in [d.code for d in loaded.diagnostics]) is expected, (which, loaded.diagnostics)


def test_fixable_flag_matches_the_rules() -> None:
    """A code marked fixable in the registry offers a fix on its bad example, and only then."""
    from helpers import lint

    for code in RULE_CODES:
        info = registry().get(code)
        diags = [d for d in lint(info.bad, example_path(code)) if d.code == code]
        assert any(d.fix for d in diags) == info.fixable, code
