"""Random valid IR through every level and every pass alone: the verifier stays happy and the
oracle sees the same behaviour."""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sim_behaviour import Baseline, same_behaviour
from random_ir import modules
from mcc.compiler import ir, profiles
from mcc.compiler.ir_verify import verify
from mcc.compiler.opt import LEVELS, PASSES, optimize

CHOICES = [(level, None) for level in LEVELS] + [("Os", name) for name in PASSES]


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(dialect=st.sampled_from(["arcus", "mcode", "x150"]), data=st.data())
def test_random_programs_keep_contract_and_behaviour(dialect, data):
    module = data.draw(modules(dialect))
    assert verify(module) == []
    profile = profiles.load(module.profile)
    baseline = Baseline(module)  # the source simulated once per scenario for all the choices
    for level, passes in CHOICES:
        work = ir.copy_module(module)
        optimize(work, level, profile, passes, verify=True)
        assert verify(work) == [], (level, passes)
        same_behaviour(module, work, baseline=baseline)
