"""The `mcc` group imports the modules of its other commands only when they are needed
(cli/commands.py `LazyGroup`, issue 26): `mcc check` of a small file is a whole process, and the
options of `mcc lint`, `mcc sim` and the device link cost it time without being used."""

from __future__ import annotations

import importlib
import json
import subprocess
import sys
from pathlib import Path

from click.testing import CliRunner

from mcc.cli.commands import LAZY_COMMANDS, cli

OTHER_MODULES = sorted(set(LAZY_COMMANDS.values()))


def test_the_table_names_every_command_where_it_is_defined() -> None:
    """Each module registers exactly the commands the table gives it."""
    for module in OTHER_MODULES:
        importlib.import_module(module)
    for name, command in cli.commands.items():
        defined_in = command.callback.__module__
        if defined_in == "mcc.cli.commands":
            assert name not in LAZY_COMMANDS
        else:
            assert LAZY_COMMANDS.get(name) == defined_in, name
    assert set(LAZY_COMMANDS) <= set(cli.commands)


def test_help_lists_every_command() -> None:
    result = CliRunner().invoke(cli, ["--help"])
    assert result.exit_code == 0
    listed = [line.split()[0] for line in result.output.split("Commands:\n", 1)[1].splitlines() if line.strip()]
    assert listed == sorted(set(cli.commands) | set(LAZY_COMMANDS))


def test_an_unknown_command_is_compared_with_every_command() -> None:
    """click's suggestion comes from every command, the lazily imported ones too."""
    result = CliRunner().invoke(cli, ["termnal"])
    assert result.exit_code == 2
    assert "No such command 'termnal'. Did you mean 'terminal'?" in result.output


def test_check_imports_no_other_command(tmp_path: Path) -> None:
    """A check (text, JSON and SARIF output) loads none of the other commands' modules."""
    program = tmp_path / "small.prg"
    program.write_text("HSPD=20000\nX1000\nEND\n", encoding="utf-8")
    probe = ("import json, sys\nfrom mcc.cli.main import main\n"
             f"for fmt in ('text', 'json', 'sarif'):\n"
             f"    try:\n        main(['check', '--format', fmt, {str(program)!r}])\n"
             "    except SystemExit:\n        pass\n"
             "print(json.dumps(sorted(sys.modules)), file=sys.stderr)")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=120)
    loaded = set(json.loads(done.stderr.strip().splitlines()[-1]))
    assert "mcc.compiler.driver" in loaded
    assert not loaded & set(OTHER_MODULES), sorted(loaded & set(OTHER_MODULES))
