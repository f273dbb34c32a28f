"""Virtual devices served on the loopback address for the link tests (a real TCP socket)."""

from __future__ import annotations

import contextlib

import pytest


@contextlib.contextmanager
def serving(device):
    from mcc.link.device.server import DeviceServer

    # time_scale 0: only the commands' own time passes (their characters and execution time), not
    # the wall time between them, so a test reads the same state however loaded the machine is; a
    # test that waits says so with device.elapse(seconds), the host's sleep
    with DeviceServer(device, time_scale=0.0) as server:
        yield server


@pytest.fixture
def serve():
    """serve(device) -> the server (its .url is the socket:// port); stopped after the test."""
    stack = contextlib.ExitStack()

    def start(device):
        return stack.enter_context(serving(device))

    with stack:
        yield start


class Result:
    def __init__(self, returncode: int, stdout: str, stderr: str) -> None:
        self.returncode, self.stdout, self.stderr = returncode, stdout, stderr


# The virtual device answers from a thread of the test process: on a loaded machine (the suite runs
# on both cores) a reply can take longer than a real device's 1-2 s timeout, which would fail a test
# about something else. Commands that talk to a device wait this long unless the test says otherwise.
PATIENT_TIMEOUT = "10"
TALKING = {"download", "upload", "send"}


def with_patience(args: tuple[str, ...]) -> tuple[str, ...]:
    if args and args[0] in TALKING and "--timeout" not in args and "--help" not in args:
        return (*args, "--timeout", PATIENT_TIMEOUT)
    return args


def mcc(*args: str) -> Result:
    """Run an `mcc` command in this process (click's runner: the same command, parsing and exit
    codes as the installed script, without starting an interpreter per call; the virtual device
    runs in a thread of this process and the link still goes through a real socket)."""
    from click.testing import CliRunner

    from mcc.cli.commands import cli

    args = with_patience(args)
    result = CliRunner().invoke(cli, list(args), env={"NO_COLOR": "1"}, catch_exceptions=False)
    return Result(result.exit_code, result.stdout, result.stderr)
