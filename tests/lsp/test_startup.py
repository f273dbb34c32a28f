"""`initialize` is answered before the server imports the compiler: loading the server module
imports pygls and the few light modules the capabilities need, not Lark, the catalogs, the IR or the
lint rules (a thread imports them after the answer, lsp/server.py `warm_up`)."""

from __future__ import annotations

import json
import subprocess
import sys

HEAVY = ("lark", "mcc.grammars.lark_runtime", "mcc.compiler.driver", "mcc.compiler.ir", "mcc.compiler.lint.engine",
         "mcc.compiler.catalog", "mcc.lsp.documents", "mcc.lsp.analysis")


def test_the_server_module_does_not_import_the_compiler():
    probe = "import sys, json; import mcc.lsp.server; print(json.dumps(sorted(sys.modules)))"
    loaded = set(json.loads(subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                                           check=True, timeout=120).stdout))
    assert "pygls.lsp.server" in loaded
    assert not loaded & set(HEAVY), sorted(loaded & set(HEAVY))


def test_initialize_is_answered_and_the_compiler_is_imported_after_it():
    server = subprocess.Popen([sys.executable, "-m", "mcc", "lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
    try:
        def send(message: dict) -> None:
            body = json.dumps(message).encode()
            server.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
            server.stdin.flush()

        def receive() -> dict:
            length = 0
            while (line := server.stdout.readline().strip()):
                if line.lower().startswith(b"content-length:"):
                    length = int(line.split(b":")[1])
            return json.loads(server.stdout.read(length))

        send({"jsonrpc": "2.0", "id": 1, "method": "initialize",
              "params": {"processId": None, "rootUri": None, "capabilities": {}}})
        answer = receive()
        assert answer["id"] == 1 and "codeActionProvider" in answer["result"]["capabilities"]
        send({"jsonrpc": "2.0", "method": "initialized", "params": {}})
        # the first document is analysed once the thread's imports are done (the import lock)
        send({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {"textDocument": {
            "uri": "file:///tmp/startup.prg", "languageId": "arcus", "version": 1, "text": "X1000(\nEND\n"}}})
        published = receive()
        while published.get("method") != "textDocument/publishDiagnostics":
            published = receive()
        assert published["params"]["diagnostics"]
        send({"jsonrpc": "2.0", "id": 2, "method": "shutdown"})
        send({"jsonrpc": "2.0", "method": "exit"})
        server.wait(timeout=60)
    finally:
        if server.poll() is None:
            server.kill()
