"""The Arcus family: the PMX-2ED-SA, ACE-SDE and DMX-ETH profiles of the PMX-4EX-SA's standalone
language (docs/dialects/arcus.md, "Family"). Each fixture in tests/arcus/family/ was written for
these tests from its manual (the lines cite pages); the manuals are not read here."""

from __future__ import annotations

from pathlib import Path

import pytest

from mcc.compiler import driver, profiles

FAMILY = Path(__file__).parent / "family"
FIXTURES = {"pmx-2ed-sa": "pmx2ed_two_programs.prg", "ace-sde": "ace_sde_latch.prg", "dmx-eth": "dmx_eth_focuser.prg"}


def check(text: str, profile: str, name: str = "prog.prg") -> list:
    return driver.check_file(name, "arcus", profiles.load(profile), text).diagnostics


def codes(text: str, profile: str) -> list[str]:
    return [d.code for d in check(text, profile)]


@pytest.mark.parametrize("profile", sorted(FIXTURES))
def test_fixture_checks_clean_under_its_profile(mcc, profile: str) -> None:
    """PMX-2ED-SA p.60-62 (Table 10.0), ACE-SDE p.72-75 (Table 9.0): every statement of the
    fixtures is one of the product's; `mcc check --profile` finds nothing."""
    result = mcc("check", "--profile", profile, str(FAMILY / FIXTURES[profile]))
    assert result.returncode == 0, result.stdout + result.stderr
    assert "No problems found in 1 file." in result.stdout


@pytest.mark.parametrize("profile, budget", [("pmx-2ed-sa", 1275), ("ace-sde", 1785), ("dmx-eth", 7650)])
def test_program_memory_is_the_products(profile: str, budget: int) -> None:
    """2ED p.42 §7.19.1 "1,275 assembly lines"; ACE p.47 §6.21.1 "1785 assembly lines"; the
    DMX-ETH's 7650 from a real program's header (profile note). A program above the budget is
    A201 with the product's number."""
    lines = budget // 2 + 10  # V1=V1+1 is 2 assembly lines (the profile's V_OP)
    text = "V1=0\n" + "V1=V1+1\n" * lines + "END\n"
    found = [d for d in check(text, profile) if d.code == "A201"]
    assert found and f"{budget}" in found[0].message, [d.message for d in check(text, profile)]
    small = "V1=0\n" + "V1=V1+1\n" * 10 + "END\n"
    assert "A201" not in codes(small, profile)


@pytest.mark.parametrize("profile, bad, good, shown", [
    ("pmx-2ed-sa", "V64", "V0", "V0-V63"),      # 2ED p.44 §7.19.6
    ("ace-sde", "V0", "V100", "V1-V100"),       # ACE p.49 §6.21.6
    ("dmx-eth", "V101", "V100", "V1-V100"),
])
def test_variables_are_the_products(profile: str, bad: str, good: str, shown: str) -> None:
    """The variable range is the profile's `[arcus] variables`, named in A103."""
    found = [d for d in check(f"{bad}=1\nEND\n", profile) if d.code == "A103"]
    assert found and shown in found[0].message and profile in found[0].message
    assert "A103" not in codes(f"{good}=1\nEND\n", profile)


@pytest.mark.parametrize("profile, line", [("pmx-2ed-sa", "Z1000"), ("pmx-2ed-sa", "HSPDU=100"),
                                           ("ace-sde", "Y1000"), ("ace-sde", "WAITY"), ("dmx-eth", "V1=PY")])
def test_axes_are_the_products(profile: str, line: str) -> None:
    """2ED p.5 (2 axes, X and Y); ACE p.5 (single axis, X): another axis letter is A129."""
    assert codes(f"{line}\nEND\n", profile) == ["A129"]


def test_prg_blocks_are_the_siblings_and_counted_by_the_profile() -> None:
    """PRG n exists on the siblings (2ED p.61, ACE p.74), not on the PMX-4EX-SA (one program
    counter, L1635: A121 naming the products that have it); the count is `[arcus] programs`
    (2ED p.42 §7.19: two)."""
    text = "PRG 0\nX1\nEND\nPRG 1\nX2\nEND\n"
    assert codes(text, "pmx-2ed-sa") == []
    on_4ex = check(text, "pmx-4ex-sa")
    assert [d.code for d in on_4ex if d.severity.value == "error"] == ["A121", "A121"]
    assert "PMX-2ED-SA" in on_4ex[0].message and "ACE-SDE" in on_4ex[0].message
    too_many = check("PRG 0\nX1\nEND\nPRG 2\nX2\nEND\n", "pmx-2ed-sa")
    assert [d.code for d in too_many] == ["A104"] and "programs 0-1" in too_many[0].message
    assert codes("PRG 0\nSR1=1\nSR2=1\nEND\n", "ace-sde") == ["A119"]


@pytest.mark.parametrize("line", ["ARCP0:100:30000", "TR=100", "EO1=1", "SYNXO"])
def test_a_4ex_statement_on_the_ace_sde_names_where_it_exists(line: str) -> None:
    """ACE p.72-75 (Table 9.0) has no ARC, TR, EO<bit> or SYN<axis>O: each is A121, a statement of
    another controller of the family, not an unknown word."""
    found = check(f"{line}\nEND\n", "ace-sde")
    assert [d.code for d in found] == ["A121"] and "PMX-4EX-SA" in found[0].message


