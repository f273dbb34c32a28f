"""What a new user meets first (issue 24), run as a user runs `mcc`: a folder of programs with
other extensions, mcontrol's preprocessor, MicroLYNX files, host entry points, Arcus comments at
the end of lines, and messages that name what the user wrote."""

from __future__ import annotations

from pathlib import Path

from conftest import run_mcc

# A subroutine S9, and after its RT a label K9 that nothing in the file names: the host starts it
# with `EX K9` (lexium-mcode.txt L533: "EX K1 executes a program labeled K1"), and it branches back
# to the main program. Real MDrive programs are laid out so.
ENTRY_POINT = """PG 1
LB G1
  CL S9
  BR G1
LB S9
  MR 10
  H
  RT
LB K9
  MA 0
  H
  BR G1
PG
S
' end
"""


def test_a_label_the_host_starts_after_rt_is_an_entry_point(tmp_path: Path) -> None:
    """M302 is no error on K9's BR (K9 is not a part of S9), so `mcc lint` passes where `mcc check`
    does, and `--unsafe-fixes` does not offer to delete K9 (M305); lexium-mcode.txt L533."""
    path = tmp_path / "host.mxt"
    path.write_text(ENTRY_POINT)
    assert run_mcc("check", str(path)).returncode == 0
    linted = run_mcc("lint", str(path))
    assert linted.returncode == 0, linted.stdout
    assert "M302" not in linted.stdout and "M305" not in linted.stdout
    diff = run_mcc("lint", "--diff", "--unsafe-fixes", str(path))
    assert "-LB K9" not in diff.stdout


# The manual's own Arcus examples put comments after statements (arcus-pmx-4ex-sa.txt L1864
# "CIRP1000:1000 ;***Using X 1000 ...", L2230 "HSPD=10000 ;***Sets the high speed ...").
ARCUS_COMMENTED = "HSPD=10000 ;***Sets the high speed\nLSPD=100 ;***and the low speed\nX1000 ;***move X\nEND\n"


def test_arcus_trailing_comments_are_left_alone_unless_a315_is_selected(tmp_path: Path) -> None:
    """A315 (comments on their own line, L1725) is opt-in: `lint --fix` leaves the manual's layout
    (L1864, L2230) as it is; `--extend-select A315` reports and moves them."""
    path = tmp_path / "cell.prg"
    path.write_text(ARCUS_COMMENTED)
    plain = run_mcc("lint", "--fix", str(path))
    assert "A315" not in plain.stdout and path.read_text() == ARCUS_COMMENTED, plain.stdout
    chosen = run_mcc("lint", "--extend-select", "A315", str(path))
    assert chosen.stdout.count("[A315]") == 3, chosen.stdout
    widened = run_mcc("lint", "--select", "ALL", str(path))
    assert "A315" not in widened.stdout


# A clean MCode program (lexium-mcode.txt L533: PG/LB/E; "S" saves it, L5269, and a comment line
# after it sends its line end).
CLEAN_MCODE = "PG 1\nLB G1\n  MA 10\n  H\n  E\nPG\nS\n' end\n"


def folder_of_other_extensions(tmp_path: Path) -> Path:
    """The folder a new user points mcc at: programs saved as .lxt, .txt and a 6K file."""
    folder = tmp_path / "programs"
    folder.mkdir()
    (folder / "a.lxt").write_text(CLEAN_MCODE)
    (folder / "b.txt").write_text(CLEAN_MCODE)
    (folder / "c.6k").write_text("DEF main\nDRIVE1\nGO1\nEND\n")
    return folder


def test_lint_and_check_on_a_folder_of_unknown_extensions_is_a_usage_error(tmp_path: Path) -> None:
    """Nothing checked is not "No problems found in 0 files": each skipped file is named with the
    reason, and the exit code is 2 (usage), for lint, check and fmt alike."""
    folder = folder_of_other_extensions(tmp_path)
    for command in ("lint", "check", "fmt"):
        result = run_mcc(command, str(folder))
        assert result.returncode == 2, (command, result.stdout, result.stderr)
        assert "in 0 files" not in result.stdout
        for name in ("a.lxt", "b.txt", "c.6k"):
            assert f"{name}: unknown extension" in result.stderr, (command, result.stderr)
        assert 'extensions = {' in result.stderr and "no program to" in result.stderr


def test_extensions_in_the_configuration_map_files_to_a_dialect(tmp_path: Path) -> None:
    """`[tool.mcc] extensions = {lxt = "mcode", txt = "mcode"}`: lint and check find and read those
    files; the one left (.6k) is reported as skipped in one note."""
    folder = folder_of_other_extensions(tmp_path)
    (tmp_path / "pyproject.toml").write_text('[tool.mcc]\nextensions = {lxt = "mcode", txt = "mcode"}\n')
    linted = run_mcc("lint", str(folder))
    assert linted.returncode == 0 and "No problems found in 2 files." in linted.stdout, linted.stdout
    assert "skipped 1 file of unknown extension (.6k 1)" in linted.stderr
    checked = run_mcc("check", str(folder))
    assert checked.returncode == 0 and "No problems found in 2 files." in checked.stdout, checked.stdout
    one = run_mcc("check", str(folder / "a.lxt"))
    assert one.returncode == 0, one.stdout
    piped = run_mcc("check", "-", "--stdin-filename", str(folder / "b.txt"), input=CLEAN_MCODE)
    assert piped.returncode == 0, piped.stderr
    simulated = run_mcc("sim", str(folder / "a.lxt"))
    assert simulated.returncode == 0 and "G004" not in simulated.stdout + simulated.stderr, simulated.stdout


