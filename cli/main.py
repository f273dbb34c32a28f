"""The `mcc` command line.

Start-up matters (mcc runs in pre-commit hooks and editors): this module imports only click at
load time; the compiler, Lark and rich are imported inside the commands that need them, and
`mcc --version` is answered before click is even imported.
"""

from __future__ import annotations

import os
import sys

EXIT_OK, EXIT_ERRORS, EXIT_USAGE = 0, 1, 2


def main(argv: list[str] | None = None) -> None:
    args = sys.argv[1:] if argv is None else argv
    if args == ["--version"]:
        from mcc import __version__

        print(f"mcc {__version__}")
        raise SystemExit(0)
    from mcc.cli.commands import cli

    try:
        cli.main(args=args, prog_name="mcc", standalone_mode=True)
    except KeyboardInterrupt:
        raise SystemExit(130) from None
    except BrokenPipeError:
        # The reader went away (mcc check ... | head): not an error worth a traceback.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        raise SystemExit(EXIT_OK) from None
