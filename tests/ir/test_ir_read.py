"""The IR reader (compiler/ir_read.py): the text form of `mcc ir` parsed back. Printing what it read
gives the text again, for every sample and golden program of each dialect, generated programs
through their frontends, random IR and every operation of the table; a text that is not IR is
refused at a line and column; tests can state IR directly (tests/ir/ir_text.py)."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import every_op
from codegen_programs import EXTENSIONS, generate
from ir_programs import modules_of
from ir_text import expected, ir_from_text, ir_text
from mcc.compiler import driver, ir, profiles
from mcc.compiler.ir_print import to_text
from mcc.compiler.ir_read import IRSyntaxError, read_text
from mcc.compiler.ir_verify import verify
from mcc.compiler.opt import optimize

DIALECTS = ("mcode", "arcus", "x150")


def random_modules():
    """tests/opt/random_ir.py's strategy (its folder is on the path only when tests/opt runs)."""
    import sys
    from pathlib import Path

    folder = str(Path(__file__).resolve().parent.parent / "opt")
    if folder not in sys.path:
        sys.path.append(folder)
    from random_ir import modules

    return modules


def round_trip(module: ir.Module) -> None:
    text = to_text(module)
    assert to_text(read_text(text)) == text


@pytest.mark.parametrize("dialect", DIALECTS)
def test_every_sample_and_golden_program_reads_back(dialect):
    count = 0
    for _path, module in modules_of(dialect):
        round_trip(module)
        count += 1
    assert count >= 10


@pytest.mark.parametrize("dialect", DIALECTS)
def test_generated_programs_read_back_lowered_and_optimized(dialect):
    """Programs of tests/codegen_programs.py through the dialect's frontend, as lowered and at -Os."""
    for seed in range(20):
        program = generate(dialect, seed)
        result = driver.check_file("random" + EXTENSIONS[dialect], dialect, None, program.text)
        module = result.analysis.module
        round_trip(module)
        work = ir.copy_module(module)
        optimize(work, "Os", profiles.load(work.profile), None)
        round_trip(work)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(dialect=st.sampled_from(DIALECTS), data=st.data())
def test_random_valid_modules_read_back_and_keep_the_contract(dialect, data):
    """tests/opt/random_ir.py's modules: the module read back keeps the verifier's contract too."""
    modules = random_modules()
    module = data.draw(modules(dialect))
    round_trip(module)
    assert verify(read_text(to_text(module))) == []


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(every_op.modules())
def test_every_operation_of_the_table_reads_back(module):
    round_trip(module)


def test_spans_come_from_the_line_suffixes():
    module = ir_from_text("""
        routine main (main)
        %1:
          delay 0.5 s  ; L7
          end
    """, path="cell.ir")
    block = module.routines[0].blocks[0]
    assert block.ops[0].span.line == 7 and block.ops[0].span.file == "cell.ir"
    assert block.terminator.span is None


def test_a_long_expression_reads_without_deep_recursion():
    text = "V1 = " + "(" * 4999 + "V1" + " + 1)" * 4999 + " + 1"
    module = ir_from_text(f"routine main (main)\na:\n  {text}\n  end\n")
    assert ir_text(module).count("+ 1") == 5000


@pytest.mark.parametrize("text, line, col, message", [
    ("routine main (main)\n%1:\n  move sideways X=1 steps\n  end\n", 4, 8, "'sideways' is not one of absolute"),
    ("routine main (main)\n%1:\n  delay (1 + 2\n  end\n", 4, 15, "expected ')'"),
    ("routine main (main)\n%1:\n  teleport X\n  end\n", 4, 3, "expected an operation"),
    ("routine main (main)\n%1:\n  end\n  delay 1 s\n", 4, 3, "'end' is a terminator"),
    ("routine main (main)\n%1:\n  delay 1 s\n  move absolute X=1 steps\n", 5, 3, "expected a terminator"),
    ("routine main (weekly)\n%1:\n  end\n", 2, 15, "routine kind 'weekly'"),
    ("%1:\n  end\n", 2, 1, "a block outside a routine"),  # line 1 is the module line ir_from_text adds
    ("routine main (main)\n  end\n", 3, 1, "an operation outside a block"),
    ("routine main (main)\n%1:\nroutine S1 (subroutine)\n", 3, 1, "block %1 has no terminator line"),
    ("var V1: int64\n", 2, 9, "variable type 'int64'"),
    ("routine main (main)\n%1:\n  print \"open\n  end\n", 4, 9, "a quoted text"),
    ("routine main (main)\n%1:\n  home X switch direction +1 zero end speed\n  end\n", 4, 38, "unexpected text"),
])
def test_text_that_is_not_ir_is_refused_at_a_line_and_column(text, line, col, message):
    with pytest.raises(IRSyntaxError) as caught:
        ir_from_text(text)
    error = caught.value
    assert (error.line, error.col) == (line, col), str(error)
    assert message in error.message
    assert str(error).startswith(f"{line}:{col}: ")


