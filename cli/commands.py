"""The click commands: check, compile, explain (lint and fmt live in their own modules)."""

from __future__ import annotations

import os
import sys

import click

from mcc import __version__
from mcc.cli.main import EXIT_ERRORS, EXIT_OK

DIALECT_NAMES = ["mcode", "x150", "arcus"]  # kept in step with mcc.compiler.dialects (tested)
FORMATS = ["text", "json"]

CONTEXT = {"help_option_names": ["-h", "--help"], "max_content_width": 100}


@click.group(context_settings=CONTEXT)
@click.version_option(__version__, "--version", prog_name="mcc", message="%(prog)s %(version)s")
def cli() -> None:
    """mcc: check, lint, format and compile motion-controller programs.

    \b
    Dialects (chosen from the file extension unless --dialect is given):
      mcode  Lexium MCode (Schneider/Novanta Lexium MDrive, Motion Module)  .mxt .ixt .mcode
      x150   Parker/Digiplan X150 and X150E indexers                        .x150
      arcus  Arcus Performax PMX-4EX-SA standalone language                 .prg

    \b
    Exit codes: 0 no errors, 1 errors found, 2 usage error.
    Run `mcc COMMAND --help` for a command's options and `mcc explain CODE` for a diagnostic.
    """


def load_profile(name: str | None):
    """The --profile option: a built-in profile name or a path to a TOML file."""
    if not name:
        return None
    from mcc.compiler import profiles

    try:
        return profiles.load(name)
    except profiles.ProfileError as exc:
        raise click.BadParameter(str(exc), param_hint="--profile") from None


def use_color(fmt: str) -> bool:
    return fmt == "text" and sys.stdout.isatty() and "NO_COLOR" not in os.environ


def check_profile_dialect(profile, dialects_used: set[str]) -> None:
    if profile is not None and profile.dialect not in dialects_used:
        raise click.BadParameter(
            f"profile '{profile.name}' is for {profile.dialect}, not for "
            f"{', '.join(sorted(dialects_used)) or 'these files'}", param_hint="--profile")


@cli.command()
@click.argument("files", nargs=-1, required=True, type=click.Path(exists=True, dir_okay=False))
@click.option("--dialect", type=click.Choice(DIALECT_NAMES), help="Dialect of every FILE (default: from the extension).")
@click.option("--format", "fmt", type=click.Choice(FORMATS), default="text", show_default=True,
              help="text: one diagnostic per finding with the source line; json: one JSON object on stdout.")
@click.option("--profile", help="Target profile: a built-in name (see `mcc profiles`) or a path to a TOML file.")
def check(files: tuple[str, ...], dialect: str | None, fmt: str, profile: str | None) -> None:
    """Check FILES for syntax and semantic errors, without writing anything.

    \b
    Examples:
      mcc check samples/mcode/pick_and_place.mxt
      mcc check --format json *.prg
      mcc check --profile lmm program.mxt
    """
    from mcc.compiler import driver

    prof = load_profile(profile)
    results = [driver.check_file(path, dialect, prof) for path in files]
    check_profile_dialect(prof, {r.dialect for r in results})
    report(results, fmt)
    sys.exit(EXIT_ERRORS if any(r.has_errors for r in results) else EXIT_OK)


def report(results, fmt: str, extra=None) -> None:
    """Print the diagnostics of `results` in the chosen format."""
    from mcc.cli import render

    if fmt == "json":
        files = []
        for result in results:
            entry = result.to_json()
            if extra is not None:
                entry.update(extra(result))
            files.append(entry)
        click.echo(render.dump_json({"files": files}))
        return
    writer = render.TextWriter(sys.stdout, use_color(fmt))
    every = []
    for result in results:
        diags = sorted(result.diagnostics, key=lambda d: d.sort_key())
        every += diags
        render.write_text(writer, diags, {result.path: result.source} if result.source else {})
    writer.line(render.summary_line(every, len(results)), "bold")


