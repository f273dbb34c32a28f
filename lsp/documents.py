"""The open documents and their analyses: off the protocol thread, stale work dropped at once.

Every edit bumps the document's generation and its newest text is analysed off the protocol
thread, in one worker: the frontend's checks (parsing only the lines that changed since the
document's previous version), then the lint rules, after which the diagnostics are published
(once: the checks alone are published first only when the rules are still running `early`
seconds after the analysis started), then the editor model, and `memory_delay` seconds later,
unless the document changed meanwhile, the program memory (Arcus and X150 programs are priced by
their backend, which takes as long as the checks: done at once, it would hold up the next
keystroke's checks) and the cycle time (a bounded simulation, cycles.py; the simulator stops at
its next checkpoint when a newer edit arrives).

An analysis that a newer edit made stale stops at the compiler's next checkpoint (every few
hundred lines of lowering, between the checks, between lint rules, in the editor model:
compiler/cancel.py), a few milliseconds later, and nothing stale is published. So an edit that
arrives while an analysis runs is analysed at once too: waiting for a quiet time (`debounce`,
default 0) would only delay the diagnostics of the last keystroke. Requests (hover, completion,
definition, ...) read `latest`, the last snapshot with an editor model, and never wait.
"""

from __future__ import annotations

import asyncio
import logging
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Callable

from mcc.compiler import cancel, config
from mcc.compiler.config import Resolver
from mcc.lsp import analysis, cycles, incremental, memory
from mcc.lsp.analysis import Snapshot

log = logging.getLogger(__name__)
PUBLISH_WAIT = 0.5  # seconds the worker waits at most for the protocol thread to send the diagnostics


