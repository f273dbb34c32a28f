"""The cycle time code lens (issue 27, lsp/cycles.py): on the main loop's line and each called
subroutine's first line, from the bounded run of `mcc compile` (30 virtual seconds, every input
low). The expected figures are worked out by hand from the manuals' motion rules, not read from
the simulator."""

from __future__ import annotations

import pytest
from lsprotocol import types as t

from lsp_client import Doc, client  # noqa: F401 (client is the fixture)
from mcc.lsp import analysis, lenses


def cycle_lenses(name: str, text: str) -> list[tuple[int, str]]:
    """(1-based line, title) of each cycle lens of the program."""
    snap = analysis.analyze(f"file:///tmp/{name}", f"/tmp/{name}", 1, text)
    assert not snap.check_errors, [d.message for d in snap.diagnostics]
    return [(lens.range.start.line + 1, lens.command.title) for lens in lenses.cycle_lenses(snap)]


MCODE = "VI=1000\nVM=9000\nA=40000\nD=40000\nPG 1\nLB K1\n  CL K2\n  H 100\n  BR K1\nLB K2\n  MR 20000\n  H\n  RT\nE\nPG\n"


def test_mcode_cycle_and_call() -> None:
    """MCode: VI = 1000 steps/s (lexium-mcode.txt L664), VM = 9000 steps/s (L671), A = D = 40000
    steps/s² (L678, L685). MR 20000: ramp up (9000 - 1000) / 40000 = 0.2 s over
    (1000 + 9000) / 2 · 0.2 = 1000 steps, ramp down the same, the other 18000 steps at 9000 steps/s
    take 2 s: 2.4 s, and H waits for it (L3048), so the call of K2 (CL, L913) lasts 2.4 s. The main
    loop K1 adds H 100, 100 ms (L3050): 2.5 s a pass, one move."""
    assert cycle_lenses("m.mxt", MCODE) == [(6, "cycle 2.500 s, 1 moves"), (10, "call 2.400 s")]


def test_arcus_cycle_and_call() -> None:
    """Arcus: a trapezoidal profile by default (arcus-pmx-4ex-sa.txt L435) from LSPD = 1000 to
    HSPD = 9000 pulses/s (L2212) in ACC = 200 ms (L441, L1505). X20000 in INC mode: ramp up
    0.2 s over (1000 + 9000) / 2 · 0.2 = 1000 pulses, ramp down the same, 18000 pulses at 9000/s
    take 2 s: the subroutine (WAITX waits for the move) lasts 2.4 s; the WHILE loop adds
    DELAY=100, 100 ms (L1868, "DELAY=1000 ... Wait 1 second" L1735): 2.5 s a pass."""
    text = "HSPD=9000\nLSPD=1000\nACC=200\nEO=1\nINC\nWHILE 1=1\nGOSUB 1\nDELAY=100\nENDWHILE\nEND\n" \
           "SUB 1\nX20000\nWAITX\nENDSUB\n"
    assert cycle_lenses("a.prg", text) == [(6, "cycle 2.500 s, 1 moves"), (11, "call 2.400 s")]


def test_x150_cycle() -> None:
    """X150: A10 = 10 rev/s² (parker-x150.md L195), V1 = 1 rev/s (L4540), D4000 = 1 rev at 4000
    steps/rev (L810, L837), T0.5 = half a second (L4101), L0 repeats forever (L2318). From
    standstill: ramp up 1/10 = 0.1 s over 0.5 · 10 · 0.1² = 0.05 rev, ramp down the same, the other
    0.9 rev at 1 rev/s take 0.9 s: 1.1 s a move, plus 0.5 s: 1.6 s a pass, on the L0 line."""
    assert cycle_lenses("x.x150", "MPI\nA10\nV1\nL0\nD4000\nG\nT0.5\nN\n") == [(4, "cycle 1.600 s, 1 moves")]


def test_x150_sequence_call() -> None:
    """X150: sequence 2 (XD2 ... XT, parker-x150.md L1772, L1265) moves 1 rev in 1.1 s as above
    (L195, L4540, L810) and runs once, by XR2: the lens is on its XD line, where the outline and
    the memory lens put the sequence."""
    text = "1A10\n1V1\n1XE2\n1XD2\n1D4000\n1G\n1XT\n1XR2\n"
    assert cycle_lenses("s.x150", text) == [(4, "call 1.100 s")]


