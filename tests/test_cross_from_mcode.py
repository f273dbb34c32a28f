"""MCode programs converted to X150 and to the Arcus PMX-4EX-SA (issue 24): constructs the target has
under another form are converted, and each conversion is validated by simulation (driver.compile_file
verifies by default), so a program written behaves like its source."""

from __future__ import annotations

from mcc.compiler import driver

EXT = {"mcode": ".mxt", "x150": ".x150", "arcus": ".prg"}
COMMENT = {"mcode": "'", "x150": ";", "arcus": ";"}


def convert(text: str, target: str, source: str = "mcode"):
    result = driver.compile_file(f"fixture{EXT[source]}", source, target, text=text)
    errors = [(d.code, d.span.line if d.span else None, d.message) for d in result.diagnostics
              if d.severity.value == "error"]
    return result, errors


def written(text: str, target: str, source: str = "mcode") -> str:
    result, errors = convert(text, target, source)
    assert not errors, errors
    out = result.listing.text
    again = driver.compile_file(f"out{EXT[target]}", target, text=out)
    assert not again.has_errors, [d.message for d in again.diagnostics if d.severity.value == "error"]
    return out


def body(text: str, target: str) -> list[str]:
    """The statements written, without the conversion header's comments."""
    return [line for line in text.splitlines() if line.strip() and not line.startswith(COMMENT[target])]


# -- a polling loop into X150 -----------------------------------------------------------------------

POLL_AND_CALL = "PG 100\nLB G1\nCL K1, I2=1\nBR G1\nLB K1\nRT\nE\nPG\n"


def test_polling_loop_with_a_conditional_call_converts_to_x150() -> None:
    """lexium-mcode.txt L612-L621 (CL K1, I2=1 then BR G1: call K1 while input 2 is high, forever)
    is X150 `L` .. `N` around `IF(IN_X1) XR2 NIF` (parker-x150.md L2328: L without a count repeats
    continuously). The X150 frontend lowers an endless L to a plain jump back, so the simulator sees
    the output poll as the source does, and the validation agrees."""
    out = written(POLL_AND_CALL, "x150")
    assert body(out, "x150")[2:6] == ["L", "IF(IN_X1)", "XR2", "NIF"]


def test_endless_x150_loop_has_no_counter() -> None:
    """parker-x150.md L2328: `L` or `L0` repeats the commands continuously; a counted `L3` keeps
    its hidden counter (the frontend's %L variables)."""
    endless = driver.check_file("f.x150", "x150", text="XE1\nXD1\nL0\nT1\nN\nXT\n").analysis.module
    counted = driver.check_file("f.x150", "x150", text="XE1\nXD1\nL3\nT1\nN\nXT\n").analysis.module
    assert not [name for name in endless.variables if name.startswith("%L")]
    assert [name for name in counted.variables if name.startswith("%L")] == ["%L1"]
