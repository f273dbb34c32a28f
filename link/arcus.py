"""Arcus PMX-4EX-SA ASCII host protocol over RS-485 (manual L924-L940, table L1492-L1715).

A command is `@<device><command>` and CR; the reply is one line ending in CR: `OK`, a value, or
`?<message>` for an invalid command (L1494). The standalone program is compiled by the vendor's
Windows software into assembly lines whose format the manual does not document (L1109, SAn
L1642-L1645): mcc cannot turn a .prg into what the controller stores. What the protocol does
document, mcc does: read and write the compiled lines as they are (`SAn`, `SAn=value`, so a
controller's program can be saved to an image file and put back), run and stop it (`SR`),
read its status (`SASTAT`, `SPC`) and read and write the variables V0-V63.
"""

from __future__ import annotations

import re
import time

from mcc.link.errors import LinkError
from mcc.link.ports import Channel
from mcc.link.protocol import DeviceError, LostReply, Mismatch, Reply, Step

PROGRAM_LINES = 3230  # assembly lines of program memory (L827; SPC 0..3229, L1635)
VARIABLES = 64        # V0..V63 (L1703-L1706)
SASTAT = {"0": "stopped", "1": "running", "2": "paused", "4": "in error"}
IMAGE_LINE = re.compile(r"^SA(\d+)=(.*)$")
NOT_DOWNLOADABLE = (
    "a .prg cannot be downloaded by mcc: the controller stores a standalone program only as the "
    "\"assembly level code\" that the Arcus Windows software compiles it into (manual L1105-L1112; "
    "memory is counted in those lines, L827-L829), and the manual does not document that code: SAn "
    "reads and SAn=value writes a \"single line of compiled code\" whose format is never given "
    "(L1642-L1645). Instead, open the .prg in the Arcus Windows software (\"Program and Control "
    "Software\", manual section 12), click Compile, then Download; mcc can then run and stop it "
    "(mcc send SR=1 / SR=0), read its status and variables, save it to an image (mcc upload --image "
    "FILE.sa) and put that image on other controllers, verified line by line (mcc download FILE.sa).")


