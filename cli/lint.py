"""`mcc lint` and `mcc fmt`: the linter and the formatter, with the habits ruff users know.

Both take files and directories (directories are searched for the dialects' extensions), read the
nearest `[tool.mcc]` / mcc.toml, and work on many files in parallel. See docs/LINT.md.
"""

from __future__ import annotations

import os
import sys

import click

from mcc.cli.commands import DIALECT_NAMES, cli, read_stdin, regular_files, stdin_option, use_color
from mcc.cli.main import EXIT_ERRORS, EXIT_OK, EXIT_USAGE

LINT_FORMATS = ["text", "json", "sarif", "github", "gitlab", "junit"]
SEVERITY_NAMES = ["error", "warning", "info"]
PROGRESS_MIN_FILES = 20


def jobs_default() -> int:
    return os.cpu_count() or 1


def make_resolver(config: str | None, isolated: bool, select, extend_select, ignore, profile, fail_on):
    from mcc.compiler import config as config_mod

    try:
        overrides = config_mod.overrides(select, extend_select, ignore, profile, fail_on)
    except config_mod.ConfigError as exc:
        raise click.UsageError(str(exc)) from None
    return config_mod.Resolver(overrides, config, isolated)


def progress_starter(total: int, label: str):
    """A rich progress bar on stderr for long runs on a terminal; nothing otherwise."""
    if total < PROGRESS_MIN_FILES or not sys.stderr.isatty():
        return None

    def start():
        from rich.console import Console
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        bar = Progress(TextColumn(label), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                       console=Console(file=sys.stderr), transient=True)
        bar.start()
        task = bar.add_task(label, total=total)
        state = {"done": 0}

        def advance(n: int) -> None:
            state["done"] += n
            bar.advance(task, n)
            if state["done"] >= total:
                bar.stop()

        return advance

    return start


def config_outcomes(resolver):
    from mcc.compiler.lint.engine import Outcome

    return [Outcome(path, "config", list(diags), source.text if source else None)
            for path, diags, source in resolver.diagnostics()]


LISTED_UNKNOWN = 20  # files of unknown extension named one by one when nothing else was found


def expand(paths, resolver, force_exclude: bool = False, respect_gitignore: bool = True,
           verb: str = "lint") -> list[str]:
    """The files to work on. Special files met in directories are skipped with a note on stderr, and
    so are files whose extension no dialect has (counted per extension; named one by one when they
    are all there is). No file at all is a usage error (exit 2): a run that checked nothing must
    not pass as clean, unless --force-exclude left out every file named (pre-commit)."""
    from mcc.compiler.lint import engine

    skipped: list[str] = []
    unknown: list[str] = []
    targets = engine.expand(paths or ["."], resolver, skipped, force_exclude, respect_gitignore, unknown)
    for note in skipped:
        click.echo(f"note: {note}", err=True)
    if unknown:
        for line in unknown_notes(unknown, listed=not targets):
            click.echo(line, err=True)
    if not targets and not (force_exclude and paths):
        where = " ".join(paths) if paths else "."
        click.echo(f"mcc: error: no program to {verb} in {where}: no file has an extension of a dialect "
                   f"({' '.join(ext for ext in all_extensions())}) or one mapped by `extensions` in the "
                   "configuration", err=True)
        sys.exit(EXIT_USAGE)
    return targets


def all_extensions() -> tuple[str, ...]:
    from mcc.compiler import dialects

    return dialects.all_extensions()


def unknown_notes(unknown: list[str], listed: bool) -> list[str]:
    """Notes on the files left out for their extension: one line with the count per extension and
    how to map one (docs/CONFIGURATION.md, `extensions`); with `listed`, each file first."""
    by_ext: dict[str, int] = {}
    for path in unknown:
        ext = os.path.splitext(path)[1].lower() or "(none)"
        by_ext[ext] = by_ext.get(ext, 0) + 1
    lines = []
    if listed:
        for path in unknown[:LISTED_UNKNOWN]:
            lines.append(f"note: skipped {path}: unknown extension {os.path.splitext(path)[1] or '(none)'}")
        if len(unknown) > LISTED_UNKNOWN:
            lines.append(f"note: ... and {len(unknown) - LISTED_UNKNOWN} more")
    counts = ", ".join(f"{ext} {n}" for ext, n in sorted(by_ext.items(), key=lambda kv: (-kv[1], kv[0])))
    example = next((e.lstrip(".") for e in sorted(by_ext, key=lambda e: -by_ext[e]) if e != "(none)"), "lxt")
    total = len(unknown)
    lines.append(f"note: skipped {total} file{'s' if total != 1 else ''} of unknown extension ({counts}); if they "
                 f"are programs, map the extension to a dialect in [tool.mcc]: extensions = {{{example} = "
                 "\"mcode\"} (docs/CONFIGURATION.md), or name a file with --dialect")
    return lines


