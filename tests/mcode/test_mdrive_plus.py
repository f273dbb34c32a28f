"""The MDrivePlus / MForce profile (`mdrive-plus`) and the migration of its programs to Lexium
profiles, end to end as a user runs them (`mcc check`, `mcc compile --source-profile`).

Sources (docs/dialects/mcode.md, "The MDrivePlus / MForce family"): application notes "Converting
MDrive MCode to Lexium MCode" ([conv]), "Configuring MDrive I/O: MCode Basics" ([io]), "Intro to
MCode: Basic Motion Commands" ([motion]); real programs in Dennis-van-Gils/python-dvg-devices and
greezybacon/mcontrol (the golden cases tests/golden/mcode/mdriveplus_*)."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from mcc.cli.commands import cli
from mcc.compiler import profiles
from mcc.compiler.mcode import catalog


def run(*args: str):
    return CliRunner().invoke(cli, list(args), catch_exceptions=False)


def write(tmp_path: Path, text: str, name: str = "prog.mxt") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_family_catalog_is_data():
    """[conv]: S1-S4 are the family's I/O set-up; [mctl] real programs declare `VA LO`, `VA BM`, label
    `LB AO`: those Lexium names are free on the family; [conv]: the analog input reads 10 bits."""
    cat = catalog.for_profile(profiles.load("mdrive-plus"))
    assert cat.family == "mdrive-plus" and cat.io_setup == "point"
    assert cat.lookup("S1") is not None and cat.lookup("S4") is not None and cat.lookup("S5") is None
    for name in ("AO", "BM", "DJ", "FS", "LS", "F1", "CF"):
        assert not cat.is_reserved(name, "3.0"), name
    assert cat.lookup("I5").entry.range == (0, 1023)
    assert catalog.for_profile(profiles.load("lmd-c")).lookup("I5").entry.range == (0, 4095)


def test_profile_markers_for_suggestion():
    """The `[detect] markers` a profile suggestion reads: per-point I/O set-up ([conv])."""
    markers = profiles.load("mdrive-plus").get("detect.markers")
    assert "S1=" in markers and all(isinstance(m, str) for m in markers)


def test_check_mdriveplus_program_clean(tmp_path):
    """[dvg] constructs: S1 from a variable, labels F1/F2, `A 8192` without `=`: clean on the family,
    M102/M104 on a Lexium profile."""
    text = "VA L1=3\nS1 = L1, 1, 0\nA 8192\nVA X=1\nPG 100\nLB F1\n S2=17,1,0\n X=I5\n E\nPG\n"
    path = write(tmp_path, text)
    result = run("check", "--profile", "mdrive-plus", path)
    assert result.exit_code == 0, result.output
    assert "No problems found" in result.output
    lexium = run("check", "--profile", "lmd-c", path)
    assert lexium.exit_code == 1 and "M102" in lexium.output and "M104" in lexium.output


def test_migration_converts_io_and_analog(tmp_path):
    """[conv]: S1-S4 become IS (input functions) / OS (output functions); the 10-bit reading becomes
    the 12-bit one divided by 4; sinking/sourcing is wiring on Lexium (warning M203)."""
    path = write(tmp_path, "S1=1,0,0\nS2=17,1,1\nPG 100\nLB SU\n HM 1\n H\n R1=I5\n PR R1\n E\nPG\n")
    scenario = write(tmp_path, "[analog]\n1 = 300\n", "analog.toml")
    out = tmp_path / "lexium.mxt"
    result = run("compile", "--source-profile", "mdrive-plus", "--profile", "lmd-o", "--inputs", scenario,
                 path, "-o", str(out))
    assert result.exit_code == 0, result.output
    text = out.read_text(encoding="utf-8").splitlines()
    assert text[:2] == ["IS=1,1,0", "OS=2,17,1"]
    assert "R1=I5/4" in text
    assert result.output.count("M203") == 2 and "sourcing" in result.output
    check = run("check", "--profile", "lmd-o", str(out))
    assert check.exit_code == 0, check.output


def test_migration_refuses_naming_the_line(tmp_path):
    """OL (I/O points 1-4 as a bank, [mctl]) has no Lexium equivalent; an S1 set-up computed at run
    time cannot choose IS or OS; encoder counts differ (2048 vs 4000 per revolution, [motion]):
    M202 on each line, exit 1, nothing written."""
    path = write(tmp_path, "VA L1=3\nS1=L1,0,0\nOL 5\nEE=1\nPG 100\n R1=C2\n E\nPG\n")
    out = tmp_path / "lexium.mxt"
    result = run("compile", "--source-profile", "mdrive-plus", "--profile", "lmd-c", path, "-o", str(out))
    assert result.exit_code == 1
    lines = {line.split(":")[1] for line in result.output.splitlines() if "M202" in line}
    assert lines == {"2", "3", "4", "6"}, result.output
    assert not out.exists()


def test_migration_is_validated_by_simulation(tmp_path):
    """The migration is simulated against the source like every compile: the analog scenario is
    given in the MDrivePlus's counts and read by the Lexium drive at the same voltage (x4)."""
    from mcc.cli.sim import load_scenarios
    from mcc.compiler import driver
    from mcc.sim.verify import check_translation

    path = write(tmp_path, "PG 100\nLB SU\n R1=I5*4\n PR R1\n E\nPG\n")
    scenarios = load_scenarios((write(tmp_path, "[analog]\n1 = 300\n", "analog.toml"),))
    source, target = profiles.load("mdrive-plus"), profiles.load("lmd-o")
    module = driver.check_file(path, "mcode", source).analysis.module
    good = "PG 100\nLB SU\nR1=I5/4*4\nPR R1\nE\nPG\n"
    assert check_translation(path, "mcode", module, good, "mcode", target, scenarios, source) == ""
    wrong = good.replace("I5/4*4", "I5*4")
    assert "1200" in check_translation(path, "mcode", module, wrong, "mcode", target, scenarios, source)


