"""The machine's envelope (issue 27): `[tool.mcc.axes]` and the lint rules G301-G304.

Each dialect has a program that leaves its travel on one path only (a warning naming the path), one
that cannot leave it (nothing), and a loop whose count comes from a variable (bounded when the
program sets it, G303 when nothing does). The limit switch that stops an axis at its end of travel:
lexium-mcode.txt L3935, parker-x150.md L2400, arcus-pmx-4ex-sa.txt L333.
"""

from __future__ import annotations

import textwrap

import pytest

from helpers import lint
from mcc.compiler import config
from mcc.compiler.envelope import axes

ENVELOPE = """
[tool.mcc.axes.1]
min = 0
max = 10000
[tool.mcc.axes.X]
min = 0
max = 10000
"""


def settings(text: str = ENVELOPE) -> config.Settings:
    loaded = config.parse(textwrap.dedent(text), "pyproject.toml")
    assert not loaded.diagnostics
    return loaded.settings


def found(text: str, path: str, code: str = "G3"):
    return [d for d in lint(text, path, settings()) if d.code.startswith(code)]


# one path leaves: a warning whose notes name the path --------------------------------------------

def test_mcode_one_path_leaves() -> None:
    """MCode MA to a register one branch sets beyond the travel (lexium-mcode.txt L3935)."""
    diags = found("""
        PG 100
        R1=5000
        BR K2, I1=1
        R1=12000
        LB K2
        MA R1
        H
        E
        PG
    """, "a.mxt")
    assert [(d.code, d.severity.value, d.span.line) for d in diags] == [("G301", "warning", 6)]
    assert "line 4: R1 = 12000: on this path the target leaves the travel" in diags[0].notes


def test_x150_one_path_leaves() -> None:
    """X150 MPI after an IF that moves further (parker-x150.md L2400): only the IF path leaves."""
    diags = found("""
        MPA
        A10
        V1
        D5000
        G
        IF(IN1)
        D9000
        G
        NIF
        MPI
        D2000
        G
    """, "a.x150")
    assert [(d.code, d.severity.value, d.span.line) for d in diags] == [("G301", "warning", 11)]
    assert "7000 .. 11000" in diags[0].message
    assert any("line 6: a branch" in note for note in diags[0].notes)


def test_arcus_one_path_leaves() -> None:
    """Arcus XV1 with V1 set beyond the travel inside an IF (arcus-pmx-4ex-sa.txt L333)."""
    diags = found("""
        ABS
        HSPD=1000
        LSPD=100
        ACC=100
        V1=5000
        IF DI1=1
        V1=12000
        ENDIF
        XV1
        WAITX
        END
    """, "a.prg")
    assert [(d.code, d.severity.value, d.span.line) for d in diags] == [("G301", "warning", 9)]
    assert "line 7: V1 = 12000: on this path the target leaves the travel" in diags[0].notes


# every path leaves: an error ------------------------------------------------------------------------

def test_every_path_leaves_is_an_error() -> None:
    """MA 12000 with a travel of 0..10000 runs into the limit whatever happens before it."""
    diags = found("PG 100\nMA 12000\nH\nE\nPG\n", "a.mxt")
    assert [(d.code, d.severity.value) for d in diags] == [("G301", "error")]


# cannot leave: nothing ------------------------------------------------------------------------------

@pytest.mark.parametrize("path, text", [
    ("a.mxt", "PG 100\nMA 0\nH\nR2=0\nLB K3\nMR 1000\nH\nR2=R2+1\nBR K3, R2<10\nE\nPG\n"),
    ("a.x150", "MPA\nA10\nV1\nD0\nG\nL10\nMPI\nD1000\nG\nN\n"),
    ("a.prg", "ABS\nHSPD=1000\nLSPD=100\nACC=100\nX0\nWAITX\nV1=0\nWHILE V1<10\nINC\nX1000\nWAITX\nV1=V1+1\n"
              "ENDWHILE\nEND\n"),
])
def test_counted_loop_to_the_end_of_travel_cannot_leave(path: str, text: str) -> None:
    """Ten passes of +1000 from 0 end exactly at the max 10000: the loop's count bounds it (MCode BR
    counted loop lexium-mcode.txt L3935; X150 L10..N parker-x150.md L2400; Arcus WHILE L333)."""
    assert found(text, path) == []


