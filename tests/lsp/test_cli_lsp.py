"""`mcc lsp` as a command: its help, usage errors, and that the rest of the CLI never loads pygls."""

from __future__ import annotations

import subprocess
import sys

from conftest import run_mcc


def test_lsp_help_and_usage_errors():
    result = run_mcc("lsp", "--help")
    assert result.returncode == 0 and "language server" in result.stdout and "--tcp" in result.stdout
    bad = run_mcc("lsp", "--tcp", "localhost")
    assert bad.returncode == 2 and "HOST:PORT" in bad.stderr
    both = run_mcc("lsp", "--stdio", "--tcp", "127.0.0.1:2087")
    assert both.returncode == 2 and "--stdio" in both.stderr


def test_stdio_flag_that_editor_clients_pass_is_accepted():
    """vscode-languageclient and others start servers with `--stdio`: it must answer initialize."""
    import json

    request = json.dumps({"jsonrpc": "2.0", "id": 1, "method": "initialize",
                          "params": {"processId": None, "rootUri": None, "capabilities": {}}})
    message = f"Content-Length: {len(request)}\r\n\r\n{request}".encode()
    server = subprocess.Popen([sys.executable, "-m", "mcc", "lsp", "--stdio"], stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        server.stdin.write(message)
        server.stdin.flush()
        header = server.stdout.readline()
        assert header.startswith(b"Content-Length:"), header
    finally:
        server.kill()
        server.wait()


def test_the_cli_does_not_import_the_language_server():
    code = "import sys, mcc.cli.commands; print('pygls' in sys.modules, 'mcc.lsp.server' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["False", "False"]


def test_tcp_server_answers_initialize(tmp_path):
    import json
    import socket
    import time

    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    server = subprocess.Popen([sys.executable, "-m", "mcc", "lsp", "--tcp", f"127.0.0.1:{port}"],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        deadline = time.time() + 60
        while True:
            try:
                conn = socket.create_connection(("127.0.0.1", port), timeout=60)
                break
            except OSError:
                if time.time() > deadline:
                    raise
                time.sleep(0.1)
        with conn:
            body = json.dumps({"jsonrpc": "2.0", "id": 1, "method": "initialize",
                               "params": {"processId": None, "rootUri": None, "capabilities": {}}}).encode()
            conn.sendall(b"Content-Length: %d\r\n\r\n" % len(body) + body)
            data = b""
            while b"serverInfo" not in data or not data.rstrip().endswith(b"}"):
                chunk = conn.recv(65536)
                if not chunk:
                    break
                data += chunk
        reply = json.loads(data.split(b"\r\n\r\n", 1)[1])
        assert reply["result"]["serverInfo"]["name"] == "mcc"
        assert reply["result"]["capabilities"]["hoverProvider"] is True
    finally:
        server.terminate()
        server.wait(timeout=30)
