"""One test per pass on hand-built IR: what it changes, and the cases where it must not fire."""

from __future__ import annotations

import pytest

from sim_behaviour import same_behaviour
from mcc.compiler import ir, profiles
from mcc.compiler.ir_print import to_text
from mcc.compiler.opt import optimize, pass_names

ARCUS = profiles.load("pmx-4ex-sa")
MCODE = profiles.load("lmd-c")
X150 = profiles.load("x150-x150ds")


def V(name):
    return ir.Var(name)


def C(value, unit=ir.Unit.NONE):
    return ir.Const(value, unit)


def steps(v):
    return C(v, ir.Unit.STEPS)


def speed(v):
    return C(v, ir.Unit.STEPS_PER_S)


def move(axis, target):
    return ir.Move(ir.MoveMode.ABSOLUTE, ((axis, target),))


def assign(name, value):
    return ir.Assign(V(name), value)


def block(label, ops, term, named=False):
    return ir.Block(label, list(ops), term, named=named)


def module(*blocks, routines=(), dialect="arcus", variables=None):
    main = ir.Routine("main", ir.RoutineKind.MAIN, list(blocks))
    return ir.Module(dialect, {"arcus": "pmx-4ex-sa", "mcode": "lmd-c", "x150": "x150-x150ds"}[dialect],
                     variables or {}, [main, *routines], steps_per_rev=4000)


def run(m, passes, level="O2", profile=ARCUS):
    """Run `passes` on a copy (verifier on), check behaviour, return the copy."""
    work = ir.copy_module(m)
    optimize(work, level, profile, passes, verify=True)
    same_behaviour(m, work)
    return work


def ops(m, routine="main"):
    return [op for b in m.routine(routine).blocks for op in b.ops]


def handler(*body_ops):
    return ir.Routine("H", ir.RoutineKind.HANDLER, [block("h", body_ops, ir.Return())])


# -- fold -------------------------------------------------------------------------------------

def test_fold_computes_constants_and_propagates_them_to_plain_uses():
    m = module(block("a", [assign("V1", ir.BinOp("*", C(4), C(250))), assign("V2", ir.BinOp("+", V("V1"), C(1))),
                           ir.SetOutput(1, V("V1"))], ir.End()))
    out = ops(run(m, "fold"))
    assert out[0].value == C(1000) and out[1].value == C(1001) and out[2].value == C(1000)


def test_fold_never_puts_a_plain_constant_where_a_unit_is_needed():
    m = module(block("a", [assign("V1", C(1000)), move("X", V("V1")), ir.Delay(ir.BinOp("*", V("V1"), C(1)))],
                     ir.End()))
    out = ops(run(m, "fold"))
    assert out[1].targets[0][1] == V("V1")
    assert isinstance(out[2].duration, ir.BinOp)


@pytest.mark.parametrize("expr", [
    ir.BinOp("/", C(7), C(2)),  # inexact division
    ir.BinOp("+", C(2 ** 31 - 1), C(1)),  # overflows 32 bits
    ir.BinOp("+", C(1.5), C(1)),  # floating point
    ir.BinOp("+", steps(5), C(1)),  # units disagree
])
def test_fold_leaves_what_dialects_compute_differently(expr):
    m = module(block("a", [assign("V1", expr)], ir.End()))
    assert ops(run(m, "fold"))[0].value == expr


def test_fold_forgets_at_calls_natives_and_never_trusts_handler_written_variables():
    sub = ir.Routine("S1", ir.RoutineKind.SUBROUTINE, [block("s", [assign("V1", C(9))], ir.Return())], number=1)
    m = module(block("a", [assign("V1", C(1)), ir.Call("S1"), ir.SetOutput(1, V("V1")),
                           assign("V2", C(1)), ir.Native("arcus", "EO", (C(1),)), ir.SetOutput(2, V("V2")),
                           assign("V3", C(1)), ir.SetOutput(3, V("V3"))], ir.End()),
               routines=(sub, handler(assign("V3", C(5)))), dialect="mcode")
    work = ir.copy_module(m)
    optimize(work, "O1", MCODE, "fold", verify=True)
    out = ops(work)
    assert out[2].value == V("V1") and out[5].value == V("V2") and out[7].value == V("V3")


def test_fold_decides_a_branch_condition():
    m = module(block("a", [assign("V1", C(1))], ir.Branch(ir.Compare("=", V("V1"), C(1)), "b", "c")),
               block("b", [ir.SetOutput(1, C(1))], ir.End()), block("c", [ir.SetOutput(1, C(0))], ir.End()))
    work = run(m, "fold,branches,unreachable")
    assert [b.label for b in work.routine("main").blocks] == ["a", "b"]


