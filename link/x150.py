"""Parker/Digiplan X150 host protocol (manual: command format L116-L132, replies L163-L165, EX
L1433-L1439, XD/XT/XSD/XSS/XU L4904-L5447, PASS L3064, SV).

A command is `[address]MNEMONIC[value]` and a delimiter (CR). With echo on (SSA0, the default) the
controller echoes what it receives; reports answer `*...` or a bare digit (XSD, XSS, XSR) ending
in CR; in terminal mode (EX1, the default) messages start with `;` and each command ends with the
prompt `>`. mcc works in terminal mode, because the prompt is the only documented end of a reply.
Download errors are read where the manual reports them: `XSD` after each `XT` (0 OK, 1 sequence
exists, 2 buffer full), `XSS` (0 empty, 2 exists) and the `R` status (`*R` ready, no error).

Every command that asks a device for a report is sent with a device address: "All commands that
request data to be transmitted back to the host are device specific" (L181). A sequence defined
without an address (`XD1`) is stored by every device on the chain (XD is Universal, L4899), so its
download status and its read-back are asked of each device the program names (or the one given
with --address, else device 1), each compared with what was sent.
"""

from __future__ import annotations

import re
import time

from mcc.link.errors import LinkError
from mcc.link.ports import Channel
from mcc.link.protocol import DeviceError, LostReply, Mismatch, Reply, Step, echo_at
from mcc.link.settings import LinkSettings

COMMAND = re.compile(r"^\s*(\d*)\s*([A-Z\"#;^]+)(.*)$")
RUN_MNEMONICS = ("G", "GH", "XR", "XG", "GOSUB", "GOTO", "XRP")
SAVE_MNEMONICS = ("SV",)
XSD_MEANING = {"0": "received OK", "1": "cannot overwrite an existing sequence (erase it first with XE)",
               "2": "sequence buffer full"}
R_MEANING = {"*R": "ready", "*S": "ready, function error", "*T": "ready, communications error",
             "*U": "ready, function and communications error", "*B": "busy", "*C": "busy, function error",
             "*D": "busy, communications error", "*E": "busy, function and communications error"}


def split(command: str) -> tuple[str, str, str]:
    """(address, mnemonic, rest) of one command; the mnemonic is matched greedily on letters."""
    match = re.match(r"^\s*(\d*)(XD|XT|XE|XU|XSD|XSS|XSR|SV|PASS|EX|XR|XG|XRP|GOSUB|GOTO|GH|G)(?![A-Z])(.*)$",
                     command)
    if match:
        return match.group(1), match.group(2), match.group(3)
    match = COMMAND.match(command)
    return (match.group(1), match.group(2), match.group(3)) if match else ("", "", command)


def explain(code: str) -> str:
    return XSD_MEANING.get(code) or R_MEANING.get(code) or ""


