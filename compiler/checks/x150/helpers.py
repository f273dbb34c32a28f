"""What several X150 checks share: the bytes each sequence stores (X123, X124, X141 and the memory
`mcc check` reports), and the walk of nesting through the sequence calls (X110, X140)."""

from __future__ import annotations

from dataclasses import dataclass

from mcc.compiler.checks import Program
from mcc.compiler.x150 import catalog as cat
from mcc.compiler.x150.lower import OPENERS, Site
from mcc.compiler.x150.structure import Unit


def stored_bytes(unit: Unit) -> int:
    """The bytes a sequence stores: each command in its canonical form (upper case, the device
    address in front, the B prefix on an immediate `*` command) and its delimiter, XT included
    (L241). The X150 backend writes sequences in the same form."""
    from mcc.compiler.x150.format import command_text  # format imports x150/checks (canonical_case)
    own = len(str(unit.address)) if unit.address is not None else 0  # the unit's address, written in front
    total = len("XT") + 1 + own
    for command in unit.commands:
        info = command.info
        if info is None and not command.host:
            continue
        written = command.text
        text = written if written == written.upper() else command_text(command)  # upper case: canonical
        address = str(command.address) if command.address is not None else ""
        # the address, then the body (the text after the address, if it starts with it), then the delimiter
        size = (len(address) or own) + (len(text) - len(address) if text.startswith(address) else len(text)) + 1
        if info is not None and info.b_prefixable and not command.buffered:
            size += 1  # the B prefix
        total += size
    return total


@dataclass(frozen=True)
class Limits:
    store: int  # the sequence store of one device (L4871)
    buffer: int  # the command buffer a sequence is downloaded through (L241, L4904)
    buffer_ratio: float  # X124 from this share of the buffer (x150.buffer_warn_ratio)
    store_ratio: float  # X141 from this share of the store (x150.store_warn_ratio)


def limits(program: Program) -> Limits:
    profile = program.profile
    catalog = cat.load()
    return Limits(int(profile.get("limits.sequence_store_bytes", catalog.limit("sequence_store_bytes", default=8000))),
                  int(profile.get("limits.command_buffer_bytes", catalog.limit("command_buffer_bytes", default=2000))),
                  float(profile.get("x150.buffer_warn_ratio", 0.9)), float(profile.get("x150.store_warn_ratio", 0.9)))


def sizes(program: Program) -> list[tuple[Unit, int]]:
    """(unit, bytes) of every sequence definition, in file order (found once per program)."""
    return program.shared("x150:sizes", lambda: [(unit, stored_bytes(unit)) for unit in program.lowering.units
                                                  if unit.is_sequence and unit.start is not None])


def latest(program: Program) -> dict[tuple[int, int | None], tuple[Unit, int]]:
    """(number, device) -> the last definition of that sequence for that device, and its bytes:
    a later XDn replaces the earlier one in the store."""
    found: dict[tuple[int, int | None], tuple[Unit, int]] = {}
    for unit, size in sizes(program):
        found[(unit.number or 0, unit.address)] = (unit, size)
    return found


@dataclass(frozen=True)
class Store:
    """The sequences of one device (or of each device, when none is addressed) in file order:
    `total` bytes up to `unit`, sequence `number`; `full` when that one no longer fits."""

    who: str
    number: int
    unit: Unit
    total: int
    full: bool


def stores(program: Program) -> list[Store]:
    """Per device: where its sequences overflow the store, else what they fill with the last one."""

    def walk() -> list[Store]:
        store = limits(program).store
        defined = latest(program)
        devices = sorted({address for _, address in defined if address is not None})
        found = []
        for device in devices or [None]:
            total = 0
            last = None
            who = f"device {device}" if device is not None else "each device"
            for (number, address), (unit, size) in sorted(defined.items(), key=lambda kv: kv[1][0].start.span.start):
                if address is not None and address != device:
                    continue
                total += size
                last = Store(who, number, unit, total, total > store)
                if last.full:
                    break
            if last is not None:
                found.append(last)
        return found

    return program.shared("x150:stores", walk)


def memory(program: Program) -> dict:
    """The sequence memory `mcc check --format json` and the editor show."""
    found = limits(program)
    per_device: dict[str, int] = {}
    defined = latest(program)
    for (_, address), (_, size) in defined.items():
        key = str(address) if address is not None else "*"
        per_device[key] = per_device.get(key, 0) + size
    return {"unit": "bytes", "used": max(per_device.values(), default=0), "budget": found.store,
            "by_device": per_device, "command_buffer": found.buffer,
            "largest_sequence": max((size for _, size in defined.values()), default=0)}


@dataclass(frozen=True)
class Nesting:
    """A call `site` runs sequence `target` with `context` open around it (constructs per kind and
    "call" for the calls), the target itself opening `inside` (its own deepest constructs)."""

    site: Site
    target: str
    context: dict[str, int]
    inside: dict[str, int]


def nesting(program: Program) -> list[Nesting]:
    """Every rise of what is open around a called sequence, found by following the calls of the
    file from the sequences nothing calls (a fixpoint; depths stop at the limit + 1, so recursion
    ends). Sequence calls nest at most 16 deep (L1750, L5140)."""

    def walk() -> list[Nesting]:
        lowering = program.lowering
        limit = lowering.nesting
        kinds = tuple(OPENERS.values())
        entry: dict[str, dict[str, int]] = {}
        calls = [s for s in lowering.sites if s.kind == "call" and s.targets]
        by_routine: dict[str, list[Site]] = {}
        for site in calls:
            by_routine.setdefault(site.routine, []).append(site)
        called = {t for s in calls for t in s.targets}
        work = [r.name for r in lowering.module.routines if r.name not in called]
        for name in work:
            entry[name] = {k: 0 for k in kinds + ("call",)}
        found = []
        while work:
            name = work.pop()
            here = entry[name]
            for site in by_routine.get(name, ()):
                for target in site.targets:
                    nested = {k: min(limit + 1, here[k] + site.depth.get(k, 0)) for k in kinds}
                    nested["call"] = min(limit + 1, here["call"] + 1)
                    old = entry.get(target)
                    if old is not None and all(nested[k] <= old[k] for k in nested):
                        continue
                    merged = {k: max(nested[k], old[k]) if old else nested[k] for k in nested}
                    entry[target] = merged
                    work.append(target)
                    found.append(Nesting(site, target, merged, lowering.max_depth.get(target, {})))
        return found

    return program.shared("x150:nesting", walk)
