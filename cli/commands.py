"""The click commands: check, compile, explain (lint and fmt live in their own modules)."""

from __future__ import annotations

import importlib
import os
import sys

import click

from mcc import __version__
from mcc.cli.main import EXIT_ERRORS, EXIT_OK, EXIT_USAGE



class DialectChoice(click.Choice):
    """The registered dialects (compiler/dialects.py) as a click choice, read when click first asks
    for them (parsing or help of a command that takes one), so that `mcc --help` and `mcc --version`
    do not import the compiler."""

    def __init__(self) -> None:
        super().__init__((), case_sensitive=True)

    @property
    def choices(self) -> tuple[str, ...]:
        from mcc.compiler import dialects

        return tuple(dialects.names())

    @choices.setter
    def choices(self, _value) -> None:
        """click.Choice sets its choices on construction: this one has none of its own."""


DIALECT_NAMES = DialectChoice()
FORMATS = ["text", "json"]
CHECK_FORMATS = ["text", "json", "sarif", "github", "gitlab", "junit"]  # as `mcc lint --format`

CONTEXT = {"help_option_names": ["-h", "--help"], "max_content_width": 100}

# The commands defined in other modules of cli/, by name: each module registers its commands on
# `cli` when it is imported, which `LazyGroup` does only when one of them is run or listed.
LAZY_COMMANDS = {"lint": "mcc.cli.lint", "fmt": "mcc.cli.lint", "ir": "mcc.cli.ir", "lsp": "mcc.cli.lsp",
                 "sim": "mcc.cli.sim", "download": "mcc.cli.link", "upload": "mcc.cli.link",
                 "send": "mcc.cli.link", "terminal": "mcc.cli.link", "device": "mcc.cli.link",
                 "debug": "mcc.cli.debug"}


class LazyGroup(click.Group):
    """The `mcc` group, whose commands in other modules (LAZY_COMMANDS) are imported when they are
    needed: `mcc check` does not build the options of `mcc lint`, `mcc sim` or the device link, nor
    import what their modules import (issue 26: a small check is a whole process). `mcc --help`
    lists every command, so it imports them all; so does an unknown command, so that click's
    "did you mean" suggestions are made from every command, as before."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(set(self.commands) | set(LAZY_COMMANDS))

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in self.commands:
            if cmd_name in LAZY_COMMANDS:
                importlib.import_module(LAZY_COMMANDS[cmd_name])
            else:
                for module in sorted(set(LAZY_COMMANDS.values())):
                    importlib.import_module(module)
        return self.commands.get(cmd_name)


@click.group(cls=LazyGroup, context_settings=CONTEXT)
@click.version_option(__version__, "--version", prog_name="mcc", message="%(prog)s %(version)s")
def cli() -> None:
    """mcc: check, lint, format and compile motion-controller programs.

    \b
    Dialects (chosen from the file extension, or `extensions` in [tool.mcc], unless --dialect is given):
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


def file_settings(path: str):
    """The configuration of `path` (the nearest mcc.toml / pyproject.toml [tool.mcc]) for choosing
    its profile (compiler/selection.py: --profile, then a `mcc: profile=` line, then
    per-file-profiles, then target). Mistakes in the file are reported by `mcc lint`."""
    from mcc.compiler import config

    return config.Resolver().for_path(path)


def regular_files(ctx, param, value):
    """Click callback: a path named on the command line must not be a FIFO, device or socket
    (reading one would wait forever or never end); directories are left to the command."""
    from mcc.compiler import files

    paths = value if isinstance(value, tuple) else (value,)
    for path in paths:
        if path is not None and files.is_special(path):
            raise click.BadParameter(f"{path}: {files.unreadable(path)}", ctx=ctx, param=param)
    return value


STDIN = "-"


def stdin_option(func):
    """--stdin-filename, for commands that read a program from standard input as `-`."""
    return click.option("--stdin-filename", metavar="PATH",
                        help="With `-`: the name of the program read from standard input. It chooses the "
                             "dialect (by its extension) and the configuration (the nearest to it), and names "
                             "the program in messages; editors pass the buffer's file name.")(func)


