"""The adapter: answers the Debug Adapter Protocol's requests for a program on the simulator.

One client, one program. The reader (this thread) answers requests; the program runs in the
session's thread (session.py) and reports stops, prints and its end through the connection's
events. Variables are read only while the program is paused, when its state stands still.
Every request the capabilities claim is covered by tests/debug/test_debug_protocol.py.
"""

from __future__ import annotations

import os
import socket
import sys
from typing import Any

from mcc.debug import conditions
from mcc.debug.protocol import Connection, ProtocolError
from mcc.debug.session import Session, Stopped

THREAD_ID = 1
# Variable references of the scopes; an axis's own reference is AXIS_BASE + its index.
PROGRAM, AXES, IO, MACHINE, AXIS_BASE = 1, 2, 3, 4, 100
ERRORS_FILTER = "errors"

CAPABILITIES: dict[str, Any] = {
    "supportsConfigurationDoneRequest": True,
    "supportsConditionalBreakpoints": True,
    "supportsHitConditionalBreakpoints": True,
    "supportsSetVariable": True,
    "supportsEvaluateForHovers": True,
    "supportsTerminateRequest": True,
    "exceptionBreakpointFilters": [
        {"filter": ERRORS_FILTER, "label": "Runtime errors and limit switches", "default": True,
         "description": "Stop where a runtime error no handler catches (division by zero, stack overflow, an "
                        "axis hitting a limit switch) would end the run"}],
}


