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