@cli.command(name="compile")
@click.argument("file", type=click.Path(exists=True, dir_okay=False))
@click.option("--target", type=click.Choice(DIALECT_NAMES), help="Dialect to generate (default: the source dialect).")
@click.option("--dialect", type=click.Choice(DIALECT_NAMES), help="Dialect of FILE (default: from the extension).")
@click.option("-o", "--output", "output", type=click.Path(dir_okay=False),
              help="Write the device-ready program here (default: print it on stdout; with --format json it is "
                   "returned in the \"text\" field).")
@click.option("--listing", type=click.Path(dir_okay=False),
              help="Also write a listing: every output line numbered, with the source lines it came from.")
@click.option("--format", "fmt", type=click.Choice(FORMATS), default="text", show_default=True,
              help="How to report diagnostics and statistics.")
@click.option("--profile", help="Target profile: a built-in name or a path to a TOML file.")
def compile_cmd(file: str, target: str | None, dialect: str | None, output: str | None, listing: str | None,
                fmt: str, profile: str | None) -> None:
    """Compile FILE into a device-ready program.

    The program is checked first; nothing is written when it has errors. The output passes
    `mcc check` with no errors, and compiling it again gives the same text.

    \b
    Examples:
      mcc compile samples/mcode/pick_and_place.mxt
      mcc compile program.prg -o build/program.prg --listing build/program.lst
      mcc compile program.mxt --format json -o out.mxt
    """
    from mcc.compiler import driver

    prof = load_profile(profile)
    result = driver.compile_file(file, dialect, target, prof)
    check_profile_dialect(prof, {result.dialect, result.target})
    produced = result.listing is not None and not result.has_errors
    if produced:
        from mcc.compiler.lint.files import write_atomic

        if output:
            write_atomic(output, result.listing.text)
            result.output = output
        if listing:
            write_atomic(listing, result.listing.render())

    def extra(res) -> dict:
        data = {"output": res.output, "target": res.target,
                "stats": res.listing.stats if res.listing is not None else {}}
        if produced and not output:
            data["text"] = res.listing.text
        return data

    if fmt == "json":
        report([result], fmt, extra)
    else:
        from mcc.cli import render

        # The program goes to stdout, so diagnostics and the summary go to stderr.
        writer = render.TextWriter(sys.stderr, sys.stderr.isatty() and "NO_COLOR" not in os.environ)
        diags = sorted(result.diagnostics, key=lambda d: d.sort_key())
        render.write_text(writer, diags, {result.path: result.source} if result.source else {})
        if produced and not output:
            sys.stdout.write(result.listing.text)
        if produced:
            stats = ", ".join(f"{k} {v}" for k, v in result.listing.stats.items())
            where = f" -> {output}" if output else ""
            writer.line(f"compiled {file} ({result.dialect} -> {result.target}){where}: {stats}", "bold")
        else:
            writer.line(render.summary_line(diags, 1), "bold")
    sys.exit(EXIT_ERRORS if result.has_errors else EXIT_OK)


@cli.command()
@click.argument("code", required=False)
@click.option("--list", "list_all", is_flag=True, help="List every diagnostic code with its summary.")
def explain(code: str | None, list_all: bool) -> None:
    """Explain a diagnostic CODE (e.g. `mcc explain M101`): what it means, why it matters, a bad
    and a good example."""
    from mcc.compiler.codes import registry

    reg = registry()
    if list_all or not code:
        for info in reg:
            click.echo(f"{info.code:6} {info.severity.value:8} {info.name:32} {info.summary}")
        return
    info = reg.get(code)
    if info is None:
        raise click.BadParameter(f"unknown code '{code}' (see `mcc explain --list`)", param_hint="CODE")
    click.echo(info.page(), nl=False)


@cli.command()
def profiles() -> None:
    """List the built-in target profiles (for --profile)."""
    from mcc.compiler import profiles as profiles_mod

    for name in profiles_mod.builtin_names():
        prof = profiles_mod.load(name)
        click.echo(f"{name:14} {prof.dialect:6} {prof.title}")

# `mcc lint` and `mcc fmt` register themselves on `cli` (cli/lint.py).
from mcc.cli import lint as _lint  # noqa: E402,F401  (imported last: it uses `cli`)
# `mcc download`, `upload`, `send`, `terminal` and `device` register themselves too (cli/link.py).
from mcc.cli import link as _link  # noqa: E402,F401