# -- copies ------------------------------------------------------------------------------------

def test_copies_reads_the_source_until_either_is_assigned():
    m = module(block("a", [assign("V1", V("V2")), ir.SetOutput(1, V("V1")), assign("V2", C(3)),
                           ir.SetOutput(2, V("V1"))], ir.End()))
    out = ops(run(m, "copies"))
    assert out[1].value == V("V2") and out[3].value == V("V1")


def test_copies_never_crosses_variable_types_or_handler_writes():
    floats = {"F1": ir.Variable("F1", ir.VarType.FLOAT64)}
    m = module(block("a", [assign("V1", V("F1")), ir.SetOutput(1, V("V1")), assign("V3", V("V4")),
                           ir.SetOutput(2, V("V3"))], ir.End()),
               routines=(handler(assign("V4", C(1))),), dialect="mcode", variables=floats)
    work = ir.copy_module(m)
    optimize(work, "O1", MCODE, "copies", verify=True)
    out = ops(work)
    assert out[1].value == V("V1") and out[3].value == V("V3")


# -- dead stores -------------------------------------------------------------------------------

def test_dead_stores_removes_an_overwritten_store_at_O2_only():
    m = module(block("a", [assign("V1", C(0)), assign("V1", C(5)), ir.SetOutput(1, V("V1"))], ir.End()))
    assert len(ops(run(m, "dead_stores", "O2"))) == 2
    assert len(ops(run(m, "dead_stores", "O1"))) == 3


def test_dead_stores_stops_at_reads_time_calls_and_handler_reads():
    m = module(block("a", [assign("V1", C(0)), ir.Delay(C(0.1, ir.Unit.S)), assign("V1", C(5)),
                           assign("V2", C(0)), assign("V2", V("V2")),
                           assign("V3", C(0)), assign("V3", C(1))], ir.End()),
               routines=(handler(ir.SetOutput(1, V("V3"))),), dialect="mcode")
    work = ir.copy_module(m)
    optimize(work, "O2", MCODE, "dead_stores", verify=True)
    assert len(ops(work)) == 7


def test_dead_stores_drops_hidden_variables_nothing_reads():
    m = module(block("a", [assign("%n1", C(3)), ir.SetOutput(1, C(1))], ir.End()),
               variables={"%n1": ir.Variable("%n1")})
    work = run(m, "dead_stores", "O1")
    assert len(ops(work)) == 1 and "%n1" not in work.variables


# -- settings ----------------------------------------------------------------------------------

def hspd(axis, v):
    return ir.SetMotion(ir.MotionParam.MAX_SPEED, axis, speed(v))


def test_settings_removes_a_value_already_in_force():
    m = module(block("a", [hspd("X", 5000), move("X", steps(1)), hspd("X", 5000), move("X", steps(2))], ir.End()))
    assert len(ops(run(m, "settings", "O1"))) == 3


def test_settings_keeps_a_star_setting_after_one_axis_changed():
    m = module(block("a", [hspd("*", 5000), hspd("X", 1000), hspd("*", 5000), move("X", steps(1))], ir.End()))
    assert len(ops(run(m, "settings", "O2"))) == 4


def test_settings_forgets_at_calls_and_stops_when_a_handler_changes_motion():
    m = module(block("a", [hspd("X", 5000), ir.Native("arcus", "EO", (C(1),)), hspd("X", 5000)], ir.End()))
    assert len(ops(run(m, "settings", "O1"))) == 3
    m = module(block("a", [hspd("X", 5000), hspd("X", 5000)], ir.End()), routines=(handler(hspd("X", 1)),),
               dialect="mcode")
    assert len(ops(run(m, "settings", "O2", MCODE))) == 2


def test_settings_across_blocks_at_O2():
    m = module(block("a", [hspd("X", 5000)], ir.Jump("b")),
               block("b", [hspd("X", 5000), move("X", steps(1))], ir.End()))
    assert len(ops(run(m, "settings", "O2"))) == 2


