"""Drive set-up left out of a conversion (issue 24, docs/decisions/0019-drive-setup-dropped.md).

MCode's run and hold currents set the motor current only (lexium-mcode.txt L5134 RC, L3077 HC); the
X150 has no command for the motor current (parker-x150.md, "Command Summary" L5615-L5850) and the
Arcus PMX-4EX-SA drives an external stepper driver by pulse, direction and enable outputs
(arcus-pmx-4ex-sa.txt L299-L307), which holds the current setting, so a conversion leaves them out with warning G051 and lists them at the top of the
output; `cross.drop-drive-setup = false` refuses them as before."""

from __future__ import annotations

import pytest

import conversion

from mcc.backends import drive_setup
from mcc.compiler import config, dialects, driver
from mcc.compiler.ir_names import SETTINGS


# RC=75 and HC=10 as in lexium-mcode.txt L5147 (RC=75) and L3077-L3090 (HC 0-100 %); VI=400 so
# that X150, which starts moves from standstill, ends them within 1 ms of the source (X216, L662-L666)
CURRENTS = "RC=75\nHC=10\nVI=400\nPG 100\nMR 5120\nH\nE\nPG\n"


def compile_to(text: str, target: str, settings=None):
    return driver.compile_file("fixture.mxt", "mcode", target, text=text, settings=settings)


def by_code(result, code: str) -> list[int]:
    return [d.span.line for d in result.diagnostics if d.code == code]


@pytest.mark.parametrize("target", ["x150", "arcus"])
def test_currents_are_left_out_with_a_warning_and_listed(target: str) -> None:
    """lexium-mcode.txt L5134 (RC: the motor run current, 1-100 %) and L3077 (HC: the hold current):
    no motion, output, print, variable or time depends on them, and the target sets the motor
    current on the drive: the program converts, G051 names lines 1 and 2, and the output's first
    comment lines list both settings."""
    result = compile_to(CURRENTS, target)
    assert not result.has_errors, [d.message for d in result.diagnostics]
    assert by_code(result, "G051") == [1, 2]
    assert all(d.severity.value == "warning" for d in result.diagnostics if d.code == "G051")
    text = result.listing.text
    assert f"{dialects.get(target).comment}   line 1: run_current" in text
    assert f"{dialects.get(target).comment}   line 2: hold_current" in text
    statements = [line for line in text.splitlines() if not line.startswith(dialects.get(target).comment)]
    assert not any("75" in line or "RC" in line for line in statements), statements
    # the output checks clean in its own dialect
    again = driver.compile_file(f"out{conversion.extension(target)}", target, text=text)
    assert not again.has_errors, [d.message for d in again.diagnostics]


@pytest.mark.parametrize("target", ["x150", "arcus"])
def test_the_configuration_key_keeps_the_refusal(target: str) -> None:
    """`cross.drop-drive-setup = false` ([tool.mcc]) turns the drop back into the refusal on the
    setting's line (G003), as before the decision."""
    loaded = config.parse("[tool.mcc]\ncross.drop-drive-setup = false\n", "/tmp/pyproject.toml")
    assert not loaded.diagnostics
    assert loaded.settings.drop_drive_setup is False
    result = compile_to(CURRENTS, target, loaded.settings)
    assert by_code(result, "G003") == [1, 2]
    assert not by_code(result, "G051")


def test_the_configuration_key_is_checked() -> None:
    """A value that is not a boolean, and an unknown key under `cross`, are configuration errors."""
    loaded = config.parse('[tool.mcc.cross]\ndrop-drive-setup = "no"\nother = 1\n', "/tmp/pyproject.toml")
    assert sorted(d.code for d in loaded.diagnostics) == ["G102", "G103"]
    assert loaded.settings.drop_drive_setup is True
    assert config.parse("[tool.mcc]\n", "/tmp/pyproject.toml").settings.drop_drive_setup is True


def test_a_setting_read_back_is_kept() -> None:
    """`PR RC` prints the run current (lexium-mcode.txt L5134: RC is readable): leaving RC=75 out
    would change the print, so the setting stays and the backend refuses it on its line."""
    program = "RC=75\nPG 100\nPR RC\nE\nPG\n"
    result = compile_to(program, "arcus")
    assert 1 in by_code(result, "G003")
    assert not by_code(result, "G051")


def test_the_same_dialect_keeps_its_settings() -> None:
    """MCode to MCode writes RC and HC (lexium-mcode.txt L5147): nothing is left out."""
    result = compile_to(CURRENTS, "mcode")
    assert not by_code(result, "G051")
    assert "RC=75" in result.listing.text


def test_only_drive_set_up_is_marked() -> None:
    """The set of drive-only settings is data (ir_names.SETTINGS). RC and HC are; the hold-current
    delay HT is not, because MP and MV stay active through the HT and MT delays (lexium-mcode.txt
    L4207, L4429), and neither are debounce, encoder or settling settings, which change timing or
    motion."""
    assert SETTINGS["run_current"].drive_only and SETTINGS["hold_current"].drive_only
    for name in ("hold_delay", "settle_time", "input_debounce", "encoder_enable", "stall_factor"):
        assert not SETTINGS[name].drive_only, name
    assert drive_setup.droppable("run_current", "x150")
    assert not drive_setup.droppable("run_current", "mcode")


def test_hold_delay_stays_refused() -> None:
    """HT=100 (lexium-mcode.txt L3237, the hold current delay) is not left out: the moving flags
    include it (L4207), so X150 refuses it on its line as before."""
    result = compile_to("HT=100\nPG 100\nMR 5120\nH\nE\nPG\n", "x150")
    assert 1 in by_code(result, "G003")