def test_the_module_line_is_required():
    with pytest.raises(IRSyntaxError, match="^1:1: expected the module line"):
        read_text("routine main (main)\n")
    with pytest.raises(IRSyntaxError, match="no module line"):
        read_text("")


def test_a_bare_name_is_a_declared_variable_before_a_reading():
    """`moving` is the reading of that name unless a var line declares a variable of it."""
    reading = ir_from_text("routine main (main)\na:\n  V1 = moving\n  end\n")
    assert reading.routines[0].blocks[0].ops[0].value == ir.Status("moving")
    declared = ir_from_text("var moving: int32\nroutine main (main)\na:\n  V1 = moving\n  end\n")
    assert declared.routines[0].blocks[0].ops[0].value == ir.Var("moving")


# ---------------------------------------------------------------------------------------------
# Optimizer passes stated as IR in, IR out


def optimized(text: str, passes: str, level: str = "O2", dialect: str = "arcus") -> str:
    module = ir_from_text(text, dialect)
    assert verify(module) == []
    optimize(module, level, profiles.load(module.profile), passes, verify=True)
    return ir_text(module)


def test_fold_as_ir_text():
    """The fold pass computes constants and propagates them to plain uses (tests/opt/test_passes.py,
    the same case built from dataclasses)."""
    assert optimized("""
        routine main (main)
        a:
          V1 = 4 * 250  ; L1
          V2 = V1 + 1  ; L2
          output 1 = V1  ; L3
          end  ; L4
    """, "fold") == expected("""
        routine main (main)
        a:
          V1 = 1000  ; L1
          V2 = 1001  ; L2
          output 1 = 1000  ; L3
          end  ; L4
    """)


def test_dead_stores_as_ir_text():
    text = """
        routine main (main)
        a:
          V1 = 0  ; L1
          V1 = 5  ; L2
          output 1 = V1  ; L3
          end  ; L4
    """
    assert optimized(text, "dead_stores") == expected("""
        routine main (main)
        a:
          V1 = 5  ; L2
          output 1 = V1  ; L3
          end  ; L4
    """)
    assert optimized(text, "dead_stores", "O1") == expected(text)


def test_branches_as_ir_text():
    """A branch to one block either way, and one whose condition is a constant, become jumps."""
    assert optimized("""
        routine main (main)
        a:
          branch V1 < 1 ? b : b
        b:
          branch 1 = 2 ? c : d
        c:
          output 1 = 1
          end
        d:
          end
    """, "branches") == expected("""
        routine main (main)
        a:
          jump b
        b:
          jump d
        c:
          output 1 = 1
          end
        d:
          end
    """)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_any_text_reads_or_is_refused_at_a_line(data):
    """No Python exception but IRSyntaxError for any text: printed modules with characters cut,
    doubled or replaced."""
    text = to_text(data.draw(every_op.modules()))
    for _ in range(data.draw(st.integers(1, 4))):
        at = data.draw(st.integers(0, len(text)))
        change = data.draw(st.sampled_from(["cut", "double", "replace"]))
        piece = data.draw(st.sampled_from(list(" ()[],=:;%-+\"'{}|^$@.0123456789xXL\n") + ["9" * 5000, "\t"]))
        if change == "cut":
            text = text[:at] + text[at + data.draw(st.integers(1, 8)):]
        elif change == "double":
            text = text[:at] + text[at:at + 4] + text[at:]
        else:
            text = text[:at] + piece + text[at + 1:]
    try:
        read_text(text)
    except IRSyntaxError as error:
        assert error.line >= 1 and error.col >= 1