def read_stdin(paths, stdin_filename: str | None, dialect: str | None) -> tuple[str, str] | None:
    """(name, text) when `paths` asks for standard input (`-`), else None."""
    if STDIN not in paths:
        if stdin_filename:
            raise click.UsageError("--stdin-filename names the program read from standard input: pass `-` as the "
                                   "file to read it")
        return None
    if len(paths) > 1:
        raise click.UsageError("`-` reads one program from standard input: name no other file with it")
    from mcc.compiler import dialects

    name = stdin_filename or STDIN
    if dialect is None and dialects.from_path(name) is None and not mapped_extension(name):
        raise click.UsageError("cannot tell the dialect of standard input: pass --dialect, or --stdin-filename "
                               f"with the program's name ({', '.join(dialects.all_extensions())})")
    from mcc.compiler import files

    # the bytes decoded as a file's are (compiler/files.py: UTF-8, else Latin-1), never a traceback
    return name, files.decode(click.get_binary_stream("stdin").read()).text


def mapped_extension(name: str) -> bool:
    """Whether the configuration nearest to `name` maps its extension to a dialect (`extensions`)."""
    if name == STDIN:
        return False
    from mcc.compiler import config

    return config.Resolver().for_path(name).dialect_for(name) is not None


def use_color(fmt: str) -> bool:
    return fmt == "text" and sys.stdout.isatty() and "NO_COLOR" not in os.environ


def check_profile_dialect(profile, dialects_used: set[str]) -> None:
    if profile is not None and profile.dialect not in dialects_used:
        raise click.BadParameter(
            f"profile '{profile.name}' is for {profile.dialect}, not for "
            f"{', '.join(sorted(dialects_used)) or 'these files'}", param_hint="--profile")


@cli.command()
@click.argument("files", nargs=-1, required=True, type=click.Path(exists=True, allow_dash=True),
                callback=regular_files)
@click.option("--dialect", type=DIALECT_NAMES, help="Dialect of every FILE (default: from the extension).")
@click.option("--format", "fmt", type=click.Choice(CHECK_FORMATS), default="text", show_default=True,
              help="text: one diagnostic per finding with the source line; json: one JSON object on stdout; "
                   "sarif, github, gitlab, junit: as `mcc lint --format`.")
@click.option("--rules-url", metavar="URL", help="SARIF: each rule's helpUri, with {code} replaced by the code.")
@click.option("--profile", help="Target profile: a built-in name (see `mcc profiles`) or a path to a TOML file. Wins "
                                "over a `mcc: profile=` line in the file and the configuration's per-file-profiles "
                                "and target (docs/CONFIGURATION.md).")
@click.option("--verify-ir", is_flag=True, help="Also run the IR verifier after lowering (violations are G010).")
@click.option("--force-exclude", is_flag=True,
              help="Apply `exclude` and .gitignore to the files named on the command line too (as `mcc lint`).")
@click.option("--respect-gitignore/--no-respect-gitignore", default=True, show_default=True,
              help="In directories, skip the files .gitignore ignores (inside a git work tree).")
@stdin_option
def check(files: tuple[str, ...], dialect: str | None, fmt: str, rules_url: str | None, profile: str | None,
          verify_ir: bool, force_exclude: bool, respect_gitignore: bool, stdin_filename: str | None) -> None:
    """Check FILES (files or directories) for syntax and semantic errors, without writing anything.
    Directories are searched as `mcc lint` searches them (the dialects' extensions and the
    configuration's `extensions`; `exclude` and .gitignore skipped). `-` reads the program from
    standard input (name it with --stdin-filename).

    \b
    Examples:
      mcc check samples/mcode/pick_and_place.mxt
      mcc check programs/
      mcc check --format json *.prg
      mcc check --profile lmm program.mxt
      mcc check - --stdin-filename feeder.mxt < feeder.mxt
    """
    from mcc.compiler import driver

    prof = load_profile(profile)
    piped = read_stdin(files, stdin_filename, dialect)
    if piped is not None:
        results = [driver.check_file(piped[0], dialect, prof, piped[1], settings=file_settings(piped[0]))]
    else:
        results = [driver.check_file(path, dialect, prof, settings=file_settings(path))
                   for path in discover(files, force_exclude, respect_gitignore)]
    if verify_ir:
        for result in results:
            driver.verify_ir(result)
    check_profile_dialect(prof, {r.dialect for r in results})
    from mcc.cli.render import machine_report

    if not machine_report(results, fmt, rules_url):
        report(results, fmt)
    sys.exit(EXIT_ERRORS if any(r.has_errors for r in results) else EXIT_OK)