def test_source_profile_of_another_dialect_is_a_usage_error(tmp_path):
    path = write(tmp_path, "PG 100\n E\nPG\n")
    result = run("compile", "--source-profile", "pmx-4ex-sa", "--profile", "lmd-o", path)
    assert result.exit_code == 2 and "--source-profile" in result.output


def test_lint_takes_float_registers_from_the_program(tmp_path):
    """F1 is a user variable on an MDrivePlus (real programs declare `VA F1=410`, greezybacon/mcontrol
    mdrive_base.mxt): lint M308 (a float truncated, lexium-mcode.txt L2812) is for the Lexium float
    registers only."""
    path = write(tmp_path, "VA F1=410\nVA FS=0\nPG 100\nLB K1\n FS=F1+1\n PR FS\n E\nPG\nS\n' end\n")
    result = run("lint", "--profile", "mdrive-plus", path)
    assert "M308" not in result.output, result.output
    lexium = run("lint", "--profile", "lmd-c", path)
    assert "M104" in lexium.output


def test_family_command_without_public_source(tmp_path):
    """S5 (analog set-up in mcc's older table) has no public description: M102 says mcc cannot check it."""
    path = write(tmp_path, "S5=9,0\nPG 1\n E\nPG\n")
    result = run("check", "--profile", "mdrive-plus", path)
    assert result.exit_code == 1 and "M102" in result.output and "no public source" in result.output


def test_migration_back_to_the_family(tmp_path):
    """Lexium -> MDrivePlus: IS/OS become S<n> ([conv]); a Lexium function S1-S4 lack (12, capture;
    [io] lists 0-8, 11, 16-20), one point used as input and output, and the 12-bit analog reading,
    which the 10-bit one cannot give, are refused on their lines."""
    ok = write(tmp_path, "IS=2,1,0\nOS=1,17,1\nPG 100\nLB SU\n HM 1\n H\n E\nPG\n", "ok.mxt")
    result = run("compile", "--source-profile", "lmd-c", "--profile", "mdrive-plus", ok)
    assert result.exit_code == 0, result.output
    assert result.output.splitlines()[:2] == ["S2=1,0", "S1=17,1"]
    bad = write(tmp_path, "IS=1,12,0\nOS=1,17,1\nPG 100\nLB SU\n R1=I5\n E\nPG\n", "bad.mxt")
    refused = run("compile", "--source-profile", "lmd-c", "--profile", "mdrive-plus", bad)
    assert refused.exit_code == 1
    assert [line.split(":")[1] for line in refused.output.splitlines() if "M202" in line] == ["1", "1", "5"]


def test_migration_refuses_reading_an_output_point(tmp_path):
    """On an MDrivePlus I2 reads I/O point 2 even when it is an output; on a Lexium drive input 2 and
    output 2 are two pins ([conv]: "In the Lexium MDrive, the I/O points are fixed as inputs and outputs")."""
    path = write(tmp_path, "S1=0,0,0\nS2=17,1,0\nPG 100\nLB SU\n BR SU, I2=0\n E\nPG\n")
    result = run("compile", "--source-profile", "mdrive-plus", "--profile", "lmd-o", path)
    assert result.exit_code == 1 and ":5:" in next(l for l in result.output.splitlines() if "M202" in l)


def test_migration_validation_drives_the_analog_input(tmp_path):
    """Without scenarios, a migrated program that reads the analog input is also run with a reading
    (a third of the 10-bit full scale, plus one, [conv]) on both products: a conversion that forgot
    the scale is found."""
    from mcc.compiler import driver
    from mcc.sim.verify import check_translation

    path = write(tmp_path, "PG 100\nLB SU\n R1=I5\n PR R1\n E\nPG\n")
    source, target = profiles.load("mdrive-plus"), profiles.load("lmd-o")
    module = driver.check_file(path, "mcode", source).analysis.module
    good = "PG 100\nLB SU\nR1=I5/4\nPR R1\nE\nPG\n"
    assert check_translation(path, "mcode", module, good, "mcode", target, None, source) == ""
    found = check_translation(path, "mcode", module, good.replace("I5/4", "I5"), "mcode", target, None, source)
    assert "342" in found and "1368" in found


def test_lexium_io_setup_on_the_family_names_the_products(tmp_path):
    """IS/OS are Lexium's: "The S1-S4 command has been changed to Is for input setup and Os for
    output setup" ([conv]); on the family IS is M114 naming where it exists, not an undeclared name."""
    path = write(tmp_path, "IS=1,1,0\nPG 1\n E\nPG\n")
    result = run("check", "--profile", "mdrive-plus", path)
    assert result.exit_code == 1 and "M114" in result.output and "Lexium MDrive" in result.output