def common_options(func):
    options = [
        click.option("--dialect", type=DIALECT_NAMES, help="Dialect of every file (default: from the extension)."),
        click.option("--config", "config", type=click.Path(exists=True, dir_okay=False), callback=regular_files,
                     help="Use this configuration file for every file instead of the nearest pyproject.toml/mcc.toml."),
        click.option("--isolated", is_flag=True, help="Ignore every configuration file."),
        click.option("--profile", help="Target profile (a built-in name or a TOML file); overrides `target`."),
        click.option("-j", "--jobs", type=click.IntRange(min=1), default=None,
                     help="Worker processes (default: the number of CPUs; 1 runs in this process)."),
        stdin_option,
        click.option("--force-exclude", is_flag=True,
                     help="Apply `exclude` and .gitignore to the files named on the command line too (and to "
                          "--stdin-filename), as pre-commit needs: it names every staged file."),
        click.option("--respect-gitignore/--no-respect-gitignore", default=True, show_default=True,
                     help="Skip the files .gitignore ignores (inside a git work tree)."),
    ]
    for option in reversed(options):
        func = option(func)
    return func


@cli.command()
@click.argument("paths", nargs=-1, type=click.Path(exists=True, allow_dash=True), callback=regular_files)
@click.option("--format", "fmt", type=click.Choice(LINT_FORMATS), default="text", show_default=True,
              help="text: findings with the source line; json: as `mcc check`, with each fix's edits; sarif: "
                   "SARIF 2.1.0 for code scanning; github: workflow annotations; gitlab: GitLab Code Quality; "
                   "junit: JUnit XML test results.")
@click.option("--rules-url", metavar="URL", help="SARIF: each rule's helpUri, with {code} replaced by the code "
                                                  "(default: mcc's docs/rules/CODE.md when run from a checkout).")
@click.option("--select", multiple=True, metavar="CODES", help="Check only these codes or prefixes (e.g. M3,G101); replaces `select`.")
@click.option("--extend-select", multiple=True, metavar="CODES", help="Also check these codes or prefixes.")
@click.option("--ignore", multiple=True, metavar="CODES", help="Do not report these codes or prefixes.")
@click.option("--fix", is_flag=True, help="Apply the safe fixes and report what remains.")
@click.option("--unsafe-fixes", is_flag=True, help="Also apply (or show) fixes that may change behaviour.")
@click.option("--diff", is_flag=True, help="Show the fixes as a unified diff; write nothing.")
@click.option("--verify/--no-verify", default=None,
              help="With --fix: simulate each file before and after its fixes and leave it unchanged (S010) if "
                   "they behave differently. On by default (a file with errors of its own, which has no "
                   "behaviour to keep, is then fixed unvalidated; --verify refuses it); --no-verify writes the "
                   "fixes unvalidated (and says so).")
@click.option("--statistics", is_flag=True, help="Print how often each code occurs instead of each finding.")
@click.option("--fail-on", type=click.Choice(SEVERITY_NAMES),
              help="Exit 1 when a finding has at least this severity (default: `fail-on`, else warning: "
                   "errors and warnings fail, notes do not).")