def discover(paths: tuple[str, ...], force_exclude: bool, respect_gitignore: bool) -> list[str]:
    """The files `mcc check` works on: those named, and those found in the directories named, by the
    discovery `mcc lint` uses (cli/lint.py `expand`, compiler/lint/ignore.py)."""
    if not force_exclude and not any(os.path.isdir(p) for p in paths):
        return list(paths)
    from mcc.cli.lint import expand
    from mcc.compiler import config

    return expand(list(paths), config.Resolver(), force_exclude, respect_gitignore, verb="check")


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
@click.argument("file", type=click.Path(exists=True, dir_okay=False), callback=regular_files)
@click.option("--target", type=DIALECT_NAMES, help="Dialect to generate (default: the source dialect).")
@click.option("--dialect", type=DIALECT_NAMES, help="Dialect of FILE (default: from the extension).")
@click.option("-o", "--output", "output", type=click.Path(dir_okay=False),
              help="Write the device-ready program here (default, or `-`: print it on stdout; with --format json "
                   "it is returned in the \"text\" field).")
@click.option("--listing", type=click.Path(dir_okay=False),
              help="Also write a listing: every output line numbered, with the source lines it came from.")
@click.option("--format", "fmt", type=click.Choice(FORMATS), default="text", show_default=True,
              help="How to report diagnostics and statistics.")
@click.option("--profile", help="Target profile: a built-in name or a path to a TOML file.")
@click.option("--source-profile", metavar="PROFILE",
              help="The profile FILE was written for, when it is not the target's (default: --profile): FILE is "
                   "checked with it, and an MCode program moved to another MCode family (e.g. --source-profile "
                   "mdrive-plus --profile lmd-o) is converted and validated on the way.")
@click.option("-O0", "opt_level", flag_value="O0", help="No optimization: the program as written.")
@click.option("-O1", "opt_level", flag_value="O1", default=True,
              help="Local, safe optimizations (the default): folding, copies, dead stores, repeated settings, "
                   "branches, unreachable blocks, block merging.")
@click.option("-O2", "opt_level", flag_value="O2", help="-O1 across blocks and routines, plus tail merging.")
@click.option("-Os", "opt_level", flag_value="Os",
              help="-O2 plus procedural abstraction: repeated runs of operations become subroutines.")
@click.option("--passes", help="Run exactly these passes, comma-separated (see docs/OPTIMIZER.md).")
@click.option("--overwrite-input", is_flag=True,
              help="Allow -o or --listing to replace a file this run reads (FILE itself or the --profile file); "
                   "refused by default, so that a slip never replaces the source with the compiled text.")
@click.option("--verify/--no-verify", "verify", default=None,
              help="Simulate the source and the compiled program and write nothing if they behave differently. "
                   "On by default whenever the output is not the program as written (another target, or an "
                   "optimization that changed something); --verify also checks a plain re-spelling, --no-verify "
                   "turns validation off (and says so).")
@click.option("--inputs", "inputs", multiple=True, type=click.Path(exists=True, dir_okay=False),
              metavar="SCENARIO.toml", help="Scenarios for the validation (repeatable; default: generated from the "
                                            "program, every input it reads low, high and toggling).")