def test_a_misspelt_dialect_in_extensions_is_reported(tmp_path: Path) -> None:
    """The key is validated like the others (G103 on the TOML file, with the close name)."""
    folder = folder_of_other_extensions(tmp_path)
    (tmp_path / "mcc.toml").write_text('extensions = {lxt = "mcod"}\n')
    result = run_mcc("lint", str(folder / "a.lxt"))
    assert result.returncode == 1
    assert "G103" in result.stdout and "'mcod' is not a dialect" in result.stdout and "did you mean 'mcode'" \
        in result.stdout, result.stdout


def test_check_takes_directories_with_lints_discovery(tmp_path: Path) -> None:
    """`mcc check DIR` finds what `mcc lint DIR` finds: .gitignore (in a git work tree) and `exclude`
    leave files out, --force-exclude applies them to the files named too."""
    (tmp_path / ".git").mkdir()
    (tmp_path / ".gitignore").write_text("build/\n")
    (tmp_path / "mcc.toml").write_text('exclude = ["vendor"]\n')
    for rel in ("src/a.mxt", "build/b.mxt", "vendor/c.mxt"):
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text("MX 1\n")  # an unknown command: an error wherever it is read
    checked = run_mcc("check", ".", cwd=tmp_path)
    assert checked.returncode == 1
    assert "src/a.mxt" in checked.stdout and "build" not in checked.stdout and "vendor" not in checked.stdout
    forced = run_mcc("check", "--force-exclude", "vendor/c.mxt", cwd=tmp_path)
    assert forced.returncode == 0 and "vendor" not in forced.stdout, forced.stdout


MICROLYNX = Path(__file__).parent / "data" / "first_contact" / "microlynx_stage.lxt"


def test_a_microlynx_program_is_recognised_once_in_every_reader(tmp_path: Path) -> None:
    """An IMS MicroLYNX program (MUNIT, ACCL, MOVA, PGM ... LBL ... END ... PGM; written for this
    test after public MODS instrument programs) gets one G020 naming the language, not an error per
    line, whichever dialect's extension it carries. lexium-mcode.txt L615-L616 ("PG 100", "LB G1")
    are the MCode forms the advice names."""
    text = MICROLYNX.read_text(encoding="utf-8")
    for ext in (".mxt", ".prg", ".x150"):
        path = tmp_path / f"stage{ext}"
        path.write_text(text)
        result = run_mcc("check", str(path))
        assert result.returncode == 1
        assert result.stdout.count("error[") == 1 and "error[G020]" in result.stdout, (ext, result.stdout)
        assert "IMS MicroLYNX" in result.stdout


def test_messages_name_what_the_user_wrote(tmp_path: Path) -> None:
    """`Pos=0` is read as OS addressed to the party-mode device P (a one-character device name before
    a command, lexium-mcode.txt L1067 table of commands): the message starts with what was written
    and how it was read, and says how to make Pos a variable (VA, L537). `END` alone is a misspelt
    command (E ends a program), not a label to write with LB."""
    path = tmp_path / "first.mxt"
    path.write_text("PG 1\nLB G1\n  Pos=0\n  END\n  E\nPG\n")
    result = run_mcc("check", str(path))
    lines = [line for line in result.stdout.splitlines() if "error[" in line]
    pos = next(line for line in lines if ":3:" in line)
    assert "'Pos' reads as OS addressed to the party-mode device P" in pos and "cannot be a variable" in pos, pos
    end = next(line for line in lines if ":4:" in line)
    assert "'END'" in end and "LB END" not in end and "did you mean E" in end, end


MCONTROL = Path(__file__).parent / "data" / "first_contact" / "mcontrol_preprocessed.mxt"


def test_mcontrol_preprocessor_source_gets_one_diagnostic_naming_it(tmp_path: Path) -> None:
    """A program written for mcontrol's preprocessor (`#include "../brake.mxt"`, `#if` ... `#endif`,
    laid out after public mcontrol modules) gets one M142 naming the preprocessor, with its
    directive lines as notes, and no "unexpected character '#'"; lint says the same and fmt leaves
    the file alone. MCode has no `#` (comments are ' or the backquote, lexium-mcode.txt L615)."""
    path = tmp_path / "zaxis.mxt"
    path.write_text(MCONTROL.read_text(encoding="utf-8"))
    for command in ("check", "lint"):
        result = run_mcc(command, str(path))
        assert result.returncode == 1
        assert result.stdout.count("error[") == 1 and "error[M142]" in result.stdout, (command, result.stdout)
        assert "mcontrol's MCode preprocessor" in result.stdout and "unexpected character" not in result.stdout
        assert result.stdout.count("= note:") == 4  # #include, #if, #else, #endif
    before = path.read_text()
    formatted = run_mcc("fmt", str(path))
    assert formatted.returncode == 1 and "M142" in formatted.stderr and path.read_text() == before
