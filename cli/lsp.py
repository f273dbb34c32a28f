"""`mcc lsp`: start the language server (pygls is imported only when the command runs)."""

from __future__ import annotations

import re

import click

from mcc.cli.commands import cli
from mcc.cli.main import EXIT_USAGE

ADDRESS = re.compile(r"(?:(?P<host>[^:]*):)?(?P<port>\d{1,5})\Z")


@cli.command()
@click.option("--tcp", metavar="HOST:PORT", help="Listen on a TCP socket instead of stdio (for debugging).")
@click.option("--log-file", type=click.Path(dir_okay=False), help="Write the server's log here (default: stderr).")
@click.option("-v", "--verbose", is_flag=True, help="Log every request (debug level).")
@click.option("--stdio", is_flag=True, help="Talk over stdin/stdout (the default; accepted because many editor "
                                             "clients pass it).")
def lsp(tcp: str | None, log_file: str | None, verbose: bool, stdio: bool) -> None:
    """Run the language server for editors (stdio by default).

    \b
    Diagnostics (check + lint with the project's configuration), hover, completion, signature
    help, go to definition, references, rename, outline, folding, semantic tokens, code actions
    (fixes, noqa, explanations), formatting and program memory, for the three dialects.
    Needs the optional extra: pip install "mcc[lsp]". Editor set-up: docs/EDITORS.md.
    """
    if tcp is not None and stdio:
        raise click.BadParameter("--stdio and --tcp choose different channels: give one", param_hint="--stdio")
    if tcp is not None:
        match = ADDRESS.match(tcp)
        if match is None or not 0 < int(match.group("port")) < 65536:
            raise click.BadParameter(f"'{tcp}' is not HOST:PORT (e.g. 127.0.0.1:2087)", param_hint="--tcp")
    try:
        import pygls  # noqa: F401
    except ImportError:
        click.echo('mcc lsp needs pygls: install the extra with  pip install "mcc[lsp]"', err=True)
        raise SystemExit(EXIT_USAGE) from None
    from mcc.lsp.server import start

    start(tcp, log_file, verbose)