@click.option("--exit-zero", is_flag=True, help="Exit 0 even when there are findings (not on a usage error).")
@common_options
def lint(paths, fmt, rules_url, select, extend_select, ignore, fix, unsafe_fixes, diff, verify, statistics, fail_on, exit_zero,
         dialect, config, isolated, profile, jobs, stdin_filename, force_exclude, respect_gitignore) -> None:
    """Check PATHS (files or directories; default: the current directory) with every check and lint rule.

    \b
    Examples:
      mcc lint .                                  every .mxt .ixt .mcode .prg .x150 below here
      mcc lint --select M3 --ignore M305 src/     only the MCode lint rules, without M305
      mcc lint --fix programs/                    apply the safe fixes
      mcc lint --format sarif . > mcc.sarif       for GitHub code scanning
      mcc lint --format gitlab . > gl-code-quality-report.json
      mcc lint --format junit . > mcc-junit.xml   test results for a CI server
      mcc lint --statistics .                     how often each code occurs
      mcc lint - --stdin-filename a.mxt < a.mxt   a program from standard input (editors)

    With `-` and --fix, the fixed program is written to standard output and the findings that
    remain to standard error. Suppress a finding with a comment on its line: MCode `' noqa: M301`, Arcus and X150
    `; noqa: A301`. Exit codes: 0 no error or warning (notes pass), 1 an error or warning (or a finding at
    --fail-on), 2 usage error.
    """
    from mcc.compiler.lint import engine

    if fix and verify is False:
        click.echo("mcc: note: --no-verify: the fixed files are not validated against the originals in the "
                   "simulator", err=True)
    resolver = make_resolver(config, isolated, select, extend_select, ignore, profile, fail_on)
    options = engine.Options(fix=fix, diff=diff, unsafe_fixes=unsafe_fixes, dialect=dialect, verify=verify is not False,
                             verify_required=verify is True)
    piped = read_stdin(paths, stdin_filename, dialect)
    if piped is not None:
        if force_exclude and stdin_excluded(piped[0], resolver, respect_gitignore):
            if fix:
                sys.stdout.write(piped[1])  # an editor's buffer comes back unchanged
            sys.exit(EXIT_OK)
        lint_stdin(piped, resolver, options, fmt, statistics, fail_on, exit_zero, rules_url)
    targets = expand(paths, resolver, force_exclude, respect_gitignore)
    work = [(path, resolver.for_path(path)) for path in targets]
    outcomes = engine.run(work, options, jobs or jobs_default(), progress_starter(len(work), "linting"))
    outcomes = config_outcomes(resolver) + sorted(outcomes, key=lambda o: o.path)
    if diff:
        report_diff(outcomes)
        sys.exit(EXIT_ERRORS if any(o.diff for o in outcomes) and not exit_zero else EXIT_OK)
    report(outcomes, fmt, statistics, fix, unsafe_fixes, len(work), rules_url)
    if any(getattr(o, "write_error", False) for o in outcomes):
        sys.exit(EXIT_USAGE)  # a fixed file could not be written (G006): as for any file error
    failing = {path: settings.fail_on for path, settings in work}
    sys.exit(EXIT_OK if exit_zero else exit_code(outcomes, failing, fail_on))


def stdin_excluded(name: str, resolver, respect_gitignore: bool) -> bool:
    """--force-exclude with `-`: whether the file --stdin-filename names is excluded (then the
    program is neither linted nor formatted, as for a file named on the command line)."""
    from mcc.compiler.lint import engine, ignore

    return engine.excluded(name, resolver) or (respect_gitignore and ignore.gitignored(name))


def lint_stdin(piped: tuple[str, str], resolver, options, fmt: str, statistics: bool, fail_on, exit_zero: bool,
               rules_url: str | None = None):
    """`mcc lint -`: the program from standard input. With --fix the fixed text goes to standard
    output (what an editor puts back in the buffer) and the report to standard error."""
    from mcc.compiler.lint import engine, fixes

    name, text = piped
    settings = resolver.for_path(name)
    outcome = engine.lint_source(name, text, settings, options)
    outcomes = config_outcomes(resolver) + [outcome]
    if options.diff:
        changed = outcome.text != text
        if changed:
            sys.stdout.write(fixes.unified_diff(name, text, outcome.text))
        sys.exit(EXIT_ERRORS if changed and not exit_zero else EXIT_OK)
    if options.fix:
        outcome.written = outcome.text != text  # written to standard output
        sys.stdout.write(outcome.text)
        sys.stdout.flush()
        sys.stdout = sys.stderr  # the report follows the program, on standard error
    report(outcomes, fmt, statistics, options.fix, options.unsafe_fixes, 1, rules_url)
    sys.exit(EXIT_OK if exit_zero else exit_code(outcomes, {name: settings.fail_on}, fail_on))