def test_settings_at_O2_keeps_an_axis_setting_that_one_path_changed():
    """An unaddressed X150 `V5` reaches every device (parker-x150.md L179: a universal command is
    for all positioners); `1V10` on one path leaves device 1 at 10 there, so `1V5` after the join
    is needed. Before the fix the meet lost device 1's own value and read it as the `*` value."""
    branch = ir.Branch(ir.Compare("=", V("VAR1"), C(1)), "b", "c")
    m = module(block("a", [hspd("*", 5)], branch), block("b", [hspd("1", 10)], ir.Jump("c")),
               block("c", [hspd("1", 5), move("1", steps(1)), ir.WaitMotion("1")], ir.End()), dialect="x150")
    assert len(ops(run(m, "settings", "O2", X150))) == 5  # nothing removed


def test_settings_at_O2_removes_a_star_setting_in_force_on_every_path_and_across_calls():
    """The `*` setting already in force after a join and a call that sets nothing is redundant
    (issue 23: -O2 kept it); after a call that changes it, it is not (arcus-pmx-4ex-sa.txt
    L443-L445: HSPD sets the global high speed)."""
    quiet = ir.Routine("S1", ir.RoutineKind.SUBROUTINE, [block("s", [assign("V2", C(1))], ir.Return())], number=1)
    loud = ir.Routine("S2", ir.RoutineKind.SUBROUTINE, [block("t", [hspd("*", 3000)], ir.Return())], number=2)
    branch = ir.Branch(ir.Compare("=", V("V1"), C(1)), "b", "c")
    m = module(block("a", [hspd("*", 5000)], branch), block("b", [assign("V3", C(1))], ir.Jump("c")),
               block("c", [ir.Call("S1"), hspd("*", 5000), move("X", steps(1)), ir.WaitMotion("X"), ir.Call("S2"),
                           hspd("*", 5000), move("X", steps(2)), ir.WaitMotion("X")], ir.End()),
               routines=(quiet, loud))
    kept = [op for op in ops(run(m, "settings", "O2")) if isinstance(op, ir.SetMotion)]
    assert len(kept) == 2


# -- branches ----------------------------------------------------------------------------------

def test_branches_with_one_target_or_constant_condition_become_jumps():
    m = module(block("a", [], ir.Branch(ir.Compare("<", V("V1"), C(1)), "b", "b")),
               block("b", [], ir.Branch(ir.Compare("=", C(1), C(2)), "c", "d")),
               block("c", [ir.SetOutput(1, C(1))], ir.End()), block("d", [], ir.End()))
    work = run(m, "branches")
    assert [type(b.terminator).__name__ for b in work.routine("main").blocks[:2]] == ["Jump", "Jump"]
    assert work.routine("main").blocks[1].terminator.target == "d"


def test_branches_thread_jumps_on_mcode_only_and_never_past_a_named_label():
    blocks = [block("a", [], ir.Jump("b")), block("b", [], ir.Jump("c")), block("c", [], ir.Jump("d"), named=True),
              block("d", [ir.SetOutput(1, C(1))], ir.End())]
    m = module(*blocks, dialect="mcode")
    work = run(m, "branches", "O1", MCODE)
    assert work.routine("main").blocks[0].terminator.target == "c"
    arcus = module(*[block(b.label, b.ops, ir.Jump(b.terminator.target) if isinstance(b.terminator, ir.Jump)
                           else ir.End(), b.named) for b in blocks])
    assert run(arcus, "branches").routine("main").blocks[0].terminator.target == "b"


# -- unreachable -------------------------------------------------------------------------------

def test_unreachable_removes_dead_blocks_and_uncalled_arcus_subroutines():
    sub = ir.Routine("S1", ir.RoutineKind.SUBROUTINE, [block("s", [ir.SetOutput(1, C(1))], ir.Return())], number=1)
    err = ir.Routine("S31", ir.RoutineKind.SUBROUTINE, [block("e", [ir.SetOutput(2, C(1))], ir.Return())], number=31)
    m = module(block("a", [], ir.End()), block("dead", [ir.SetOutput(1, C(0))], ir.End()), routines=(sub, err))
    work = run(m, "unreachable", "O2")
    assert [b.label for b in work.routine("main").blocks] == ["a"]
    assert [r.name for r in work.routines] == ["main", "S31"]  # SUB 31 runs on an error
    assert len(run(m, "unreachable", "O1").routines) == 3


