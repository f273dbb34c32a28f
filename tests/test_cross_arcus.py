"""Arcus PMX-4EX-SA programs into MCode and X150 (issue 24): the output and input banks, the enable
outputs. Each conversion is validated by simulation (driver.compile_file verifies by default); what
stays refused names its line and what to do."""

from __future__ import annotations

import conversion
from mcc.compiler import driver, profiles
from mcc.sim.interpreter import simulate
from mcc.sim.scenario import Scenario
from mcc.sim.verify import check_translation

body = conversion.body


def convert(text: str, target: str, source: str = "arcus"):
    return conversion.convert(text, source, target)


def written(text: str, target: str, source: str = "arcus") -> list[str]:
    """The statements written (conversion.body of the checked output)."""
    return body(conversion.written(text, source, target), target)


def outputs_set(text: str, dialect: str, profile: str) -> dict[int, int]:
    module = driver.check_file(f"o{conversion.extension(dialect)}", dialect, None, text).analysis.module
    trace = simulate(module, Scenario(), None, profiles.load(profile))
    return {e.data["output"]: e.data["value"] for e in trace.events if e.kind == "output"}


# -- output banks ---------------------------------------------------------------------------------

def test_a_bank_value_sets_the_outputs_each_product_has() -> None:
    """arcus-pmx-4ex-sa.txt L752: DO is the 8 outputs as one value; lexium-mcode.txt L851: OT sets
    the 3 outputs. The simulator sets the profile's `[machine.outputs] count` outputs, not eight
    everywhere."""
    assert outputs_set("DO=1\n", "arcus", "pmx-4ex-sa") == {1: 1, **{n: 0 for n in range(2, 9)}}
    assert outputs_set("PG 1\nOT=1\nE\nPG\n", "mcode", "lmd-c") == {1: 1, 2: 0, 3: 0}


def test_an_arcus_output_bank_is_an_x150_pattern_of_six_outputs() -> None:
    """arcus-pmx-4ex-sa.txt L1951-L1953: DO=7 turns DO1-DO3 on "and rest off"; parker-x150.md
    L2731-L2753: O sets the outputs by pattern, 1-6 (L2779). DO=7 is O111000: outputs 4-6 go off as
    on the PMX-4EX-SA; the validation compares the six outputs both have."""
    out = written("DO=7\nDELAY=100\nDO=0\n", "x150")
    assert out[out.index("O111000"):out.index("O111000") + 3] == ["O111000", "T0.1", "O000000"]


def test_an_arcus_bank_value_that_turns_on_an_output_x150_lacks_is_refused_on_its_line() -> None:
    """arcus-pmx-4ex-sa.txt L752 (DO7 and DO8 exist) and parker-x150.md L2779 (outputs 1-6): DO=64
    turns output 7 on, which X150 cannot: G003 on its line, naming the output."""
    _, errors = convert("DO=1\nDO=64\n", "x150")
    assert [(code, line) for code, line, _ in errors] == [("G003", 2)]
    assert "output 7" in errors[0][2]


def test_an_arcus_output_bank_stays_ot_on_mcode() -> None:
    """arcus-pmx-4ex-sa.txt L752 and lexium-mcode.txt L4669: DO=5 is OT=5; validated with the three
    outputs the drive has."""
    assert "OT=5" in written("DO=5\nDELAY=100\nDO=0\n", "mcode")


# -- input banks ----------------------------------------------------------------------------------

DI_255 = "IF DI=255\nDO=1\nENDIF\n"


def test_an_arcus_input_bank_compared_with_a_number_is_an_x150_input_pattern() -> None:
    """arcus-pmx-4ex-sa.txt L797 and L1905-L1906: DI reads the levels of DI1-DI8, 255 when none is
    triggered (sunk to ground); parker-x150.md L2120: an X150 input is active at a low level by
    default, so level 1 reads 0. `IF DI=255` tests inputs 1-8 inactive: IF(IN_00000000)."""
    out = written(DI_255, "x150")
    assert out[out.index("IF(IN_00000000)"):out.index("IF(IN_00000000)") + 3] == \
        ["IF(IN_00000000)", "O100000", "NIF"]


def test_an_arcus_input_bank_is_refused_on_mcode_which_has_four_inputs() -> None:
    """lexium-mcode.txt L3433: IN reads inputs 1-4 (IN=255 is never true there); arcus L797: DI
    reads eight. The comparison tests inputs 5-8, which the drive lacks: refused on line 1."""
    _, errors = convert(DI_255, "mcode")
    assert [(code, line) for code, line, _ in errors] == [("G003", 1)]
    assert "input 5" in errors[0][2]


