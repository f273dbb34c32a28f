"""The scheduling of analyses (lsp/documents.py), in-process: what is published and made current
after each edit, in which order. The protocol-level tests are in test_features.py and
test_robustness.py."""

from __future__ import annotations

import asyncio
import threading
from pathlib import Path

import pytest

from mcc.lsp.documents import Documents

FIXTURES = Path(__file__).parent / "fixtures"
URI = "file:///docs/cell.prg"
PATH = "/docs/cell.prg"


class Recorder(Documents):
    """Documents that remember every snapshot they made current, in order."""

    def __init__(self, **options) -> None:
        self.published: list = []
        self.delivered: list = []
        self.snapshots: list = []
        self.announced: list = []  # the snapshots whose program memory was announced (lens refresh)
        super().__init__(self.published.append, priced=self.announced.append, **options)

    def deliver(self, snap, generation, queries=True, publish=True):
        self.delivered.append((snap.version, snap.complete, publish))
        self.snapshots.append(snap)
        return super().deliver(snap, generation, queries, publish)


async def until(condition, timeout: float = 60.0) -> None:
    deadline = asyncio.get_running_loop().time() + timeout
    while not condition():
        assert asyncio.get_running_loop().time() < deadline, "the analysis did not finish"
        await asyncio.sleep(0.01)


def complete(docs: Documents, version: int) -> bool:
    snap = docs.latest.get(URI)
    return snap is not None and snap.version == version and snap.complete


@pytest.mark.asyncio
async def test_diagnostics_are_published_once_then_the_memory_follows_after_a_pause():
    docs = Recorder(memory_delay=0.2, early=60)  # the rules never take a minute here
    text = (FIXTURES / "cell.prg").read_text(encoding="utf-8")
    docs.changed(URI, PATH, lambda: (text, 1), delay=0)
    await until(lambda: complete(docs, 1))
    assert [snap.version for snap in docs.published] == [1]  # checks and lint rules together
    assert docs.latest[URI].memory is not None  # the program was priced (Arcus assembly lines)
    published_at = docs.delivered.index((1, False, True))
    assert docs.delivered[published_at + 1:] == [(1, False, False), (1, True, False)]  # model, memory
    docs.shutdown()


@pytest.mark.asyncio
async def test_an_edit_during_the_pause_is_priced_and_the_older_version_never():
    docs = Recorder(memory_delay=0.3)
    text = (FIXTURES / "cell.prg").read_text(encoding="utf-8")
    versions = {"text": text, "version": 1}
    docs.changed(URI, PATH, lambda: (versions["text"], versions["version"]), delay=0)
    await until(lambda: any(v == 1 and publish for v, _, publish in docs.delivered))
    versions.update(text=text.replace("DELAY=250", "DELAY=300"), version=2)
    docs.changed(URI, PATH, lambda: (versions["text"], versions["version"]), delay=0)
    await until(lambda: complete(docs, 2))
    assert (1, True, False) not in docs.delivered  # version 1 was never priced
    assert docs.latest[URI].memory is not None
    assert [snap.version for snap in docs.announced] == [2]
    docs.shutdown()


@pytest.mark.asyncio
async def test_until_a_version_is_priced_its_lenses_show_the_previous_figures_on_its_lines():
    docs = Recorder(memory_delay=0.2)
    text = (FIXTURES / "cell.prg").read_text(encoding="utf-8")
    versions = {"text": text, "version": 1}
    docs.changed(URI, PATH, lambda: (versions["text"], versions["version"]), delay=0)
    await until(lambda: complete(docs, 1))
    before = docs.latest[URI].memory
    versions.update(text="; a line above everything\n" + text, version=2)
    docs.changed(URI, PATH, lambda: (versions["text"], versions["version"]), delay=0)
    await until(lambda: complete(docs, 2))
    waiting = next(snap for snap in docs.snapshots if snap.version == 2 and snap.index.routines and not snap.complete)
    assert [(r.name, r.line + 1, r.used) for r in before.routines] == \
        [(r.name, r.line, r.used) for r in waiting.memory.routines]
    assert docs.latest[URI].memory.routines == waiting.memory.routines  # the same program, priced again
    assert [snap.version for snap in docs.announced] == [1, 2]
    docs.shutdown()


@pytest.mark.asyncio
async def test_without_a_delay_the_memory_is_priced_at_once():
    docs = Recorder(memory_delay=0)
    text = (FIXTURES / "cell.prg").read_text(encoding="utf-8")
    docs.changed(URI, PATH, lambda: (text, 1), delay=0)
    await until(lambda: complete(docs, 1))
    assert docs.latest[URI].memory is not None
    docs.shutdown()


@pytest.mark.asyncio
async def test_slow_rules_let_the_checks_be_published_first():
    docs = Recorder(early=0)  # every rule counts as slow
    text = (FIXTURES / "cell.prg").read_text(encoding="utf-8")  # one lint finding (A307; A315 is opt-in)
    docs.changed(URI, PATH, lambda: (text, 1), delay=0)
    await until(lambda: complete(docs, 1))
    checks, everything = docs.published
    assert checks.version == everything.version == 1
    assert [d.code for d in checks.diagnostics] == []
    assert [d.code for d in everything.diagnostics] == ["A307"]
    docs.shutdown()


@pytest.mark.asyncio
async def test_an_edit_abandons_the_analysis_under_way_at_its_next_checkpoint(monkeypatch):
    """The version being lowered when a newer edit arrives stops between the lowering and the
    checks (compiler/cancel.py): it is never published, and the newer one is."""
    from mcc.compiler import cancel
    from mcc.compiler.arcus import frontend

    reached, edited = threading.Event(), threading.Event()
    abandoned = []

    def checkpoint() -> None:
        if not reached.is_set():
            reached.set()
            edited.wait(10)  # the worker waits here, after lowering version 1, for version 2
        try:
            cancel.checkpoint()
        except cancel.Cancelled:
            abandoned.append(True)
            raise

    monkeypatch.setattr(frontend, "checkpoint", checkpoint)
    docs = Recorder(early=60)
    text = (FIXTURES / "cell.prg").read_text(encoding="utf-8")
    versions = {"text": text, "version": 1}
    docs.changed(URI, PATH, lambda: (versions["text"], versions["version"]), delay=0)
    await until(reached.is_set)
    versions.update(text=text.replace("DELAY=250", "DELAY=300"), version=2)
    docs.changed(URI, PATH, lambda: (versions["text"], versions["version"]))
    edited.set()
    await until(lambda: complete(docs, 2))
    assert abandoned == [True]
    assert [snap.version for snap in docs.published] == [2]
    assert all(version == 2 for version, _, _ in docs.delivered)
    docs.shutdown()