def test_a_loop_waiting_for_an_input_says_so() -> None:
    """MCode: BR K1, I1=0 (lexium-mcode.txt L617 for the conditional form) with every input low
    loops forever without moving: no time per pass to show, the lens says it waits."""
    text = "PG 1\nLB K1\n  BR K1, I1=0\n  MR 100\n  H\n  BR K1\nE\nPG\n"
    assert cycle_lenses("w.mxt", text) == [(2, "cycle: waits for an input (all inputs low)")]


def test_a_cycle_longer_than_the_bound_is_a_lower_bound() -> None:
    """MCode: H 65000 waits 65 s (lexium-mcode.txt L3050, range 1-65000 ms L3052): the bounded run
    stops at 30 virtual seconds before the loop closes, so the lens says "cycle > 30.0 s"."""
    text = "PG 1\nLB K1\n  H 65000\n  BR K1\nE\nPG\n"
    assert cycle_lenses("l.mxt", text) == [(2, "cycle > 30.0 s")]


@pytest.mark.asyncio(loop_scope="module")
async def test_the_lens_reaches_the_editor_and_stays_while_the_file_has_errors(client) -> None:
    """Through the protocol: the lens arrives after the pause in the typing (a code lens refresh);
    an edit that breaks the file keeps the last figures, moved with their line (a line inserted
    above moves the lens down one line)."""
    doc = Doc(client, "cycle.mxt", MCODE)
    await doc.settled()
    found = await client.text_document_code_lens_async(t.CodeLensParams(doc.id()))
    assert [(lens.range.start.line, lens.command.title) for lens in found] == \
        [(5, "cycle 2.500 s, 1 moves"), (9, "call 2.400 s")]
    doc.edit(4, 0, 0, "BR K7\n")  # an undefined label: an error, and every line below moves down
    diagnostics = await doc.settled()
    assert any(d.severity == t.DiagnosticSeverity.Error for d in diagnostics)
    found = await client.text_document_code_lens_async(t.CodeLensParams(doc.id()))
    assert [(lens.range.start.line, lens.command.title) for lens in found] == \
        [(6, "cycle 2.500 s, 1 moves"), (10, "call 2.400 s")]


@pytest.mark.parametrize("text", ["PG 1\nLB K1\n  H 10\n  BR K1\nE\nPG\n"])
def test_carried_lenses_follow_their_text(text) -> None:
    """Unit form of the above: a carried lens goes to the nearest line holding the same text, and
    is dropped when that text is gone."""
    from mcc.lsp import cycles

    before = analysis.analyze("file:///tmp/c.mxt", "/tmp/c.mxt", 1, text)
    assert [(lens.line, lens.title) for lens in before.cycles.lenses] == [(2, "cycle 0.010 s, 0 moves")]
    moved = analysis.analyze("file:///tmp/c.mxt", "/tmp/c.mxt", 2, "' note\n" + text)
    assert [lens.line for lens in cycles.carried(before.cycles, moved).lenses] == [3]
    gone = analysis.analyze("file:///tmp/c.mxt", "/tmp/c.mxt", 3, text.replace("LB K1", "LB K2"))
    assert cycles.carried(before.cycles, gone).lenses == []


def test_a_stale_run_stops_at_the_simulators_checkpoint() -> None:
    """The run of a version a newer edit made stale stops (compiler/cancel.py): the simulator
    checks every CANCEL_EVERY steps, so a loop of H 1 (1 ms, lexium-mcode.txt L3050), 30,000
    passes in the 30 s bound, is abandoned rather than run to its end."""
    from mcc.compiler import cancel
    from mcc.lsp import cycles

    text = "VA Np=0\nPG 1\nLB K1\n  H 1\n  IC Np\n  BR K1\nE\nPG\n"
    snap = analysis.analyze("file:///tmp/stale.mxt", "/tmp/stale.mxt", 1, text)
    assert snap.cycles is not None and snap.cycles.lenses[0].title == "cycle 0.001 s, 0 moves"
    with cancel.stopping_when(lambda: True), pytest.raises(cancel.Cancelled):
        cycles.cycles(snap)
