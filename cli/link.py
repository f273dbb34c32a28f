"""`mcc download`, `mcc upload`, `mcc terminal`, `mcc send` and `mcc device`: the device link.

Ports are pyserial URLs; serial settings come from the profile's `[link]` table and the options
below override them. See docs/LINK.md for each dialect's framing and what needs the vendor's tools.
"""

from __future__ import annotations

import functools
import json
import sys

import click

from mcc.cli.commands import DIALECT_NAMES, cli, load_profile
from mcc.cli.main import EXIT_ERRORS, EXIT_OK

FORMATS = ["text", "json"]
PROGRESS_MIN_STEPS = 40


def port_options(func):
    """The options every command that talks to a device takes."""
    options = [
        click.option("--port", "port", required=True, metavar="URL",
                     help="pyserial URL: /dev/ttyUSB0, COM3, socket://HOST:PORT, rfc2217://HOST:PORT, loop://"),
        click.option("--profile", help="Target profile whose [link] table gives the serial settings "
                                       "(default: the dialect's default profile)."),
        click.option("--address", help="MCode party name (DN), X150 device address, Arcus device number (00-99)."),
        click.option("--baudrate", type=int, help="Baud rate (profile: link.baudrate)."),
        click.option("--parity", type=click.Choice(["N", "E", "O", "M", "S"]), help="Parity (profile: link.parity)."),
        click.option("--timeout", type=float, help="Seconds to wait for one reply (profile: link.timeout, default 2)."),
        click.option("--retries", type=int, help="Resends of a command whose reply was lost or NAKed when "
                                                 "resending is safe (profile: link.retries, default 2)."),
        click.option("--party/--no-party", default=None, help="MCode: the device is in party mode (PY=1)."),
        click.option("--checksum", type=click.IntRange(0, 2), help="MCode: the device's checksum mode CK."),
    ]
    for option in reversed(options):
        func = option(func)
    return func


def link_settings(dialect: str, profile_name: str | None, **overrides):
    from mcc.compiler import dialects
    from mcc.compiler import profiles as profiles_mod
    from mcc.link.settings import from_profile

    prof = load_profile(profile_name) if profile_name else profiles_mod.load(dialects.get(dialect).default_profile)
    if prof.dialect != dialect:
        raise click.BadParameter(f"profile '{prof.name}' is for {prof.dialect}, not {dialect}", param_hint="--profile")
    try:
        return prof, from_profile(prof, overrides)
    except ValueError as exc:
        raise click.UsageError(str(exc)) from None


def overrides_of(kwargs: dict) -> dict:
    return {k: kwargs.get(k) for k in ("address", "baudrate", "parity", "timeout", "retries", "party", "checksum")}


def fail(message: str, state: str = "", fmt: str = "text") -> None:
    if fmt == "json":
        click.echo(json.dumps({"ok": False, "message": message, "device_state": state}, indent=2))
    else:
        click.secho(f"error: {message}", fg="red", err=True)
        if state:
            click.echo(f"device: {state}", err=True)
    sys.exit(EXIT_ERRORS)