def test_unreachable_keeps_named_labels_mcode_routines_and_x150_xg_routines():
    m = module(block("a", [], ir.End()), block("K1", [ir.SetOutput(1, C(0))], ir.End(), named=True),
               routines=(ir.Routine("S1", ir.RoutineKind.SUBROUTINE, [block("s", [], ir.Return())]),),
               dialect="mcode")
    work = run(m, "unreachable", "O2", MCODE)
    assert len(work.routine("main").blocks) == 2 and work.routine("S1") is not None
    seq = ir.Routine("2", ir.RoutineKind.SUBROUTINE, [block("q", [], ir.Return())], number=2)
    x = module(block("a", [], ir.GotoRoutine("2")), block("after", [ir.SetOutput(1, C(1))], ir.Jump("a")),
               routines=(seq,), dialect="x150")
    assert len(run(x, "unreachable", "O2", X150).routine("main").blocks) == 2


# -- merge -------------------------------------------------------------------------------------

def test_merge_joins_a_block_into_its_only_predecessor_but_not_named_ones():
    m = module(block("a", [ir.SetOutput(1, C(1))], ir.Jump("b")), block("b", [ir.SetOutput(2, C(1))], ir.Jump("c")),
               block("c", [], ir.End(), named=True))
    work = run(m, "merge", "O1")
    assert [b.label for b in work.routine("main").blocks] == ["a", "c"]


def test_merge_never_merges_a_loop_entry_into_its_latch():
    m = module(block("a", [ir.SetOutput(1, C(1))], ir.Branch(ir.Compare("<", V("V1"), C(1)), "b", "c")),
               block("b", [], ir.Jump("a")), block("c", [], ir.End()))
    work = run(m, "merge", "O1")
    assert [b.label for b in work.routine("main").blocks] == ["a", "b", "c"]


# -- tails -------------------------------------------------------------------------------------

def test_tails_moves_the_common_last_operation_after_the_join():
    m = module(block("a", [], ir.Branch(ir.Compare("=", V("V1"), C(0)), "b", "c")),
               block("b", [ir.SetOutput(1, C(1)), move("X", steps(10))], ir.Jump("d")),
               block("c", [ir.SetOutput(2, C(1)), move("X", steps(10))], ir.Jump("d")),
               block("d", [], ir.End()))
    work = run(m, "tails")
    blocks = {b.label: b for b in work.routine("main").blocks}
    assert len(blocks["b"].ops) == 1 and len(blocks["c"].ops) == 1 and len(blocks["d"].ops) == 1


def test_tails_never_joins_into_a_loop_header():
    # a: ...; jump h.   h: WHILE V1 < 2 -> body / exit.   body: same last op; jump h
    m = module(block("a", [move("X", steps(10))], ir.Jump("h")),
               block("h", [], ir.Branch(ir.Compare("<", V("V1"), C(2)), "body", "exit")),
               block("body", [assign("V1", ir.BinOp("+", V("V1"), C(1))), move("X", steps(10))], ir.Jump("h")),
               block("exit", [], ir.End()))
    work = run(m, "tails")
    assert work.routine("main").block("h").ops == []


# -- outline -----------------------------------------------------------------------------------

GRIP = [ir.WaitMotion("X"), move("Z", steps(-6000)), ir.WaitMotion("Z"), ir.SetOutput(1, C(1)),
        ir.Delay(C(0.25, ir.Unit.S)), move("Z", steps(0)), ir.WaitMotion("Z")]


def test_outline_turns_repeated_runs_into_one_subroutine():
    body = []
    for x in (1000, 2000, 3000, 4000):
        body += [move("X", steps(x))] + GRIP
    m = module(block("a", body, ir.End()))
    work = run(m, "outline", "Os")
    subs = [r for r in work.routines if r.kind is ir.RoutineKind.SUBROUTINE]
    assert len(subs) == 1 and len(subs[0].blocks[0].ops) == len(GRIP)
    assert sum(isinstance(op, ir.Call) for op in ops(work)) == 4
    assert len(ops(work)) == 8


def test_outline_skips_runs_with_calls_natives_and_handlers_and_respects_capacity():
    native = ir.Native("arcus", "EO", (C(1),))
    m = module(block("a", [native, move("X", steps(1)), native] * 4, ir.End()))
    assert not [r for r in run(m, "outline", "Os").routines if r.kind is ir.RoutineKind.SUBROUTINE]
    full = tuple(ir.Routine(f"S{n}", ir.RoutineKind.SUBROUTINE, [block(f"s{n}", [], ir.Return())], number=n)
                 for n in range(0, 31))
    m = module(block("a", [ir.Call("S0")] + GRIP * 3, ir.End()), routines=full)
    assert len(run(m, "outline", "Os").routines) == len(full) + 1  # every number but 31 in use


