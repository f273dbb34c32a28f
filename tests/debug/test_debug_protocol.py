"""`mcc debug` driven over its pipes by a tiny DAP client (dap_client.py), as an editor drives it.

Every request the adapter claims in its capabilities is exercised here (test_capabilities_are_
all_tested keeps the list honest), for a program of each dialect: a loop with a breakpoint, a
subroutine (X150: a sequence) to step into, an input to change. The manuals' debugging features
this mirrors: MCode trace, single step and breakpoints (lexium-mcode.txt L1757, L2773-L2790);
X150 single step (parker-x150.md XST).
"""

from __future__ import annotations

import socket
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

from dap_client import Client

FIXTURES = Path(__file__).parent / "fixtures"


@dataclass
class Program:
    """A fixture and its lines: the loop's line, the call, the subroutine's first line, the two
    branches input 1 chooses between, the loop variable and an axis. Which branch an untouched input
    takes is the product's input polarity (docs/SIMULATOR.md "Inputs"); flipped, it takes the other."""

    file: str
    loop_line: int
    call_line: int
    sub_line: int
    branches: tuple[int, int]
    counter: str
    axis: str


PROGRAMS = {
    "mcode": Program("loop.mxt", 10, 11, 20, (17, 14), "Q1", "1"),
    "arcus": Program("loop.prg", 8, 9, 18, (12, 14), "V1", "X"),
    "x150": Program("loop.x150", 16, 17, 4, (20, 22), "VAR1", "1"),
}


@pytest.fixture
def client():
    made = Client.stdio()
    yield made
    made.close()


def launch(client: Client, program: str, breakpoints=(), **extra) -> dict:
    client.ok("initialize", {"adapterID": "mcc", "clientID": "pytest", "linesStartAt1": True,
                             "columnsStartAt1": True, "pathFormat": "path"})
    client.ok("launch", {"program": str(FIXTURES / program), **extra})
    client.event("initialized")
    found = client.ok("setBreakpoints", {"source": {"path": str(FIXTURES / program)},
                                         "breakpoints": list(breakpoints)})
    client.ok("configurationDone")
    return found


def variables(client: Client, ref: int) -> dict[str, str]:
    return {v["name"]: v["value"] for v in client.ok("variables", {"variablesReference": ref})["variables"]}


def scope_refs(client: Client) -> dict[str, int]:
    scopes = client.ok("scopes", {"frameId": 1})["scopes"]
    return {s["name"]: s["variablesReference"] for s in scopes}


def frames(client: Client) -> list[dict]:
    return client.ok("stackTrace", {"threadId": 1, "startFrame": 0, "levels": 20})["stackFrames"]


def stop(client: Client, reason: str) -> dict:
    event = client.next_stop()
    assert event["event"] == "stopped", event
    assert event["body"]["reason"] == reason, event
    return event


