"""Hover: what a command is (from the catalog), where a name is defined and how often it is used,
and a motion value in physical units under the target profile."""

from __future__ import annotations

from lsprotocol import types as t

from mcc.lsp import catalog_info, model
from mcc.lsp.convert import range_of
from mcc.lsp.editor import editor_of

STEP_UNITS = ("steps", "user steps", "pulses", "motor steps")
TIME_RATES = ("", "/s", "/sec", "/s²", "/s^2")


def hover(snap, offset: int) -> t.Hover | None:
    token = snap.index.token_at(offset)
    if token is None:
        return None
    text = ""
    if token.symbol:
        text = symbol_markdown(snap, snap.index.symbols.get(token.symbol))
    elif token.entry is not None:
        spelled = snap.source.text[token.span.start:token.span.end]
        text = catalog_info.hover_markdown(token.entry, snap.profile, spelled)
    elif token.kind == model.NUMBER and token.value is not None:
        text = number_markdown(snap, token)
    if not text:
        return None
    return t.Hover(contents=t.MarkupContent(kind=t.MarkupKind.Markdown, value=text), range=range_of(token.span))


def symbol_markdown(snap, symbol: model.Symbol | None) -> str:
    if symbol is None:
        return ""
    lines = [f"**{symbol.label}** — {symbol.kind}"]
    declared = editor_of(snap.dialect).variables_declared  # else every assignment is a definition
    if symbol.definitions:
        where = ", ".join(f"line {s.line}" for s in symbol.definitions[:5])
        verb = "assigned" if symbol.kind == model.SYMBOL_VARIABLE and not declared else "defined"
        lines.append(f"- {verb} at {where}" + (" …" if len(symbol.definitions) > 5 else ""))
        first = symbol.definitions[0]
        lines += ["", "```", snap.source.line_text(first.line).strip(), "```"]
    else:
        lines.append("- not defined in this file")
    uses = len(symbol.references)
    # one count, of the occurrences find-references lists (the data flow counts operations, which
    # differ from the text: `IC Q1` both reads and writes it); the data flow adds its verdict only
    if symbol.kind != model.SYMBOL_VARIABLE or declared:  # a declared variable (MCode VA): used
        lines.append(f"- used {times(uses)}")
        if symbol.kind != model.SYMBOL_VARIABLE:
            return "\n".join(lines)
    else:  # every assignment is a definition (Arcus, X150)
        lines.append(f"- written {times(len(symbol.definitions))}, read {times(uses)}")
    lines += data_flow(snap, symbol.name, uses)
    return "\n".join(lines)


def times(count: int) -> str:
    return f"{count} time{'s' if count != 1 else ''}"


def data_flow(snap, name: str, read_in_text: int) -> list[str]:
    """What the program's data flow says of a variable: the def-use chains the check's analysis
    keeps (`compiler/symbols.py`), so the editor does not walk the program again."""
    analysis = snap.analysis
    if analysis is None:
        return []
    defuse = analysis.defuse
    key = next((n for n in (name, name.upper()) if n in defuse.defs or n in defuse.uses), None)
    if key is None:
        return []
    writes = len(defuse.defs.get(key, ()))
    uses = defuse.uses.get(key, ())
    reads = sum(not use.self_update for use in uses)
    if writes and not reads:
        own = " (read only to update itself)" if read_in_text else ""
        return [f"- data flow: its value is never read{own}"]
    if reads and not writes:
        return ["- data flow: never written in this file"]
    return []


def steps_per_rev(snap) -> float:
    """The profile's steps per revolution, scaled by the file's own microstep resolution where the
    dialect's editor names one (MCode `MS=`: the profiles give it at MS=256, a 1.8° motor)."""
    profile = snap.profile
    base = float(getattr(profile, "steps_per_rev", 0) or 0)
    editor = editor_of(snap.dialect)
    if base and editor.microstep_setting and editor.microstep_setting in snap.index.settings:
        return base * snap.index.settings[editor.microstep_setting] / editor.microstep_reference
    return base


def number_markdown(snap, token: model.Token) -> str:
    entry = token.command
    if entry is None:
        return ""
    unit = entry.unit or ""
    base = unit.split("/")[0].strip()
    per_rev = steps_per_rev(snap)
    rest = unit[len(unit.split("/")[0]):].strip()  # "/sec", "/s²", ""
    if base not in STEP_UNITS or not per_rev or rest not in TIME_RATES:
        return ""
    revs = token.value / per_rev
    name = snap.source.text[token.span.start:token.span.end]
    lines = [f"**{name} {unit}** = {revs:g} rev{rest}"]
    if rest.strip() in ("/sec", "/s"):
        lines[0] += f" = {revs * 60:g} rpm"
    setting = editor_of(snap.dialect).microstep_setting
    ms = f" at {setting}={snap.index.settings[setting]:g}" if setting and setting in snap.index.settings else ""
    lines.append(f"- {per_rev:g} {base} = 1 rev{ms} (target {snap.profile.name})")
    lines.append(f"- argument of {entry.name} ({entry.title})")
    return "\n".join(lines)
