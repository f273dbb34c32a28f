"""Cooperative cancellation (compiler/cancel.py): checkpoints do nothing unless a callback is
installed for the thread, and Cancelled gets through the compiler's no-traceback guards."""

from __future__ import annotations

import threading

import pytest

from mcc.compiler import cancel, driver

PROGRAM = "ABS\nHSPD=1000\nX1000\nEND\n"


def test_without_a_callback_a_checkpoint_does_nothing():
    cancel.checkpoint()
    for index in range(3 * cancel.EVERY):
        cancel.every(index)


def test_a_checkpoint_raises_when_the_callback_says_stop_and_the_callback_is_restored():
    answers = iter([False, True])
    with cancel.stopping_when(lambda: next(answers)):
        cancel.checkpoint()  # False: goes on
        with pytest.raises(cancel.Cancelled):
            cancel.checkpoint()
        with cancel.stopping_when(None):
            cancel.checkpoint()  # an inner block without a callback never stops
    cancel.checkpoint()  # the callback is gone after the block


def test_the_callback_belongs_to_the_thread_that_installed_it():
    raised = []

    def other() -> None:
        try:
            cancel.checkpoint()
        except cancel.Cancelled:
            raised.append(True)

    with cancel.stopping_when(lambda: True):
        thread = threading.Thread(target=other)
        thread.start()
        thread.join()
    assert raised == []


def test_a_cancelled_check_is_not_reported_as_an_internal_error():
    """driver.analyze_source turns any Exception into G001; Cancelled is not one."""
    with cancel.stopping_when(lambda: True), pytest.raises(cancel.Cancelled):
        driver.check_file("cell.prg", text=PROGRAM)
    result = driver.check_file("cell.prg", text=PROGRAM)
    assert result.analysis is not None and not [d for d in result.diagnostics if d.code == "G001"]