@pytest.mark.parametrize("dialect", sorted(PROGRAMS))
def test_a_session_breaks_in_the_loop_steps_into_the_subroutine_and_changes_an_input(client, dialect):
    """The issue's session: breakpoint in a loop, run to it, read the position and a variable,
    step over to the call, into the subroutine and out again, change the loop variable and an
    input while paused, and see the program take the other branch (MCode BR on I1, L2773;
    X150 IF(IN_1); Arcus IF DI1=1)."""
    p = PROGRAMS[dialect]
    made = launch(client, p.file, [{"line": p.loop_line}, {"line": 1}])["breakpoints"]
    assert made[0]["verified"] and made[0]["line"] == p.loop_line
    assert not made[1]["verified"] and "generates no operation" in made[1]["message"]  # line 1 is a comment
    assert client.ok("threads")["threads"] == [{"id": 1, "name": "program"}]

    hit = stop(client, "breakpoint")
    assert hit["body"]["hitBreakpointIds"] == [made[0]["id"]]
    top = frames(client)[0]
    assert top["line"] == p.loop_line and top["source"]["path"] == str(FIXTURES / p.file)
    assert " s" in top["name"]  # the virtual time is in the top frame's name
    refs = scope_refs(client)
    assert set(refs) == {"Program variables", "Axes", "Inputs and outputs", "Machine"}
    assert variables(client, refs["Program variables"])[p.counter] == "0"
    axes = client.ok("variables", {"variablesReference": refs["Axes"]})["variables"]
    axis = next(a for a in axes if a["name"] == f"axis {p.axis}")
    assert axis["value"].startswith("1000 steps")  # the first move of 1000 steps has ended
    detail = variables(client, axis["variablesReference"])
    assert detail["position (steps)"] == "1000" and detail["speed (steps/s)"] == "0" and "max_speed" in detail
    machine = variables(client, refs["Machine"])
    assert float(machine["virtual time (s)"]) > 0

    client.ok("continue", {"threadId": 1})  # the second round
    stop(client, "breakpoint")
    assert variables(client, refs["Program variables"])[p.counter] == "1"

    client.ok("next", {"threadId": 1})  # over the increment, to the call
    stop(client, "step")
    assert frames(client)[0]["line"] == p.call_line
    client.ok("stepIn", {"threadId": 1})  # into the subroutine / sequence
    stop(client, "step")
    stack = frames(client)
    assert stack[0]["line"] == p.sub_line and len(stack) >= 2 and stack[1]["line"] == p.call_line
    client.ok("stepOut", {"threadId": 1})
    stop(client, "step")
    assert len(frames(client)) == len(stack) - 1

    # the loop variable and the input, changed while paused: the run goes on from there
    assert client.ok("setVariable", {"variablesReference": refs["Program variables"], "name": p.counter,
                                     "value": "2"})["value"] == "2"
    assert client.ok("evaluate", {"expression": f"{p.counter} + 1", "context": "watch"})["result"] == "3"
    inputs = client.ok("variables", {"variablesReference": refs["Inputs and outputs"]})["variables"]
    first = next(v for v in inputs if v["name"] == "input 1")
    flipped = "0" if first["value"] == "1" else "1"
    assert client.ok("setVariable", {"variablesReference": refs["Inputs and outputs"], "name": "input 1",
                                     "value": flipped})["value"] == flipped
    client.ok("setBreakpoints", {"source": {"path": str(FIXTURES / p.file)},
                                 "breakpoints": [{"line": p.branches[0]}, {"line": p.branches[1]}]})
    client.ok("continue", {"threadId": 1})
    stop(client, "breakpoint")
    # the changed input takes the branch the run without the debugger does not take
    assert frames(client)[0]["line"] == other_branch(p)
    assert variables(client, refs["Program variables"])[p.counter] == "3"  # 2, then one more round

    client.ok("continue", {"threadId": 1})
    assert client.next_stop()["event"] == "terminated"
    assert client.event("exited")["body"]["exitCode"] == 0
    assert "stopped: end" in client.outputs("console")
    client.ok("disconnect")


def default_branch(p: Program) -> int:
    """The branch line a run without the debugger (input 1 untouched) executes."""
    from mcc.compiler import driver
    from mcc.sim.interpreter import Options, Simulator

    result = driver.check_file(str(FIXTURES / p.file))
    sim = Simulator(result.analysis.module, None, Options(), result.profile)
    lines: set[int] = set()
    sim.observer = lambda kind, frame, item, *rest: lines.add(item.span.line) if (
        kind == "step" and getattr(item, "span", None) is not None) else None
    assert sim.run().stopped == "end"
    taken = [line for line in p.branches if line in lines]
    assert len(taken) == 1, (p.file, taken)
    return taken[0]


def other_branch(p: Program) -> int:
    first, second = p.branches
    return second if default_branch(p) == first else first


@pytest.mark.parametrize("dialect", sorted(PROGRAMS))
def test_a_run_without_the_debugger_takes_exactly_one_branch(dialect):
    """What the session test relies on: an untouched input 1 takes one of the two branches, so
    the flipped input must take the other."""
    assert default_branch(PROGRAMS[dialect]) in PROGRAMS[dialect].branches


def test_prints_arrive_as_output_events(client):
    """Each PR becomes an output event (category stdout) as it runs (lexium-mcode.txt PR L4744)."""
    launch(client, "loop.mxt")
    assert client.next_stop()["event"] == "terminated"
    assert "NO INPUT" in client.outputs("stdout")


def test_no_debug_runs_to_the_end_without_stopping(client):
    """VS Code's Run Without Debugging (launch with noDebug): breakpoints and errors do not stop."""
    launch(client, "divide.mxt", [{"line": 6}], noDebug=True, stopOnEntry=True)
    assert client.next_stop()["event"] == "terminated"
    assert client.event("exited")["body"]["exitCode"] == 1


def test_a_condition_stops_only_when_it_holds(client):
    """A breakpoint condition in the dialect's spelling (`=`, AND) on a program variable and an input."""
    launch(client, "loop.mxt", [{"line": 10, "condition": "Q1 = 2 AND input(1) = 0"}])
    stop(client, "breakpoint")
    refs = scope_refs(client)
    assert variables(client, refs["Program variables"])["Q1"] == "2"
    client.ok("continue", {"threadId": 1})
    assert client.next_stop()["event"] == "terminated"