def test_the_validation_finds_an_input_bank_read_over_another_width() -> None:
    """The MCode program `BR ...,IN<>255` (lexium-mcode.txt L3433: 4 inputs, at most 15) was written
    for `IF DI=255` and passed, as both lower to the same operations: a translation into another
    dialect is now always simulated, and a bank reads the product's own inputs."""
    mcode = "PG 1\nBR Z0,IN<>255\nOT=1\nLB Z0\nPG\n"
    problem = check_translation("d.prg", "arcus", DI_255, mcode, "mcode")
    assert "output 1" in problem


# -- enable outputs -------------------------------------------------------------------------------

def warnings(result) -> list[tuple[str, int]]:
    return [(d.code, d.span.line) for d in result.diagnostics if d.severity.value == "warning"]


def test_an_arcus_enable_mask_is_the_mcode_drive_enable_of_its_axis() -> None:
    """arcus-pmx-4ex-sa.txt L748 and L2142 (`EO=3` turns the first two enable outputs on, bit 0 the
    X axis's driver); lexium-mcode.txt L2362-L2378: DE=1 enables the drive's bridge. The program
    moves X: its bit is DE; bit 1 (axis Y, never used) is a driver the MCode drive does not have."""
    out = written("EO=3\nX1000\nEO=2\n", "mcode")
    assert out.index("DE=1") < out.index("MA 1000") < out.index("DE=0")


def test_an_arcus_enable_mask_computed_at_run_time_is_its_bit_in_mcode() -> None:
    """arcus-pmx-4ex-sa.txt L2148 (`EO=V2`, the enable outputs from a variable) and lexium-mcode.txt
    L1262 (`&`, bitwise AND): the X axis's enable is bit 0 of V2, `DE=<V2>&1`."""
    out = written("IF V1=1\nEO=V2\nENDIF\n", "mcode")
    assert any(line.startswith("DE=") and line.endswith("&1") for line in out)


def test_an_arcus_enable_mask_is_x150_st0_or_st1() -> None:
    """arcus-pmx-4ex-sa.txt L748; parker-x150.md L4010-L4031: ST0 enables the drive, ST1 shuts it
    down (buffered, saveable in a sequence)."""
    out = written("EO=1\nX1000\nEO=0\n", "x150")
    assert [line for line in out if "ST" in line] == ["1ST0", "1ST1"]


def test_an_arcus_enable_mask_computed_at_run_time_is_refused_on_x150() -> None:
    """parker-x150.md L4013: ST takes n = 1 or 0, a number: a mask from a variable (arcus L2148) has
    no X150 form; refused on its line."""
    _, errors = convert("EO=V2\n", "x150")
    assert [(code, line) for code, line, _ in errors] == [("G003", 1)]
    assert "constant only" in errors[0][2]


def test_the_enable_of_an_axis_never_moved_is_left_out_with_a_warning() -> None:
    """arcus-pmx-4ex-sa.txt L748 (EO2 enables axis Y's driver, L2170 `EO2=V2`): a one-axis target
    drives X only (its DE, lexium-mcode.txt L2362; ST, parker-x150.md L4010); Y is never moved, so
    its enable is left out, G060 on its line. The X enable (EO1) is written."""
    for target, enable in (("mcode", "DE=1"), ("x150", "1ST0")):
        result, errors = convert("EO1=1\nEO2=V2\nX1000\n", target)
        assert not errors, errors
        assert warnings(result) == [("G060", 2)]
        assert enable in body(result.listing.text, target)


def test_an_enable_before_the_moves_does_not_choose_the_drive_axis() -> None:
    """The axis the program moves is the target's drive (docs/CROSS.md): `EO2=1` before `X1000`
    leaves Y's enable out and converts the move, instead of refusing X as a second axis."""
    result, errors = convert("EO2=1\nX1000\n", "mcode")
    assert not errors, errors
    assert warnings(result) == [("G060", 1)]
    assert "MA 1000" in body(result.listing.text, "mcode")


def test_a_moved_second_axis_is_still_refused_naming_it() -> None:
    """A one-axis MCode drive cannot move Y as well as X: refused at the Y move, naming the axis."""
    _, errors = convert("EO=3\nX1000\nY1000\n", "mcode")
    assert [(code, line) for code, line, _ in errors] == [("G003", 3)]
    assert "axis Y" in errors[0][2]


# -- abort ----------------------------------------------------------------------------------------

def test_an_abort_where_no_move_can_run_is_written_as_nothing() -> None:
    """arcus-pmx-4ex-sa.txt L1497-L1502: ABORT "immediately stops all the motor if in motion"; after
    WAITX (L2706) the axis stands still, so it stops nothing. MCode has no abort statement (ESC from
    the host, lexium-mcode.txt) and X150 never saves K in a sequence (parker-x150.md): nothing is
    written for it, and the rest converts."""
    source = "X1000\nWAITX\nABORT\nDO=1\n"
    assert "OT=1" in written(source, "mcode")
    out = written(source, "x150")
    assert "O100000" in out and not any(line.endswith("K") for line in out)


