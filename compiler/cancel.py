"""Cooperative cancellation: long analyses stop early when their result is no longer wanted.

The editor server (lsp/documents.py) analyses a document in a worker thread; when a newer
keystroke arrives, the analysis under way is stale, and the sooner it stops the sooner the
newest text is analysed. The server installs a `should_stop()` callback for the thread with
`stopping_when`; the compiler calls `checkpoint()` between pieces of work (between lowering and
the checks, every few hundred lines of lowering, between lint rules), and `checkpoint()` raises
`Cancelled` when the callback answers True.

Without a callback installed (the command line, the tests, the worker processes of `mcc lint`)
`checkpoint()` is one thread-local lookup: nothing changes and nothing is cancelled.

`Cancelled` is a BaseException, like KeyboardInterrupt, so that the compiler's "no traceback"
guards (`except Exception` turned into G001) let it through to the server that asked for it.
Code between checkpoints must leave shared state (the editor's cached syntax lines) as a
finished run would, or not touch it; the syntax tree of the text being analysed is thrown away.
"""

from __future__ import annotations

import threading
from contextlib import contextmanager
from typing import Callable, Iterator


class Cancelled(BaseException):
    """The analysis was abandoned at a checkpoint: its result is no longer wanted."""


_state = threading.local()

EVERY = 256  # lines (or items) between two checkpoints in a loop: see `every`


def checkpoint() -> None:
    """Raise Cancelled if the current thread's `should_stop` callback answers True."""
    should_stop = getattr(_state, "should_stop", None)
    if should_stop is not None and should_stop():
        raise Cancelled


def every(index: int) -> None:
    """`checkpoint()` every EVERY-th index of a loop (cheap enough to call for every line)."""
    if not index % EVERY:
        checkpoint()


@contextmanager
def stopping_when(should_stop: Callable[[], bool] | None) -> Iterator[None]:
    """Within the block, this thread's checkpoints ask `should_stop` (None: never stop)."""
    previous = getattr(_state, "should_stop", None)
    _state.should_stop = should_stop
    try:
        yield
    finally:
        _state.should_stop = previous