@pytest.mark.parametrize("line", ["DEC=100", "TOC=10", "LHOMEX+", "V1=AI1", "SR0=1", "STORE"])
def test_a_sibling_statement_on_the_4ex_names_where_it_exists(line: str) -> None:
    """DEC (2ED p.60), TOC (p.62), LHOME (p.61), AI in a program (p.60), SR (p.61), STORE (p.62)
    are the siblings'; on the PMX-4EX-SA they are A121 (AI, SR and STORE are host commands there,
    A102)."""
    expected = "A102" if line.split("=")[-1].startswith(("AI", "SR", "STORE")) or line == "STORE" else "A121"
    found = codes(f"{line}\nEND\n", "pmx-4ex-sa")
    assert found == [expected] or (line.startswith("SR") and found == ["A121"]), found


def test_eo_enables_the_motor_and_converts_to_other_dialects(mcc, tmp_path: Path) -> None:
    """EO "can be used to enable or disable the current to the motor" (ACE p.31 §6.5; 2ED p.26
    §7.5): with `[arcus] enable_outputs = "drive"` EO=1 is a drive enable, which MCode writes as
    DE=1 and X150 as ST0; the ACE-SDE itself gets EO=1 back (it has no EO1)."""
    source = tmp_path / "enable.prg"
    source.write_text("HSPD=20000\nACC=300\nEO=1\nX1000\nWAITX\nEO=0\nEND\n")
    to_mcode = mcc("compile", "--profile", "ace-sde", str(source), "--target", "mcode")
    assert to_mcode.returncode == 0, to_mcode.stdout + to_mcode.stderr
    assert "DE=1" in to_mcode.stdout and "DE=0" in to_mcode.stdout
    to_x150 = mcc("compile", "--profile", "ace-sde", str(source), "--target", "x150")
    assert to_x150.returncode == 0, to_x150.stdout + to_x150.stderr
    assert "ST0" in to_x150.stdout and "ST1" in to_x150.stdout
    same = mcc("compile", "--profile", "ace-sde", str(source))
    assert same.returncode == 0 and "EO=1" in same.stdout.splitlines() and "EO1" not in same.stdout


def test_eo_on_two_axes_is_one_enable_per_axis() -> None:
    """2ED p.26 Table 7.1: bit 0 enables X, bit 1 enables Y; EO=1 enables X and disables Y."""
    from mcc.compiler import ir

    result = driver.check_file("p.prg", "arcus", profiles.load("pmx-2ed-sa"), "EO=1\nEND\n")
    ops = [op for _, block in result.analysis.module.blocks() for op in block.ops]
    assert [(op.axis, op.on.value) for op in ops if isinstance(op, ir.DriveEnable)] == [("X", 1), ("Y", 0)]
    four = driver.check_file("p.prg", "arcus", profiles.load("pmx-4ex-sa"), "EO=1\nEND\n")
    assert not any(isinstance(op, ir.DriveEnable) for _, b in four.analysis.module.blocks() for op in b.ops)


def test_several_programs_compile_to_arcus_and_are_refused_elsewhere(mcc) -> None:
    """PRG blocks are written back as PRG blocks (2ED p.66 example 7); another dialect runs one
    program at a time, so the conversion is refused on each PRG line (G003)."""
    fixture = str(FAMILY / FIXTURES["pmx-2ed-sa"])
    same = mcc("compile", "--profile", "pmx-2ed-sa", fixture)
    assert same.returncode == 0, same.stdout + same.stderr
    lines = same.stdout.splitlines()
    assert lines[0] == "PRG 0" and "PRG 1" in lines and lines.count("END") == 2
    other = mcc("compile", "--profile", "pmx-2ed-sa", fixture, "--target", "mcode")
    output = other.stdout + other.stderr
    assert other.returncode == 1 and "G003" in output and "program 1 runs at the same time" in output


def test_format_writes_prg_with_a_space_as_the_manuals_do() -> None:
    """`PRG 0` (2ED p.61, ACE p.74 examples), like GOSUB n and SUB n."""
    from mcc.compiler.arcus.format import format_text

    assert format_text("prg0\nx1000\nEND\n", "p.prg", profiles.load("ace-sde")).splitlines()[:2] == ["PRG 0", "X1000"]


def test_motor_status_bits_of_the_siblings_are_not_the_4exs() -> None:
    """ACE p.39 Table 6.1 numbers the motor status bits otherwise than the PMX-4EX-SA (L720: bit 0
    accelerating; on the ACE-SDE bit 0 is constant speed): MSTX stays an Arcus register there
    (converting it is refused), and is the neutral motor_status on the PMX-4EX-SA."""
    from mcc.compiler import ir

    def reads(profile: str) -> list:
        result = driver.check_file("p.prg", "arcus", profiles.load(profile), "V1=MSTX\nEND\n")
        return [op.value for _, block in result.analysis.module.blocks() for op in block.ops]

    assert isinstance(reads("ace-sde")[0], ir.DeviceRef)
    assert isinstance(reads("pmx-4ex-sa")[0], ir.Status) and reads("pmx-4ex-sa")[0].meaning == "motor_status"