def exit_code(outcomes, failing: dict[str, str], override: str | None) -> int:
    from mcc.compiler.config import DEFAULT_FAIL_ON
    from mcc.compiler.diagnostics import Severity

    for outcome in outcomes:
        threshold = Severity(override or failing.get(outcome.path, DEFAULT_FAIL_ON)).rank
        if any(d.severity.rank >= threshold for d in outcome.diagnostics):
            return EXIT_ERRORS
    return EXIT_OK


def report_diff(outcomes) -> None:
    changed = [o for o in outcomes if o.diff]
    for outcome in changed:
        sys.stdout.write(outcome.diff)
    fixes = sum(o.fixed for o in changed)
    if changed:
        click.echo(f"Would fix {fixes} problem{'s' if fixes != 1 else ''} in {len(changed)} "
                   f"file{'s' if len(changed) != 1 else ''}.", err=True)
    else:
        click.echo("No fixes available.", err=True)


def report(outcomes, fmt: str, statistics: bool, fixed_run: bool, unsafe: bool, files: int,
           rules_url: str | None = None) -> None:
    from mcc.cli import render
    from mcc.compiler.lint import output

    if statistics:
        rows = output.statistics(outcomes)
        if fmt == "json":
            click.echo(render.dump_json({"statistics": rows}))
            return
        for row in rows:
            mark = "[*]" if row["fixable"] else "   "
            click.echo(f"{row['count']:>6}  {row['code']:<5} {mark} {row['name']}")
        return
    if fmt == "json":
        click.echo(render.dump_json(output.to_json(outcomes)))
        return
    if render.machine_report(outcomes, fmt, rules_url):
        return
    writer = render.TextWriter(sys.stdout, use_color(fmt))
    every = []
    for outcome in outcomes:
        diags = sorted(outcome.diagnostics, key=lambda d: d.sort_key())
        every += diags
        source = outcome.source
        render.write_text(writer, diags, {outcome.path: source} if source else {})
    fixed = sum(o.fixed for o in outcomes)
    if fixed_run and fixed:
        writer.line(f"Fixed {fixed} problem{'s' if fixed != 1 else ''} in {sum(1 for o in outcomes if o.written)} "
                    f"file{'s' if sum(1 for o in outcomes if o.written) != 1 else ''}.", "bold green")
    writer.line(render.summary_line(every, files), "bold")
    safe = sum(1 for d in every if d.fix is not None and d.fix.safe)
    hidden = sum(1 for d in every if d.fix is not None and not d.fix.safe)
    if safe:
        writer.line(f"[*] {safe} fixable with `mcc lint --fix`.", "")
    if hidden and not unsafe:
        writer.line(f"({hidden} more fix{'es' if hidden != 1 else ''} available with `--fix --unsafe-fixes`.)", "dim")


@cli.command()
@click.argument("paths", nargs=-1, type=click.Path(exists=True, allow_dash=True), callback=regular_files)
@click.option("--check", is_flag=True, help="Write nothing; exit 1 and list the files that would change.")
@click.option("--diff", is_flag=True, help="Write nothing; print the changes as a unified diff (exit 1 if any).")
@click.option("--verify", is_flag=True, help="Also simulate each file before and after formatting and leave it "
                                             "unchanged if they behave differently (formatting is always checked "
                                             "to leave the program's IR unchanged, which needs no simulation).")
