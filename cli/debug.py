"""`mcc debug`: the Debug Adapter Protocol server on the simulator (mcc/debug/)."""

from __future__ import annotations

import click

from mcc.cli.commands import cli


@cli.command(name="debug")
@click.option("--port", type=click.IntRange(0, 65535), metavar="PORT",
              help="Listen on this TCP port (on --host) for one client instead of speaking on stdin/stdout; "
                   "0 picks a free port and prints it.")
@click.option("--host", default="127.0.0.1", show_default=True, help="The address --port listens on.")
def debug_cmd(port: int | None, host: str) -> None:
    """Debug a program on the simulator from an editor (Debug Adapter Protocol).

    An editor starts `mcc debug` and speaks the Debug Adapter Protocol with it on stdin/stdout
    (or on a TCP port with --port). The program runs on the same simulator as `mcc sim`, in
    virtual time: nothing moves, nothing waits in real time.

    \b
    What a session can do:
      launch          program, scenario (TOML, as `mcc sim --inputs`), profile, stopOnEntry,
                      until (virtual seconds), maxSteps
      breakpoints     by line, with a condition (Q1 > 3 AND input(1) = 1) and a hit count
                      (N, >= N, % N); a line that generates nothing is reported unverified
      stepping        continue, pause, step over / into / out of subroutines and sequences,
                      by source line; stops on runtime errors and limit switches
      variables       program variables, each axis (position, speed, settings), inputs and
                      outputs, virtual time; change a variable or an input while paused

    \b
    Examples (the editor runs these; see docs/EDITORS.md, "Debugging"):
      mcc debug                 VS Code (the mcc extension), nvim-dap `executable` adapter
      mcc debug --port 4711     nvim-dap `server` adapter, or any client over TCP
    """
    from mcc.debug import server

    if port is None:
        server.serve_stdio()
        return

    def ready(bound: int) -> None:
        click.echo(f"mcc debug: listening on {host}:{bound}", err=True)

    try:
        server.serve_tcp(host, port, ready)
    except OSError as exc:
        raise click.UsageError(f"cannot listen on {host}:{port}: {exc.strerror or exc}") from None
