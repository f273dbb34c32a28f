"""The IR printer: a stable text form (golden) and the JSON form the issue specifies; `mcc ir`."""

from __future__ import annotations

import json

from conftest import SAMPLES, run_mcc
from mcc.compiler import ir
from mcc.compiler.ir_print import to_json, to_text
from mcc.compiler.span import Span


def span(line):
    return Span("p.prg", line, 1, line, 5)


def sample_module() -> ir.Module:
    cond = ir.Compare("=", ir.Status("input", index=2, span=span(4)), ir.Const(1))
    main = ir.Routine("main", ir.RoutineKind.MAIN, [
        ir.Block("%1", [
            ir.SetMotion(ir.MotionParam.MAX_SPEED, "X", ir.Const(8000, ir.Unit.STEPS_PER_S), span(1)),
            ir.Move(ir.MoveMode.ABSOLUTE, (("X", ir.Const(4000, ir.Unit.STEPS)), ("Y", ir.Var("V1"))),
                    span=span(2)),
            ir.Assign(ir.Var("V1"), ir.BinOp("*", ir.BinOp("+", ir.Var("V1"), ir.Const(1)), ir.Const(2)),
                      span(3)),
            ir.Delay(ir.Const(0.25, ir.Unit.S)),
        ], ir.Branch(cond, "%2", "%1", span(4))),
        ir.Block("%2", [ir.Call("S1", span=span(5))], ir.End(span(6))),
    ])
    sub = ir.Routine("S1", ir.RoutineKind.SUBROUTINE, [ir.Block("S1", [ir.Stop("*", ramp=False)], ir.Return())],
                     number=1)
    return ir.Module("arcus", "pmx-4ex-sa", {"V1": ir.Variable("V1")}, [main, sub], steps_per_rev=4000)


GOLDEN_TEXT = """\
module arcus profile=pmx-4ex-sa steps_per_rev=4000
var V1: int32

routine main (main)
%1:
  set max_speed X = 8000 steps/s  ; L1
  move absolute X=4000 steps Y=V1  ; L2
  V1 = (V1 + 1) * 2  ; L3
  delay 0.25 s
  branch input[2] = 1 ? %2 : %1  ; L4
%2:
  call S1  ; L5
  end  ; L6

routine S1 (subroutine) number=1
S1:
  stop * abort
  return
"""


def test_text_form_is_stable():
    assert to_text(sample_module()) == GOLDEN_TEXT


def test_json_form_has_the_documented_shape():
    data = to_json(sample_module())
    assert data["dialect"] == "arcus" and data["profile"] == "pmx-4ex-sa"
    routine = data["routines"][0]
    assert routine["name"] == "main" and routine["kind"] == "main"
    first = routine["blocks"][0]
    assert first["label"] == "%1"
    assert first["ops"][0] == {"op": "SetMotion", "param": "max_speed", "axis": "X",
                               "value": {"expr": "Const", "value": 8000, "unit": "steps/s"},
                               "line": 1, "col": 1}
    assert first["terminator"]["terminator"] == "Branch"
    assert data["variables"][0]["name"] == "V1"
    json.dumps(data)


def test_a_long_expression_prints_without_deep_recursion():
    expr = ir.Var("V1")
    for _ in range(5000):
        expr = ir.BinOp("+", expr, ir.Const(1))
    text = to_text(ir.Module("arcus", "p", routines=[ir.Routine("main", ir.RoutineKind.MAIN, [
        ir.Block("a", [ir.Assign(ir.Var("V2"), expr)], ir.End())])]))
    assert text.count("+ 1") == 5000


def test_mcc_ir_prints_each_dialect(tmp_path):
    for path in (SAMPLES / "arcus" / "pick_and_place.prg", SAMPLES / "mcode" / "pick_and_place.mxt",
                 SAMPLES / "x150" / "01_feed_punch_cell.x150"):
        done = run_mcc("ir", "--no-verify-ir", str(path))
        assert done.returncode == 0, done.stderr
        assert done.stdout.startswith("module "), done.stdout[:200]
        assert "Traceback" not in done.stderr


def test_mcc_ir_json(tmp_path):
    done = run_mcc("ir", "--no-verify-ir", "--format", "json", str(SAMPLES / "arcus" / "pick_and_place.prg"))
    data = json.loads(done.stdout)
    entry = data["files"][0]
    assert set(entry) >= {"path", "dialect", "module", "diagnostics"}
    assert {"dialect", "profile", "variables", "routines"} <= set(entry["module"])
    assert entry["module"]["routines"][0]["blocks"][0]["ops"][0]["op"]


def test_mcc_ir_reports_syntax_errors_without_a_traceback(tmp_path):
    bad = tmp_path / "bad.prg"
    bad.write_text("IF X=\nEND\n")
    done = run_mcc("ir", str(bad))
    assert done.returncode == 1
    assert "bad.prg:1:" in done.stderr and "Traceback" not in done.stderr