@common_options
def fmt(paths, check, diff, verify, dialect, config, isolated, profile, jobs, stdin_filename, force_exclude,
        respect_gitignore) -> None:
    """Rewrite PATHS (files or directories; default: the current directory) in the canonical style
    of their dialect.

    \b
    Examples:
      mcc fmt .                        format every program below here
      mcc fmt --check .                in CI: exit 1 if a file is not formatted
      mcc fmt --diff program.mxt       show what would change
      mcc fmt - --stdin-filename a.prg < a.prg > b.prg     standard input to standard output

    Formatting keeps every comment and never changes what a program does: mcc compares the program
    before and after and leaves a file alone if they differ. A file with a syntax error is not
    formatted (fix the error first). Exit codes: 0 done (or nothing to
    change), 1 files would change (--check, --diff) or could not be formatted, 2 usage error.
    """
    from mcc.compiler.lint import engine, formatting

    resolver = make_resolver(config, isolated, (), (), (), profile, None)
    piped = read_stdin(paths, stdin_filename, dialect)
    if piped is not None:
        if force_exclude and stdin_excluded(piped[0], resolver, respect_gitignore):
            if not (check or diff):
                sys.stdout.write(piped[1])  # an excluded program is passed through unchanged
            sys.exit(EXIT_OK)
        fmt_stdin(piped, resolver, check, diff, verify, dialect)
    targets = expand(paths, resolver, force_exclude, respect_gitignore, verb="format")
    work = [(path, resolver.for_path(path)) for path in targets]
    options = formatting.Options(check=check, diff=diff, dialect=dialect, verify=verify)
    outcomes = engine.run(work, options, jobs or jobs_default(), progress_starter(len(work), "formatting"),
                          func=formatting.format_file)
    outcomes.sort(key=lambda o: o.path)
    for outcome in outcomes:
        if outcome.error:
            click.echo(f"error: {outcome.path}: {outcome.error}", err=True)
        elif diff and outcome.diff:
            sys.stdout.write(outcome.diff)
        elif check and outcome.changed:
            click.echo(f"Would reformat: {outcome.path}")
    skipped: dict[str, int] = {}
    for outcome in outcomes:
        if outcome.skipped:
            skipped[outcome.dialect] = skipped.get(outcome.dialect, 0) + 1
    for name, count in sorted(skipped.items()):
        click.echo(f"note: mcc has no {name} formatter yet; {count} file{'s' if count != 1 else ''} left as "
                   "they are", err=True)
    changed = sum(1 for o in outcomes if o.changed)
    same = sum(1 for o in outcomes if not o.changed and not o.error and not o.skipped)
    verb = "would be reformatted" if check or diff else "reformatted"
    summary = f"{changed} file{'s' if changed != 1 else ''} {verb}, {same} file{'s' if same != 1 else ''} " \
              "left unchanged"
    click.echo(summary, err=diff)
    failed = any(o.error for o in outcomes)
    if any(o.write_error for o in outcomes):
        sys.exit(EXIT_USAGE)
    sys.exit(EXIT_ERRORS if failed or (check or diff) and changed else EXIT_OK)


def fmt_stdin(piped: tuple[str, str], resolver, check: bool, diff: bool, verify: bool, dialect: str | None):
    """`mcc fmt -`: the formatted program on standard output (nothing when it cannot be formatted:
    the reason goes to standard error and the exit code is 1, so an editor keeps its buffer)."""
    from mcc.compiler import driver
    from mcc.compiler.lint import formatting

    name, text = piped
    found = driver.resolve_dialect(name, dialect)
    if formatting.formatter(found.name) is None:
        click.echo(f"note: mcc has no {found.name} formatter yet; the program is left as it is", err=True)
        sys.stdout.write(text)
        sys.exit(EXIT_OK)
    formatted, error = formatting.format_source(name, text, found.name, resolver.for_path(name))
    if not error and verify and formatted != text:
        problem = formatting._simulated_difference(name, found.name, text, formatted)
        error = f"--verify: {problem}; the program was left unchanged" if problem else ""
    if error:
        click.echo(f"error: {name}: {error}", err=True)
        sys.exit(EXIT_ERRORS)
    if diff:
        if formatted != text:
            from mcc.compiler.lint.fixes import unified_diff

            sys.stdout.write(unified_diff(name, text, formatted))
        sys.exit(EXIT_ERRORS if formatted != text else EXIT_OK)
    if check:
        if formatted != text:
            click.echo(f"Would reformat: {name}")
        sys.exit(EXIT_ERRORS if formatted != text else EXIT_OK)
    sys.stdout.write(formatted)
    sys.exit(EXIT_OK)


__all__ = ["lint", "fmt", "EXIT_USAGE"]