def test_outline_counts_benefit_in_arcus_lines():
    # a three-axis move costs three lines: two copies of a two-operation run are worth a call
    wide = ir.Move(ir.MoveMode.ABSOLUTE, (("X", steps(1)), ("Y", steps(2)), ("Z", steps(3))))
    run_ = [wide, wide, wide, ir.SetOutput(1, C(1))]
    m = module(block("a", run_ + [ir.SetOutput(2, C(0))] + run_ + [ir.SetOutput(3, C(0))] + run_, ir.End()))
    work = run(m, "outline", "Os")
    assert any(r.name.startswith("%sub") for r in work.routines)


def test_outline_index_bookkeeping_with_several_runs_in_one_block():
    a = [move("X", steps(1)), ir.SetOutput(1, C(1)), ir.Delay(C(0.1, ir.Unit.S)), ir.SetOutput(1, C(0))]
    b = [move("Y", steps(2)), ir.SetOutput(2, C(1)), ir.Delay(C(0.2, ir.Unit.S)), ir.SetOutput(2, C(0))]
    m = module(block("a", a + b + a + [ir.WaitMotion("X")] + b + a + b, ir.End()))
    run(m, "outline", "Os")  # the oracle checks the order of everything


def test_unknown_pass_is_refused():
    with pytest.raises(ValueError, match="unknown pass nope"):
        pass_names("O1", "fold,nope")


def test_ir_text_of_an_optimized_module_prints():
    m = module(block("a", [assign("V1", ir.BinOp("*", C(4), C(250)))], ir.End()))
    assert "V1 = 1000" in to_text(run(m, "fold"))


def test_outline_never_takes_arcus_sub_31_or_a_number_the_target_lacks():
    from mcc.backends.arcus import emit

    subs = tuple(ir.Routine(f"S{n}", ir.RoutineKind.SUBROUTINE, [block(f"s{n}", [], ir.Return())], number=n)
                 for n in range(1, 30))  # SUB 1-29 in use: only SUB 30 is free for outlining
    runs = [[ir.SetOutput(k, C(1)), ir.Delay(C(0.1, ir.Unit.S)), ir.SetOutput(k, C(0)), ir.WaitMotion("X")]
            for k in (1, 2, 3)]
    body = [ir.Call(f"S{n}") for n in range(1, 30)] + [op for r in runs for op in r * 3]
    m = module(block("a", body, ir.End()), routines=subs)
    work = run(m, "outline", "Os")
    new = [r for r in work.routines if r.name.startswith("%sub")]
    assert len(new) == 1
    listing = emit(work, ARCUS)
    assert "SUB 31" not in listing.text and "SUB 30" in listing.text


def test_outline_does_nothing_on_x150_with_sequences_stored_on_the_controller():
    body = GRIP * 4
    m = module(block("a", body + [ir.Call("5")], ir.End()), dialect="x150")
    m.externals.append("5")
    assert len(run(m, "outline", "Os", X150).routines) == 1


def test_outline_on_mcode_keeps_each_new_subroutine_in_its_callers_program_region():
    """lexium-mcode.txt L4794 (`PG 1 [MAIN PROG] [SUBROUTINES]`) and L510-L512 (after the closing PG
    a line runs at once): the new subroutine is placed after the last routine of its callers'
    region, before the immediate stream that follows it, and never called from another region."""
    first = ir.Routine("AA", ir.RoutineKind.MAIN, [block("AA", GRIP * 3, ir.End(), named=True)], origin=100)
    second = ir.Routine("CC", ir.RoutineKind.MAIN, [block("CC", GRIP * 2, ir.End(), named=True)], origin=200)
    tail = ir.Routine("immediate", ir.RoutineKind.IMMEDIATE, [block("%i", [ir.Save()], ir.FallOff())])
    m = ir.Module("mcode", "lmd-c", {}, [first, second, tail], steps_per_rev=51200)
    work = run(m, "outline", "Os", MCODE)
    names = [r.name for r in work.routines]
    assert names[-1] == "immediate", names
    region_of = {}  # the region each routine is written in: a PG address opens one
    for routine in work.routines[:-1]:
        region_of[routine.name] = routine.origin if routine.origin is not None else region_of[names[len(region_of) - 1]]
    new = [name for name in names if name.startswith("%sub")]
    assert new
    for name in new:
        callers = {r.name for r in work.routines for b in r.blocks for op in b.ops
                   if isinstance(op, ir.Call) and op.routine == name}
        assert {region_of[c] for c in callers} == {region_of[name]}, (name, callers, names)
