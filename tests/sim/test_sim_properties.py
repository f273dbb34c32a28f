"""Properties over random valid IR programs and random motion profiles."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from mcc.compiler.ir_verify import verify
from mcc.sim import Options, simulate
from mcc.sim.motion import Limits, plan
from mcc.sim.trace import STOP_REASONS
from mcc.sim.verify import compare, compare_traces
from sim_strategy import SHAPES, modules, scaled

FAST = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
OPTIONS = Options(until=120, max_steps=20_000)


@FAST
@given(modules())
def test_the_strategy_builds_only_modules_the_verifier_accepts(module):
    assert verify(module) == []


@FAST
@given(modules())
def test_every_valid_program_runs_to_a_documented_stop_and_runs_the_same_twice(module):
    first = simulate(module, options=OPTIONS)
    again = simulate(module, options=OPTIONS)
    assert first.stopped in STOP_REASONS
    assert [e.to_json() for e in first.events] == [e.to_json() for e in again.events]
    assert compare_traces(first, again) is None


@FAST
@given(modules())
def test_a_program_agrees_with_itself_at_a_finer_step(module):
    # every position, speed and acceleration doubled with twice the steps per revolution: the
    # same machine motion, so the traces agree once positions are scaled
    assert compare(module, scaled(module, 2), options=OPTIONS) is None


@FAST
@given(modules(), st.integers(1, 3))
def test_changing_a_move_is_a_divergence(module, extra):
    from mcc.compiler import ir

    moves = [op for _, b in module.blocks() for op in b.ops if isinstance(op, ir.Move)]
    assume(moves)
    first = simulate(module, options=OPTIONS)
    assume(first.stopped == "end" and any(e.kind == "move" and e.data["from"] != e.data["to"]
                                          for e in first.events))
    changed = scaled(module, 1)
    for _, block in changed.blocks():
        block.ops = [_shifted(op, 100 * extra) if isinstance(op, ir.Move) else op for op in block.ops]
    assert compare(module, changed, options=OPTIONS) is not None


def _shifted(op, delta):
    from mcc.compiler import ir

    return ir.Move(op.mode, tuple((a, ir.Const(e.value + delta, e.unit)) for a, e in op.targets))


@settings(max_examples=200, deadline=None)
@given(st.floats(1, 1e6), st.floats(0, 500), st.floats(1, 1e5), st.floats(1, 1e7), st.floats(1, 1e7),
       st.booleans())
def test_a_profile_covers_its_distance_and_respects_its_speeds(length, initial, maximum, acc, dec, smooth):
    segments = plan(0.0, length, Limits(initial, maximum, acc, dec, smooth))
    assert sum(s.length for s in segments) == pytest.approx(length, rel=1e-9)
    top = max(maximum, initial)
    for seg in segments:
        assert max(seg.v0, seg.v1) <= top * (1 + 1e-9)
        for k in range(5):
            s = seg.s0 + seg.length * k / 4  # time_at inverts distance (which is monotonic)
            assert seg.distance(seg.time_at(s)) == pytest.approx(s, rel=1e-9, abs=1e-6)
    for before, after in zip(segments, segments[1:]):
        assert before.t1 == pytest.approx(after.t0) and before.v1 == pytest.approx(after.v0)


# A small program with a move, a speed and a delay in each dialect: its IR keeps the contract once
# the dialect's frontend is converted (issue 8), and from then on the round trip below is tested.
PROBES = {
    "arcus": "ABS\nHSPD=1000\nX1000\nWAITX\nDELAY=100\nEND\n",
    "mcode": "VM=20000\nPG 100\nLB AA\n  MA 1000\n  H\n  H 100\n  E\nPG\n",
    "x150": "1XE10\n1XD10\n1MPA\n1A10\n1V1\n1D1000\n1G\n1T0.1\n1XT\n",
}


def contract_probe(dialect: str) -> str:
    """The first contract violation of the dialect's probe program ("" when it keeps it)."""
    from mcc.compiler import dialects, driver
    from mcc.compiler.ir_verify import verify as verify_ir

    path = f"probe{dialects.get(dialect).extensions[0]}"
    result = driver.check_file(path, dialect, None, PROBES[dialect])
    assert not result.has_errors, [d.message for d in result.diagnostics]
    problems = verify_ir(result.analysis.module)
    return str(problems[0]) if problems else ""


# Each target gets programs shaped to what it can write (sim_strategy.SHAPES), so that most of them
# are written and the round trip tests the translation. A program the backend refuses (an error
# diagnostic: the user is told it cannot be written) is skipped and counted; at least half must be
# written, so a backend that started refusing everything fails here instead of passing vacuously.
ROUND_TRIPS = 40


@pytest.mark.parametrize("target", ["arcus", "mcode", "x150"])
def test_a_backend_and_its_frontend_keep_what_a_program_does(target):
    """Random valid IR through each backend and back through that dialect's frontend: same trace."""
    from mcc.compiler import dialects, driver, profiles
    from mcc.compiler.ir_verify import verify as verify_ir

    probe = contract_probe(target)
    assert not probe, f"the {target} frontend does not keep the IR contract ({probe})"
    dialect = dialects.get(target)
    profile = profiles.load(dialect.default_profile)
    counts = {"written": 0, "refused": 0}

    @settings(max_examples=ROUND_TRIPS, deadline=None, database=None, derandomize=True,
              suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
    @given(module=modules(shape=SHAPES[target]))
    def round_trip(module):
        listing = dialect.load_backend().emit(module, profile)
        refusals = [d for d in listing.diagnostics if d.severity.value == "error"]
        if refusals:
            counts["refused"] += 1  # the target cannot express this program, and the user is told so
            assert all(d.code for d in refusals)
            return
        counts["written"] += 1
        back = driver.check_file(f"generated{dialect.extensions[0]}", target, profile, listing.text)
        errors = [d.message for d in back.diagnostics if d.severity.value == "error"]
        assert not errors, f"the {target} backend wrote a program with errors: {errors}\n{listing.text}"
        assert verify_ir(back.analysis.module) == []
        found = compare(module, back.analysis.module, options=OPTIONS)
        assert found is None, f"{found}\n{listing.text}"

    round_trip()
    assert counts["written"] >= counts["refused"], counts
