"""Choosing the profile of each file (compiler/selection.py; docs/CONFIGURATION.md, "Choosing the
profile"): --profile, then a `mcc: profile=` comment at the top of the file, then
`per-file-profiles`, then `target`, then the dialect's default -- the same for `mcc check`,
`compile`, `lint` and the editor server; and the profile a failing file fits (G021)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mcc.compiler import config, driver, selection
from mcc.compiler.span import SourceFile

# A two-axis program with two PRG blocks (PMX-2ED-SA manual p.61-62, p.66): clean only as PMX-2ED-SA.
TWO_AXES = "PRG 0\nHSPD=1000\nX1000Y500\nWAITX\nEND\nPRG 1\nDO1=1\nEND\n"
# One axis and V100 (ACE-SDE manual p.49: V1-V100): clean as ACE-SDE or DMX-ETH, not PMX-2ED-SA.
ONE_AXIS = "PRG 0\nHSPD=1000\nX1000\nWAITX\nV100=1\nEND\n"


def project(tmp_path: Path, config_text: str, files: dict[str, str]) -> Path:
    (tmp_path / "mcc.toml").write_text(config_text)
    for name, text in files.items():
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return tmp_path


def test_per_file_profiles_glob_chooses_the_profile(mcc, tmp_path: Path) -> None:
    """`per-file-profiles = {"cell2/*.prg" = "pmx-2ed-sa"}` checks the files it matches with that
    profile; others keep the default (and, failing, get the G021 suggestion)."""
    root = project(tmp_path, 'per-file-profiles = { "cell2/*.prg" = "pmx-2ed-sa" }\n',
                   {"cell2/a.prg": TWO_AXES, "elsewhere/a.prg": TWO_AXES})
    result = mcc("check", "cell2/a.prg", cwd=root)
    assert result.returncode == 0, result.stdout
    other = mcc("check", "elsewhere/a.prg", cwd=root)
    assert other.returncode == 1 and "G021" in other.stdout and "'pmx-2ed-sa'" in other.stdout


def test_directive_beats_the_configuration_and_the_command_line_beats_both(mcc, tmp_path: Path) -> None:
    """Precedence: --profile > `; mcc: profile=` > per-file-profiles > target > default."""
    root = project(tmp_path, 'target = "pmx-4ex-sa"\nper-file-profiles = { "*.prg" = "pmx-2ed-sa" }\n',
                   {"one.prg": "; mcc: profile=ace-sde\n" + ONE_AXIS, "two.prg": TWO_AXES})
    assert mcc("check", "one.prg", cwd=root).returncode == 0      # directive (ace-sde) over the glob (2ED: V100)
    assert mcc("check", "two.prg", cwd=root).returncode == 0      # the glob over target
    forced = mcc("check", "--profile", "pmx-2ed-sa", "one.prg", cwd=root)
    assert forced.returncode == 1 and "A103" in forced.stdout and "pmx-2ed-sa" in forced.stdout
    (root / "mcc.toml").write_text('target = "pmx-2ed-sa"\n')
    assert mcc("check", "two.prg", cwd=root).returncode == 0      # target when no glob matches


def test_pyproject_tool_mcc_per_file_profiles(mcc, tmp_path: Path) -> None:
    """The same key in `[tool.mcc.per-file-profiles]` of a pyproject.toml, for compile too."""
    (tmp_path / "pyproject.toml").write_text('[tool.mcc.per-file-profiles]\n"*.prg" = "pmx-2ed-sa"\n')
    (tmp_path / "p.prg").write_text(TWO_AXES)
    result = mcc("compile", "p.prg", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines()[0] == "PRG 0" and "asm_budget 1275" in result.stderr


def test_lint_uses_the_chosen_profile_and_reports_a_bad_per_file_profile(mcc, tmp_path: Path) -> None:
    root = project(tmp_path, 'per-file-profiles = { "*.prg" = "pmx-2ed-sa", "x/*" = "no-such-profile" }\n',
                   {"two.prg": TWO_AXES})
    result = mcc("lint", "two.prg", cwd=root)
    assert "G103" in result.stdout and "no-such-profile" in result.stdout
    assert "A121" not in result.stdout and "G021" not in result.stdout


@pytest.mark.parametrize("text, dialect", [
    ("' mcc: profile=lmm\nMA 100\n", "mcode"),
    ("` mcc: profile=lmm\nMA 100\n", "mcode"),
    ("; a program for the second cell\n;mcc:profile = pmx-2ed-sa\nX1\n", "arcus"),
    ("; mcc: profile=x150-blhx\n1A10\n", "x150"),
])
def test_directive_is_a_comment_of_each_dialect(text: str, dialect: str) -> None:
    """The directive is written in the dialect's own comment (MCode ' or `, Arcus and X150 ;)
    among the comments before the first statement."""
    found = selection.directive(SourceFile("p", text), dialect)
    assert found is not None
    assert found[0] in ("lmm", "pmx-2ed-sa", "x150-blhx")


def test_a_directive_below_the_first_statement_is_not_one() -> None:
    assert selection.directive(SourceFile("p", "X1\n; mcc: profile=ace-sde\n"), "arcus") is None


@pytest.mark.parametrize("directive, expected", [("pmx-2ed", "unknown profile"), ("lmm", "is for mcode")])
def test_a_bad_directive_is_reported_and_ignored(directive: str, expected: str) -> None:
    result = driver.check_file("p.prg", text=f"; mcc: profile={directive}\nX1000\nEND\n")
    assert [d.code for d in result.diagnostics] == ["G022"] and expected in result.diagnostics[0].message
    assert result.profile.name == "pmx-4ex-sa" and result.profile_source == "default"


def test_a_directive_may_name_a_profile_file_next_to_the_program(tmp_path: Path) -> None:
    (tmp_path / "cell.toml").write_text('extends = "pmx-2ed-sa"\nname = "cell"\n[arcus.cost]\nbudget = 100\n')
    program = tmp_path / "p.prg"
    program.write_text("; mcc: profile=./cell.toml\n" + TWO_AXES)
    result = driver.check_file(str(program))
    assert result.profile.name == "cell" and not result.diagnostics


def test_suggestion_names_the_fitting_profile_instead_of_the_errors() -> None:
    """G021 replaces the errors of the wrong product; it is generic over the built-in profiles'
    `[detect]` markers and picks the one that leaves the fewest errors (2ED p.5: Y exists only
    on the 2-axis product; ACE p.49: V100 only on the 1-axis ones)."""
    two = driver.check_file("p.prg", text=TWO_AXES)
    assert [d.code for d in two.diagnostics] == ["G021"]
    assert "'pmx-2ed-sa'" in two.diagnostics[0].message and "checks clean" in two.diagnostics[0].message
    one = driver.check_file("p.prg", text=ONE_AXIS)
    assert [d.code for d in one.diagnostics] == ["G021"]
    assert "'ace-sde' or 'dmx-eth'" in one.diagnostics[0].message


def test_no_suggestion_for_a_chosen_profile_a_clean_file_or_a_file_without_markers() -> None:
    chosen = driver.check_file("p.prg", text="; mcc: profile=pmx-4ex-sa\n" + TWO_AXES)
    assert "G021" not in [d.code for d in chosen.diagnostics] and "A121" in [d.code for d in chosen.diagnostics]
    assert driver.check_file("p.prg", text="X1000\nWAITX\nEND\n").diagnostics == []
    plain = driver.check_file("p.prg", text="X1000\nV64=1\nEND\n")
    assert [d.code for d in plain.diagnostics] == ["A103"]


def test_every_detect_table_is_well_formed() -> None:
    """The `[detect]` key of the profile files (docs/CONFIGURATION.md): markers compile, `min`
    is at least 1, and each sibling's markers match the fixture written for it."""
    found = {d.profile: d for d in selection.detectors()}
    assert {"pmx-2ed-sa", "ace-sde", "dmx-eth"} <= set(found)
    family = Path(__file__).parent / "arcus" / "family"
    for profile, name in (("pmx-2ed-sa", "pmx2ed_two_programs.prg"), ("ace-sde", "ace_sde_latch.prg"),
                          ("dmx-eth", "dmx_eth_focuser.prg")):
        assert found[profile].minimum >= 1
        assert selection.matches(SourceFile(name, (family / name).read_text()), found[profile]), profile


def test_editor_server_chooses_as_the_command_line_does(tmp_path: Path) -> None:
    """lsp/incremental.py resolves the profile through selection.choose: the directive and the
    configuration apply in the editor too."""
    pytest.importorskip("pygls")
    from mcc.lsp import incremental

    root = project(tmp_path, 'per-file-profiles = { "*.prg" = "pmx-2ed-sa" }\n', {})
    settings = config.Resolver().for_path(str(root / "a.prg"))
    checked, _ = incremental.check_text(str(root / "a.prg"), TWO_AXES, settings, None, None)
    assert checked.profile.name == "pmx-2ed-sa" and not checked.result.diagnostics
    checked, _ = incremental.check_text(str(root / "a.prg"), "; mcc: profile=ace-sde\n" + ONE_AXIS, settings,
                                        None, None)
    assert checked.profile.name == "ace-sde"