def link_errors(func):
    """Every LinkError becomes a clear message and exit 1, never a traceback."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        from mcc.link.errors import LinkError

        try:
            return func(*args, **kwargs)
        except LinkError as exc:
            fail(exc.message, exc.device_state, kwargs.get("fmt", "text"))

    return wrapper


def connect(dialect: str, url: str, settings):
    from mcc.link import protocols
    from mcc.link.ports import Channel, open_port

    channel = Channel(open_port(url, settings), settings)
    return protocols.get(dialect)(channel, settings)


def source_line(span) -> str:
    try:
        with open(span.file, encoding="utf-8", errors="replace") as handle:
            for number, line in enumerate(handle, 1):
                if number == span.line:
                    return line.rstrip("\n")
    except OSError:
        pass
    return ""


# -- download ---------------------------------------------------------------------------------
@cli.command()
@click.argument("file", type=click.Path(exists=True, dir_okay=False))
@port_options
@click.option("--dialect", type=DIALECT_NAMES, help="Dialect of FILE (default: from the extension; "
                                                                 ".sa is an Arcus program image).")
@click.option("--save", is_flag=True, help="After verifying, save to non-volatile memory (MCode S, X150 SV).")
@click.option("--run", is_flag=True, help="After verifying (and saving), start the program and report its status.")
@click.option("--dry-run", is_flag=True, help="Print the exchange that would be sent, without opening a port.")
@click.option("--format", "fmt", type=click.Choice(FORMATS), default="text", show_default=True,
              help="text for people; json (one object with every step's outcome) for CI.")
@link_errors
def download(file: str, port: str, dialect: str | None, save: bool, run: bool, dry_run: bool, fmt: str,
             profile: str | None, **kwargs) -> None:
    """Compile FILE and put it on the device at --port, then read it back and compare.

    FILE is a source file or an already compiled listing (compiling a listing gives it back).
    Each command's reply is checked; the first device error stops the download and is reported
    with the source line it came from. Lines that save (S, SV) or start motion or a program are
    held back until what the device holds has been verified, and sent only with --save / --run.
    Exit 0 when the program is on the device and verified, 1 otherwise.

    \b
    Examples:
      mcc download feeder.mxt --port /dev/ttyUSB0 --save
      mcc download cell.x150 --port socket://192.168.0.20:4001 --run --format json
      mcc download feeder.mxt --port loop:// --dry-run
    """
    from mcc.link import protocols

    from mcc.compiler import dialects, driver

    found = (dialect is None and dialects.from_image(file)) or driver.resolve_dialect(file, dialect)
    if found is None:
        raise click.BadParameter(f"cannot tell the dialect of '{file}': pass --dialect", param_hint="FILE")
    prof, settings = link_settings(found.name, profile, **overrides_of(kwargs))
    proto_class = protocols.get(found.name)
    if found.image_extensions:  # the device is downloaded a memory image, not the listing
        if not file.lower().endswith(found.image_extensions):
            fail(f"{file}: {protocols.module(found.name).NOT_DOWNLOADABLE}",
                 "nothing was sent: the device is as it was", fmt)
        with open(file, encoding="utf-8", errors="replace") as handle:
            steps = proto_class(None, settings).plan_image(handle.read(), file)
    else:
        result = driver.compile_file(file, found.name, None, prof)
        if result.listing is None or result.has_errors:
            from mcc.cli.commands import report

            report([result], fmt)
            fail(f"{file} has errors: nothing was sent", "the device is as it was", "text")
        steps = proto_class(None, settings).plan(result.listing.lines)
    if dry_run:
        print_plan(proto_class(None, settings), steps, save, run, fmt)
        return
    proto = connect(found.name, port, settings)
    from mcc.link.download import download as run_download

    advance, finish = progress_bar(len(steps), fmt)
    try:
        outcome = run_download(proto, steps, save, run, advance)
    finally:
        finish()
        proto.channel.close()
    print_report(file, outcome, proto.channel.transcript, fmt)
    sys.exit(EXIT_OK if outcome.ok else EXIT_ERRORS)


def progress_bar(total: int, fmt: str):
    if total < PROGRESS_MIN_STEPS or fmt != "text" or not sys.stderr.isatty():
        return None, lambda: None
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    bar = Progress(TextColumn("downloading"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                   console=Console(file=sys.stderr), transient=True)
    bar.start()
    task = bar.add_task("download", total=total)
    return (lambda n: bar.advance(task, n)), bar.stop


def print_plan(proto, steps, save: bool, run: bool, fmt: str) -> None:
    rows = []
    for step in steps:
        if step.kind == "save" and not save or step.kind == "run" and not run:
            rows.append({**step.to_json(), "bytes": None, "note": f"held back (pass --{step.kind})"})
            continue
        rows.append({**step.to_json(), "bytes": proto.frame(step.command).decode("latin-1")})
    if fmt == "json":
        click.echo(json.dumps({"dry_run": True, "steps": rows}, indent=2))
        return
    for row in rows:
        where = ", ".join(row["sources"]) or "-"
        data = repr(row["bytes"]) if row["bytes"] is not None else row["note"]
        click.echo(f"{row['kind']:7} {data:40} ; {where}")
    click.echo(f"then: read back and compare; {'save; ' if save else ''}{'run' if run else ''}".rstrip("; "))


def print_report(file: str, outcome, transcript, fmt: str) -> None:
    if fmt == "json":
        from mcc.link.ports import transcript_text

        click.echo(json.dumps({"file": file, **outcome.to_json(), "transcript": transcript_text(transcript)},
                              indent=2))
        return
    if outcome.ok:
        click.echo(f"{file}: {outcome.message} ({outcome.sent} commands)")
        if outcome.status:
            click.echo("status: " + ", ".join(f"{k} {v}" for k, v in outcome.status.items()))
        if outcome.held_back:
            click.echo("held back (pass --save / --run): " + "; ".join(outcome.held_back))
        click.echo(f"device: {outcome.device_state}")
        return
    click.secho(f"error: {outcome.message}", fg="red", err=True)
    if outcome.error in ("lost", "garbled", "port"):
        if outcome.meaning:
            click.echo(f"  {outcome.meaning}", err=True)
    elif outcome.error:
        click.echo(f"  device error {outcome.error}: {outcome.meaning}".rstrip(": "), err=True)
    if outcome.failed is not None:
        for span in sorted(set(outcome.failed.sources), key=lambda s: (s.file, s.line)):
            click.echo(f"  --> {span.file}:{span.line}", err=True)
            text = source_line(span)
            if text:
                click.echo(f"  {span.line:5} | {text}", err=True)
    for mismatch in outcome.mismatches:
        click.echo(f"  {mismatch.where}: sent {mismatch.expected!r}, device holds {mismatch.found!r}", err=True)
    click.echo(f"device: {outcome.device_state}", err=True)


# -- upload -----------------------------------------------------------------------------------
@cli.command()
@port_options
@click.option("--dialect", type=DIALECT_NAMES, required=True, help="The device's dialect.")
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Write the source here (default: stdout).")
@click.option("--password", help="X150: the upload password (PASS) to lift the protection for this upload.")
@click.option("--devices", help="X150: comma-separated device addresses to read (default: --address or 1).")
@click.option("--image", type=click.Path(dir_okay=False),
              help="Arcus: also save the compiled program lines (SAn) to this image file for mcc download.")
@link_errors
def upload(port: str, dialect: str, output: str | None, password: str | None, devices: str | None,
           image: str | None, profile: str | None, **kwargs) -> None:
    """Read the program back from the device and write it as a source file `mcc check` accepts.

    \b
    mcode  the global user variables (PR UV) and program memory (L) between PG lines
    x150   every stored sequence (XSS, XU) as XE/XD ... XT
    arcus  the variables V0-V63; the program itself only as an image (--image)

    \b
    Examples:
      mcc upload --port /dev/ttyUSB0 --dialect mcode -o backup.mxt
      mcc upload --port COM3 --dialect x150 --devices 1,2 -o cell.x150
      mcc upload --port /dev/ttyUSB1 --dialect arcus --image machine.sa -o variables.prg
    """
    from mcc.compiler import dialects, driver
    from mcc.compiler.lint.files import write_atomic
    from mcc.link import protocols

    _prof, settings = link_settings(dialect, profile, **overrides_of(kwargs))
    proto = connect(dialect, port, settings)
    try:
        proto.hello()
        text = protocols.module(dialect).upload(proto, password or "", devices.split(",") if devices else None)
        if image and dialects.get(dialect).image_extensions:
            write_atomic(image, proto.image())
        proto.goodbye()
    finally:
        proto.channel.close()
    if not text:
        fail("the device holds no program to upload", "nothing was changed on the device")
    extension = dialects.get(dialect).output_extension
    checked = driver.check_file(output or f"<upload>{extension}", dialect, text=text)
    if output:
        write_atomic(output, text)
        click.echo(f"wrote {output}", err=True)
    else:
        click.echo(text, nl=False)
    if checked.has_errors:
        click.secho("warning: the uploaded program does not pass mcc check; run mcc check on it", fg="yellow",
                    err=True)
        sys.exit(EXIT_ERRORS)


# -- send and terminal ------------------------------------------------------------------------
@cli.command()
@port_options
@click.option("--dialect", type=DIALECT_NAMES, required=True, help="The device's dialect.")
@click.option("--format", "fmt", type=click.Choice(FORMATS), default="text", show_default=True)
@click.argument("commands", nargs=-1, required=True)
@link_errors
def send(port: str, dialect: str, commands: tuple[str, ...], fmt: str, profile: str | None, **kwargs) -> None:
    """Send COMMANDS one after the other and print each reply (for scripts).

    Stops at the first command the device refuses; exit 1 then, or when a reply is lost.

    \b
    Examples:
      mcc send --port /dev/ttyUSB0 --dialect mcode "PR P" "PR ER"
      mcc send --port socket://10.0.0.5:4001 --dialect arcus SR=1 SASTAT
    """
    from mcc.link.protocol import LostReply
    from mcc.link.protocols import describe

    _prof, settings = link_settings(dialect, profile, **overrides_of(kwargs))
    proto = connect(dialect, port, settings)
    results, ok = [], True
    try:
        for command in commands:
            try:
                reply = proto.transact(command)
            except LostReply as exc:
                results.append({"command": command, "ok": False, "error": "garbled" if exc.garbled else "lost",
                                "text": str(exc)})
                ok = False
                break
            results.append({"command": command, "ok": reply.ok, "lines": reply.lines, "error": reply.error,
                            "meaning": reply.meaning, "text": describe(dialect, reply)})
            if not reply.ok:
                ok = False
                break
    finally:
        proto.channel.close()
    if fmt == "json":
        click.echo(json.dumps({"ok": ok, "replies": results}, indent=2))
    else:
        for row in results:
            click.echo(f"{row['command']}: {row['text']}")
    sys.exit(EXIT_OK if ok else EXIT_ERRORS)


@cli.command()
@port_options
@click.option("--dialect", type=DIALECT_NAMES, required=True, help="The device's dialect.")
@link_errors
def terminal(port: str, dialect: str, profile: str | None, **kwargs) -> None:
    """An interactive terminal to the device: type commands, read the replies in words.

    Up/down arrows recall earlier commands (kept in ~/.mcc_terminal_history). Lines starting with
    a colon are for the terminal: `:explain CODE` explains a device error number or an mcc
    diagnostic code, `:status` reads the device's status, `:quit` (or Ctrl-D) leaves.
    """
    from mcc.link.terminal import Terminal

    _prof, settings = link_settings(dialect, profile, **overrides_of(kwargs))
    proto = connect(dialect, port, settings)
    try:
        click.echo(f"connected: {proto.hello()}")
        Terminal(proto, dialect).loop()
        proto.goodbye()
    finally:
        proto.channel.close()


# -- the virtual device -----------------------------------------------------------------------
@cli.command()
@click.option("--dialect", type=DIALECT_NAMES, required=True, help="The device to be.")
@click.option("--listen", default="127.0.0.1:0", show_default=True, metavar="HOST:PORT",
              help="Where to listen (port 0: any free port, printed at start).")
@click.option("--program", type=click.Path(exists=True, dir_okay=False),
              help="Arcus: start holding this .prg, as if the vendor's software had downloaded it.")
@click.option("--fault", default="", help="Inject faults, e.g. drop_reply=5,garble=9,close=12 "
                                         "(the Nth command received).")
@click.option("--addresses", default="1,2,3,4", show_default=True, help="X150: the device addresses on the chain.")
@click.option("--party", "party_names", default="",
              help="MCode: comma-separated names (DN) of drives in party mode on one bus, e.g. a,b.")
@click.option("--program-lines", type=int, default=1500, show_default=True,
              help="MCode: program memory in lines (error 45 beyond it; the manual gives no size).")
@click.option("--sequence-bytes", type=int, default=8000, show_default=True,
              help="X150: sequence memory in bytes (L4871).")
@click.option("--run-limit", type=click.FloatRange(min=0, min_open=True), default=60.0, show_default=True,
              metavar="SECONDS",
              help="Virtual seconds a program may run on the simulator's machine; a program still going "
                   "then is held, reported 'running'.")
@click.option("--time-scale", type=click.FloatRange(min=0), default=1.0, show_default=True, metavar="X",
              help="Virtual seconds that pass per second the host is silent (1: real time, as a drive; "
                   "0: only the commands' own time passes).")
@click.option("--profile", default=None, metavar="NAME",
              help="MCode: the product to be (a built-in profile or a TOML file): its machine, and the "
                   "identity PR VR and PR PN report (default: the dialect's default profile).")
def device(dialect: str, listen: str, program: str | None, fault: str, addresses: str, party_names: str,
           program_lines: int, sequence_bytes: int, run_limit: float, time_scale: float,
           profile: str | None) -> None:
    """Run a virtual device on a TCP port, behind the dialect's host protocol.

    Connect with --port socket://HOST:PORT. The device keeps its state between connections
    until it is stopped (Ctrl-C). Programs and commands run on the simulator's machine (as
    `mcc sim`) in virtual time that runs as a drive's clock does: each command takes its
    characters' time on the line and the product's execution time, and while the host is silent
    time passes (--time-scale); moves and programs go on across commands. See docs/LINK.md for
    what it models.

    \b
    Example:
      mcc device --dialect mcode --listen 127.0.0.1:4001 &
      mcc download samples/mcode/pick_and_place.mxt --port socket://127.0.0.1:4001
    """
    from mcc.compiler.profiles import ProfileError
    from mcc.link.device.faults import Faults
    from mcc.link.device.server import DeviceServer
    from mcc.link.device.virtual import make_device

    try:
        faults = Faults.parse(fault)
    except ValueError as exc:
        raise click.BadParameter(str(exc), param_hint="--fault") from None
    host, _, port_text = listen.rpartition(":")
    if not port_text.isdigit():
        raise click.BadParameter("use HOST:PORT", param_hint="--listen")
    try:
        dev = make_device(dialect, faults, addresses=tuple(a.strip() for a in addresses.split(",") if a.strip()),
                          program_lines=program_lines, sequence_bytes=sequence_bytes, program=program,
                          party=tuple(n.strip() for n in party_names.split(",") if n.strip()), run_limit=run_limit,
                          profile=profile)
    except ProfileError as exc:
        raise click.BadParameter(str(exc), param_hint="--profile") from None
    except ValueError as exc:
        raise click.BadParameter(str(exc), param_hint="--program") from None
    server = DeviceServer(dev, host or "127.0.0.1", int(port_text), time_scale=time_scale)
    click.echo(f"virtual {dialect} device on {server.url} (Ctrl-C to stop)", err=True)
    sys.stderr.flush()
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.stop()
