"""The backend's control-flow rebuilding, expression splitting and ABS/INC insertion, tested by
behaviour: a random IR program and its compiled Arcus text (read back by the Arcus frontend)
must do the same things in the same order and time, in the simulator (tests/sim_behaviour.py)."""

from __future__ import annotations

import random

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as hs

from mcc.backends import arcus as backend
from mcc.compiler import driver, ir, profiles

from sim_behaviour import same_behaviour as same_in_the_simulator

PROFILE = profiles.load("pmx-4ex-sa")
VARS = ["V1", "V2", "V3", "R7"]  # R7: a name from another dialect, mapped to a free V


def const(n):
    return ir.Const(n)


def random_expr(rnd: random.Random, depth: int):
    pick = rnd.random()
    if depth <= 0 or pick < 0.35:
        return rnd.choice([const(rnd.randint(-3, 9)), ir.Var(rnd.choice(VARS)),
                           ir.Status("input", "", rnd.randint(1, 3))])
    if pick < 0.45:
        return ir.UnOp("~", random_expr(rnd, depth - 1))
    return ir.BinOp(rnd.choice(["+", "-", "*", "&", "|", "%", "/"]), random_expr(rnd, depth - 1),
                    random_expr(rnd, depth - 1))


def random_cond(rnd: random.Random, depth: int = 1):
    pick = rnd.random()
    if depth > 0 and pick < 0.15:
        return ir.Logic(rnd.choice(["and", "or"]), random_cond(rnd, depth - 1), random_cond(rnd, depth - 1))
    if depth > 0 and pick < 0.2:
        return ir.Not(random_cond(rnd, depth - 1))
    return ir.Compare(rnd.choice(["=", "!=", "<", "<=", ">", ">="]), random_expr(rnd, rnd.randint(0, 1)),
                      random_expr(rnd, 0))


def random_op(rnd: random.Random, subs: list[str]):
    pick = rnd.random()
    if pick < 0.4:
        return ir.Assign(ir.Var(rnd.choice(VARS)), random_expr(rnd, rnd.randint(0, 2)))
    if pick < 0.55:
        mode = rnd.choice([ir.MoveMode.ABSOLUTE, ir.MoveMode.RELATIVE])
        target = rnd.choice([ir.Const(rnd.randint(0, 99), ir.Unit.STEPS), ir.Var(rnd.choice(VARS))])
        return ir.Move(mode, (("X", target),))
    if pick < 0.65:
        return ir.SetOutput(rnd.randint(1, 8), const(rnd.randint(0, 1)))
    if pick < 0.8 and subs:
        return ir.Call(rnd.choice(subs), random_cond(rnd, 0) if rnd.random() < 0.3 else None)
    return ir.Delay(ir.Const(rnd.randint(1, 50) / 1000, ir.Unit.S))


def random_routine(rnd: random.Random, name: str, kind: ir.RoutineKind, subs: list[str]) -> ir.Routine:
    count = rnd.randint(1, 7)
    labels = [f"{name}_{i}" for i in range(count)]
    blocks = []
    for label in labels:
        ops = [random_op(rnd, subs) for _ in range(rnd.randint(0, 2))]
        pick = rnd.random()
        if pick < 0.45:
            term = ir.Branch(random_cond(rnd), rnd.choice(labels), rnd.choice(labels))
        elif pick < 0.8:
            term = ir.Jump(rnd.choice(labels))
        elif pick < 0.88:
            term = ir.End()
        else:
            term = ir.Return() if kind is ir.RoutineKind.SUBROUTINE else ir.FallOff()
        blocks.append(ir.Block(label, ops, term))
    return ir.Routine(name, kind, blocks)


def random_module(seed: int) -> ir.Module:
    rnd = random.Random(seed)
    module = ir.Module("arcus", "test", path="random.ir")
    subs = ["S1"] if rnd.random() < 0.4 else []
    module.routines.append(random_routine(rnd, "main", ir.RoutineKind.MAIN, subs))
    for name in subs:
        module.routines.append(random_routine(rnd, name, ir.RoutineKind.SUBROUTINE, []))
    return module