# a loop whose count comes from a variable -----------------------------------------------------------

@pytest.mark.parametrize("path, text, line", [
    ("a.mxt", "PG 100\nMA 0\nH\nR2=0\nLB K3\nMR 1000\nH\nR2=R2+1\nBR K3, R2<R4\nE\nPG\n", 6),
    ("a.prg", "ABS\nHSPD=1000\nLSPD=100\nACC=100\nX0\nWAITX\nV1=0\nWHILE V1<V2\nINC\nX1000\nWAITX\nV1=V1+1\n"
              "ENDWHILE\nEND\n", 10),
    ("a.x150", "MPA\nA10\nV1\nD0\nG\nL(VAR1)\nMPI\nD1000\nG\nN\n", 8),  # L(VAR1): parker-x150.md L2340
])
def test_loop_counted_to_an_unknown_variable_is_unbounded(path: str, text: str, line: int) -> None:
    """The count comes from a register nothing in the program sets (the host may): G303."""
    diags = found(text, path)
    assert [(d.code, d.span.line) for d in diags] == [("G303", line)]


@pytest.mark.parametrize("path, text, bound", [
    ("a.mxt", "PG 100\nR4={n}\nMA 0\nH\nR2=0\nLB K3\nMR 1000\nH\nR2=R2+1\nBR K3, R2<R4\nE\nPG\n", 10),
    ("a.prg", "ABS\nHSPD=1000\nLSPD=100\nACC=100\nV2={n}\nX0\nWAITX\nV1=0\nWHILE V1<V2\nINC\nX1000\nWAITX\n"
              "V1=V1+1\nENDWHILE\nEND\n", 10),
    ("a.x150", "MPA\nA10\nV1\nD0\nG\nVAR1={n}\nL(VAR1)\nMPI\nD1000\nG\nN\n", 10),
])
def test_loop_counted_to_a_variable_the_program_sets(path: str, text: str, bound: int) -> None:
    """A count from a variable set before the loop bounds it: 10 passes stay inside, 11 may leave."""
    assert found(text.format(n=bound), path) == []
    diags = found(text.format(n=bound + 1), path)
    assert [(d.code, d.severity.value) for d in diags] == [("G301", "warning")]
    assert any("at most 11 passes" in note for note in diags[0].notes)


def test_x150_endless_loop_of_relative_moves() -> None:
    """X150 L0 repeats forever (parker-x150.md L2400 ends it at the limit): G303."""
    diags = found("MPI\nA10\nV1\nL0\nD1000\nG\nN\n", "a.x150")
    assert [d.code for d in diags] == ["G303"]


def test_balanced_relative_moves_in_an_endless_loop() -> None:
    """Out and back each pass: the loop's count does not matter."""
    assert found("PG 100\nMA 5000\nH\nLB K1\nMR 1000\nH\nMR -1000\nH\nBR K1\nPG\n", "a.mxt") == []


# speed and homing -----------------------------------------------------------------------------------

def test_speed_and_acceleration_above_the_mechanics() -> None:
    """VM and A above max-speed / max-accel (lexium-mcode.txt L3935 is what stops it otherwise)."""
    diags = lint("PG 100\nVM 200000\nA 5000\nMA 100\nH\nE\nPG\n", "a.mxt", settings("""
        [tool.mcc.axes.1]
        max-speed = 100000
        max-accel = 1000
    """))
    assert [(d.code, d.span.line) for d in diags if d.code == "G302"] == [("G302", 2), ("G302", 3)]


def test_move_before_homing() -> None:
    """must-home: a move on a path that has not homed is an error; after HM none."""
    cfg = settings("""
        [tool.mcc.axes.1]
        must-home = true
    """)
    bad = lint("PG 100\nMA 100\nH\nE\nPG\n", "a.mxt", cfg)
    assert [d.code for d in bad if d.code == "G304"] == ["G304"]
    good = lint("PG 100\nHM 1\nH\nMA 100\nH\nE\nPG\n", "a.mxt", cfg)
    assert [d.code for d in good if d.code == "G304"] == []
    some = lint("PG 100\nBR K2, I1=1\nHM 1\nH\nLB K2\nMA 100\nH\nE\nPG\n", "a.mxt", cfg)
    assert [(d.code, d.severity.value) for d in some if d.code == "G304"] == [("G304", "warning")]


