"""`mcc ir`: print the shared IR a file lowers to, as stable text or JSON (docs/IR.md)."""

from __future__ import annotations

import sys

import click

from mcc.cli.commands import DIALECT_NAMES, FORMATS, check_profile_dialect, cli, load_profile
from mcc.cli.main import EXIT_ERRORS, EXIT_OK


@cli.command(name="ir")
@click.argument("files", nargs=-1, required=True, type=click.Path(exists=True, dir_okay=False))
@click.option("--dialect", type=DIALECT_NAMES, help="Dialect of every FILE (default: from the extension).")
@click.option("--format", "fmt", type=click.Choice(FORMATS), default="text", show_default=True,
              help="text: the IR's stable text form; json: one JSON object with each file's module.")
@click.option("--profile", help="Target profile: a built-in name or a path to a TOML file.")
@click.option("--verify-ir/--no-verify-ir", default=True, show_default=True,
              help="Run the IR verifier and report each violation (G010).")
def ir_cmd(files: tuple[str, ...], dialect: str | None, fmt: str, profile: str | None, verify_ir: bool) -> None:
    """Print the shared IR that FILES lower to.

    The text form lists each routine's blocks with their operations, one per line, each followed
    by the source line it came from; the JSON form is documented in docs/IR.md. Diagnostics go to
    stderr in text mode. Nothing is printed for a file whose syntax errors stop lowering.

    \b
    Examples:
      mcc ir samples/arcus/pick_and_place.prg
      mcc ir --format json samples/x150/01_feed_punch_cell.x150
    """
    from mcc.cli import render
    from mcc.compiler import driver, ir_print

    prof = load_profile(profile)
    from mcc.cli.commands import file_settings

    results = [driver.check_file(path, dialect, prof, settings=file_settings(path)) for path in files]
    check_profile_dialect(prof, {r.dialect for r in results})
    if verify_ir:
        for result in results:
            driver.verify_ir(result)

    def module_of(result):
        return result.analysis.module if result.analysis is not None else None

    if fmt == "json":
        files_out = []
        for result in results:
            entry = result.to_json()
            module = module_of(result)
            entry["module"] = ir_print.to_json(module) if module is not None else None
            files_out.append(entry)
        click.echo(render.dump_json({"files": files_out}))
    else:
        writer = render.TextWriter(sys.stderr, False)
        for result in results:
            module = module_of(result)
            if module is not None:
                if len(results) > 1:
                    sys.stdout.write(f"; {result.path}\n")
                sys.stdout.write(ir_print.to_text(module))
            diags = sorted(result.diagnostics, key=lambda d: d.sort_key())
            render.write_text(writer, diags, {result.path: result.source} if result.source else {})
    sys.exit(EXIT_ERRORS if any(r.has_errors for r in results) else EXIT_OK)