def compile_and_read_back(module: ir.Module):
    listing = backend.emit(module, PROFILE)
    errors = [d for d in listing.diagnostics if d.severity.value == "error"]
    if errors:
        return listing, None
    result = driver.check_file("out.prg", "arcus", text=listing.text)
    assert not result.has_errors, [(d.code, d.span.line, d.message) for d in result.diagnostics] + [listing.text]
    return listing, result.analysis.module


def same_behaviour(original: ir.Module, compiled: ir.Module) -> None:
    same_in_the_simulator(original, compiled)


SHARDS = 4  # 200 programs in 4 tests of 50, which the two test workers share (tests/conftest.py SPREAD)


@pytest.mark.parametrize("shard", range(SHARDS))
@settings(max_examples=200 // SHARDS, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=hs.integers(0, 10**9))
def test_random_programs_keep_their_behaviour(shard: int, seed: int) -> None:
    # each shard its own programs, even where the derandomized profile (CI) draws the same seeds
    module = random_module(seed * SHARDS + shard)
    listing, compiled = compile_and_read_back(module)
    assume(compiled is not None)  # not when it needs more temporaries than reserved
    same_behaviour(module, compiled)
    again = backend.emit(compiled, PROFILE)
    assert again.text == listing.text, "compiling the output again changed it"


def block(label, ops, term):
    return ir.Block(label, list(ops), term)


def module_of(*routines) -> ir.Module:
    module = ir.Module("arcus", "test", path="t.ir")
    module.routines = list(routines)
    return module


def irreducible() -> ir.Module:
    """Two blocks that jump into each other, each entered from the entry: no IF/WHILE form."""
    v1 = ir.Var("V1")
    main = ir.Routine("main", ir.RoutineKind.MAIN, [
        block("e", [ir.Assign(v1, const(0))], ir.Branch(ir.Compare("=", ir.Var("V2"), const(1)), "a", "b")),
        block("a", [ir.SetOutput(1, const(1))], ir.Branch(ir.Compare("<", v1, const(5)), "b", "x")),
        block("b", [ir.Assign(v1, ir.BinOp("+", v1, const(1)))], ir.Branch(ir.Compare("<", v1, const(9)), "a", "x")),
        block("x", [], ir.End()),
    ])
    return module_of(main)


def test_irreducible_graph_becomes_a_dispatch_loop_with_a_note() -> None:
    module = irreducible()
    listing, compiled = compile_and_read_back(module)
    notes = [d for d in listing.diagnostics if d.code == "A202"]
    assert len(notes) == 1 and notes[0].severity.value == "info"
    assert "V63" in notes[0].message
    lines = listing.text.splitlines()
    assert lines[0] == "V63=1" and lines[1] == "WHILE V63!=0" and "IF V63=1" in lines
    assert listing.stats["dispatch_loops"] == 1
    for value in (0, 1):
        module.routines[0].blocks[0].ops.insert(0, ir.Assign(ir.Var("V2"), const(value)))
        same_behaviour(module, compiled if value == 0 else compile_and_read_back(module)[1])
        del module.routines[0].blocks[0].ops[0]


def test_structured_graph_gets_if_elseif_else_and_while() -> None:
    v1, v2 = ir.Var("V1"), ir.Var("V2")
    main = ir.Routine("main", ir.RoutineKind.MAIN, [
        block("e", [ir.Assign(v1, const(0))], ir.Jump("h")),
        block("h", [], ir.Branch(ir.Compare("<", v1, const(3)), "b", "out")),
        block("b", [], ir.Branch(ir.Compare("=", v2, const(1)), "t1", "t2")),
        block("t1", [ir.SetOutput(1, const(1))], ir.Jump("j")),
        block("t2", [], ir.Branch(ir.Compare("=", v2, const(2)), "t3", "t4")),
        block("t3", [ir.SetOutput(2, const(1))], ir.Jump("j")),
        block("t4", [ir.SetOutput(3, const(1))], ir.Jump("j")),
        block("j", [ir.Assign(v1, ir.BinOp("+", v1, const(1)))], ir.Jump("h")),
        block("out", [], ir.End()),
    ])
    listing, _ = compile_and_read_back(module_of(main))
    assert listing.text.splitlines() == [
        "V1=0", "WHILE V1<3", "IF V2=1", "DO1=1", "ELSEIF V2=2", "DO2=1", "ELSE", "DO3=1", "ENDIF", "V1=V1+1",
        "ENDWHILE", "END"]
    assert not [d for d in listing.diagnostics if d.code == "A202"]


def test_loop_left_from_the_middle_runs_under_a_flag() -> None:
    v1 = ir.Var("V1")
    main = ir.Routine("main", ir.RoutineKind.MAIN, [block("e", [ir.Call("S")], ir.End())])
    sub = ir.Routine("S", ir.RoutineKind.SUBROUTINE, [
        block("s", [], ir.Jump("h")),
        block("h", [ir.SetOutput(1, const(1))], ir.Jump("m")),
        block("m", [ir.Assign(v1, ir.BinOp("+", v1, const(1)))], ir.Branch(ir.Compare(">", v1, const(5)), "out", "n")),
        block("n", [ir.SetOutput(2, const(1))], ir.Jump("h")),
        block("out", [ir.SetOutput(3, const(1))], ir.Return()),
    ])
    module = module_of(main, sub)
    listing, compiled = compile_and_read_back(module)
    assert listing.text.splitlines() == [
        "GOSUB 1", "END", "SUB 1", "V63=1", "WHILE V63=1", "DO1=1", "V1=V1+1", "IF V1>5", "V63=0", "ELSE", "DO2=1",
        "ENDIF", "ENDWHILE", "DO3=1", "ENDSUB"]
    same_behaviour(module, compiled)


def test_expressions_are_split_through_temporaries() -> None:
    v1, v2 = ir.Var("V1"), ir.Var("V2")
    value = ir.BinOp("+", ir.BinOp("*", v2, const(3)), ir.BinOp("-", v1, const(4)))
    main = ir.Routine("main", ir.RoutineKind.MAIN, [
        block("e", [ir.Assign(v1, value), ir.SetMotion(ir.MotionParam.MAX_SPEED, "X", ir.BinOp("+", v1, const(100)))],
              ir.Branch(ir.Compare("<", ir.BinOp("+", v1, const(1)), v2), "t", "x")),
        block("t", [ir.Delay(ir.Const(0.005, ir.Unit.S))], ir.Jump("x")),
        block("x", [], ir.End()),
    ])
    listing, _ = compile_and_read_back(module_of(main))
    assert listing.text.splitlines() == [
        "V60=V2*3", "V61=V1-4", "V1=V60+V61", "V60=V1+100", "HSPDX=V60", "V60=V1+1", "IF V60<V2", "DELAY=5",
        "ENDIF", "END"]


def test_profile_chooses_the_temporaries() -> None:
    data = dict(PROFILE.data)
    data["arcus"] = {**data["arcus"], "temporaries": [40, 41]}
    profile = profiles.Profile(PROFILE.name, "arcus", PROFILE.product, PROFILE.title, PROFILE.firmware,
                               PROFILE.axes, 0, data)
    v1 = ir.Var("V1")
    main = ir.Routine("main", ir.RoutineKind.MAIN, [
        block("e", [ir.Assign(v1, ir.BinOp("+", ir.BinOp("*", v1, const(3)), const(1)))], ir.End())])
    assert backend.emit(module_of(main), profile).text.splitlines()[:2] == ["V40=V1*3", "V1=V40+1"]


def test_program_using_a_needed_temporary_is_warned() -> None:
    v60 = ir.Var("V60")
    main = ir.Routine("main", ir.RoutineKind.MAIN, [
        block("e", [ir.Assign(v60, const(5)), ir.Assign(ir.Var("V1"), ir.BinOp("+", ir.BinOp("*", v60, const(3)),
                                                                                 const(1)))], ir.End())])
    module = module_of(main)
    module.variables["V60"] = ir.Variable("V60")
    listing = backend.emit(module, PROFILE)
    assert [d.code for d in listing.diagnostics] == ["A203"]


def test_too_deep_an_expression_runs_out_of_temporaries() -> None:
    expr = ir.Var("V1")
    for _ in range(6):
        expr = ir.BinOp("*", const(2), ir.BinOp("+", expr, const(1)))
    main = ir.Routine("main", ir.RoutineKind.MAIN, [block("e", [ir.Assign(ir.Var("V2"), expr)], ir.End())])
    listing = backend.emit(module_of(main), PROFILE)
    assert "A205" in [d.code for d in listing.diagnostics]


def a205(text: str, dialect: str):
    result = driver.compile_file(f"temps.{dialect}", dialect, "arcus", None, text)
    return [d for d in result.diagnostics if d.code == "A205"]


def test_running_out_of_temporaries_names_the_expression_that_needs_them() -> None:
    """Arcus computes one operator per line (arcus-pmx-4ex-sa.txt L1797: a register's value is a
    literal or one variable), so an X150 chain evaluated left to right (parker-x150.md L4638) takes
    one temporary per operator; the refusal points at that line, not at the whole file (issue 23:
    135 fuzz refusals named no line)."""
    text = "1XE1\n1XD1\n1VAR2=3\n1VAR1=VAR2+1*2+1*2+1*2\n1IF(VAR1>3)\n1O1\n1NIF\n1XT\n"
    found = a205(text, "x150")
    assert [(d.span.line, d.span.column) for d in found] == [(4, 1)]


def test_running_out_of_loop_flags_names_the_routine_whose_loops_need_them() -> None:
    """Sixteen nested X150 loops (L..N, parker-x150.md L2332 allows 16) each need a loop flag
    on Arcus: the refusal names the sequence that holds them (line 2, its XE), not line 1 column 1."""
    text = "; sixteen nested loops\n1XE1\n1XD1\n" + "1L2\n" * 16 + "1G\n" + "1N\n" * 16 + "1XT\n"
    found = a205(text, "x150")
    assert [d.span.line for d in found] == [2]


def test_the_fuzz_finding_of_a_refusal_without_a_line_now_names_the_sequence() -> None:
    """bench/fuzz_codegen.py x150 seed 208, minimized (was bench/findings/
    x150-arcus-temporaries-refused-without-line.x150): A205 was reported on the whole file.
    Sequence 1's nested loops (parker-x150.md L2332) need the fifth temporary: the refusal names its
    XD line."""
    text = ("1XD3\n1L2\n1G\n1G\n1N\n1IF(VAR3>3)\n1NIF\n1L2\n1N\n1XT\n"
            "1XD2\n1L2\n1L3\n1G\n1O1\n1T0.25\n1N\n1IF(VAR2>-8)\n1NIF\n1N\n1XT\n"
            "1XD1\n1L3\n1L3\n1VAR1=-4000\n1D(VAR3)\n1G\n1N\n1N\n1IF(VAR4>54)\n1NIF\n1XT\n")
    found = a205(text, "x150")
    assert [d.span.line for d in found] == [22]


def test_logic_conditions_predicated_calls_and_input_waits() -> None:
    v1, v2 = ir.Var("V1"), ir.Var("V2")
    di1 = ir.Status("input", "", 1)
    main = ir.Routine("main", ir.RoutineKind.MAIN, [
        block("e", [ir.Call("K", ir.Compare("=", v1, const(2))), ir.WaitInput(ir.Compare("=", di1, const(1)))],
              ir.Branch(ir.Logic("or", ir.Compare("=", v1, const(1)),
                                 ir.Not(ir.Logic("and", ir.Compare(">", v2, const(3)), ir.Truth(v1)))), "t", "x")),
        block("t", [ir.SetOutput(1, const(1))], ir.Jump("x")),
        block("x", [], ir.End()),
    ])
    # HOMEX-: 0 at the switch, no creep back (arcus-pmx-4ex-sa.txt L662)
    sub = ir.Routine("K", ir.RoutineKind.SUBROUTINE, [block("k", [ir.Home("X", "switch", -1, zero="switch")],
                                                             ir.Return())])
    module = module_of(main, sub)
    listing, compiled = compile_and_read_back(module)
    text = listing.text.splitlines()
    assert text[:5] == ["IF V1=2", "GOSUB 1", "ENDIF", "WHILE DI1!=1", "ENDWHILE"]
    assert text[-4:] == ["END", "SUB 1", "HOMEX-", "ENDSUB"]
    same_behaviour(module, compiled)


def test_moves_get_abs_or_inc_where_the_mode_is_not_known() -> None:
    main = ir.Routine("main", ir.RoutineKind.MAIN, [block("e", [
        ir.Move(ir.MoveMode.ABSOLUTE, (("X", const(10)),)), ir.Move(ir.MoveMode.ABSOLUTE, (("Y", const(5)),)),
        ir.Move(ir.MoveMode.RELATIVE, (("X", const(1)), ("Y", const(2)))), ir.Move(ir.MoveMode.RELATIVE, (("Z", const(3)),)),
    ], ir.End())])
    listing, compiled = compile_and_read_back(module_of(main))
    assert listing.text.splitlines() == ["X10", "Y5", "INC", "X1Y2", "Z3", "END"]  # ABS at power-up (profile)
    modes = [op.mode for op in compiled.routines[0].blocks[0].ops if isinstance(op, ir.Move)]
    assert modes == [ir.MoveMode.ABSOLUTE] * 2 + [ir.MoveMode.RELATIVE] * 2


def test_other_dialects_operations_are_reported_not_crashed() -> None:
    main = ir.Routine("main", ir.RoutineKind.MAIN, [block("e", [
        ir.Native("mcode", "IS", (const(1),)), ir.Print((ir.Text("hello"),)), ir.Save(),
        ir.Assign(ir.Var("V1"), ir.Func("sqrt", (ir.Var("V2"),))), ir.SetOutput(1, const(1)),
        ir.SetMotion(ir.MotionParam.ACCEL, "X", ir.Const(5000, ir.Unit.STEPS_PER_S2)),
        ir.Slew("X", ir.Const(100)), ir.Move(ir.MoveMode.ABSOLUTE, (("W", const(1)),)),
    ], ir.GotoRoutine("K"))])
    handler = ir.Routine("H", ir.RoutineKind.HANDLER, [block("h", [], ir.Return())])
    listing = backend.emit(module_of(main, handler), PROFILE)
    codes = sorted(d.code for d in listing.diagnostics)
    # the acceleration too: no speeds are known to make it a ramp time; and the slew, since X's own
    # acceleration is used only with X's own speeds, unknown there (arcus-pmx-4ex-sa.txt L447-L457)
    assert codes == ["G003"] * 9
    assert listing.text.splitlines() == ["DO1=1", "Y1", "END"]  # axis W is the first free letter


def test_literal_only_operands_computed_at_run_time_are_reported() -> None:
    main = ir.Routine("main", ir.RoutineKind.MAIN, [block("e", [
        ir.Delay(ir.Var("V1")), ir.Native("arcus", "TR", (ir.Var("V2"),), "="),
        ir.Arc(("X", "Y"), (ir.Var("V1"), const(0)), True, const(9000)),
    ], ir.End())])
    listing = backend.emit(module_of(main), PROFILE)
    assert [d.code for d in listing.diagnostics] == ["A206"] * 3


def test_routines_without_numbers_get_free_subroutine_numbers() -> None:
    main = ir.Routine("main", ir.RoutineKind.MAIN, [block("e", [ir.Call("A"), ir.Call("B")], ir.End())])
    first = ir.Routine("A", ir.RoutineKind.SUBROUTINE, [block("a", [], ir.Return())], number=None)
    second = ir.Routine("B", ir.RoutineKind.SUBROUTINE, [block("b", [], ir.Return())], number=1)
    listing = backend.emit(module_of(main, first, second), PROFILE)
    assert listing.text.splitlines() == ["GOSUB 2", "GOSUB 1", "END", "SUB 2", "ENDSUB", "SUB 1", "ENDSUB"]
