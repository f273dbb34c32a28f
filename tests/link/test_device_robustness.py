"""A virtual device answers whatever arrives on the line (noise included) without failing, so that a
host's mistakes show as protocol replies, never as a dead connection."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from mcc.link.device.arcus import ArcusDevice
from mcc.link.device.mcode import MCodeDevice
from mcc.link.device.x150 import X150Device

WORDS = ["PG 1", "PG", "LB AA", "VA QQ=3", "PR QQ", "L", "CP 1", "S", "EX AA", "EM=1", "CK=1", "PY=1", "ER=0",
         "1XD1", "1XT", "1XU", "1XSD", "1PASS1234", "1SV", "@00SR=1", "@00SA0=ABS", "@00V1=5", "@00SASTAT"]
LINES = st.lists(st.one_of(st.sampled_from(WORDS), st.text(max_size=20)), max_size=25)


@settings(max_examples=60, deadline=None)
@given(LINES, st.sampled_from(["\r", "\n"]))
def test_devices_answer_any_line_without_failing(lines, end):
    for device in (MCodeDevice(), X150Device(), ArcusDevice()):
        for line in lines:
            reply = device.feed((line + end).encode("utf-8", "replace"))
            assert isinstance(reply, bytes)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.binary(max_size=30), max_size=20))
def test_devices_survive_raw_noise(chunks):
    for device in (MCodeDevice(), X150Device(), ArcusDevice()):
        device.feed(b"CK=1\r")   # checksum mode for the MCode drive: noise is NAKed or refused
        for chunk in chunks:
            assert isinstance(device.feed(chunk + b"\r"), bytes)


class NoisyPort:
    """A port whose device answers `noise` to everything (then nothing)."""

    def __init__(self, noise: bytes) -> None:
        self.noise = noise
        self.in_waiting = 0

    def write(self, data: bytes) -> int:
        return len(data)

    def flush(self) -> None:
        pass

    def read(self, size: int = 1) -> bytes:
        out, self.noise = self.noise[:size], self.noise[size:]
        return out

    def close(self) -> None:
        pass


@settings(max_examples=50, deadline=None)
@given(st.binary(max_size=40), st.sampled_from(["mcode", "x150", "arcus"]), st.integers(0, 2))
def test_hosts_turn_any_reply_into_a_reply_or_a_link_failure(noise, dialect, checksum):
    from mcc.link import protocols
    from mcc.link.errors import LinkError
    from mcc.link.ports import Channel
    from mcc.link.protocol import DeviceError, LostReply
    from mcc.link.settings import LinkSettings

    settings = LinkSettings(timeout=0.01, retries=1, checksum=checksum if dialect == "mcode" else 0)
    proto = protocols.get(dialect)(Channel(NoisyPort(noise), settings), settings)
    try:
        reply = proto.transact("PR P" if dialect == "mcode" else "1R" if dialect == "x150" else "SASTAT")
        assert isinstance(reply.lines, list)
    except (LostReply, DeviceError, LinkError):
        pass
