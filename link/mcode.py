"""Lexium MCode host protocol: party prefix, checksum, echo and prompt (manual §7.1, spec §1.9-1.11).

A command is `[DN]command[CS]<terminator>`: DN is the party name when PY=1 (then the terminator is
LF, L5002), CS the checksum character when CK=1/2 (L2066-L2082). In echo mode EM=0 the device
echoes the command, ends the line with CR LF (or ACK/NAK in checksum mode, L6888-L6892), prints
any output (PR, L) one line each, and ends with the prompt: `>` when the command was accepted,
`?` when it raised an error, whose code `PR ER` reads and clears (L2696, L8446).
"""

from __future__ import annotations

import itertools
import re
import time
from functools import lru_cache
from pathlib import Path

from mcc.compiler import toml
from mcc.link.errors import LinkError
from mcc.link.ports import Channel
from mcc.link.protocol import DeviceError, LostReply, Mismatch, Reply, Step, echo_at, normalize
from mcc.link.settings import LinkSettings

ACK, NAK = b"\x06", b"\x15"
# Immediate commands that start motion or a program: held back until the download is verified
# and sent only with --run (a download must not move the machine by itself).
RUN_MNEMONICS = ("EX", "MA", "MR", "SL", "HM", "HI")
SAVE_MNEMONICS = ("S",)
CLEAR_COMMAND = "CP 1"   # clear program memory and user variables (L2149): a download starts clean


def checksum(text: str) -> int:
    """The MCode checksum character: two's complement of the 7-bit sum, OR 0x80 (L6864-L6868)."""
    return ((-sum(text.encode("latin-1"))) & 0x7F) | 0x80


@lru_cache(maxsize=None)
def mcode_names() -> frozenset[str]:
    """Every MCode name of the catalog (indexed families expanded), to recognise party prefixes."""
    from mcc.compiler import catalog

    found = set()
    for entry in catalog.load("mcode").entries:
        index = entry.get("index")
        found.update(f"{entry.name}{i}" for i in range(index[0], index[1] + 1)) if index else found.add(entry.name)
    return frozenset(name.upper() for name in found)


@lru_cache(maxsize=None)
def error_table() -> dict[int, dict]:
    data = toml.loads((Path(__file__).parent / "mcode_errors.toml").read_text(encoding="utf-8"))
    return {int(code): entry for code, entry in data["error"].items()}


def explain(code: str) -> str:
    try:
        entry = error_table().get(int(code))
    except ValueError:
        entry = None
    if entry is None:
        return "not in the manual's error tables"
    return f"{entry['meaning']} ({entry['manual']})"


def mnemonic(command: str) -> str:
    match = re.match(r"\s*([A-Za-z][A-Za-z0-9_]*)", command)
    return match.group(1).upper() if match else ""


