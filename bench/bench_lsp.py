"""Benchmark: `mcc lsp` on a generated 3,000-line program of each dialect, through the protocol.

A real server process (stdio) is driven by pygls's client as an editor drives it. For each dialect:

- edit -> fresh diagnostics: the time from sending an incremental `didChange` to the last
  `publishDiagnostics` of that version, the one with everything `mcc check` and `mcc lint` report
  (the server publishes once when the checks and the rules are done; it publishes the checks
  first only when the rules are still running 150 ms after the analysis started, and the first
  publication is then shown too). The edits are real and vary: a digit changed, a digit typed
  (every later line moves by a character), a line break typed (every later line moves down).
  They come one at a time, so each is the first after a quiet spell and is analysed at once.
  Target: <= 150 ms.
- typing: bursts of five keystrokes 40 ms apart in one number (each edit arrives while the previous
  one is analysed, which stops at its next checkpoint, compiler/cancel.py); the time from the last
  keystroke to the last publication of its version, the abandoned analyses (and the debounce, when
  one is set with --debounce) included: what the user sees once they stop typing.
- start-up: the time from starting `mcc lsp` to the answer to `initialize` (the server answers it
  before it imports the compiler), next to the time Python takes to import pygls alone.
- hover and completion latency at random tokens, when the server is idle and while it is
  re-analysing after an edit (requests answer from the latest finished analysis). Target: <= 50 ms.

Medians and 95th percentiles of one run are printed next to the targets; the machine's load is
printed too, since other processes compete for the CPUs, and so is the CPU time the server's
analysis thread spent in the checks and the rules of each edit (reported by `mcc/status`), which
the load does not inflate.

An independent client (`RawClient`: JSON-RPC over the server's stdio written from the protocol's
specification with the standard library, no pygls) runs the same edits and takes, for each, the
time from sending `didChange` to the arrival of the publication whose diagnostics are exactly what
`mcc check` + `mcc lint` report for the new text (computed in this process before the edit is
sent), so that nothing of the server's own bookkeeping (`mcc/status`) decides when it is done.
It also reads the server process's CPU time, all its threads (Linux /proc schedstat), from just
before `didChange` to its last publication of the version: the work an edit's diagnostics cost the
server, protocol included, which the machine's load does not inflate (an idle machine's wall
clock would be about that).

Run: .venv/bin/python bench/bench_lsp.py [--lines 3000] [--edits 12] [--requests 40] [--dialects x150]
     [--debounce MS] [--client pygls|raw|both]
"""

from __future__ import annotations

import argparse
import asyncio
import os
import random
import statistics
import sys
import tempfile
import threading
import time
from pathlib import Path

from lsprotocol import types as t
from pygls.lsp.client import LanguageClient

EXTENSIONS = {"mcode": ".mxt", "arcus": ".prg", "x150": ".x150"}
TARGET_DIAGNOSTICS_MS = 150
TARGET_QUERY_MS = 50


def generate(dialect: str, lines: int) -> str:
    """A program of `lines` lines in the style of the samples (setup, then many motion blocks) that
    `mcc check` accepts: the tail (routines, END, XT) is reserved first, the body fills the rest."""
    head: list[str] = []
    body: list[str] = []
    tail: list[str] = []
    if dialect == "mcode":
        labels = [f"{a}{b}" for a in "JKNQW" for b in "0123456789"]
        head = ["' generated benchmark program", "VA Np=0", "MS=256", "VI=2000", "VM=400000", "A=800000", "D=A",
                "PG 1", "LB SU", "  HM 1", "  H", "LB G1"]
        tail = ["  BR G1", "  E"] + [line for label in labels for line in (f"LB {label}", "  PR Np", "  RT")] + \
               ["PG", "S", "' end"]
        block = lambda i: [f"  BR {labels[i % len(labels)]},I1=0", f"  MA {1000 * (i % 50)}", "  H",  # noqa: E731
                           f"  MR -{100 + i % 7}", "  H", "  O1=1", "  H 250", "  IC Np"]
    elif dialect == "arcus":
        head = ["; generated benchmark program", "ABS", "HSPD=30000", "LSPD=500", "ACC=250", "EO=1", "V1=0"]
        tail = ["END", "SUB 1", "V1=0", "DO2=1", "DELAY=100", "DO2=0", "ENDSUB"]
        block = lambda i: [f"X{1000 * (i % 50)}Y{200 * (i % 9)}", "WAITX", "WAITY", "DO1=1",  # noqa: E731
                           "DELAY=250", "DO1=0", "V1=V1+1", "IF V1>=10", "GOSUB 1", "ENDIF"]
    else:  # sequences of 24 commands on devices 1 to 8 (each device's store holds 8,000 bytes)
        head = ["; generated benchmark program"] + [f"{d}CUR4000" for d in range(1, 9)]
        tail = ["1SV", "1XR1"]
        block = lambda i: [f"{i % 8 + 1}XE{i // 8 % 64 + 1}", f"{i % 8 + 1}XD{i // 8 % 64 + 1}"] + \
            [c for k in range(6) for c in (f"{i % 8 + 1}D{1000 * ((i + k) % 50) + 10}", f"{i % 8 + 1}G",
                                           f"{i % 8 + 1}T0.2", f"{i % 8 + 1}O1")] + [f"{i % 8 + 1}XT"]
    i = 0
    while True:
        more = block(i)
        if len(head) + len(body) + len(more) + len(tail) > lines:
            break
        body += more
        i += 1
    text = head + body + tail
    text += [("' " if dialect == "mcode" else "; ") + "padding"] * (lines - len(text))
    return "\n".join(text) + "\n"