def test_no_envelope_no_finding() -> None:
    assert [d for d in lint("PG 100\nMA 99999999\nH\nE\nPG\n", "a.mxt") if d.code.startswith("G3")] == []


# configuration ----------------------------------------------------------------------------------------

def test_millimetres_with_a_lead() -> None:
    """200 steps/rev on a 5 mm lead: 40 steps per mm; 0..250 mm is 0..10000 steps."""
    found_axes, problems = axes.parse({"X": {"unit": "mm", "steps-per-rev": 200, "lead": 5, "min": 0, "max": 250,
                                             "max-speed": 100}})
    assert problems == []
    assert (found_axes["X"].min, found_axes["X"].max, found_axes["X"].max_speed) == (0, 10000, 4000)
    assert found_axes["X"].shown(10000) == "250 mm (10000 steps)"


def test_degrees() -> None:
    found_axes, _ = axes.parse({"U": {"unit": "deg", "steps-per-rev": 3600, "max": 90}})
    assert found_axes["U"].max == 900


def test_misspelt_and_invalid_keys() -> None:
    loaded = config.parse('[tool.mcc.axes.X]\nmaxx = 10\nmin = "a"\nunit = "mm"\n', "pyproject.toml")
    messages = [(d.code, d.span.line, d.message) for d in loaded.diagnostics]
    assert ("G102", 2, "unknown envelope key 'maxx'; did you mean 'max'?") in messages
    assert any(code == "G103" and line == 3 for code, line, _ in messages)
    assert any(code == "G103" and "steps-per-mm" in message for code, _, message in messages)


def test_profile_envelope_under_the_projects(tmp_path) -> None:
    """A profile's [envelope.<axis>] applies, the project's keys over it."""
    from mcc.compiler import profiles

    path = tmp_path / "machine.toml"
    path.write_text('extends = "lmd-c"\n[envelope.1]\nmin = 0\nmax = 500\nmust-home = true\n', encoding="utf-8")
    profile = profiles.load(str(path))
    merged = axes.envelopes(profile, settings("[tool.mcc.axes.1]\nmax = 800\n").axes)
    assert (merged["1"].min, merged["1"].max, merged["1"].must_home) == (0, 800, True)
    bad = tmp_path / "bad.toml"
    bad.write_text('extends = "lmd-c"\n[envelope.1]\nmni = 0\n', encoding="utf-8")
    with pytest.raises(profiles.ProfileError, match="mni"):
        profiles.load(str(bad))


def test_ramp_time_and_slew_speed_above_the_mechanics() -> None:
    """Arcus ACC is a ramp time in ms from LSPD to HSPD (arcus-pmx-4ex-sa.txt L333 is the limit that
    stops the axis otherwise): (10001 - 1) / 0.1 s = 100000 steps/s² > 50000; with ACC=300,
    (10001 - 1) / 0.3 = 33333 steps/s² is inside. MCode SL 200000 is above max-speed 100000."""
    cfg = settings("""
        [tool.mcc.axes.X]
        max-accel = 50000
        [tool.mcc.axes.1]
        max-speed = 100000
    """)
    program = "ABS\nHSPD=10001\nLSPD=1\nACC={acc}\nX1000\nWAITX\nEND\n"
    fast = [(d.code, d.span.line) for d in lint(program.format(acc=100), "a.prg", cfg) if d.code == "G302"]
    assert fast == [("G302", 5)]
    assert [d for d in lint(program.format(acc=300), "a.prg", cfg) if d.code == "G302"] == []
    slew = [(d.code, d.span.line) for d in lint("PG 100\nSL 200000\nH 100\nSL 0\nE\nPG\n", "a.mxt", cfg)
            if d.code == "G302"]
    assert slew == [("G302", 2)]


def test_call_summarised_callee_first() -> None:
    """A subroutine that moves +6000 relative (MCode MR in a CL'd routine, lexium-mcode.txt L3935):
    from MA 0 the first call ends at 6000, the second would go to 12000: the second call is an error
    at its line; the callee alone cannot know (it runs from wherever it is called)."""
    diags = found("PG 100\nMA 0\nH\nCL K9\nCL K9\nE\nLB K9\nMR 6000\nH\nRT\nPG\n", "a.mxt")
    assert [(d.code, d.severity.value, d.span.line) for d in diags] == [("G301", "error", 5)]
    assert "this call of K9" in diags[0].message
