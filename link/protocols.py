"""The host protocol of a dialect, reached through its registration (`Dialect.link`,
compiler/<dialect>/dialect.py): the link never names a dialect.

A dialect's link module (link/<dialect>.py) provides, besides its `Protocol` class:
- `explain_code(code) -> str`: a device error or report number in words (`mcc terminal`'s `:explain`);
- `describe(reply) -> str | None`: words for the data of an accepted reply, or None when the data
  says enough (`mcc send`, `mcc terminal`);
- `upload(proto, password, addresses) -> str`: the program the device holds, as source mcc checks
  (`mcc upload`; a dialect without passwords or several devices ignores them).
"""

from __future__ import annotations

from mcc.compiler import dialects


def module(dialect: str):
    return dialects.get(dialect).load_link()


def get(dialect: str):
    return module(dialect).Protocol


def describe(dialect: str, reply) -> str:
    """A reply in words: data, and an error with its meaning."""
    data = " | ".join(reply.lines)
    if not reply.ok:
        return f"error {reply.error}: {reply.meaning}" + (f"  ({data})" if data else "")
    if reply.lines:
        words = module(dialect).describe(reply)
        if words is not None:
            return words
    return data or "ok"