class Adapter:
    def __init__(self, connection: Connection):
        self.conn = connection
        self.session: Session | None = None
        self.path = ""
        self.launched = False
        self.configured = False
        self.stop_on_entry = False
        self.pending_errors_filter = True
        self.done = False

    # -- the loop --------------------------------------------------------------------------------

    def serve(self) -> None:
        while not self.done:
            try:
                message = self.conn.read()
            except ProtocolError as exc:
                self.conn.event("output", {"category": "stderr", "output": f"mcc debug: {exc}\n"})
                continue
            if message is None:
                break
            if message.get("type") == "request":
                self.dispatch(message)
        if self.session is not None:
            self.session.terminate()

    def dispatch(self, request: dict) -> None:
        command = request.get("command", "")
        handler = getattr(self, "on_" + "".join("_" + c.lower() if c.isupper() else c for c in command), None)
        if handler is None:
            self.conn.respond(request, success=False, message=f"mcc debug does not support '{command}'")
            return
        args = request.get("arguments") or {}
        try:
            handler(request, args)
        except RequestError as exc:
            self.conn.respond(request, success=False, message=str(exc))
        except Exception as exc:  # noqa: BLE001 - no traceback reaches the client
            self.conn.respond(request, success=False, message=f"mcc debug: internal error in {command}: {exc!r}")

    # -- requests --------------------------------------------------------------------------------

    def on_initialize(self, request, args) -> None:
        self.conn.respond(request, CAPABILITIES)

    def on_launch(self, request, args) -> None:
        from mcc.debug.launch import LaunchError, prepare

        if self.launched:
            raise RequestError("a program is launched already: one program per session")

        try:
            simulator, path = prepare(args)
        except LaunchError as exc:
            for line in exc.details:
                self.conn.event("output", {"category": "stderr", "output": line + "\n"})
            raise RequestError(str(exc)) from None
        self.path = path
        self.session = Session(simulator, path, self._stopped, self._output, self._ended)
        self.session.stop_on_errors = self.pending_errors_filter
        self.stop_on_entry = bool(args.get("stopOnEntry", False)) and not args.get("noDebug")
        self.session.no_debug = bool(args.get("noDebug", False))
        self.launched = True
        self.conn.respond(request)
        # the client sends breakpoints after this event: the program's lines are known by now
        self.conn.event("initialized")
        self._maybe_start()

    def on_set_breakpoints(self, request, args) -> None:
        source = args.get("source") or {}
        wanted = args.get("breakpoints")
        if wanted is None:
            wanted = [{"line": line} for line in args.get("lines", [])]
        session = self._session()
        if not _same_file(source.get("path", ""), self.path):
            made = [{"verified": False, "line": spec.get("line", 0),
                     "message": f"mcc debug runs {os.path.basename(self.path)}; this file is not part of it"}
                    for spec in wanted]
        else:
            made = [bp.to_json(self.path) for bp in session.set_breakpoints(wanted)]
        self.conn.respond(request, {"breakpoints": made})

    def on_set_exception_breakpoints(self, request, args) -> None:
        on = ERRORS_FILTER in (args.get("filters") or [])
        self.pending_errors_filter = on
        if self.session is not None:
            self.session.stop_on_errors = on
        self.conn.respond(request, {"breakpoints": [{"verified": True}] if on else []})

    def on_configuration_done(self, request, args) -> None:
        self.configured = True
        self.conn.respond(request)
        self._maybe_start()

    def on_threads(self, request, args) -> None:
        self.conn.respond(request, {"threads": [{"id": THREAD_ID, "name": "program"}]})

    def on_stack_trace(self, request, args) -> None:
        sim = self._paused().simulator
        frames = []
        stack = list(reversed(sim.stack))
        stopped_item = self.session.stopped_at[1] if self.session.stopped_at else None
        for n, frame in enumerate(stack):
            item = (stopped_item or _current_item(frame)) if n == 0 else _caller_item(frame)
            line = getattr(getattr(item, "span", None), "line", None) or 1
            name = frame.routine.name + (f" (on {frame.handler})" if frame.handler else "")
            if n == 0:
                name += f" @ {sim.now:.3f} s"
            frames.append({"id": n + 1, "name": name, "line": line, "column": 1,
                           "source": {"name": os.path.basename(self.path), "path": self.path}})
        start, levels = int(args.get("startFrame", 0)), int(args.get("levels", 0) or len(frames))
        self.conn.respond(request, {"stackFrames": frames[start:start + levels], "totalFrames": len(frames)})

    def on_scopes(self, request, args) -> None:
        self._paused()
        scopes = [("Program variables", PROGRAM, False), ("Axes", AXES, False), ("Inputs and outputs", IO, False),
                  ("Machine", MACHINE, False)]
        self.conn.respond(request, {"scopes": [{"name": name, "variablesReference": ref, "expensive": expensive,
                                                "presentationHint": "locals" if ref == PROGRAM else "registers"}
                                               for name, ref, expensive in scopes]})

    def on_variables(self, request, args) -> None:
        sim = self._paused().simulator
        ref = int(args.get("variablesReference", 0))
        self.conn.respond(request, {"variables": variables(sim, ref)})

    def on_set_variable(self, request, args) -> None:
        sim = self._paused().simulator
        ref, name, text = int(args.get("variablesReference", 0)), str(args.get("name", "")), str(args.get("value", ""))
        number = _number(text)
        if ref == PROGRAM:
            if name not in sim.vars:
                raise RequestError(f"'{name}' is not a variable of the program")
            try:
                stored = sim.set_variable(name, number)
            except ValueError as exc:
                raise RequestError(str(exc)) from None
            self.conn.respond(request, {"value": _show(stored)})
        elif ref == IO and name.startswith("input "):
            if number not in (0, 1):
                raise RequestError("an input takes a level: 0 (low) or 1 (high), as in a scenario")
            sim.set_input(int(name.split()[1]), int(number))
            self.conn.respond(request, {"value": str(int(number))})
        else:
            raise RequestError(f"'{name}' cannot be changed: program variables and inputs can")

    def on_evaluate(self, request, args) -> None:
        sim = self._paused().simulator
        try:
            value = conditions.evaluate(str(args.get("expression", "")), conditions.Machine(sim))
        except conditions.ExpressionError as exc:
            raise RequestError(str(exc)) from None
        self.conn.respond(request, {"result": _show(value), "variablesReference": 0})

    def on_continue(self, request, args) -> None:
        self._paused().resume("continue")
        self.conn.respond(request, {"allThreadsContinued": True})

    def on_next(self, request, args) -> None:
        self._paused().resume("over")
        self.conn.respond(request)

    def on_step_in(self, request, args) -> None:
        self._paused().resume("in")
        self.conn.respond(request)

    def on_step_out(self, request, args) -> None:
        self._paused().resume("out")
        self.conn.respond(request)

    def on_pause(self, request, args) -> None:
        self._session().pause()
        self.conn.respond(request)

    def on_terminate(self, request, args) -> None:
        self.conn.respond(request)
        if self.session is not None and self.session.thread is not None:
            self.session.terminate()
        else:
            self._ended(None)

    def on_disconnect(self, request, args) -> None:
        if self.session is not None:
            self.session.terminate()
            if self.session.thread is not None:
                self.session.thread.join(timeout=5)
        self.conn.respond(request)
        self.done = True

    # -- events from the program's thread ----------------------------------------------------------

    def _stopped(self, stopped: Stopped) -> None:
        body = {"reason": stopped.reason, "threadId": THREAD_ID, "allThreadsStopped": True,
                "description": stopped.description}
        if stopped.text:
            body["text"] = stopped.text
            self._output(f"{stopped.description}: {stopped.text}\n", "stderr")
        if stopped.breakpoints:
            body["hitBreakpointIds"] = stopped.breakpoints
        self.conn.event("stopped", body)

    def _output(self, text: str, category: str = "stdout") -> None:
        self.conn.event("output", {"category": category, "output": text})

    def _ended(self, trace) -> None:
        if trace is not None:
            axes = ", ".join(f"{name}={_show(pos)}" for name, pos in sorted(trace.axes.items())) or "none"
            self._output(f"stopped: {trace.stopped} at {trace.time:.3f} s after {trace.steps} steps: {trace.reason}; "
                         f"positions {axes}\n", "console")
            for diag in trace.diagnostics:
                if diag.code.startswith("S") and diag.severity.value == "error":
                    self._output(f"{os.path.basename(self.path)}:{diag.span.line}: {diag.code} {diag.message}\n",
                                 "stderr")
        code = 1 if trace is not None and trace.stopped == "error" else 0
        self.conn.event("exited", {"exitCode": code})
        self.conn.event("terminated")

    # -- helpers ---------------------------------------------------------------------------------

    def _maybe_start(self) -> None:
        if self.launched and self.configured and self.session is not None and self.session.thread is None:
            self.session.start(self.stop_on_entry)

    def _session(self) -> Session:
        if self.session is None:
            raise RequestError("no program is running: send launch first")
        return self.session

    def _paused(self) -> Session:
        session = self._session()
        if not session.paused:
            raise RequestError("the program is running: pause it first")
        return session


