"""The `mcc` command line.

Start-up matters (mcc runs in pre-commit hooks and editors): this module imports only click at
load time; the compiler, Lark and rich are imported inside the commands that need them, and
`mcc --version` is answered before click is even imported.
"""

from __future__ import annotations

import atexit
import gc
import os
import sys

EXIT_OK, EXIT_ERRORS, EXIT_USAGE = 0, 1, 2


def main(argv: list[str] | None = None) -> None:
    # When the interpreter exits it clears the modules and runs several full collections, each of
    # which walks every object still alive: after a check of a small file (the parser, catalogs,
    # IR, the compiler's classes), about a fifth of the whole process (issue 26). Moved to the
    # collector's permanent generation at exit, they are not walked; what the modules held is still
    # freed by reference counting as they are cleared. mcc makes no reference cycles
    # (tests/test_no_cycles.py) and writes its files in `with` blocks, so nothing waits for those
    # collections to be closed or flushed (decision 0024).
    atexit.register(gc.freeze)
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
