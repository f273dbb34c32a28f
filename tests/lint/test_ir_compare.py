"""The IR comparison the formatter relies on: positions are ignored, everything else counts."""

from __future__ import annotations

from mcc.compiler import driver
from mcc.compiler.ir_compare import differences, equivalent


def module(text: str, path: str = "a.mxt"):
    return driver.check_file(path, "mcode", text=text).analysis.module


def test_positions_and_paths_are_ignored() -> None:
    a = module("PG 1\nLB G1\n  MA 100\n  E\nPG\n", "a.mxt")
    b = module("\n\nPG 1\nLB G1\n        MA   100\n  E\nPG\n", "elsewhere/b.mxt")
    assert differences(a, b) == [] and equivalent(a, b)


def test_a_changed_value_is_found_with_its_path() -> None:
    a = module("PG 1\nLB G1\n  MA 100\n  E\nPG\n")
    b = module("PG 1\nLB G1\n  MA 101\n  E\nPG\n")
    [difference] = differences(a, b)
    assert difference.startswith("module.routines[0].blocks[0].ops[0].targets[0][1].value: 100 != 101")


def test_structure_and_types_count() -> None:
    a = module("PG 1\nLB G1\n  MA 100\n  E\nPG\n")
    assert differences(a, module("PG 1\nLB G1\n  MA 100\n  H\n  E\nPG\n"))  # one more operation
    assert differences(a, module("PG 1\nLB G1\n  MA 100.0\n  E\nPG\n"))  # int vs float
    assert not equivalent(a, module("PG 1\nLB G1\n  MR 100\n  E\nPG\n"))