@pytest.mark.parametrize("hit, expected", [("2", ["1"]), (">= 2", ["1", "2"]), ("% 3", ["2"])])
def test_a_hit_count_stops_at_the_hits_it_names(client, hit, expected):
    """hitCondition N stops at the Nth hit only, >= N from the Nth on, % N at every Nth."""
    launch(client, "loop.mxt", [{"line": 10, "hitCondition": hit}])
    seen = []
    while True:
        event = client.next_stop()
        if event["event"] == "terminated":
            break
        seen.append(variables(client, scope_refs(client)["Program variables"])["Q1"])
        client.ok("continue", {"threadId": 1})
    assert seen == expected


def test_a_malformed_hit_count_is_reported_unverified(client):
    made = launch(client, "loop.mxt", [{"line": 10, "hitCondition": "often"}])["breakpoints"]
    assert not made[0]["verified"] and "hit count" in made[0]["message"]


def test_a_condition_that_cannot_be_evaluated_stops_and_says_why(client):
    launch(client, "loop.mxt", [{"line": 10, "condition": "NOSUCH > 1"}])
    event = stop(client, "breakpoint")
    assert "not a variable" in event["body"]["text"]


def test_stop_on_entry_stops_at_the_first_line(client):
    launch(client, "loop.mxt", stopOnEntry=True)
    stop(client, "entry")
    assert frames(client)[0]["line"] == 2  # VA Q1, the first command sent
    client.ok("continue", {"threadId": 1})
    assert client.next_stop()["event"] == "terminated"


def test_pause_stops_a_running_program_and_terminate_ends_it(client):
    """A loop paced by H 10 (lexium-mcode.txt H, a delay in ms) runs for a long virtual time."""
    launch(client, "forever.mxt", until=1e9, maxSteps=10**9)
    assert client.request("variables", {"variablesReference": 1})["success"] is False  # running: not readable
    client.ok("pause", {"threadId": 1})
    stop(client, "pause")
    assert frames(client)[0]["line"] in (5, 6, 7)
    client.ok("terminate")
    assert client.next_stop()["event"] == "terminated"
    client.ok("disconnect")


def test_a_runtime_error_stops_where_it_happens(client):
    """Division by zero (S002) stops before the run ends, with the error's state readable."""
    launch(client, "divide.mxt")
    client.ok("setExceptionBreakpoints", {"filters": ["errors"]})
    event = stop(client, "exception")
    assert event["body"]["text"].startswith("S002")
    assert frames(client)[0]["line"] == 7
    client.ok("continue", {"threadId": 1})
    assert client.next_stop()["event"] == "terminated"
    assert client.event("exited")["body"]["exitCode"] == 1


def test_without_the_errors_filter_a_runtime_error_just_ends_the_run(client):
    client.ok("initialize", {"adapterID": "mcc"})
    client.ok("setExceptionBreakpoints", {"filters": []})
    client.ok("launch", {"program": str(FIXTURES / "divide.mxt")})
    client.event("initialized")
    client.ok("configurationDone")
    assert client.next_stop()["event"] == "terminated"
    assert "S002" in client.outputs("stderr")


def test_a_limit_switch_stops_the_program(client, tmp_path):
    """An axis crossing the scenario's limit switch (S004, docs/SIMULATOR.md "Limit switches")."""
    scenario = tmp_path / "limits.toml"
    scenario.write_text("[axes.1]\nlimit_plus = 1500\n")
    launch(client, "loop.mxt", scenario=str(scenario))
    event = stop(client, "exception")
    assert event["body"]["text"].startswith("S004") and "limit switch" in event["body"]["text"]
    axis = client.ok("variables", {"variablesReference": scope_refs(client)["Axes"]})["variables"][0]
    assert variables(client, axis["variablesReference"])["fault"] == "1"
    client.ok("disconnect")


def test_a_run_that_ends_waiting_pauses_on_its_last_state(client):
    """A loop polling an input nothing sets ends the run "waiting" (docs/SIMULATOR.md "Time"); the
    debugger pauses there once (as on an end of travel) so the state it ended in can be read."""
    launch(client, "waits.mxt")
    event = stop(client, "exception")
    assert event["body"]["description"] == "waiting" and "polls in a loop" in event["body"]["text"]
    assert frames(client)[0]["line"] in (6, 7)
    assert variables(client, scope_refs(client)["Program variables"])["Q1"] == "1"
    client.ok("continue", {"threadId": 1})
    assert client.next_stop()["event"] == "terminated"