class Protocol:
    dialect = "arcus"
    writes_to_flash = True   # "the program is immediately written on the flash memory" (L844)
    unsaved_note = "written to flash as downloaded (L844)"

    def __init__(self, channel: Channel | None, settings) -> None:
        self.channel = channel
        self.settings = settings

    def frame(self, command: str) -> bytes:
        return f"@{self.settings.address or '00'}{command}{self.settings.terminator}".encode("latin-1")

    @staticmethod
    def end(buffer: bytes) -> int:
        for mark in (b"\r", b"\x00"):
            at = buffer.find(mark)
            if at >= 0:
                return at + 1
        return 0

    def transact(self, command: str, retry: bool = True) -> Reply:
        assert self.channel is not None
        last = None
        for attempt in range(1 + self.settings.retries):
            if self.settings.pace:
                time.sleep(self.settings.pace)
            self.channel.send(self.frame(command))
            raw, complete = self.channel.read_until(self.end)
            if not complete:
                last = LostReply(command, raw)
                self.channel.discard_input()
                if retry and attempt < self.settings.retries:
                    continue
                raise last
            text = raw.rstrip(b"\r\x00").decode("latin-1")
            if text.startswith("?"):
                return Reply(command, False, [], error=text[1:] or "?", meaning=text[1:], raw=raw)
            if not all(32 <= ord(c) < 127 for c in text):
                self.channel.discard_input()
                raise LostReply(command, raw, garbled=True)
            return Reply(command, True, [text], raw=raw)
        raise last

    def query(self, command: str) -> list[str]:
        reply = self.transact(command)
        if not reply.ok:
            raise DeviceError(reply)
        return reply.lines

    def hello(self, steps=None) -> str:
        assert self.channel is not None
        self.channel.discard_input()
        try:
            version = self.query("VER")[0]
            state = SASTAT.get(self.query("SASTAT")[0], "unknown")
        except LostReply as exc:
            raise LinkError(f"no answer from device {self.settings.address or '00'}: {exc}. Check the port, "
                            f"the baud rate ({self.settings.baudrate}) and the device number (DN).",
                            "nothing was changed on the device") from None
        return f"version {version}, standalone program {state}"

    def goodbye(self) -> None:
        pass

    # -- download of a program image -------------------------------------------------------
    def plan_image(self, text: str, path: str) -> list[Step]:
        """The steps of an image file: one `SAn=value` line per compiled line (from mcc upload)."""
        from mcc.compiler.span import Span

        steps = [Step("SR=0", "clear")]
        for number, line in enumerate(text.splitlines(), 1):
            if not line.strip() or line.startswith(";"):
                continue
            match = IMAGE_LINE.match(line.strip())
            if not match or int(match.group(1)) >= PROGRAM_LINES:
                raise LinkError(f"{path}:{number}: not a program image line (expected SAn=value with n "
                                f"0-{PROGRAM_LINES - 1}, as written by mcc upload --image): {line.strip()}",
                                "nothing was sent")
            steps.append(Step(line.strip(), "send", (Span(path, number, 1, number, len(line) + 1, 0, 0),),
                              True, number))
        return steps

    def check_step(self, step: Step, reply: Reply) -> None:
        pass

    def save_command(self, steps) -> list[str]:
        return []  # the program is written to flash as it is downloaded (L844, L1032)

    def run_commands(self, steps) -> list[str]:
        return ["SR=1"]

    def after_failure(self, steps_sent, failed) -> str:
        """Read back the compiled lines the download wrote, so that the report names them."""
        good = 0
        for step in steps_sent:
            if step.stored:
                match = IMAGE_LINE.match(step.command)
                if self.read_line(int(match.group(1))) != match.group(2):
                    break
                good += 1
        return (f"{good} compiled lines read back as sent; the program on the controller is incomplete: "
                "do not run it (SR=1) before a complete download")

    def read_line(self, index: int) -> str:
        return self.query(f"SA{index}")[0]

    def verify(self, steps: list[Step]) -> tuple[list[Mismatch], str]:
        mismatches = []
        for step in steps:
            if not step.stored:
                continue
            match = IMAGE_LINE.match(step.command)
            found = self.read_line(int(match.group(1)))
            if found != match.group(2):
                mismatches.append(Mismatch(f"SA{match.group(1)}", match.group(2), found))
        return mismatches, f"{sum(s.stored for s in steps)} compiled lines read back"

    def status(self) -> dict:
        code = self.query("SASTAT")[0]
        return {"SASTAT": f"{code} ({SASTAT.get(code, 'undocumented')})", "SPC": self.query("SPC")[0]}

    # -- upload ----------------------------------------------------------------------------
    def image(self) -> str:
        """Every compiled line up to the first empty one, as `SAn=value` lines."""
        out = []
        for index in range(PROGRAM_LINES):
            value = self.read_line(index)
            if not value.strip() or value.strip() == "OK":
                break
            out.append(f"SA{index}={value}")
        return "\n".join(out) + "\n" if out else ""

    def upload(self) -> str:
        """The variables V0-V63 as a .prg that sets them (what the protocol can read of a program)."""
        values = [(n, self.query(f"V{n}")[0]) for n in range(VARIABLES)]
        body = [f"V{n}={value}" for n, value in values if value not in ("0", "0.0")]
        header = ["; variables read from the controller with the ASCII protocol (V0-V63; those not listed are 0).",
                  "; The standalone program itself is compiled code whose format is not documented: use",
                  "; mcc upload --image FILE to save it as an image that mcc download can put back."]
        return "\n".join([*header, *body, "END"]) + "\n"


# -- what the link asks of the dialect (link/protocols.py) ------------------------------------
def explain_code(code: str) -> str:
    return f"SASTAT {code}: {SASTAT.get(code, 'undocumented')}"


def describe(reply: Reply) -> str | None:
    """SASTAT's number with its meaning."""
    if reply.command.upper() != "SASTAT":
        return None
    data = " | ".join(reply.lines)
    return f"{data}  ({SASTAT.get(data, 'undocumented')})"


def upload(proto: Protocol, password: str, addresses: list[str] | None) -> str:
    """The variables V0-V63 (no password, one controller)."""
    return proto.upload()
