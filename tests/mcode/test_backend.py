"""The MCode backend on IR built by hand: generated labels follow the naming rules and never collide."""

from __future__ import annotations

import re

from mcc.backends import mcode as backend
from mcc.compiler import driver, ir
from mcc.compiler import profiles
from mcc.compiler.mcode import catalog
from mcc.compiler.span import Span

PROFILE = profiles.load("lmd-c")


def loop_module(user_names: list[str]) -> ir.Module:
    """main: %1 counts Z0 up; a branch back to the unnamed loop head needs a generated label."""
    module = ir.Module("mcode", "lmd-c")
    for name in user_names:
        module.variables[name] = ir.Variable(name)
    counter = ir.Var(user_names[0])
    head = ir.Block("%1", [ir.Assign(counter, ir.BinOp("+", counter, ir.Const(1)))],
                    ir.Branch(ir.Compare("<", counter, ir.Const(10)), "%1", "%2"))
    tail = ir.Block("%2", [ir.Move(ir.MoveMode.RELATIVE, (("", ir.Const(100)),))], ir.Jump("%3"))
    after = ir.Block("%3", [ir.WaitMotion("")], ir.End())
    main = ir.Routine("@1", ir.RoutineKind.MAIN, [head, tail, after], origin=1)
    sub = ir.Routine("%sub", ir.RoutineKind.SUBROUTINE, [ir.Block("%4", [], ir.Return())])
    head.ops.append(ir.Call("%sub"))
    module.routines += [main, sub]
    return module


def test_generated_labels_are_valid_and_fresh():
    listing = backend.emit(loop_module(["Z0", "Z2", "Q1"]), PROFILE)
    text = listing.text
    labels = re.findall(r"^LB (\w+)$", text, re.M)
    assert len(labels) == 2  # the loop head and the subroutine; %2/%3 follow in order
    cat = catalog.load()
    for label in labels:
        assert re.fullmatch(r"[A-Z][A-Z0-9]", label)
        assert label not in cat.commands and label not in cat.functions
        assert label not in ("Z0", "Z2", "Q1")
    assert "IC Z0" in text and "BR " + labels[0] + ",Z0<10" in text
    assert f"CL {labels[1]}" in text


def test_generated_program_checks_clean_and_is_stable():
    text = backend.emit(loop_module(["Z0"]), PROFILE).text
    first = driver.compile_file("gen.mxt", "mcode", text=text)
    assert not first.has_errors, [(d.code, d.message) for d in first.diagnostics]
    assert first.listing.text == text


def test_unsupported_constructs_are_reported_not_raised():
    module = ir.Module("arcus", "pmx-4ex-sa")
    span = Span("x.prg", 3, 1, 3, 10, 0, 9)
    block = ir.Block("%1", [ir.Move(ir.MoveMode.MODAL, (("X", ir.Const(1)), ("Y", ir.Const(2))), span=span),
                            ir.Native("arcus", "SYNXO", span=span)], ir.End())
    module.routines.append(ir.Routine("MAIN", ir.RoutineKind.MAIN, [block], origin=1))
    listing = backend.emit(module, PROFILE)
    assert [d.code for d in listing.diagnostics] == ["G003", "G003"]
    assert all(d.span.line == 3 for d in listing.diagnostics)


def test_another_dialects_stream_that_waits_for_a_move_runs_as_a_program():
    """H (wait for the move) is a program statement in MCode (M112): an X150 stream that moves and
    waits becomes the program at address 1, run by EX 1, and it behaves as its source."""
    from mcc.sim.verify import check_translation

    source = "MN\nA10\nV10\nD-100000\nG\nT0.5\n1O1\n"
    result = driver.compile_file("s.x150", "x150", target="mcode", text=source)
    assert not result.has_errors, [d.message for d in result.diagnostics]
    lines = [line for line in result.listing.text.splitlines() if not line.startswith("'")]
    assert lines[0] == "PG 1" and "H" in lines and lines[-2:] == ["PG", "EX 1"]
    assert not driver.check_file("o.mxt", "mcode", text=result.listing.text).has_errors
    assert not check_translation("s.x150", "x150", source, result.listing.text, "mcode")


def test_an_x150_program_starts_from_standstill_so_vi_is_written_at_its_lowest():
    """X150 has no initial speed (in_force.FIXED): without VI the drive would start each move at its
    stored VI (1000 by default), above this program's max speed of 0.01 rev/s (Error 22)."""
    source = "XE1\nXD1\nMN\nV0.01\nA10\nD8000\nG\nXT\n"
    result = driver.compile_file("s.x150", "x150", target="mcode", text=source)
    assert not result.has_errors, [(d.code, d.message) for d in result.diagnostics]
    lines = result.listing.text.splitlines()
    assert lines[lines.index("PG 1") + 1:lines.index("PG 1") + 3] == ["VI=1", "VM=512"]  # 0.01 rev/s at 51200
    assert any("standstill" in line for line in lines if line.startswith("'"))
    assert not driver.compile_file("out.mxt", "mcode", text=result.listing.text).has_errors