class Bench:
    def __init__(self) -> None:
        self.client = LanguageClient("mcc-bench", "1")
        self.version: dict[str, int] = {}
        self.published: dict[tuple[str, int | None], list[float]] = {}
        self.arrived = asyncio.Event()
        self.timings: list[dict] = []  # the server's own timings of each analysis waited for (mcc/status)

        @self.client.feature(t.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        def on_diagnostics(params: t.PublishDiagnosticsParams) -> None:
            self.published.setdefault((params.uri, params.version), []).append(time.perf_counter())
            self.arrived.set()

    async def start(self, root: Path, debounce: float | None = None) -> None:
        await self.client.start_io(sys.executable, "-m", "mcc", "lsp")
        options = {"debounce": debounce} if debounce is not None else None
        await self.client.initialize_async(t.InitializeParams(
            capabilities=t.ClientCapabilities(), root_uri=root.as_uri(), initialization_options=options))
        self.client.initialized(t.InitializedParams())

    async def wait_published(self, uri: str, version: int, count: int = 1, timeout: float = 120.0) -> list[float]:
        deadline = time.perf_counter() + timeout
        while len(self.published.get((uri, version), [])) < count:
            self.arrived.clear()
            remaining = deadline - time.perf_counter()
            if remaining <= 0:
                raise TimeoutError(f"no diagnostics for {uri} version {version}")
            try:
                await asyncio.wait_for(self.arrived.wait(), remaining)
            except asyncio.TimeoutError:
                pass
        return self.published[(uri, version)]

    async def wait_complete(self, uri: str, version: int) -> list[float]:
        """The arrival times of the publications of `version`, once the server says (mcc/status)
        that its analysis is complete: the last one then holds all its diagnostics (the server
        publishes before it records the analysis as complete, on the same stream)."""
        await self.wait_published(uri, version)
        while True:
            status = await self.client.protocol.send_request_async("mcc/status", {"uri": uri})
            get = status.get if isinstance(status, dict) else lambda name: getattr(status, name, None)
            if get("version") == version and get("complete"):
                found = get("timings")  # a dict, or the client's untyped object
                self.timings.append(found if isinstance(found, dict) else found._asdict() if found else {})
                return self.published[(uri, version)]
            await asyncio.sleep(0.01)

    def change(self, uri: str, line: int, start: int, end: int, text: str) -> float:
        """Send one incremental edit (the next version); the time it was sent."""
        version = self.version[uri] = self.version.get(uri, 1) + 1
        sent = time.perf_counter()
        self.client.text_document_did_change(t.DidChangeTextDocumentParams(
            text_document=t.VersionedTextDocumentIdentifier(uri=uri, version=version),
            content_changes=[t.TextDocumentContentChangePartial(
                range=t.Range(t.Position(line, start), t.Position(line, end)), text=text)]))
        return sent

    async def stop(self) -> None:
        await self.client.shutdown_async(None)
        self.client.exit(None)
        await self.client.stop()


def positions(text: str, rng: random.Random, count: int) -> list[t.Position]:
    lines = text.split("\n")
    out = []
    while len(out) < count:
        line = rng.randrange(len(lines) - 1)
        stripped = len(lines[line]) - len(lines[line].lstrip())
        if lines[line].strip() and not lines[line].lstrip().startswith(("'", ";", "`")):
            out.append(t.Position(line, stripped + rng.randrange(max(1, len(lines[line]) - stripped))))
    return out


def summary(values: list[float]) -> str:
    values = sorted(values)
    p95 = values[min(len(values) - 1, int(round(0.95 * (len(values) - 1))))]
    return f"median {statistics.median(values):6.1f} ms, p95 {p95:6.1f} ms"


async def timed(coroutine) -> float:
    start = time.perf_counter()
    await coroutine
    return (time.perf_counter() - start) * 1000


def digit_lines(lines: list[str]) -> list[int]:
    return [i for i, line in enumerate(lines) if any(c.isdigit() for c in line)
            and not line.lstrip().startswith(("'", ";"))]


def next_edit(content: list[str], rng: random.Random, i: int) -> tuple[int, int, int, str]:
    """The i-th edit of a series (line, start, end, new text), applied to `content` (the lines):
    by turns a digit changed, a digit typed (every later line moves by one character) and a line
    break typed at the end of a line (every later line moves down)."""
    line = rng.choice(digit_lines(content))
    column = next(k for k, c in enumerate(content[line]) if c.isdigit())
    kind = i % 3
    if kind == 0:
        digit = str((int(content[line][column]) + 1) % 10)
        content[line] = content[line][:column] + digit + content[line][column + 1:]
        return line, column, column + 1, digit
    if kind == 1:
        content[line] = content[line][:column] + "1" + content[line][column:]
        return line, column, column, "1"
    end = len(content[line])
    content.insert(line + 1, "")
    return line, end, end, "\n"


async def bench_dialect(bench: Bench, root: Path, dialect: str, lines: int, edits: int, requests: int) -> dict:
    rng = random.Random(dialect)
    text = generate(dialect, lines)
    path = root / f"bench{EXTENSIONS[dialect]}"
    uri = path.as_uri()
    ident = t.TextDocumentIdentifier(uri=uri)
    bench.version[uri] = 1
    bench.client.text_document_did_open(t.DidOpenTextDocumentParams(
        t.TextDocumentItem(uri=uri, language_id=dialect, version=1, text=text)))
    await bench.wait_complete(uri, 1)
    content = text.split("\n")
    first, full, typing, cpu = [], [], [], []
    busy_hover, busy_completion = [], []
    for i in range(edits):
        sent = bench.change(uri, *next_edit(content, rng, i))
        version = bench.version[uri]
        # while the server re-analyses: queries answer from the previous analysis
        for position in positions(text, rng, 2):
            busy_hover.append(await timed(bench.client.text_document_hover_async(t.HoverParams(ident, position))))
            busy_completion.append(await timed(bench.client.text_document_completion_async(
                t.CompletionParams(ident, t.Position(position.line, 0)))))
        times = await bench.wait_complete(uri, version)
        first.append((times[0] - sent) * 1000)
        full.append((times[-1] - sent) * 1000)
        cpu.append(bench.timings[-1].get("check_cpu_ms", 0) + bench.timings[-1].get("lint_cpu_ms", 0))
    for _ in range(max(2, edits // 3)):  # bursts of typing into one number
        line = rng.choice(digit_lines(content))
        column = next(k for k, c in enumerate(content[line]) if c.isdigit())
        for _ in range(5):
            sent = bench.change(uri, line, column, column, "1")
            content[line] = content[line][:column] + "1" + content[line][column:]
            await asyncio.sleep(0.04)
        times = await bench.wait_complete(uri, bench.version[uri])
        typing.append((times[-1] - sent) * 1000)
    hover, completion = [], []
    text = "\n".join(content)
    for position in positions(text, rng, requests):
        hover.append(await timed(bench.client.text_document_hover_async(t.HoverParams(ident, position))))
        completion.append(await timed(bench.client.text_document_completion_async(
            t.CompletionParams(ident, t.Position(position.line, 0)))))
    return {"first": first, "full": full, "typing": typing, "cpu": cpu, "hover": hover, "completion": completion,
            "busy_hover": busy_hover, "busy_completion": busy_completion, "lines": len(content),
            "frontend": frontend_alone(path, text, edits)}


class RawClient:
    """An independent client: LSP as its specification describes it (JSON-RPC 2.0 messages with a
    `Content-Length` header, over the pipes of `mcc lsp --stdio`), written here with the standard
    library only, sharing no code with the server (no pygls, no lsprotocol), as an editor speaks
    to it. A thread reads the server's messages and stamps each with the time it arrived; requests
    from the server (registrations, refreshes) are answered with null, as a minimal editor does."""

    def __init__(self, argv: list[str]) -> None:
        import queue
        import subprocess

        self.process = subprocess.Popen(argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.messages: queue.Queue = queue.Queue()
        # (uri, version) -> each publication's (arrival, the server's CPU time then, diagnostic keys)
        self.publications: dict[tuple[str, int], list[tuple[float, float, list]]] = {}
        self.published = threading.Condition()
        self.next_id = 0
        self.lock = threading.Lock()
        threading.Thread(target=self.read, daemon=True).start()

    def read(self) -> None:
        import json

        stream = self.process.stdout
        while True:
            length = None
            while True:
                header = stream.readline()
                if not header:
                    return
                if header in (b"\r\n", b"\n"):
                    break
                name, _, value = header.decode("ascii").partition(":")
                if name.strip().lower() == "content-length":
                    length = int(value)
            body = stream.read(length or 0)
            arrived = time.perf_counter()
            cpu = process_cpu_ms(self.process.pid) if b'"textDocument/publishDiagnostics"' in body else 0.0
            message = json.loads(body)
            if "method" in message and "id" in message:  # a request from the server
                self.send({"jsonrpc": "2.0", "id": message["id"], "result": None})
            if message.get("method") == "textDocument/publishDiagnostics":
                params = message["params"]
                with self.published:
                    self.publications.setdefault((params["uri"], params.get("version")), []).append(
                        (arrived, cpu, sorted(diagnostic_key(d) for d in params["diagnostics"])))
                    self.published.notify_all()
                continue
            self.messages.put((arrived, message))

    def send(self, message: dict) -> float:
        import json

        body = json.dumps(message).encode("utf-8")
        with self.lock:
            self.process.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
            self.process.stdin.flush()
            return time.perf_counter()

    def notify(self, method: str, params) -> float:
        return self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def request(self, method: str, params, timeout: float = 120.0):
        self.next_id += 1
        ident = self.next_id
        self.send({"jsonrpc": "2.0", "id": ident, "method": method, "params": params})
        deadline = time.perf_counter() + timeout
        while True:
            _, message = self.messages.get(timeout=max(0.0, deadline - time.perf_counter()))
            if message.get("id") == ident and "method" not in message:
                return message.get("result")

    def wait_for(self, uri: str, version: int, expected: list, timeout: float = 120.0) -> None:
        """Until a publication of `version` equal to `expected` arrives (without asking the server
        anything meanwhile: the requests would cost it CPU time that is measured)."""
        with self.published:
            if not self.published.wait_for(lambda: any(keys == expected for _, _, keys in
                                                       self.publications.get((uri, version), [])), timeout):
                raise AssertionError(f"no publication of version {version} equal to mcc lint's in {timeout} s")

    def final(self, uri: str, version: int, expected: list) -> tuple[float, float]:
        """The arrival of the publication from which on the editor shows `expected` (code and range
        of each diagnostic, sorted) for `uri` at `version` and nothing else (the earliest one equal
        to it that no later one of the version differs from: when the lint rules find nothing new,
        the checks published first under load already are), and the server's CPU time when its
        last publication of the version arrived (all the work of the diagnostics). Asked once the
        server has published everything of the version (`mcc/status` says complete)."""
        found = self.publications.get((uri, version), [])
        start = len(found)
        while start > 0 and found[start - 1][2] == expected:
            start -= 1
        if start == len(found):
            raise AssertionError(f"the server's diagnostics of version {version} are not mcc lint's: "
                                 f"{found[-1][2] if found else 'none published'} != {expected}")
        return found[start][0], found[-1][1]

    def close(self) -> None:
        self.request("shutdown", None)
        self.notify("exit", None)
        self.process.wait(timeout=30)


def process_cpu_ms(pid: int) -> float:
    """The CPU time of every thread of process `pid` so far, in milliseconds (Linux: the first
    field of /proc/PID/task/TID/schedstat, nanoseconds on a CPU; NaN elsewhere)."""
    total = 0
    try:
        for tid in os.listdir(f"/proc/{pid}/task"):
            with open(f"/proc/{pid}/task/{tid}/schedstat", encoding="ascii") as stat:
                total += int(stat.read().split()[0])
    except OSError:
        return float("nan")
    return total / 1e6


def diagnostic_key(d: dict) -> tuple:
    r = d["range"]
    return (d.get("code"), r["start"]["line"], r["start"]["character"], r["end"]["line"], r["end"]["character"])


def expected_diagnostics(path: Path, text: str) -> list:
    """What `mcc check` and `mcc lint` report for the text (the configuration the server reads for
    the file), as (code, LSP range) keys, sorted: the diagnostics the editor must end up with."""
    from mcc.compiler.config import Resolver
    from mcc.compiler.lint import engine

    _, found = engine.lint_text(str(path), text, Resolver().for_path(str(path)))
    keys = []
    for d in found:
        if d.span.file != str(path):
            continue
        span = d.span
        keys.append((d.code, max(span.line - 1, 0), max(span.column - 1, 0), max(span.end_line - 1, 0),
                     max(span.end_column - 1, 0)))
    return sorted(keys)


def raw_dialect(root: Path, dialect: str, lines: int, edits: int) -> dict:
    """The edits of `bench_dialect` (same series) through the independent client: didChange ->
    the publication equal to `mcc check` + `mcc lint` on the new text; bursts of typing likewise,
    from the last keystroke. The server's CPU time per edit is read from `mcc/status`."""
    rng = random.Random(dialect)
    text = generate(dialect, lines)
    path = root / f"raw{EXTENSIONS[dialect]}"
    uri = path.as_uri()
    client = RawClient([sys.executable, "-m", "mcc", "lsp", "--stdio"])
    client.request("initialize", {"processId": os.getpid(), "rootUri": root.as_uri(), "capabilities": {}})
    client.notify("initialized", {})
    client.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": dialect, "version": 1,
                                                            "text": text}})
    content = text.split("\n")
    version = 1
    full, typing, cpu, process = [], [], [], []
    pid = client.process.pid

    def change(edit: tuple[int, int, int, str]) -> float:
        nonlocal version
        version += 1
        line, start, end, new = edit
        return client.notify("textDocument/didChange", {
            "textDocument": {"uri": uri, "version": version},
            "contentChanges": [{"range": {"start": {"line": line, "character": start},
                                          "end": {"line": line, "character": end}}, "text": new}]})

    def settle() -> None:  # the analysis of this version complete (memory, cycles) before the next edit
        while True:
            status = client.request("mcc/status", {"uri": uri})
            if status.get("version") == version and status.get("complete"):
                if version > 1:  # an edit's, not the first analysis of the whole file
                    cpu.append(status["timings"].get("check_cpu_ms", 0) + status["timings"].get("lint_cpu_ms", 0))
                return
            time.sleep(0.01)

    settle()
    client.final(uri, 1, expected_diagnostics(path, text))
    for i in range(edits):
        edit = next_edit(content, rng, i)
        expected = expected_diagnostics(path, "\n".join(content))  # before the edit is sent: not timed
        before = process_cpu_ms(pid)
        sent = change(edit)
        client.wait_for(uri, version, expected)
        settle()
        arrived, spent = client.final(uri, version, expected)
        full.append((arrived - sent) * 1000)
        process.append(spent - before)  # every thread of the server, to its last publication
    for _ in range(max(2, edits // 3)):
        line = rng.choice(digit_lines(content))
        column = next(k for k, c in enumerate(content[line]) if c.isdigit())
        keystrokes = []
        for _ in range(5):
            keystrokes.append((line, column, column, "1"))
            content[line] = content[line][:column] + "1" + content[line][column:]
        expected = expected_diagnostics(path, "\n".join(content))
        for edit in keystrokes:
            sent = change(edit)
            time.sleep(0.04)
        client.wait_for(uri, version, expected)
        settle()
        typing.append((client.final(uri, version, expected)[0] - sent) * 1000)
    client.close()
    return {"full": full, "typing": typing, "cpu": cpu, "process": process}


def frontend_alone(path: Path, text: str, repeat: int) -> list[float]:
    """For comparison, measured in this process in the same run: `mcc check` from scratch on the
    same text (what the server did on every edit before it parsed incrementally)."""
    import gc

    from mcc.compiler.config import Settings
    from mcc.compiler.lint import engine

    gc.set_threshold(100_000, 50, 100)  # as the server does (lsp/server.py)
    engine.check_text(str(path), text, Settings())
    times = []
    for _ in range(max(3, repeat)):
        start = time.perf_counter()
        engine.check_text(str(path), text, Settings())
        times.append((time.perf_counter() - start) * 1000)
    return times


def initialize_ms() -> float:
    """Milliseconds from starting `mcc lsp` to the first line of its answer to `initialize`."""
    import json
    import subprocess

    start = time.perf_counter()
    server = subprocess.Popen([sys.executable, "-m", "mcc", "lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
    body = json.dumps({"jsonrpc": "2.0", "id": 1, "method": "initialize",
                       "params": {"processId": None, "rootUri": None, "capabilities": {}}}).encode()
    server.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
    server.stdin.flush()
    server.stdout.readline()
    elapsed = (time.perf_counter() - start) * 1000
    server.kill()
    server.wait()
    return elapsed


def pygls_import_ms() -> float:
    import subprocess

    start = time.perf_counter()
    subprocess.run([sys.executable, "-c", "import pygls.lsp.server"], check=True)
    return (time.perf_counter() - start) * 1000


async def main_async(options) -> None:
    root = Path(tempfile.mkdtemp(prefix="mcc-bench-lsp-"))
    bench = Bench()
    await bench.start(root, options.debounce)
    try:
        starts = [initialize_ms() for _ in range(3)]
        floor = [pygls_import_ms() for _ in range(3)]
        print(f"start -> initialize answered: {summary(starts)}  (python -c 'import pygls.lsp.server': "
              f"{summary(floor)})")
        print(f"mcc lsp: {options.edits} edits, bursts of typing and {options.requests} queries per dialect")
        for dialect in options.dialects.split(","):
            if options.client in ("raw", "both"):
                raw = raw_dialect(root, dialect, options.lines, options.edits)
                print(f"\n{dialect}, independent client (stdlib JSON-RPC over stdio; diagnostics compared with "
                      "mcc lint)")
                for name, label in (("full", "edit -> all diagnostics        "),
                                    ("typing", "typing -> all diagnostics      ")):
                    ok = "within" if statistics.median(raw[name]) <= TARGET_DIAGNOSTICS_MS else "OVER"
                    print(f"  {label}: {summary(raw[name])}  [target <= {TARGET_DIAGNOSTICS_MS} ms: {ok}]")
                print(f"  analysis thread CPU (check+lint): {summary(raw['cpu'])}")
                print(f"  server process CPU, all threads, didChange -> last publication: {summary(raw['process'])}"
                      "  (about what an idle machine's wall clock would be)")
            if options.client == "raw":
                continue
            r = await bench_dialect(bench, root, dialect, options.lines, options.edits, options.requests)
            print(f"\n{dialect} ({r['lines']} lines)")
            for name, label in (("full", "edit -> all diagnostics        "),
                                ("typing", "typing -> all diagnostics      ")):
                ok = "within" if statistics.median(r[name]) <= TARGET_DIAGNOSTICS_MS else "OVER"
                print(f"  {label}: {summary(r[name])}  [target <= {TARGET_DIAGNOSTICS_MS} ms: {ok}]")
            print(f"  analysis thread CPU (check+lint): {summary(r['cpu'])}  (the edit's own work; the rest of the "
                  "wall clock is waiting for a CPU and the protocol)")
            if r["first"] != r["full"]:
                print(f"  edit -> first publication      : {summary(r['first'])} (the checks, the rules still running)")
            floor = statistics.median(r["frontend"])
            print(f"  mcc check from scratch (in-proc): {summary(r['frontend'])}  -> server (edit -> all diagnostics) "
                  f"/ check from scratch = {statistics.median(r['full']) / floor:.2f}")
            for name in ("hover", "completion"):
                ok = "within" if statistics.median(r[name]) <= TARGET_QUERY_MS else "OVER"
                print(f"  {name:10} idle                : {summary(r[name])}  [target <= {TARGET_QUERY_MS} ms: {ok}]")
                print(f"  {name:10} during analysis     : {summary(r['busy_' + name])}")
        load = ", ".join(f"{x:.2f}" for x in os.getloadavg()) if hasattr(os, "getloadavg") else "n/a"
        print(f"\nCPUs: {os.cpu_count()}, load average {load}")
    finally:
        await bench.stop()


def main() -> None:
    args = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    args.add_argument("--lines", type=int, default=3000)
    args.add_argument("--edits", type=int, default=12)
    args.add_argument("--requests", type=int, default=40)
    args.add_argument("--dialects", default="mcode,arcus,x150", help="comma-separated")
    args.add_argument("--debounce", type=float, default=None, help="the server's debounce in ms (default: its own)")
    args.add_argument("--client", choices=("pygls", "raw", "both"), default="both",
                      help="pygls's client, the independent stdlib client, or both (default)")
    asyncio.run(main_async(args.parse_args()))


if __name__ == "__main__":
    main()
