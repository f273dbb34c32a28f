"""An acceleration set after the deceleration, converted to X150 (issue 23, fuzz finding mcode seed 2432).

X150 has one ramp: it decelerates at the acceleration A (parker-x150.md L199, "A ... acceleration and
deceleration"). MCode keeps A and D apart (lexium-mcode.txt, A and D: "D ... deceleration", set
independently). `A=100000 D=100000 A=1000000 MA -25600` decelerates at 100000 in MCode and at
1000000 on the X150: the output ended its move 0.43 s early and only the validation (S010) kept it
from being written. The backend now refuses the later A on its own line (G003), before validation."""

from __future__ import annotations

from mcc.compiler import driver


def compile_mcode(tmp_path, text: str):
    path = tmp_path / "ramp.mxt"
    path.write_text(text)
    return driver.compile_file(str(path), "mcode", "x150")


def test_an_acceleration_that_leaves_another_deceleration_is_refused_on_its_line(tmp_path) -> None:
    result = compile_mcode(tmp_path, "PG 100\nVI=100\nA=100000\nD=100000\nA=1000000\nMA -25600\nH\nE\nPG\n")
    errors = [d for d in result.diagnostics if d.severity.value == "error"]
    assert [(d.code, d.span.line) for d in errors] == [("G003", 5)], [(d.code, d.message) for d in errors]
    assert "decelerates at the acceleration" in errors[0].message and "100000" in errors[0].message


def test_an_acceleration_followed_by_the_same_deceleration_is_written_and_validated(tmp_path) -> None:
    """A=D again after the change: X150's single A is exact (and the validation agrees)."""
    result = compile_mcode(tmp_path, "PG 100\nVI=100\nA=100000\nD=100000\nA=1000000\nD=1000000\nMA -25600\nH\nE\nPG\n")
    assert not [d for d in result.diagnostics if d.severity.value == "error"], \
        [(d.code, d.message) for d in result.diagnostics]
    assert result.listing is not None and "A" in result.listing.text