def test_a_handler_shows_in_the_call_stack_on_top_of_what_it_interrupted(client, tmp_path):
    """An input trip (MCode TI/TE, lexium-mcode.txt L5667) runs its handler X1 over the G2 loop:
    the stack shows `X1 (on input)` above the main routine."""
    scenario = tmp_path / "trip.toml"
    scenario.write_text("until = 5.0\n[[events]]\nat = 0.5\ninput = 1\nvalue = 0\n")
    sample = Path(__file__).resolve().parents[2] / "samples" / "mcode" / "trip_on_input.mxt"
    client.ok("initialize", {"adapterID": "mcc"})
    client.ok("launch", {"program": str(sample), "scenario": str(scenario)})
    client.event("initialized")
    client.ok("setBreakpoints", {"source": {"path": str(sample)}, "breakpoints": [{"line": 17}]})
    client.ok("configurationDone")
    stop(client, "breakpoint")
    stack = frames(client)
    assert stack[0]["name"].startswith("X1 (on input) @ 0.500 s") and stack[0]["line"] == 17
    assert len(stack) == 2
    client.ok("disconnect")


def test_a_program_with_errors_is_not_launched(client):
    client.ok("initialize", {"adapterID": "mcc"})
    response = client.request("launch", {"program": str(FIXTURES / "broken.mxt")})
    assert response["success"] is False and "M104" in response["message"]
    response = client.request("launch", {"program": str(FIXTURES / "missing.mxt")})
    assert response["success"] is False and "no program file" in response["message"]
    response = client.request("launch", {})
    assert response["success"] is False and "program" in response["message"]
    client.ok("launch", {"program": str(FIXTURES / "loop.mxt")})
    response = client.request("launch", {"program": str(FIXTURES / "loop.mxt")})
    assert response["success"] is False and "launched already" in response["message"]


def test_requests_it_does_not_know_and_broken_messages_are_answered(client):
    client.ok("initialize", {"adapterID": "mcc"})
    response = client.request("goto", {"threadId": 1, "targetId": 1})
    assert response["success"] is False and "does not support 'goto'" in response["message"]
    client.send_raw(b"Content-Length: 5\r\n\r\n{nope")
    client.send_raw(b"Content-Length: -1\r\n\r\n")
    assert client.ok("threads")["threads"]  # the adapter read on
    assert "not JSON" in client.outputs("stderr") and "out of range" in client.outputs("stderr")
    assert client.request("stackTrace", {"threadId": 1})["success"] is False  # nothing launched


def test_changing_what_cannot_change_is_refused(client):
    launch(client, "loop.mxt", [{"line": 10}])
    stop(client, "breakpoint")
    refs = scope_refs(client)
    assert client.request("setVariable", {"variablesReference": refs["Machine"], "name": "virtual time (s)",
                                          "value": "3"})["success"] is False
    assert client.request("setVariable", {"variablesReference": refs["Program variables"], "name": "Q1",
                                          "value": "many"})["success"] is False
    assert client.request("setVariable", {"variablesReference": refs["Inputs and outputs"], "name": "input 1",
                                          "value": "5"})["success"] is False
    assert client.request("evaluate", {"expression": "__import__('os')"})["success"] is False
    client.ok("disconnect")


def test_the_tcp_port_serves_one_client():
    """`mcc debug --port 0` listens, says where, and serves a client over TCP."""
    process = subprocess.Popen([sys.executable, "-m", "mcc", "debug", "--port", "0"], stderr=subprocess.PIPE)
    try:
        line = process.stderr.readline().decode()
        assert "listening on 127.0.0.1:" in line
        port = int(line.rsplit(":", 1)[1])
        with socket.create_connection(("127.0.0.1", port), timeout=30) as sock:
            reader, writer = sock.makefile("rb"), sock.makefile("wb")
            client = Client(reader, writer)
            assert client.ok("initialize", {"adapterID": "mcc"})["supportsConfigurationDoneRequest"]
            client.ok("launch", {"program": str(FIXTURES / "loop.mxt")})
            client.event("initialized")
            client.ok("configurationDone")
            assert client.next_stop()["event"] == "terminated"
            client.ok("disconnect")
        assert process.wait(timeout=30) == 0
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()


CLAIMED_AND_TESTED = {
    "supportsConfigurationDoneRequest": "configurationDone",
    "supportsConditionalBreakpoints": "condition",
    "supportsHitConditionalBreakpoints": "hitCondition",
    "supportsSetVariable": "setVariable",
    "supportsEvaluateForHovers": "evaluate",
    "supportsTerminateRequest": "terminate",
    "exceptionBreakpointFilters": "setExceptionBreakpoints",
}


def test_capabilities_are_all_tested(client):
    """Every capability the adapter declares is one this file exercises (by the request or
    argument named); a new capability needs a test here first."""
    claimed = client.ok("initialize", {"adapterID": "mcc"})
    assert set(claimed) == set(CLAIMED_AND_TESTED)
    text = Path(__file__).read_text(encoding="utf-8")
    for word in CLAIMED_AND_TESTED.values():
        assert text.count(f'"{word}"') >= 2, word