class Protocol:
    dialect = "mcode"

    def __init__(self, channel: Channel | None, settings: LinkSettings) -> None:
        self.channel = channel
        self.settings = settings

    # -- framing ---------------------------------------------------------------------------
    @property
    def terminator(self) -> str:
        return "\n" if self.settings.party else self.settings.terminator

    user_names: frozenset[str] = frozenset()

    def addressed(self, command: str) -> bool:
        """Whether a line already carries a party prefix: `*VM=5`, `^MA 0`, `aMR 100` (a first
        word that is no MCode name but is one without its first character)."""
        if command[:1] in ("*", "^"):
            return True
        first = re.match(r"[A-Za-z0-9!]+", command)
        if not first or len(first.group(0)) < 2:
            return False
        known = mcode_names()
        word = first.group(0).upper()
        return word not in known and word not in self.user_names and not word[0].isdigit() and re.match(r"[A-Z]+", word[1:]) is not None \
            and any(word[1:].startswith(name) and not word[1 + len(name):].isalpha() for name in known
                    if len(name) >= 1)

    @property
    def own_name(self) -> str:
        return self.settings.address or "!"

    def body(self, command: str) -> str:
        prefix = self.own_name if self.settings.party and not self.addressed(command) else ""
        text = prefix + command
        if self.settings.checksum:
            text += chr(checksum(text))
        return text

    def frame(self, command: str) -> bytes:
        return (self.body(command) + self.terminator).encode("latin-1")

    def reply_end(self, echo: bytes):
        """A function telling where a reply to a command echoed as `echo` ends (0: not yet)."""

        def complete(buffer: bytes) -> int:
            start = max(echo_at(buffer, echo), 0) + len(echo)   # after what a running program printed
            if len(buffer) <= start:
                return 0
            rest = buffer[start:]
            if rest[:1] == NAK:
                return start + 1 + (1 if rest[1:2] in (b">", b"?") else 0) if len(rest) >= 2 else 0
            if len(rest) >= 2 and rest[-1:] in (b">", b"?") and rest[-2:-1] in (b"\n", ACK):
                return len(buffer)
            return 0

        return complete

    # -- one exchange ----------------------------------------------------------------------
    # The manual both says programs are stored in and run from NVM (L2149) and that a reset reloads
    # them from NVM into RAM (L862); settings and variables are certainly lost without S.
    unsaved_note = ("not saved with S: settings and user variables are lost at a power cycle, and whether the "
                    "program lines are is contradictory in the manual (L2149, L862); pass --save")
    in_program = False   # between an accepted `PG n` and `PG`: lines are stored, not executed

    def transact(self, command: str, retry: bool = True, read_error: bool = True) -> Reply:
        """Send one command and read its reply; resend after a NAK or, when `retry`, a lost reply.

        A stored program line is sent with retry=False: if its reply is lost nobody knows whether
        the device stored it, and the download stops instead of perhaps storing it twice.
        """
        assert self.channel is not None
        if self.settings.party and command[:1] in ("*", "^"):
            # Every drive executes a global command and none answers (DG=1, L2399-L2404, L5004).
            self.channel.send(self.frame(command))
            self.channel.discard_input(0.05)
            return Reply(command, True)
        attempts = 1 + self.settings.retries
        last: LostReply | None = None
        for attempt in range(attempts):
            if self.settings.pace:
                time.sleep(self.settings.pace)
            framed = self.frame(command)
            echo = framed[:-len(self.terminator)]
            self.channel.send(framed)
            raw, complete = self.channel.read_until(self.reply_end(echo))
            if not complete:
                last = LostReply(command, raw)
                self.resync()
                if retry and attempt + 1 < attempts:
                    continue
                raise last
            at = echo_at(raw, echo)   # a running program's output may come first (L4895)
            rest = raw[max(at, 0) + len(echo):]
            if rest[:1] == NAK:
                last = LostReply(command, raw, garbled=True)
                continue  # the device ignored the command (L6890): sending it again is safe
            if at < 0:
                last = LostReply(command, raw, garbled=True)
                self.resync()
                raise last
            reply = self.decode(command, rest, raw)
            if reply.ok and mnemonic(command) == "PG":
                self.in_program = bool(command.split()[1:])
            if not reply.ok and read_error:
                code = self.read_error()
                reply.error, reply.meaning = code, explain(code)
            return reply
        assert last is not None
        raise last

    def decode(self, command: str, rest: bytes, raw: bytes) -> Reply:
        prompt = rest[-1:]
        body = rest[:-1]
        body = body[1:] if body[:1] == ACK else body[2:] if body[:2] == b"\r\n" else body
        lines = []
        for line in body.decode("latin-1").split("\r\n"):
            if self.settings.checksum and line:
                if sum(line.encode("latin-1")) & 0x7F:
                    raise LostReply(command, raw, garbled=True)
                line = line[:-1]
            if line:
                lines.append(line)
        return Reply(command, prompt == b">", lines, raw=raw)

    def read_error(self) -> str:
        """The pending error code (`PR ER`, which also clears it). In program mode `PR ER` would
        be stored, not executed, so program mode is left first (`PG`)."""
        if self.in_program:
            self.transact("PG", read_error=False)
            self.in_program = False
        reply = self.transact("PR ER", read_error=False)
        return reply.lines[-1].strip() if reply.ok and reply.lines else "?"

    def resync(self) -> None:
        """After a lost or garbled reply: drop what is in flight and get a fresh prompt."""
        assert self.channel is not None
        self.channel.discard_input()
        self.channel.send(self.frame(""))
        self.channel.read_until(lambda b: len(b) if b[-1:] in (b">", b"?") else 0)
        self.channel.discard_input()

    def query(self, command: str) -> list[str]:
        reply = self.transact(command)
        if not reply.ok:
            raise DeviceError(reply)
        return reply.lines

    # -- session ---------------------------------------------------------------------------
    def hello(self, steps=None) -> str:
        """Wake the device, put it in echo mode 0 (one prompt per command) and say what it is."""
        assert self.channel is not None
        self.channel.discard_input()
        if self.settings.party:
            self.channel.send(b"\n")   # one CTRL+J activates party mode (L5002, L5006)
            self.channel.discard_input()
        if self.settings.echo != 0:
            # In EM=1-3 no prompt ends a reply: switch to EM=0 first, then drop what it answered.
            self.channel.send(self.frame("EM=0"))
            self.channel.discard_input(0.2)
        self.channel.send(self.frame(""))
        self.channel.read_until(lambda b: len(b) if b[-1:] in (b">", b"?") else 0)
        try:
            return " ".join(self.query("PR VR"))
        except LostReply as exc:
            raise LinkError(f"no answer from the device: {exc}. Check the port, the baud rate "
                            f"({self.settings.baudrate}) and the party/checksum settings.",
                            "nothing was changed on the device") from None

    def goodbye(self) -> None:
        """Leave the drive in the echo mode the profile says it is used in."""
        if self.settings.echo != 0:
            self.transact(f"EM={self.settings.echo}", read_error=False)

    # -- download --------------------------------------------------------------------------
    def plan(self, lines) -> list[Step]:
        steps = [Step(CLEAR_COMMAND, "clear")]
        in_program = False
        self.user_names = frozenset(
            match.group(2).upper() for line in lines
            for match in [re.match(r"\s*\S?(VA|LB)\s+([A-Za-z][A-Za-z0-9_]*)", line.text, re.I)] if match)
        for number, line in enumerate(lines, 1):
            text = line.text.strip()
            if not text or text.startswith(("'", "`")):
                continue
            if self.addressed(text) and not self.settings.party:
                where = ", ".join(f"{s.file}:{s.line}" for s in line.sources) or f"listing line {number}"
                raise LinkError(f"{where}: `{text}` is addressed to a drive by its party name: the drives are "
                                "in party mode (PY=1), pass --party and --address NAME of the drive to verify",
                                "nothing was sent")
            word = mnemonic(text[1:] if self.addressed(text) else text)
            if word == "PG":
                in_program = bool(text[2:].strip())
                steps.append(Step(text, "send", line.sources, False, number))
            elif in_program:
                steps.append(Step(text, "send", line.sources, True, number))
            elif word in SAVE_MNEMONICS and text.upper().strip() == word:
                steps.append(Step(text, "save", line.sources, False, number))
            elif word in RUN_MNEMONICS:
                steps.append(Step(text, "run", line.sources, False, number))
            else:
                steps.append(Step(text, "send", line.sources, False, number))
        return steps

    def save_command(self, steps) -> list[str]:
        return ["S"]

    def check_step(self, step: Step, reply: Reply) -> None:
        pass

    def run_commands(self, steps: list[Step]) -> list[str]:
        held = [s.command for s in steps if s.kind == "run"]
        if held:
            return held
        origins = [s.command.split()[1] for s in steps if mnemonic(s.command) == "PG" and len(s.command.split()) > 1]
        return [f"EX {origins[0]}"] if origins else []

    def after_failure(self, steps_sent: list[Step], failed: Step | None) -> str:
        """Leave program mode if the failure happened in it, then read program memory back, so that
        the report says exactly which lines the device holds."""
        notes = []
        opened = [s for s in steps_sent + ([failed] if failed else []) if mnemonic(s.command) == "PG"]
        if opened and len(opened[-1].command.split()) > 1:
            if self.in_program:
                reply = self.transact("PG", read_error=False)
                self.in_program = not reply.ok
            notes.append("program mode was left (PG sent)" if not self.in_program else "PG was refused")
        held = self.stored()
        sent = [s.command for s in steps_sent + ([failed] if failed else []) if s.stored]
        same = sum(1 for _ in itertools.takewhile(
            lambda pair: normalize(pair[0]) == normalize(pair[1]), zip(sent, held)))
        text = f"program memory now holds {len(held)} lines"
        if held:
            text += f", the first {same} as sent"
            if len(held) > same:
                text += f"; line {same + 1} is `{held[same]}`" + (
                    f", not `{sent[same]}` as sent (garbled on the way)" if same < len(sent) else "")
        notes.append(text)
        return "; ".join(notes)

    def stored(self) -> list[str]:
        """What program memory holds, as `L` lists it (L3728); [] when it is empty."""
        return [line for line in self.query("L") if line.strip()]

    def verify(self, steps: list[Step]) -> tuple[list[Mismatch], str]:
        sent = [s.command for s in steps if s.stored]
        held = self.stored()
        mismatches = [Mismatch(f"program line {i}", a, b)
                      for i, (a, b) in enumerate(zip(sent, held), 1) if normalize(a) != normalize(b)]
        if len(held) != len(sent):
            mismatches.append(Mismatch("program length", f"{len(sent)} lines", f"{len(held)} lines"))
        return mismatches, f"program memory holds {len(held)} lines"

    def status(self) -> dict:
        """BY (1 while a program runs) and the pending error, read and cleared with PR ER."""
        busy = self.query("PR BY")
        return {"BY": busy[-1].strip() if busy else "?", "ER": self.read_error()}

    # -- upload ----------------------------------------------------------------------------
    def user_variables(self) -> list[tuple[str, str, str]]:
        """(name, G|L, value) of every user variable, from `PR UV` (`Q1 = G 25`, L5965-L5972)."""
        found = []
        for line in self.query("PR UV"):
            match = re.match(r"\s*(\w+)\s*=\s*([GL])\s+(\S+)", line)
            if match:
                found.append((match.group(1), match.group(2), match.group(3)))
        return found

    def upload(self, origin: int = 1) -> str:
        """A source file: the global user variables (`VA`) and program memory between `PG` lines."""
        lines = self.stored()
        declared = [f"VA {name}={value}" for name, scope, value in self.user_variables() if scope == "G"]
        if not lines and not declared:
            return ""
        program = [f"PG {origin}", *lines, "PG"] if lines else []
        return "\n".join([*declared, *program]) + "\n"


# -- what the link asks of the dialect (link/protocols.py) ------------------------------------
def explain_code(code: str) -> str:
    return f"error {code}: {explain(code)}"


def describe(reply: Reply) -> str | None:
    """An accepted reply's data says what it is."""
    return None


def upload(proto: Protocol, password: str, addresses: list[str] | None) -> str:
    """The program memory as MCode text (no password, one device)."""
    return proto.upload()