class Documents:
    def __init__(self, publish: Callable[[Snapshot], None], debounce: float = 0.0, early: float = 0.15,
                 memory_delay: float = 0.2, priced: Callable[[Snapshot], None] | None = None):
        self.publish = publish
        self.priced = priced  # called (protocol thread) when a version's program memory is current
        self.debounce = debounce
        self.early = early
        self.memory_delay = memory_delay
        self.latest: dict[str, Snapshot] = {}
        self.generation: dict[str, int] = {}
        self.timers: dict[str, asyncio.TimerHandle] = {}
        self.executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="mcc-check")
        self.lock = threading.Lock()
        self.resolver = Resolver()
        self.dialects: dict[str, str] = {}  # uri -> dialect, from the client's languageId
        self.checking: dict[str, int] = {}  # documents whose checks are queued or being computed
        self.caches: dict[str, incremental.LineCache] = {}  # uri -> parsed lines (worker thread only)
        self.loop: asyncio.AbstractEventLoop | None = None
        self.arrived: dict[str, float] = {}  # uri -> when its newest edit arrived (for the timings)

    # -- scheduling (protocol thread) --------------------------------------------------------------
    def changed(self, uri: str, path: str, read: Callable[[], tuple[str, int | None]], delay: float | None = None) -> None:
        """A document was opened, edited or saved: analyse its newest text after `delay` seconds."""
        if self.loop is None:
            self.loop = asyncio.get_running_loop()
        with self.lock:
            generation = self.generation.get(uri, 0) + 1
            self.generation[uri] = generation
        self.arrived[uri] = time.perf_counter()
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
        try:  # in the worker, after the document's analyses
            self.executor.submit(self.caches.pop, uri, None)
        except RuntimeError:  # the server is shutting down
            pass
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
        stop = lambda: self.stale(uri, generation)  # noqa: E731
        try:
            with cancel.stopping_when(stop):  # the compiler's checkpoints ask it (compiler/cancel.py)
                self.analyse(uri, path, version, text, generation, stop)
        except cancel.Cancelled:  # a newer edit arrived: nothing of this analysis is published
            pass
        except Exception:  # noqa: BLE001 - one bad analysis must not stop the server
            log.exception("analysis of %s failed", uri)
        finally:
            with self.lock:
                left = self.checking.get(uri, 1) - 1
                if left > 0:
                    self.checking[uri] = left
                else:
                    self.checking.pop(uri, None)

    def analyse(self, uri, path, version, text, generation, stop) -> None:
        """The steps of analysis.py, publishing the diagnostics as soon as they are complete."""
        if stop():  # a newer edit arrived while this one waited for the worker
            return
        started = time.perf_counter()
        cpu = time.thread_time()
        snap, checked, cache = analysis.check(uri, path, version, text, self.resolver, self.dialects.get(uri),
                                              self.caches.get(uri), stop)
        if cache is not None:  # right for its text even when stale: the next version starts from it
            self.caches[uri] = cache
        else:
            self.caches.pop(uri, None)
        if snap is None or stop():
            return
        published = False

        def stop_or_publish_checks() -> bool:
            """Asked between lint rules: stale work stops; slow rules let the checks go first."""
            nonlocal published
            if stop():
                return True
            if not published and time.perf_counter() - started > self.early:
                self.deliver(snap, generation, queries=False)
                published = True
            return False

        checked_cpu = time.thread_time()
        linted = analysis.lint(snap, checked, stop_or_publish_checks)
        if linted is None or stop():
            return
        arrived = self.arrived.get(uri, started)
        linted.timings = {"check_cpu_ms": (checked_cpu - cpu) * 1000, "lint_cpu_ms": (time.thread_time() - checked_cpu) * 1000,
                          "queued_ms": (started - arrived) * 1000, "edit_to_rules_done_ms": (time.perf_counter() - arrived) * 1000}
        # the editor model waits until the diagnostics are sent: run at once, it would take the GIL
        # from the protocol thread that converts and writes them (15-25 ms later on a loaded machine)
        self.deliver(linted, generation, queries=False).wait(PUBLISH_WAIT)
        indexed = analysis.with_index(linted)
        if stop():
            return
        # until this version is priced and run (or, with errors, for as long as it has them: see
        # analysis.figures_wanted), the lenses show the last figures, on this version's lines
        previous = self.latest.get(uri)
        indexed.memory = memory.carried(previous.memory if previous is not None else None, indexed)
        indexed.cycles = cycles.carried(previous.cycles if previous is not None else None, indexed)
        costly = analysis.figures_wanted(indexed)  # the backend's work, a bounded simulation
        deferred = costly and self.memory_delay > 0
        # the editor model's own failure (G001) is one more diagnostic: published again then
        self.deliver(indexed, generation, publish=len(indexed.diagnostics) != len(linted.diagnostics))
        if stop():
            return
        if not deferred:
            self.deliver(analysis.complete(indexed, costly), generation, publish=False)
        elif self.loop is not None and not self.loop.is_closed():
            # pricing the program (the backend's work) waits for a pause in the typing, so that it
            # never holds up the checks of the next keystroke
            self.loop.call_soon_threadsafe(self.price_later, indexed, generation)

    def price_later(self, snap: Snapshot, generation: int) -> None:
        """On the protocol thread: price the program `memory_delay` seconds from now, unless the
        document changes meanwhile."""
        def fire() -> None:
            if not self.stale(snap.uri, generation):
                try:
                    self.executor.submit(self.price, snap, generation)
                except RuntimeError:  # the server is shutting down
                    pass

        self.loop.call_later(self.memory_delay, fire)

    def price(self, snap: Snapshot, generation: int) -> None:
        if self.stale(snap.uri, generation):
            return
        try:
            with cancel.stopping_when(lambda: self.stale(snap.uri, generation)):
                self.deliver(analysis.complete(snap), generation, publish=False)
        except cancel.Cancelled:
            pass
        except Exception:  # noqa: BLE001
            log.exception("pricing %s failed", snap.uri)

    def deliver(self, snap: Snapshot, generation: int, queries: bool = True, publish: bool = True) -> threading.Event:
        """On the protocol thread: make `snap` what queries answer from (`queries`; a snapshot
        without its editor model only when there is nothing better) and publish its diagnostics.
        The event is set once that is done (or will not be: stale, shutting down)."""
        done = threading.Event()

        def run() -> None:
            try:
                deliver()
            finally:
                done.set()

        def deliver() -> None:
            if self.stale(snap.uri, generation):
                return
            if queries or snap.uri not in self.latest:
                self.latest[snap.uri] = snap
            if snap.complete and (snap.memory is not None or snap.cycles is not None) and self.priced is not None:
                try:
                    self.priced(snap)
                except Exception:  # noqa: BLE001
                    log.exception("announcing the program memory of %s failed", snap.uri)
            if not publish:
                return
            try:
                self.publish(snap)
            except Exception:  # noqa: BLE001
                log.exception("publishing diagnostics for %s failed", snap.uri)

        if self.loop is not None and not self.loop.is_closed():
            try:
                self.loop.call_soon_threadsafe(run)
                return done
            except RuntimeError:  # the server is shutting down
                pass
        done.set()
        return done

    def shutdown(self) -> None:
        self.executor.shutdown(wait=False, cancel_futures=True)
