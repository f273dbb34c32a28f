"""A program running on the simulator under a debugger: breakpoints, stepping, pausing.

The simulator runs in a thread of its own; its stepping interface (`Simulator.observer`, see
sim/interpreter.py) calls `Session.observe` before every operation and terminator. Most calls
return at once. When the program reaches a breakpoint, a step's end, a requested pause or a
runtime error, `observe` tells the server (`on_stop`) and blocks until the client says how to go
on; while it blocks virtual time stands still and the server reads the paused state. Stepping
follows source lines, not IR operations: a line *starts* when an item of a line other than the
last one run in the same frame comes up, or when a jump back (a loop going round) brings the same
line again.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from typing import Callable

from mcc.debug import conditions
from mcc.sim.interpreter import Simulator, Stop


# How runs end that are no reason to pause: the program's end, a runtime error (paused already,
# where it happened), the debugger's own end and the time limit (a looping program's usual end).
QUIET_STOPS = frozenset({"end", "error", "terminated", "time-limit"})


@dataclass
class Breakpoint:
    ident: int
    line: int
    verified: bool
    message: str | None = None
    condition: str | None = None
    hit_condition: str | None = None
    hits: int = 0

    def to_json(self, path: str) -> dict:
        out = {"id": self.ident, "verified": self.verified, "line": self.line, "source": {"path": path}}
        if self.message:
            out["message"] = self.message
        return out


@dataclass
class Stopped:
    reason: str  # entry | breakpoint | step | pause | exception
    description: str = ""
    text: str = ""
    breakpoints: list[int] = field(default_factory=list)


class Session:
    def __init__(self, simulator: Simulator, path: str, on_stop: Callable[[Stopped], None],
                 on_output: Callable[[str], None], on_end: Callable[[object], None]):
        self.simulator = simulator
        self.path = path
        self.on_stop, self.on_output, self.on_end = on_stop, on_output, on_end
        self.lines = executable_lines(simulator.module, path)
        self.breakpoints: dict[int, Breakpoint] = {}
        self.next_id = 0
        self.stop_on_errors = True
        self.no_debug = False  # launch's noDebug (VS Code's Run Without Debugging): never stop
        self.mode = "continue"  # continue | in | over | out
        self.step_depth = 0
        self.pause_requested = False
        self.terminating = False
        self.paused = False
        self.command: tuple[str, int] | None = None
        self.condition = threading.Condition()
        self.printed = 0
        self.last: dict[int, tuple[object, int]] = {}  # depth -> (frame, the last line run in it)
        self.stopped_at: tuple[object, object] | None = None  # (frame, item) where the run is paused
        self.thread: threading.Thread | None = None
        self.trace = None

    # -- configured from the server's thread -----------------------------------------------------

    def set_breakpoints(self, wanted: list[dict]) -> list[Breakpoint]:
        """Replace the breakpoints of the program's file; a line that generates nothing is kept
        unverified with a message saying so (nothing would ever stop there)."""
        made = {}
        for spec in wanted:
            line = int(spec.get("line", 0))
            self.next_id += 1
            bp = Breakpoint(self.next_id, line, line in self.lines, condition=spec.get("condition") or None,
                            hit_condition=spec.get("hitCondition") or None)
            if not bp.verified:
                bp.message = (f"line {line} generates no operation (a comment, a label, a declaration or a "
                              "blank line): the program never stops here; put the breakpoint on the next command")
            elif bp.hit_condition and conditions.hit_condition_error(bp.hit_condition):
                bp.verified, bp.message = False, conditions.hit_condition_error(bp.hit_condition)
            old = self.breakpoints.get(line)
            if old is not None and (old.condition, old.hit_condition) == (bp.condition, bp.hit_condition):
                bp.hits = old.hits
            made.setdefault(line, bp)
        self.breakpoints = {line: bp for line, bp in made.items() if bp.verified}
        return [made[int(spec.get("line", 0))] for spec in wanted]

    def start(self, stop_on_entry: bool) -> None:
        if stop_on_entry:
            self.mode = "entry"
        self.simulator.observer = self.observe
        self.thread = threading.Thread(target=self._run, name="mcc-debug-sim", daemon=True)
        self.thread.start()

    def resume(self, mode: str) -> None:
        """Go on: continue, or step `in`, `over` or `out` (from the thread that read the request)."""
        with self.condition:
            self.command = (mode, len(self.simulator.stack))
            self.condition.notify_all()

    def pause(self) -> None:
        self.pause_requested = True

    def terminate(self) -> None:
        self.terminating = True
        with self.condition:
            self.command = ("terminate", 0)
            self.condition.notify_all()

    # -- the simulator's thread ------------------------------------------------------------------

    def _run(self) -> None:
        try:
            trace = self.simulator.run()
        except Exception as exc:  # noqa: BLE001 - the no-traceback rule: said to the client
            self.on_output(f"mcc debug: the simulator failed: {exc!r}\n")
            trace = self.simulator.trace
            trace.stopped, trace.reason = "error", f"internal error: {exc}"
        self._flush()
        self.trace = trace
        self.on_end(trace)

    def observe(self, kind: str, frame, item, fault=None) -> None:
        self._flush()
        if self.terminating:
            raise Stop("terminated", "the debugger ended the run")
        if self.no_debug:
            return
        if kind == "stop":
            # a run that ended abnormally without a runtime error (an end of travel, a wait nothing
            # ends, a loop that never waits) pauses once more so its last state can be read
            if self.stop_on_errors and fault.stopped not in QUIET_STOPS:
                self._pause(Stopped("exception", fault.stopped, fault.reason), frame, item)
            return
        if kind == "fault":
            if self.stop_on_errors:
                text = f"{fault.code}: {fault}"
                self._pause(Stopped("exception", "runtime error", text), frame, item)
            return
        line = _line(item)
        if line is None:
            return
        sim = self.simulator
        depth = len(sim.stack)
        previous = self.last.get(depth)
        starts = previous is None or previous[0] is not frame or previous[1] != line or sim.went_back
        self.last[depth] = (frame, line)
        for deeper in [d for d in self.last if d > depth]:
            del self.last[deeper]
        if not starts:
            return
        if self.mode == "entry":
            self._pause(Stopped("entry", "entry"), frame, item)
            return
        if self.pause_requested:
            self.pause_requested = False
            self._pause(Stopped("pause", "paused"), frame, item)
            return
        bp = self.breakpoints.get(line)
        if bp is not None and self._hit(bp, frame, item):
            return
        if self.mode == "in" or (self.mode == "over" and depth <= self.step_depth) or \
                (self.mode == "out" and depth < self.step_depth):
            self._pause(Stopped("step", "step"), frame, item)

    def _hit(self, bp: Breakpoint, frame, item) -> bool:
        if bp.condition:
            try:
                if not conditions.evaluate(bp.condition, conditions.Machine(self.simulator)):
                    return False
            except conditions.ExpressionError as exc:
                self._pause(Stopped("breakpoint", "breakpoint condition error", str(exc), [bp.ident]), frame, item)
                return True
        bp.hits += 1
        if bp.hit_condition and not conditions.hit_matches(bp.hit_condition, bp.hits):
            return False
        self._pause(Stopped("breakpoint", "breakpoint", "", [bp.ident]), frame, item)
        return True

    def _pause(self, stopped: Stopped, frame, item) -> None:
        with self.condition:
            self.command = None
            self.paused = True
            self.stopped_at = (frame, item)
            self.on_stop(stopped)
            while self.command is None:
                self.condition.wait()
            mode, depth = self.command
            self.paused = False
            self.stopped_at = None
        if mode == "terminate":
            raise Stop("terminated", "the debugger ended the run")
        self.mode, self.step_depth = mode, depth
        self.pause_requested = False

    def _flush(self) -> None:
        prints = self.simulator.trace.prints
        while self.printed < len(prints):
            self.on_output(prints[self.printed][1])
            self.printed += 1


def executable_lines(module, path: str) -> set[int]:
    """The source lines of `path` that generate an operation or a terminator (where a breakpoint
    can stop)."""
    lines = set()
    for _, block in module.blocks():
        for item in [*block.ops, block.terminator]:
            span = getattr(item, "span", None)
            if span is not None and (not span.file or span.file == path or not path):
                lines.add(span.line)
    return lines


def _line(item) -> int | None:
    span = getattr(item, "span", None)
    return span.line if span is not None else None
