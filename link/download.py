"""A download from start to end, the same for every dialect: plan, send, verify, then save and run.

The order is the safety argument: nothing is saved or run before what the device holds has been
read back and compared with what was sent, and every way out (a device error, a lost or garbled
reply, a closed port, a mismatch) ends with `device_state` saying what is on the device.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from mcc.link.errors import LinkError
from mcc.link.protocol import DeviceError, LostReply, Mismatch, Step


@dataclass
class DownloadReport:
    ok: bool = False
    message: str = ""
    device: str = ""               # what the device said it is (hello)
    device_state: str = ""         # what is on the device now
    steps: list[Step] = field(default_factory=list)
    sent: int = 0                  # steps acknowledged by the device
    failed: Step | None = None     # the step the device refused or did not answer
    error: str = ""                # the device's error code (or lost/garbled)
    meaning: str = ""
    mismatches: list[Mismatch] = field(default_factory=list)
    verified: bool = False
    saved: bool = False
    ran: bool = False
    status: dict = field(default_factory=dict)
    held_back: list[str] = field(default_factory=list)

    def to_json(self) -> dict:
        return {
            "ok": self.ok, "message": self.message, "device": self.device, "device_state": self.device_state,
            "steps": len(self.steps), "sent": self.sent,
            "failed": self.failed.to_json() if self.failed else None,
            "error": self.error, "meaning": self.meaning,
            "mismatches": [vars(m) for m in self.mismatches],
            "verified": self.verified, "saved": self.saved, "ran": self.ran, "status": self.status,
            "held_back": self.held_back,
        }


def download(proto, steps: list[Step], save: bool, run: bool,
             progress: Callable[[int], None] | None = None) -> DownloadReport:
    """Send `steps` through the connected protocol `proto` and return what happened."""
    report = DownloadReport(steps=steps)
    sent: list[Step] = []
    current: list[Step] = []   # the step being sent (one at most), so that a failure names it
    try:
        report.device = proto.hello(steps)
        for step in steps:
            if step.kind in ("save", "run"):
                continue
            current[:] = [step]
            reply = proto.transact(step.command, retry=not step.stored)
            if not reply.ok:
                raise DeviceError(reply)
            proto.check_step(step, reply)
            current.clear()
            sent.append(step)
            report.sent = len(sent)
            if progress:
                progress(1)
        report.mismatches, held = proto.verify(steps)
        report.verified = not report.mismatches
        if report.mismatches:
            report.message = "the device does not hold what was sent"
            report.device_state = f"{held}; it differs from the download (not saved, not run)"
            return report
        save_commands = proto.save_command(steps)
        held_save = [s.command for s in steps if s.kind == "save"]
        if save:
            for command in save_commands:
                expect_ok(proto, command)
            report.saved = bool(save_commands)
        elif held_save:
            report.held_back += held_save
        runs = proto.run_commands(steps)
        if run:
            for command in runs:
                expect_ok(proto, command)
            report.ran = bool(runs)
            report.status = proto.status()
        else:
            report.held_back += [s.command for s in steps if s.kind == "run"]
        proto.goodbye()
        report.ok = True
        report.message = "downloaded and verified"
        state = [held, "saved" if report.saved else proto.unsaved_note]
        if report.ran:
            state.append("running")
        report.device_state = "; ".join(state)
        return report
    except DeviceError as exc:
        report.failed = current[0] if current else Step(exc.reply.command)
        report.error, report.meaning = exc.reply.error, exc.reply.meaning
        report.message = f"the device refused `{exc.reply.command}`"
    except LostReply as exc:
        report.failed = current[0] if current else Step(exc.command)
        report.error = "garbled" if exc.garbled else "lost"
        report.meaning = (f"the reply did not match what was sent (received {exc.received!r})" if exc.garbled
                          else f"no complete reply within {proto.settings.timeout:g} s (received {exc.received!r})"
                          + ("; not resent, because a stored line could be stored twice" if report.failed.stored
                             else f" after {proto.settings.retries} retries"))
        report.message = f"the reply to `{exc.command}` was {report.error}"
    except KeyboardInterrupt:
        report.message = "interrupted (Ctrl-C)"
        report.error = "interrupted"
        report.failed = current[0] if current else None
        report.device_state = describe_partial(sent, report.failed, True, flash(proto)) + (
            "; interrupted before the read-back" if not report.verified else "")
        return report
    except LinkError as exc:
        report.message = exc.message
        report.error = "port"
        report.failed = current[0] if current else None
        report.device_state = exc.device_state or describe_partial(sent, report.failed, True, flash(proto))
        if not report.verified and sent:
            report.device_state += "; the port closed, so mcc could not read back what the device holds"
        return report
    cleanup = ""
    try:
        cleanup = proto.after_failure(sent, report.failed)
    except (LinkError, LostReply, DeviceError):
        cleanup = "mcc could not read back what the device holds"
    try:
        proto.goodbye()   # e.g. restore the MCode echo mode the drive was in
    except (LinkError, LostReply, DeviceError):
        pass
    uncertain = report.error in ("lost", "garbled")
    report.device_state = describe_partial(sent, report.failed, uncertain, flash(proto)) + (
        f"; {cleanup}" if cleanup else "")
    return report


def expect_ok(proto, command: str) -> None:
    reply = proto.transact(command)
    if not reply.ok:
        raise DeviceError(reply)


def flash(proto) -> bool:
    """Whether the device writes each downloaded line to non-volatile memory at once (Arcus, L844)."""
    return getattr(proto, "writes_to_flash", False)


def describe_partial(sent: list[Step], failed: Step | None, uncertain: bool, to_flash: bool = False) -> str:
    """What is on the device after a download that stopped part way."""
    if not sent:
        return "nothing of this download was accepted by the device"
    last = sent[-1]
    stored = sum(1 for s in sent if s.stored)
    where = ", ".join(sorted({f"{s.file}:{s.line}" for s in last.sources})) or f"listing line {last.line}"
    kept = "written to flash as they arrived" if to_flash else "NOT saved"
    cleared = [s.command for s in sent if s.kind == "clear"]
    text = (f"partly written and {kept}: "
            + (f"what the device held before was cleared (`{cleared[0]}`); " if cleared else "")
            + f"the device accepted {len(sent)} commands "
            f"({stored} stored program lines), the last one `{last.command}` from {where}")
    if failed is not None and failed.kind != "verify":
        text += (f"; `{failed.command}` may have reached the device" if uncertain
                 else f"; `{failed.command}` was refused")
    return text + "; run the download again (it clears what this one left)"