class Protocol:
    dialect = "x150"
    unsaved_note = "not saved: sequences stay in volatile memory until SV (L4904); pass --save"

    def __init__(self, channel: Channel | None, settings: LinkSettings) -> None:
        self.channel = channel
        self.settings = settings

    def frame(self, command: str) -> bytes:
        return (command + self.settings.terminator).encode("latin-1")

    @staticmethod
    def complete(echo: bytes):
        def end(buffer: bytes) -> int:
            if len(buffer) > len(echo) and buffer.endswith(b">") and buffer[-2:-1] in (b"\r", b"\n", b""):
                return len(buffer)
            return 0
        return end

    def transact(self, command: str, retry: bool = True) -> Reply:
        """Send one command; the reply must start with the echo and end with the prompt."""
        assert self.channel is not None
        last: LostReply | None = None
        for attempt in range(1 + self.settings.retries):
            if self.settings.pace:
                time.sleep(self.settings.pace)
            framed = self.frame(command)
            echo = framed if self.settings.echo == 0 else b""
            self.channel.send(framed)
            raw, complete = self.channel.read_until(self.complete(echo))
            if not complete:
                last = LostReply(command, raw)
                self.channel.discard_input()
                if retry and attempt < self.settings.retries:
                    continue
                raise last
            at = echo_at(raw, echo) if echo else 0   # a running sequence's messages may come first (L5593)
            if at < 0:
                self.channel.discard_input()
                raise LostReply(command, raw, garbled=True)
            text = raw[at + len(echo):-1].decode("latin-1")
            lines = [line for line in re.split(r"[\r\n]+", text) if line]
            messages = [line for line in lines if line.startswith(";")]
            data = [line for line in lines if not line.startswith(";")]
            return Reply(command, True, data, raw=raw, meaning=" ".join(m[1:] for m in messages))
        assert last is not None
        raise last

    def query(self, command: str) -> list[str]:
        return self.transact(command).lines

    # -- session ---------------------------------------------------------------------------
    def addresses(self, steps: list[Step] | None = None) -> list[str]:
        found = []
        for step in steps or []:
            address = split(step.command)[0]
            if address and address not in found:
                found.append(address)
        return found or [self.settings.address or "1"]

    def hello(self, steps: list[Step] | None = None) -> str:
        """Put every device of the program in terminal mode (EX1) and check that each answers R."""
        assert self.channel is not None
        self.channel.discard_input()
        states = []
        for address in self.addresses(steps):
            # In computer mode (EX0) this gets no prompt: the read then ends at the timeout.
            self.channel.send(self.frame(f"{address}EX1"))
            self.channel.read_until(lambda b: len(b) if b.endswith(b">") else 0)
            self.channel.discard_input(0.02)
            try:
                status = self.query(f"{address}R")
            except LostReply as exc:
                raise LinkError(f"no answer from device {address}: {exc}. Check the port, the baud rate "
                                f"({self.settings.baudrate}), the address and that echo is on (SSA0).",
                                "nothing was changed on the device") from None
            states.append(f"device {address}: {R_MEANING.get(status[0] if status else '', 'no status')}")
        return "; ".join(states)

    def goodbye(self) -> None:
        pass

    # -- download --------------------------------------------------------------------------
    def plan(self, lines) -> list[Step]:
        lines = list(lines)
        chain = self.addresses([Step(line.text.strip()) for line in lines])
        steps: list[Step] = []
        defining = False
        opened: tuple = ()   # the sources of the XD that opened the sequence being defined
        for number, line in enumerate(lines, 1):
            text = line.text.strip()
            if not text or text.startswith(";"):
                continue
            address, word, _rest = split(text)
            if word == "XD":
                defining, opened = True, line.sources
                steps.append(Step(text, "send", line.sources, False, number))
            elif word == "XT":
                defining = False
                steps.append(Step(text, "send", line.sources, False, number))
                for device in [address] if address else chain:  # XSD is device specific (L181)
                    steps.append(Step(f"{device}XSD", "verify", tuple(opened) + tuple(line.sources), False, number))
            elif defining:
                steps.append(Step(text, "send", line.sources, True, number))
            elif word in SAVE_MNEMONICS:
                steps.append(Step(text, "save", line.sources, False, number))
            elif word in RUN_MNEMONICS:
                steps.append(Step(text, "run", line.sources, False, number))
            else:
                steps.append(Step(text, "send", line.sources, False, number))
        return steps

    def check_step(self, step: Step, reply: Reply) -> None:
        """Raise DeviceError when a download-status report says the sequence was not stored."""
        if step.kind == "verify" and split(step.command)[1] == "XSD":
            code = reply.lines[-1].strip() if reply.lines else ""
            if code != "0":
                reply.ok = False
                reply.error = code or "none"
                reply.meaning = XSD_MEANING.get(code, "no XSD report")
                raise DeviceError(reply)

    def save_command(self, steps: list[Step]) -> list[str]:
        return [f"{a}SV" for a in self.addresses(steps)]

    def run_commands(self, steps: list[Step]) -> list[str]:
        return [s.command for s in steps if s.kind == "run"]

    def after_failure(self, steps_sent: list[Step], failed: Step | None) -> str:
        opened = None
        for step in steps_sent + ([failed] if failed else []):
            word = split(step.command)[1]
            opened = step if word == "XD" else None if word == "XT" else opened
        if opened is not None:
            address = split(opened.command)[0]
            try:
                self.transact(f"{address}XT")
                number = split(opened.command)[2]
                self.transact(f"{address}XE{number}")
                return f"the unfinished sequence {number} was closed (XT) and erased (XE{number})"
            except (LostReply, LinkError):
                return "a sequence definition may still be open: send XT"
        return ""

    def sequences(self, steps: list[Step]) -> dict[tuple[str, str], list[str]]:
        """(address, number) -> the stored commands of each sequence the download defines."""
        found: dict[tuple[str, str], list[str]] = {}
        current = None
        for step in steps:
            address, word, rest = split(step.command)
            if word == "XD":
                current = (address, rest.strip())
                found[current] = []
            elif word == "XT":
                current = None
            elif current is not None and step.stored:
                found[current].append(step.command)
        return found

    def read_sequence(self, address: str, number: str) -> list[str] | None:
        """The commands of sequence `number` from `XU` (None when XSS says it does not exist)."""
        exists = self.query(f"{address}XSS{number}")
        if not exists or exists[-1].strip() != "2":
            return None
        body, inside = [], False
        for line in self.query(f"{address}XU{number}"):
            word = split(line.strip())[1]
            if word == "XD":
                inside = True
            elif word == "XT":
                inside = False
            elif inside:
                body.append(line.strip())
        return body

    def verify(self, steps: list[Step]) -> tuple[list[Mismatch], str]:
        mismatches = []
        held = []
        chain = self.addresses(steps)
        stored = [((device, number), sent) for (address, number), sent in self.sequences(steps).items()
                  for device in ([address] if address else chain)]  # an unaddressed XD: every device
        for (address, number), sent in stored:
            found = self.read_sequence(address, number)
            if found is None:
                mismatches.append(Mismatch(f"device {address} sequence {number}", "stored", "missing (XSS 0)"))
                continue
            held.append(f"{address}:{number}")
            if not found and sent:
                mismatches.append(Mismatch(f"device {address} sequence {number}", f"{len(sent)} commands",
                                           "nothing from XU (password protected? pass --password)"))
                continue
            for i, (a, b) in enumerate(zip(sent, found), 1):
                if a.replace(" ", "") != b.replace(" ", ""):
                    mismatches.append(Mismatch(f"device {address} sequence {number} command {i}", a, b))
            if len(found) != len(sent):
                mismatches.append(Mismatch(f"device {address} sequence {number} length",
                                           str(len(sent)), str(len(found))))
        for address in self.addresses(steps):
            status = self.query(f"{address}R")
            code = status[-1].strip() if status else ""
            if code not in ("*R", "*B"):
                mismatches.append(Mismatch(f"device {address} status (R)", "*R (ready, no error)",
                                           f"{code or 'nothing'} ({R_MEANING.get(code, 'unknown')})"))
        return mismatches, "sequences held: " + (", ".join(held) or "none")

    def status(self) -> dict:
        address = self.settings.address or "1"
        return {"R": (self.query(f"{address}R") or [""])[-1], "XSR": (self.query(f"{address}XSR") or [""])[-1]}

    # -- upload ----------------------------------------------------------------------------
    def upload(self, password: str = "", addresses: list[str] | None = None) -> str:
        """Every stored sequence of each device as `XE n` / `XD n` ... `XT`, which `mcc check` reads."""
        out = []
        for address in addresses or [self.settings.address or "1"]:
            if password:
                self.transact(f"{address}PASS{password}")
            for number in range(1, 65):
                body = self.read_sequence(address, str(number))
                if body is None:
                    continue
                if not body:
                    raise LinkError(f"device {address} holds sequence {number} but XU returned nothing: "
                                    "upload is password protected (PASS); pass --password NNNN",
                                    "nothing was changed on the device")
                out += [f"{address}XE{number}", f"{address}XD{number}", *body, f"{address}XT"]
            if password:
                self.transact(f"{address}PASS{password}")
        return "\n".join(out) + "\n" if out else ""


# -- what the link asks of the dialect (link/protocols.py) ------------------------------------
def explain_code(code: str) -> str:
    return explain(code) or f"{code}: not a documented X150 report code"


def describe(reply: Reply) -> str | None:
    """A single report line (`*R`, an XSD code) with its meaning."""
    data = " | ".join(reply.lines)
    words = explain(reply.lines[-1].strip())
    return f"{data}  ({words})" if words and len(reply.lines) == 1 else data or "ok"


def upload(proto: Protocol, password: str, addresses: list[str] | None) -> str:
    """Every stored sequence of the devices at `addresses`, after the password if one is given."""
    return proto.upload(password, addresses)
