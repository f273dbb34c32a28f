"""The open documents and their analyses: debounced, off the protocol thread, stale work dropped.

Every edit bumps the document's generation. The first edit after a quiet spell is analysed at
once; edits that arrive while an analysis is under way wait for a short quiet time (`debounce`)
and are coalesced. The newest text is analysed off the protocol thread: first the frontend's
checks (published at once), then the editor model, then, in a second thread, the lint rules,
asked between rules whether a newer edit has arrived, in which case the old work stops and
nothing stale is published. Requests (hover, completion, definition, ...) read `latest`, the
last finished snapshot, and never wait.
"""

from __future__ import annotations

import asyncio
import logging
import threading
from concurrent.futures import ThreadPoolExecutor
from typing import Callable

from mcc.compiler import config
from mcc.compiler.config import Resolver
from mcc.lsp import analysis
from mcc.lsp.analysis import Snapshot

log = logging.getLogger(__name__)


class Documents:
    def __init__(self, publish: Callable[[Snapshot], None], debounce: float = 0.05):
        self.publish = publish
        self.debounce = debounce
        self.latest: dict[str, Snapshot] = {}
        self.generation: dict[str, int] = {}
        self.timers: dict[str, asyncio.TimerHandle] = {}
        self.executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="mcc-check")
        self.lint_executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="mcc-lint")
        self.lock = threading.Lock()
        self.resolver = Resolver()
        self.dialects: dict[str, str] = {}  # uri -> dialect, from the client's languageId
        self.checking: dict[str, int] = {}  # documents whose checks are queued or being computed
        self.loop: asyncio.AbstractEventLoop | None = None

    # -- scheduling (protocol thread) --------------------------------------------------------------
    def changed(self, uri: str, path: str, read: Callable[[], tuple[str, int | None]], delay: float | None = None) -> None:
        """A document was opened, edited or saved: analyse its newest text after `delay` seconds."""
        if self.loop is None:
            self.loop = asyncio.get_running_loop()
        with self.lock:
            generation = self.generation.get(uri, 0) + 1
            self.generation[uri] = generation
        timer = self.timers.pop(uri, None)
        if timer is not None:
            timer.cancel()
        with self.lock:
            idle = timer is None and uri not in self.checking
        # the first edit after a quiet spell starts at once; edits that follow it while it is
        # analysed (typing) are debounced and coalesced
        wait = delay if delay is not None else (0.0 if idle else self.debounce)

        def start() -> None:
            self.timers.pop(uri, None)
            if self.stale(uri, generation):
                return
            try:
                text, version = read()
            except Exception:  # noqa: BLE001 - the document was closed meanwhile
                return
            with self.lock:
                self.checking[uri] = self.checking.get(uri, 0) + 1
            self.executor.submit(self.work, uri, path, version, text, generation)

        if wait <= 0:
            start()
        else:
            self.timers[uri] = self.loop.call_later(wait, start)

    def closed(self, uri: str) -> None:
        with self.lock:
            self.generation[uri] = self.generation.get(uri, 0) + 1
        timer = self.timers.pop(uri, None)
        if timer is not None:
            timer.cancel()
        self.latest.pop(uri, None)

    def configuration_changed(self) -> None:
        """A configuration file changed: forget the cached ones (the next analysis reads them again)."""
        config.find.cache_clear()
        config.load.cache_clear()
        config.load_profile.cache_clear()
        self.resolver = Resolver()

    def stale(self, uri: str, generation: int) -> bool:
        with self.lock:
            return self.generation.get(uri) != generation

    # -- analysis (worker threads) -----------------------------------------------------------------
    def work(self, uri: str, path: str, version: int | None, text: str, generation: int) -> None:
        """The checks, published at once; then the editor model (queries use it from then on);
        then the lint rules, in their own thread so that a new edit's checks never queue behind
        an old edit's rules (which stop at the next rule once they are stale)."""
        stop = lambda: self.stale(uri, generation)  # noqa: E731
        try:
            self.check_and_index(uri, path, version, text, generation, stop)
        finally:
            with self.lock:
                left = self.checking.get(uri, 1) - 1
                if left > 0:
                    self.checking[uri] = left
                else:
                    self.checking.pop(uri, None)

    def check_and_index(self, uri, path, version, text, generation, stop) -> None:
        try:
            snap, checked = analysis.check(uri, path, version, text, self.resolver, self.dialects.get(uri))
            if stop():
                return
            self.deliver(snap, generation, queries=False)
            snap = analysis.with_index(snap)
            if stop():
                return
            self.deliver(snap, generation, publish=False)
            self.lint_executor.submit(self.lint, snap, checked, generation)
        except Exception:  # noqa: BLE001 - one bad analysis must not stop the server
            log.exception("analysis of %s failed", uri)

    def lint(self, snap: Snapshot, checked, generation: int) -> None:
        stop = lambda: self.stale(snap.uri, generation)  # noqa: E731
        try:
            if stop():
                return
            done = analysis.complete(snap, checked, stop)
            if done is not None and not stop():
                self.deliver(done, generation)
        except Exception:  # noqa: BLE001
            log.exception("linting %s failed", snap.uri)

    def deliver(self, snap: Snapshot, generation: int, queries: bool = True, publish: bool = True) -> None:
        """On the protocol thread: make `snap` what queries answer from (`queries`; a snapshot
        without its editor model only when there is nothing better) and publish its diagnostics."""
        def run() -> None:
            if self.stale(snap.uri, generation):
                return
            if queries or snap.uri not in self.latest:
                self.latest[snap.uri] = snap
            if not publish:
                return
            try:
                self.publish(snap)
            except Exception:  # noqa: BLE001
                log.exception("publishing diagnostics for %s failed", snap.uri)

        if self.loop is not None and not self.loop.is_closed():
            try:
                self.loop.call_soon_threadsafe(run)
            except RuntimeError:  # the server is shutting down
                pass

    def shutdown(self) -> None:
        self.executor.shutdown(wait=False, cancel_futures=True)
        self.lint_executor.shutdown(wait=False, cancel_futures=True)
