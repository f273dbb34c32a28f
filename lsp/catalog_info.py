"""Catalog entries as the editor shows them: availability on the file's target, hover text,
completion snippets. Reads the generic catalog (`mcc.compiler.catalog`), one table per dialect."""

from __future__ import annotations

import re
from functools import lru_cache

from mcc.compiler import catalog as generic
from mcc.compiler.catalog import Entry

UNAVAILABLE_KINDS = {"other-product", "ascii-only", "operator", "reserved", "comment"}
PLACEHOLDER = re.compile(r"<([^<>]+)>")


def version(text: str) -> tuple[int, ...]:
    return tuple(int(p) for p in re.findall(r"\d+", str(text))) or (0,)


def availability(entry: Entry, profile) -> tuple[bool, str]:
    """(available, why) for the profile's product and firmware."""
    if profile is None:
        return True, ""
    product, firmware = profile.product, profile.firmware
    title = getattr(profile, "title", "") or product
    if entry.kind in ("other-product", "ascii-only"):
        return False, f"not part of the {title} standalone language ({entry.kind})"
    products = entry.products
    needed = entry.get("firmware", "")
    if isinstance(products, dict):
        if product not in products:
            return False, f"not available on {product}: only on {', '.join(sorted(products))}"
        needed = products[product] or needed
    elif isinstance(products, (list, tuple)) and products and product not in products:
        return False, f"not available on {product}: only on {', '.join(products)}"
    if needed and firmware and version(firmware) < version(needed):
        return False, f"needs firmware {needed}; the target {profile.name} has {firmware}"
    return True, f"available on {product}" + (f" (firmware {needed}+)" if needed else "")


def hover_markdown(entry: Entry, profile, spelled: str = "") -> str:
    name = spelled or entry.name
    lines = [f"**{name}** — {entry.title}" + (f" *({entry.kind})*" if entry.kind else "")]
    if entry.summary:
        lines += ["", entry.summary]
    if entry.syntax:
        lines += ["", "```", *entry.syntax, "```"]
    facts = []
    if entry.range:
        facts.append(f"range: {entry.range[0]} … {entry.range[1]}" + (f" {entry.unit}" if entry.unit else ""))
    elif entry.unit:
        facts.append(f"unit: {entry.unit}")
    if entry.default is not None:
        facts.append(f"default: {entry.default}")
    access, mode = entry.get("access", ""), entry.get("mode", "")
    if access:
        facts.append(f"access: {access}")
    if mode:
        facts.append(f"mode: {mode}")
    if entry.get("exec"):
        facts.append(f"execution: {entry.get('attributes') or entry.get('exec')}")
    ok, why = availability(entry, profile)
    if profile is not None:
        facts.append(("✓ " if ok else "✗ ") + why + f" (target {profile.name})")
    if entry.manual:
        facts.append(f"manual: {entry.manual}")
    if facts:
        lines += [""] + [f"- {fact}" for fact in facts]
    if entry.notes:
        lines += ["", f"*Note:* {entry.notes}"]
    return "\n".join(lines)


def snippet(entry: Entry) -> tuple[str, str]:
    """(insert text as an LSP snippet, the syntax it came from) for a command: each placeholder of
    its first syntax a tab stop (a dialect's editor may write its own, lsp/editor.py)."""
    syntax = entry.syntax[0] if entry.syntax else entry.name
    counter = 0

    def field(match: re.Match) -> str:
        nonlocal counter
        counter += 1
        return "${" + str(counter) + ":" + escape(match.group(1)) + "}"

    text = PLACEHOLDER.sub(field, escape_outside(syntax))
    return text, syntax


def escape(text: str) -> str:
    return text.replace("\\", "\\\\").replace("$", "\\$").replace("}", "\\}")


def escape_outside(text: str) -> str:
    """Escape snippet syntax outside <placeholders> (which are replaced afterwards)."""
    return text.replace("\\", "\\\\").replace("$", "\\$")


@lru_cache(maxsize=None)
def entries(dialect: str) -> tuple[Entry, ...]:
    return generic.load(dialect).entries


def lookup(dialect: str, name: str) -> Entry | None:
    upper = name.upper()
    for entry in entries(dialect):
        if entry.name.upper() == upper:
            return entry
    return None