class RequestError(Exception):
    """A request the adapter refuses; the message goes back to the client."""


def variables(sim, ref: int) -> list[dict]:
    """The variables of scope (or axis) `ref` on a paused simulator."""
    from mcc.compiler.ir import MotionParam

    if ref == PROGRAM:
        return [_var(name, value, sim.module.type_of(name)) for name, value in sorted(sim.vars.items())]
    names = sorted(sim.machine.axes)
    if ref == AXES:
        out = []
        for n, name in enumerate(names):
            axis = sim.machine.axes[name]
            state = "moving" if axis.moving(sim.now) else "idle"
            out.append({"name": f"axis {name}", "value": f"{_show(axis.at(sim.now))} steps, {state}",
                        "variablesReference": AXIS_BASE + n})
        return out
    if ref == IO:
        top = max([sim.input_count, *sim.machine.inputs, 0]) or 8
        out = []
        for index in range(1, top + 1):
            level = sim.input_level(index)
            logic = "active" if sim.input_logic(index) else "inactive"
            out.append({"name": f"input {index}", "value": str(level), "type": f"level ({logic})",
                        "variablesReference": 0})
        for index, value in sorted(sim.machine.outputs.items()):
            out.append({"name": f"output {index}", "value": str(value), "variablesReference": 0,
                        "presentationHint": {"attributes": ["readOnly"]}})
        return out
    if ref == MACHINE:
        frame = sim.stack[-1] if sim.stack else None
        wait = frame.wait.kind if frame is not None and frame.wait is not None else "no"
        return [_ro("virtual time (s)", f"{sim.now:.6f}"), _ro("steps executed", str(sim.trace.steps)),
                _ro("waiting", wait), _ro("call depth", str(len(sim.stack)))]
    if AXIS_BASE <= ref < AXIS_BASE + len(names):
        axis = sim.machine.axes[names[ref - AXIS_BASE]]
        here = axis.at(sim.now)
        out = [_ro("position (steps)", _show(here)), _ro("speed (steps/s)", _show(axis.speed(sim.now))),
               _ro("moving", str(int(axis.moving(sim.now)))), _ro("machine position", _show(here + axis.offset)),
               _ro("fault", str(axis.fault)), _ro("enabled", str(axis.enabled))]
        if axis.motion is not None and axis.moving(sim.now):
            out.append(_ro("move ends at (s)", f"{axis.motion.t_end:.6f}"))
        for param in MotionParam:
            out.append(_ro(param.value, _show(axis.setting(param, sim.machine.shared))))
        return out
    return []


def _var(name: str, value, vtype) -> dict:
    return {"name": name, "value": _show(value), "type": vtype.value if vtype is not None else "",
            "variablesReference": 0}


def _ro(name: str, value: str) -> dict:
    return {"name": name, "value": value, "variablesReference": 0, "presentationHint": {"attributes": ["readOnly"]}}


def _show(value) -> str:
    from decimal import Decimal

    if isinstance(value, float):
        return str(int(value)) if value.is_integer() and abs(value) < 1e15 else f"{value:.6g}"
    if isinstance(value, Decimal):
        return format(value.normalize(), "f")
    return str(value)


def _number(text: str):
    text = text.strip()
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        raise RequestError(f"'{text}' is not a number") from None


def _current_item(frame):
    """The operation (or terminator) a frame is at."""
    ops = frame.block.ops
    return ops[frame.index] if frame.index < len(ops) else frame.block.terminator


def _caller_item(frame):
    """The operation a frame below the top is at: the call it made (the one before its index)."""
    ops = frame.block.ops
    if 0 < frame.index <= len(ops):
        return ops[frame.index - 1]
    return ops[frame.index] if frame.index < len(ops) else frame.block.terminator


def _same_file(a: str, b: str) -> bool:
    if not a or not b:
        return not a
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.abspath(a) == os.path.abspath(b)


def serve_stdio() -> None:
    protocol_out = sys.stdout.buffer
    sys.stdout = sys.stderr  # stdout carries the protocol: a stray print must not break a message
    Adapter(Connection(sys.stdin.buffer, protocol_out)).serve()


def serve_tcp(host: str, port: int, ready=None) -> None:
    """Listen on host:port, serve one client, and stop (nvim-dap's `server` adapters, VS Code's
    `debugServer`). `ready(port)` is called once listening (port 0 picks a free one)."""
    with socket.create_server((host, port)) as server:
        if ready is not None:
            ready(server.getsockname()[1])
        client, _ = server.accept()
        with client, client.makefile("rb") as reader, client.makefile("wb") as writer:
            Adapter(Connection(reader, writer)).serve()