def compile_cmd(file: str, target: str | None, dialect: str | None, output: str | None, listing: str | None,
                fmt: str, profile: str | None, source_profile: str | None, opt_level: str, passes: str | None,
                overwrite_input: bool, verify: bool | None, inputs: tuple[str, ...]) -> None:
    """Compile FILE into a device-ready program.

    The program is checked first; nothing is written when it has errors. The output passes
    `mcc check` with no errors, and compiling it again gives the same text. Unless --no-verify,
    a program that is not the source as written (another target, an optimization that changed
    something) is simulated against its source, and nothing is written when they behave
    differently (S010 on the source line, exit 1).

    \b
    Examples:
      mcc compile samples/mcode/pick_and_place.mxt
      mcc compile program.prg -o build/program.prg --listing build/program.lst
      mcc compile program.mxt --format json -o out.mxt
      mcc compile program.prg --target mcode --verify -o program.mxt
      mcc compile mdrive.mxt --source-profile mdrive-plus --profile lmd-o -o lexium.mxt
    """
    from mcc.compiler import driver

    if output == "-":  # the usual spelling of "stdout", which is the default anyway
        output = None
    check_outputs(file, profile, output, listing, overwrite_input)
    prof = load_profile(profile)
    try:
        src_prof = load_profile(source_profile)
    except click.BadParameter as exc:
        raise click.BadParameter(exc.message, param_hint="--source-profile") from None
    if passes:
        from mcc.compiler.opt import pass_names

        try:
            pass_names(opt_level, passes)
        except ValueError as exc:
            raise click.BadParameter(str(exc), param_hint="--passes") from None
    from mcc.cli.sim import load_scenarios

    scenarios = load_scenarios(inputs)
    if verify is False:
        click.echo("mcc: note: --no-verify: the compiled program is not validated against its source in the "
                   "simulator", err=True)
    result = driver.compile_file(file, dialect, target, prof, opt_level=opt_level, passes=passes,
                                 verify=verify is not False, scenarios=scenarios, always_verify=verify is True,
                                 source_profile=src_prof, settings=file_settings(file))
    check_profile_dialect(prof, {result.dialect, result.target})
    if src_prof is not None and src_prof.dialect != result.dialect:
        raise click.BadParameter(f"profile '{src_prof.name}' is for {src_prof.dialect}, not for {result.dialect}",
                                 param_hint="--source-profile")
    produced = result.listing is not None and not result.has_errors
    write_failed = False
    if produced and (output or listing):
        write_failed = not write_outputs(result, output, listing)
        produced = not write_failed

    def extra(res) -> dict:
        data = {"output": res.output, "target": res.target,
                "stats": dict(res.listing.stats) if res.listing is not None else {}}
        if res.optimization is not None and res.listing is not None:
            data["stats"]["optimization"] = res.optimization.to_json()
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
            writer.line(f"compiled {file} ({result.dialect} -> {result.target}){where}: {stats}{cycle_text(result)}",
                        "bold")
            if result.optimization is not None and result.optimization.passes:
                writer.line(f"optimized {result.optimization.summary()}")
        else:
            writer.line(render.summary_line(diags, 1), "bold")
    sys.exit(EXIT_USAGE if write_failed else EXIT_ERRORS if result.has_errors else EXIT_OK)


def cycle_text(result) -> str:
    """", cycle 1.600 s, 1 moves": the main loop's pass in a bounded simulation of the source
    (sim/cycles.py), or nothing when the program has no main loop or cannot be simulated."""
    module = result.analysis.module if result.analysis is not None else None
    if module is None:
        return ""
    from mcc.sim.cycles import bounded_timing, cycle_title

    found = bounded_timing(module, result.profile)
    title = cycle_title(found) if found is not None else ""
    return f", {title}" if title else ""  # as the editor's lens says it (a loop polling a low input waits)


def check_outputs(file: str, profile: str | None, output: str | None, listing: str | None,
                  overwrite_input: bool) -> None:
    """Refuse, before any work, outputs that would replace what this run reads, or each other."""
    from mcc.compiler import files

    if output and listing and files.same_file(output, listing):
        raise click.BadParameter(f"{listing} is also the -o output: give the listing its own file",
                                 param_hint="--listing")
    if overwrite_input:
        return
    inputs = [file] + ([profile] if profile and os.path.isfile(profile) else [])
    for option, path in (("-o", output), ("--listing", listing)):
        for read in inputs:
            if path and files.same_file(path, read):
                what = "the source file" if read == file else "the profile"
                raise click.BadParameter(
                    f"{path} is {what} this run reads; writing the compiled program there would replace it. "
                    "Choose another path, or pass --overwrite-input if that is what you want",
                    param_hint=option)


def write_outputs(result, output: str | None, listing: str | None) -> bool:
    """Write the program and the listing together (nothing is replaced unless both can be written);
    a failure becomes diagnostic G006 on the output's path. True when written."""
    from mcc.compiler import files
    from mcc.compiler.diagnostics import Diagnostics
    from mcc.compiler.driver import file_span

    items = []
    if output:
        items.append((output, files.encode(result.listing.text, files.PLAIN)))
    if listing:
        items.append((listing, files.encode(result.listing.render(), files.PLAIN)))
    try:
        files.write_many(items)
    except OSError as exc:
        path = getattr(exc, "path", None) or exc.filename or output or listing
        diags = Diagnostics(result.diagnostics)
        diags.add("G006", file_span(path), f"cannot write {path}: {exc.strerror or exc}; nothing was written")
        result.diagnostics = diags.items
        return False
    result.output = output
    return True


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
