"""The X150/X150E backend: IR → the command stream a host sends to the controllers.

The text is the canonical form written by `writer.py` (which depends on the IR, the shared
structurer and the X150 catalog only, never on a syntax tree): the immediate stream in order, each
sequence as `XEn XDn ... XT` with its structured constructs rebuilt from the CFG, device addresses
in front, the B prefix on immediate `*` commands inside sequences, `XP`/`XFK`/`XWHEN` and `SV`
where the program has them. A program of another dialect starts with a comment block stating the
assumptions of the conversion (steps per revolution, default modes, axes). The statistics count the
sequence memory: every stored character and its delimiter is one byte (L241), against the
8,000-byte sequence store of each device (L4871).
"""

from __future__ import annotations

from mcc.backends.listing import Listing, axis_sets_written
from mcc.compiler.x150 import naming
from mcc.backends.x150.writer import write
from mcc.compiler import in_force, ir
from mcc.compiler.profiles import Profile

DIALECT = "x150"


def emit(module: ir.Module, profile: Profile) -> Listing:
    module = in_force.with_source_power_up(module, profile)  # the source's power-up speeds where ours differ
    module, refused = axis_sets_written(module, DIALECT, "X150")  # an axis's own speeds as X150 applies them
    if refused is not None:
        return refused
    written = write(module, profile)
    listing = Listing(DIALECT)
    for line in written.header:
        listing.emit(line)
    for line in written.lines:
        listing.emit(line.text, *line.sources)
    listing.diagnostics.extend(written.diagnostics)
    per_device: dict[str, int] = {}
    for name, size in written.sequence_bytes.items():
        device = naming.device_of(name)
        key = str(device) if device is not None else "*"
        per_device[key] = per_device.get(key, 0) + size
    budget = int(profile.get("limits.sequence_store_bytes", 8000))
    listing.stats = {
        "lines": len(listing.lines),
        "bytes": sum(len(line.text) + 1 for line in listing.lines),
        "sequences": len(written.sequence_bytes),
        "sequence_bytes": sum(written.sequence_bytes.values()),
        "sequence_budget": budget,
        "sequence_bytes_by_device": per_device,
        "command_buffer": int(profile.get("limits.command_buffer_bytes", 2000)),
    }
    listing.header = (f"; X150 listing for profile {profile.name}: {listing.stats['sequences']} sequence(s), "
                      f"{listing.stats['sequence_bytes']} of {budget} bytes of sequence memory "
                      "(1 byte per character and delimiter, L241)")
    return listing
