"""A check, a compile and a lint make no reference cycles (docs/PERFORMANCE.md).

`driver.fewer_collections` turns the cyclic garbage collector off while a file is analysed and
then moves what was made to the collector's oldest generation without walking it. That is only
sound if the work leaves no cyclic garbage behind: a cycle would then wait for a full collection
(in the language server, across many edits) instead of being freed by the young generations. Each
step is run on the samples, with and without syntax errors, and `gc.collect()` must find nothing.
"""

from __future__ import annotations

import gc
from pathlib import Path

import pytest

from mcc.compiler import driver
from mcc.compiler.config import Settings
from mcc.compiler.lint import engine

ROOT = Path(__file__).resolve().parent.parent
SAMPLES = sorted(p for p in (ROOT / "samples").glob("*/*") if p.suffix in (".mxt", ".x150", ".prg"))


def broken(text: str) -> str:
    """The text with a stray character in every third line: syntax errors and recovery."""
    return "".join(line.rstrip("\n") + (" @#\n" if i % 3 == 1 else "\n")
                   for i, line in enumerate(text.splitlines()))


def cyclic_garbage(work) -> int:
    """How many objects only the cycle collector frees after `work` (its second run: the first
    one fills the caches that live as long as the process)."""
    work()
    was_enabled = gc.isenabled()
    gc.collect()
    # what exists now (the test process's own objects and those caches) is moved out of the
    # collector's view, so that the collection below walks only what the second run made
    gc.freeze()
    gc.disable()
    try:
        work()
        return gc.collect()
    finally:
        gc.unfreeze()
        if was_enabled:
            gc.enable()


@pytest.mark.parametrize("path", SAMPLES, ids=lambda p: p.name)
@pytest.mark.parametrize("errors", [False, True], ids=["clean", "syntax-errors"])
def test_no_cycles(path: Path, errors: bool) -> None:
    text = path.read_text(encoding="utf-8")
    if errors:
        text = broken(text)
    name = str(path)
    assert cyclic_garbage(lambda: driver.check_file(name, text=text)) == 0
    assert cyclic_garbage(lambda: driver.compile_file(name, text=text)) == 0
    assert cyclic_garbage(lambda: engine.lint_text(name, text, Settings())) == 0


def test_the_collector_is_back_on_after_a_check() -> None:
    assert gc.isenabled()
    driver.check_file(str(SAMPLES[0]), text=SAMPLES[0].read_text(encoding="utf-8"))
    assert gc.isenabled()


def test_a_cycle_left_by_the_work_is_counted() -> None:
    """The measure is not vacuous: a list that holds itself, made by the work, is found."""
    def work() -> None:
        loop: list = []
        loop.append(loop)

    assert cyclic_garbage(work) == 1
