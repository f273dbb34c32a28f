"""`lint --fix` never changes what the device does, and settles.

For every dialect, over the samples, the samples with mistakes the fixes know put in (glued
numbers, `=<`, lower-case commands, a missing XE, unused `noqa` comments) and generated programs:
one `--fix` run settles (a second finds nothing to do), the compiled program is the same before
and after, and when nothing compiles (the text has errors) the IR and the errors are unchanged:
a safe fix never removes an error. Plus the cases that were not safe before: X102 on TX text, X126 inside a definition,
M121/M124 on `LT1000`, a marked-safe fix that changes the program, fixes that never settle.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import EXTENSIONS, dialects_with, run_mcc, sample_files
from test_format_arcus import program as arcus_program
from test_format_mcode import program as mcode_program
from test_format_x150 import stream as x150_stream
from mcc.compiler import driver
from mcc.compiler.config import Settings
from mcc.compiler.diagnostics import Diagnostic, Edit, Fix, Kind, Severity
from mcc.compiler.ir_compare import equivalent
from mcc.compiler.lint import engine, fixes
from mcc.compiler.span import SourceFile

DIALECTS = dialects_with("backend")
PROPERTY = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def fix_once(path: str, text: str, unsafe: bool = False) -> fixes.FixRun:
    options = engine.Options(fix=True, unsafe_fixes=unsafe)
    _, diags = engine.lint_text(path, text, Settings())
    return engine.fix_text(path, text, diags, Settings(), options)


def compiled(path: str, text: str):
    result = driver.compile_file(path, None, None, None, text)
    module = result.analysis.module if result.analysis is not None else None
    text_out = result.listing.text if result.listing is not None and not result.has_errors else None
    errors = sorted(d.code for d in result.diagnostics if d.severity is Severity.ERROR)
    return text_out, module, errors


def assert_fix_properties(path: str, text: str) -> str:
    run = fix_once(path, text)
    assert not run.error, run.error
    fixed = run.text
    again = fix_once(path, fixed)
    assert again.text == fixed and again.fixed == 0, "a second --fix changed the text again"
    out_before, module_before, errors_before = compiled(path, text)
    out_after, module_after, errors_after = compiled(path, fixed)
    if out_before is not None:
        assert out_after == out_before, "a safe fix changed the compiled program"
    elif fixed != text:
        # nothing compiled before: only changes of form, which keep the IR and every error
        assert module_before is not None and module_after is not None and equivalent(module_before, module_after)
        assert errors_after == errors_before, "a safe fix removed an error"
    return fixed


# the samples, as they are and with mistakes the fixes know ----------------------------------------

@pytest.mark.parametrize("path", [p for d in DIALECTS for p in sample_files(d)], ids=lambda p: p.name)
def test_samples_fix_safely(path: Path) -> None:
    assert_fix_properties(path.name, path.read_text(encoding="utf-8"))


MCODE_GLUE = re.compile(r"\b(MA|MR|PG|SL|VM|VI|HM|EX|LT) (\d+)")
X150_ERASE = re.compile(r"\b\d*XE\d+ ")


def mistakes(dialect: str, text: str, data) -> str:
    """Put into `text` mistakes that a fix knows how to repair."""
    lines = text.split("\n")
    for _ in range(data.draw(st.integers(1, 4))):
        index = data.draw(st.integers(0, max(0, len(lines) - 1)))
        line = lines[index]
        kind = data.draw(st.integers(0, 2))
        if dialect == "mcode":
            if kind == 0:
                line = MCODE_GLUE.sub(r"\1\2", line, count=1)
            elif kind == 1:
                line = line.replace("<=", "=<")
            elif line.strip() and "'" not in line and "`" not in line and "\"" not in line:
                line += "  ' noqa: M301"
        elif dialect == "x150":
            if kind == 0:
                line = line.lower()
            elif kind == 1:
                line = X150_ERASE.sub("", line, count=1)
            elif line.strip() and ";" not in line:
                line += " ; noqa: X301"
        elif line.strip() and ";" not in line:
            line += " ; noqa: A301"
        lines[index] = line
    return "\n".join(lines)


@pytest.mark.parametrize("dialect", DIALECTS)
@PROPERTY
@given(data=st.data())
def test_samples_with_mistakes_fix_safely(dialect: str, data) -> None:
    path = data.draw(st.sampled_from(sample_files(dialect)))
    text = mistakes(dialect, path.read_text(encoding="utf-8"), data)
    assert_fix_properties(path.name, text)


# generated programs (the formatter's generators) ---------------------------------------------------

GENERATORS = {"mcode": mcode_program, "x150": x150_stream, "arcus": arcus_program}


def generated(dialect: str):
    return GENERATORS[dialect]()


@pytest.mark.parametrize("dialect", DIALECTS)
@PROPERTY
@given(data=st.data())
def test_generated_programs_fix_safely(dialect: str, data) -> None:
    text = data.draw(generated(dialect))
    text = mistakes(dialect, text, data)
    assert_fix_properties(f"g{EXTENSIONS[dialect]}", text)


# the cases that were not safe ----------------------------------------------------------------------

def test_x150_case_fix_keeps_tx_text() -> None:
    _, diags = engine.lint_text("t.x150", "1tx7,1,0,gap=\n", Settings())
    x102 = [d for d in diags if d.code == "X102"]
    assert x102 and x102[0].fix.edits[0].text == "1TX7,1,0,gap="
    assert fix_once("t.x150", "1tx7,1,0,gap=\n").text == "1TX7,1,0,gap=\n"
    assert not [d for d in engine.lint_text("t.x150", "1TX7,1,0,gap=\n", Settings())[1] if d.code == "X102"]


def test_x150_case_fix_keeps_quoted_text() -> None:
    assert fix_once("t.x150", '1dtxt"Hello_World"\n').text == '1DTXT"Hello_World"\n'
    assert fix_once("t.x150", '1tx7,1,0,Gap= 1g\n').text == "1TX7,1,0,Gap= 1G\n"


def test_x126_fix_converges_inside_a_definition() -> None:
    text = "XD1 / G / XD5 / G / XT\n"
    first = fix_once("s.x150", text)
    assert first.text == "XE1 XD1 / G / XD5 / G / XT\n" and not first.error
    assert fix_once("s.x150", first.text).text == first.text
    x126 = [d for d in engine.lint_text("s.x150", first.text, Settings())[1] if d.code == "X126"]
    assert x126 and x126[0].fix is None  # still reported, but nothing to insert inside sequence 1


def test_glued_value_is_one_answer_for_m121_and_m124() -> None:
    _, diags = engine.lint_text("g.mxt", "LT1000\n", Settings())
    assert [d.code for d in diags] == ["M124"]
    run = fix_once("g.mxt", "LT1000\n")
    assert run.text == "LT 1000\n"
    assert compiled("g.mxt", "LT1000\n")[0] == compiled("g.mxt", "LT 1000\n")[0] == "LT=1000\n"
    assert [d.code for d in engine.lint_text("g.mxt", "LT\n", Settings())[1]] == ["M121"]


def test_fix_is_safe_compares_compiled_programs() -> None:
    same = fixes.Version("p.mxt", "MA 100\n", None), fixes.Version("p.mxt", "MA 100   ' move\n", None)
    assert fixes.fix_is_safe(*same)
    other = fixes.Version("p.mxt", "MA 100\n", None), fixes.Version("p.mxt", "MA 200\n", None)
    assert not fixes.fix_is_safe(*other)
    broken = fixes.Version("p.mxt", "MA 100\nMX 5\n", None), fixes.Version("p.mxt", "MA 100\n", None)
    assert not fixes.fix_is_safe(*broken)  # removing an error by deleting a line is not a change of form


def fake_lint(fix: Fix):
    """A relint that reports `fix` on every text (for the engine's own tests)."""
    def relint(text: str) -> list[Diagnostic]:
        span = SourceFile("p.mxt", text).span(0, 0)
        return [Diagnostic("M320", Severity.WARNING, Kind.LINT, "test", span, fix=fix)]
    return relint


def make(text: str) -> fixes.Version:
    return fixes.Version("p.mxt", text, None)


def test_a_marked_safe_fix_that_changes_the_program_needs_unsafe_fixes() -> None:
    text = "MA 100\n"
    source = SourceFile("p.mxt", text)
    change = Fix("make it 200", (Edit(source.span(3, 6), "200"),))  # marked safe, is not
    diags = [Diagnostic("M320", Severity.WARNING, Kind.LINT, "test", source.span(0, 2), fix=change)]
    relint = lambda t: []  # noqa: E731 - nothing left after the change
    run = fixes.fix_until_stable(text, diags, relint, make, unsafe=False)
    assert run.text == text and run.fixed == 0
    assert not run.diagnostics[0].fix.safe and "would change the compiled program" in run.diagnostics[0].fix.description
    diags = [Diagnostic("M320", Severity.WARNING, Kind.LINT, "test", source.span(0, 2), fix=change)]
    run = fixes.fix_until_stable(text, diags, relint, make, unsafe=True)
    assert run.text == "MA 200\n" and run.fixed == 1


def test_only_the_fix_that_changes_the_program_is_held_back() -> None:
    text = "MA 100\nMR 5\nMA 300\n"
    source = SourceFile("p.mxt", text)
    comment = [Fix(f"comment {i}", (Edit(source.span(end, end), f"  ' c{i}"),)) for i, end in ((0, 6), (1, 11))]
    change = Fix("make it 400", (Edit(source.span(15, 18), "400"),))
    fixes_offered = comment[:1] + [change] + comment[1:]
    diags = [Diagnostic("M320", Severity.WARNING, Kind.LINT, "test", source.span(0, 2), fix=f) for f in fixes_offered]
    run = fixes.fix_until_stable(text, diags, lambda t: [], make, unsafe=False)
    assert run.text == "MA 100  ' c0\nMR 5  ' c1\nMA 300\n" and run.fixed == 2


def test_fixes_that_never_settle_stop_with_g008_and_leave_the_text() -> None:
    grow = Fix("add a comment", (Edit(SourceFile("p.mxt", "").span(0, 0), "' x\n"),))
    text = "MA 100\n"
    run = fixes.fix_until_stable(text, fake_lint(grow)(text), fake_lint(grow), make, unsafe=False)
    assert run.error and "did not settle" in run.error and run.text == text


def test_a_fix_cycle_is_detected() -> None:
    text = "MA 100\n"
    source = SourceFile("p.mxt", text)
    one = Fix("spell it MA  100", (Edit(source.span(2, 3), "  "),))
    two = Fix("spell it MA 100", (Edit(source.span(2, 4), " "),))

    def relint(t: str) -> list[Diagnostic]:
        fix = two if "  " in t else one
        return [Diagnostic("M320", Severity.WARNING, Kind.LINT, "test", SourceFile("p.mxt", t).span(0, 0), fix=fix)]

    run = fixes.fix_until_stable(text, relint(text), relint, make, unsafe=False)
    assert run.error and "already produced" in run.error and run.text == text


def test_g008_is_reported_by_lint_and_the_file_is_left(tmp_path: Path, monkeypatch) -> None:
    path = tmp_path / "p.mxt"
    path.write_text("MA 100\n")
    monkeypatch.setattr(fixes, "fix_until_stable",
                        lambda text, *a, **k: fixes.FixRun(text, [], 0, "the fixes did not settle after 8 rounds"))
    outcome = engine.lint_file(str(path), Settings(), engine.Options(fix=True))
    assert [d.code for d in outcome.diagnostics] == ["G008"] and path.read_text() == "MA 100\n"


def test_unsafe_fixes_show_in_diff_only_when_asked(tmp_path: Path) -> None:
    path = tmp_path / "p.mxt"
    path.write_text("PG 1\nLB G1\n  H\nLB K9\n  E\nPG\n")  # K9 unused: deleting it is unsafe (M305)
    plain = run_mcc("lint", "--diff", "--select", "M305", str(path))
    assert "-LB K9" not in plain.stdout
    unsafe = run_mcc("lint", "--diff", "--unsafe-fixes", "--select", "M305", str(path))
    assert "-LB K9" in unsafe.stdout and path.read_text().count("LB K9") == 1
