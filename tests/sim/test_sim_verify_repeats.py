"""Runs that make the same events round after round at one instant, for ever (issue 23).

An Arcus loop `WHILE 1=1 / PX=0 / ENDWHILE` sets the position again and again without time
passing or anything changing. The simulator's poll detector stops it after a number of steps, and
so after a number of rounds that depends on the steps per round, which a rewrite may change: before,
the validation then reported "the output does more" for two programs that do the same thing for
ever (the 10,000-program fuzz, Arcus seed 2154). Now the rounds that repeat are compared as a round
(`sim/verify._repeating`): the same round is equal whatever the count, and a run that repeats where
the other stops doing anything is still a difference, so the comparison cannot pass by comparing
nothing.
"""

from __future__ import annotations

from mcc.compiler import driver
from mcc.sim.interpreter import simulate
from mcc.sim.verify import check_translation

FOREVER = """EO=1
WHILE 1=1
PX=0
ENDWHILE
END
"""


def translate(source: str, output: str) -> str:
    return check_translation("repeats.prg", "arcus", source, output)


def test_a_run_that_repeats_for_ever_marks_where_its_rounds_began():
    module = driver.check_file("repeats.prg", "arcus", None, FOREVER).analysis.module
    trace = simulate(module)
    assert trace.stopped == "waiting"
    assert trace.repeats_from is not None
    assert {e.kind for e in trace.events[trace.repeats_from:-1]} == {"set_position"}


def test_more_steps_per_round_is_the_same_program():
    """Two statements more per round: fewer rounds before the poll detector stops the run."""
    longer = FOREVER.replace("PX=0\n", "V2=5\nV3=V2\nV2=V3\nPX=0\n")
    assert translate(FOREVER, longer) == ""


def test_a_round_written_twice_is_the_same_program():
    assert translate(FOREVER, FOREVER.replace("PX=0\n", "PX=0\nPX=0\n")) == ""


def test_another_round_is_a_difference():
    found = translate(FOREVER, FOREVER.replace("PX=0\n", "PX=0\nPX=5\n"))
    assert found != ""


def test_stopping_after_a_few_rounds_is_a_difference():
    """The output sets the position three times and then only spins: the source goes on for ever."""
    few = """EO=1
V1=0
WHILE V1<3
PX=0
V1=V1+1
ENDWHILE
WHILE 1=1
ENDWHILE
END
"""
    module = driver.check_file("few.prg", "arcus", None, few).analysis.module
    assert simulate(module).repeats_from is None
    found = translate(FOREVER, few)
    assert "over and over" in found


def test_a_homing_on_the_switch_the_axis_stands_on_changes_nothing():
    """A second HOMEX- right after one that ended on the switch trips at once and leaves position
    and zero as they were: like a move to where the axis is, it is not an observable difference
    (seed 2154). The first homing is, even where the scenario starts the axis on its switch: on a
    machine the axis may start anywhere."""
    source = "EO=1\nHOMEX-\nWAITX\nX500\nWAITX\nEND\n"
    output = "EO=1\nHOMEX-\nWAITX\nHOMEX-\nWAITX\nX500\nWAITX\nEND\n"
    trace = simulate(driver.check_file("h.prg", "arcus", None, output).analysis.module)
    homes = [e for e in trace.events if e.kind == "home"]
    assert len(homes) == 2 and homes[1].data.get("idle") and not homes[0].data.get("idle")
    assert translate(source, output) == ""


def test_a_first_homing_is_observable_even_on_the_switch():
    assert translate("EO=1\nX500\nWAITX\nEND\n", "EO=1\nHOMEX-\nWAITX\nX500\nWAITX\nEND\n") != ""