def test_an_abort_while_a_move_may_run_stays_refused() -> None:
    """arcus-pmx-4ex-sa.txt L694, L1497: ABORT stops a move in progress without deceleration (an
    Arcus move does not wait for its end, WAIT does: L2706); neither target can store that. Refused
    on its line."""
    for target in ("mcode", "x150"):
        _, errors = convert("X1000\nABORT\n", target)
        assert [(code, line) for code, line, _ in errors] == [("G003", 2)], (target, errors)


def test_an_arcus_bank_read_into_a_variable_is_refused_on_mcode() -> None:
    """arcus-pmx-4ex-sa.txt L797 and L752: DI and DO are eight bits; lexium-mcode.txt L3433 and L851:
    IN is four inputs, OT three outputs. `V3=DI` would hold another number (255 with nothing
    connected on the PMX-4EX-SA, at most 15 on the drive): refused on its line."""
    _, errors = convert("V3=DI\nV4=DO\n", "mcode")
    assert [(code, line) for code, line, _ in errors] == [("G003", 1), ("G003", 2)]
    assert "8 inputs" in errors[0][2] and "8 outputs" in errors[1][2]


# -- a speed in a variable ------------------------------------------------------------------------

def test_an_arcus_speed_in_a_variable_goes_through_a_variable_in_rev_per_s_on_x150() -> None:
    """arcus-pmx-4ex-sa.txt L2230-L2233: `HSPD=V1` sets the high speed in pulses/s from V1;
    parker-x150.md L4542 (V in rev/s) and L4569-L4573 (decimal VARn): a free VARn holds V1 per
    revolution, then V(VARn)."""
    out = written("HSPD=10000\nV1=2500\nHSPD=V1\nX1000\n", "x150")
    at = out.index("VAR1=2500")
    assert out[at + 1:at + 3] == ["VAR50=VAR1/4000", "V(VAR50)"]


def test_a_bank_read_whose_uses_keep_only_the_drive_bits_is_written_for_mcode() -> None:
    """arcus-pmx-4ex-sa.txt L797 (DI: raw levels of DI1-DI8) and lexium-mcode.txt L3433 (IN: raw
    levels of inputs 1-4): `V1=DI` used only as `V1&6` (inputs 2 and 3) has the same value on both."""
    out = written("V1=DI\nV2=V1&6\nIF V2=2\nDO=1\nENDIF\n", "mcode")
    assert any(line.endswith("=IN") for line in out)


# -- what stays refused says what to do ------------------------------------------------------------

def test_a_second_axis_on_mcode_says_to_compile_each_axis_on_its_own() -> None:
    """arcus-pmx-4ex-sa.txt L570 (four axes); an MCode drive is one axis (lexium-mcode.txt, one
    motor per drive): the refusal names the axis and says what to do."""
    _, errors = convert("X1000\nY1000\n", "mcode")
    assert [(code, line) for code, line, _ in errors] == [("G003", 2)]
    assert "axis Y" in errors[0][2] and "each axis on its own" in errors[0][2]


def test_an_output_x150_lacks_is_named() -> None:
    """arcus-pmx-4ex-sa.txt L752 (DO1-DO8) and parker-x150.md L2779 (outputs 1-6): DO7=1 is refused
    naming output 7; DO6=1 is O with X for outputs 1-5."""
    _, errors = convert("DO7=1\nDO6=1\n", "x150")
    assert [(code, line) for code, line, _ in errors] == [("G003", 1)]
    assert "output 7" in errors[0][2]
    assert "OXXXXX1" in written("DO6=1\n", "x150")


def test_an_mcode_input_bank_compared_with_a_number_is_tested_input_by_input_on_arcus() -> None:
    """lexium-mcode.txt L3433-L3435: IN is the raw levels of inputs 1-4 (IN=5: inputs 1 and 3 high);
    arcus-pmx-4ex-sa.txt L797, L1905: DI is eight levels, 255 with nothing connected, so `DI=5` would
    never hold. The output tests DI1=1, DI2=0, DI3=1, DI4=0."""
    out = written("PG 1\nBR L1,IN=5\nO1=1\nLB L1\nE\nPG\n", "arcus", source="mcode")
    tests = [line for line in out if line.startswith("IF DI")]
    assert tests == ["IF DI1=1", "IF DI2=0", "IF DI3=1", "IF DI4=0"]
    assert not any("DI=" in line for line in out)
