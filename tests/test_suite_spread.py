"""How the suite is spread over the workers (tests/conftest.py, issue 26): a file's tests stay
together except in the SPREAD files, and the SLOW_FIRST entries name tests that exist, so a rename
does not silently send a slow test to the end of the run."""

from __future__ import annotations

from pathlib import Path

import conftest

TESTS = Path(conftest.__file__).resolve().parent


def test_a_spread_file_is_one_unit_per_test_and_any_other_file_one_unit() -> None:
    assert conftest.work_unit("tests/test_codegen_random.py::test_x[mcode-20]") == \
        "tests/test_codegen_random.py::test_x[mcode-20]"
    assert conftest.work_unit("tests/lsp/test_features.py::test_hover") == "tests/lsp/test_features.py"
    assert conftest.work_unit("tests/lsp/test_features.py::Case::test_hover[a::b]") == "tests/lsp/test_features.py"
    assert conftest.work_unit("tests/link/test_device_sim.py::test_x[a.prg]") == "tests/link/test_device_sim.py::test_x[a.prg]"


def test_every_spread_file_and_slow_entry_exists() -> None:
    for name in conftest.SPREAD:
        assert (TESTS / name).is_file(), name
    for prefix in conftest.SLOW_FIRST:
        path, _, test = prefix.partition("::")
        assert (TESTS / path).exists(), prefix
        if test:
            assert f"def {test.split('[')[0]}(" in (TESTS / path).read_text(), prefix


def test_the_slow_units_are_collected_first_in_their_order() -> None:
    assert conftest._slow_rank(conftest.SLOW_FIRST[0] + "::t") == 0
    assert conftest._slow_rank("sim/test_sim_interpreter.py::t") == len(conftest.SLOW_FIRST)
