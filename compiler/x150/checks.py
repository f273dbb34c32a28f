"""The X150 checks: per command (policy, addresses, products, values, text) and whole program
(definitions, transfers, nesting through the call graph, sequence memory).

The syntax problems are reported while reading (parser.py, tokens.py) and the structural ones
(XD/XT, unbalanced constructs, local nesting) while lowering (structure.py, lower.py). Everything
here only produces diagnostics.
"""

from __future__ import annotations

import re
from functools import lru_cache

from mcc.compiler.cancel import checkpoint
from mcc.compiler.diagnostics import Diagnostics, Edit, Fix, Severity
from mcc.compiler.profiles import Profile
from mcc.compiler.span import Span
from mcc.compiler.x150 import catalog as cat
from mcc.compiler.x150 import naming
from mcc.compiler.x150 import syntax as st
from mcc.compiler.x150.lower import OPENERS, Lowering, Site
from mcc.compiler.x150.structure import Unit

PRODUCT_NAMES = {"bdhxe": "BDHX-E", "pdhxe": "PDHX-E", "blhx": "BLHX", "pdhx": "PDHX", "x150ds": "X150DS"}
QUOTED = re.compile(r'"[^"]*"?')
QUOTE_ASCII = (33, 126)  # the quote command sends ASCII 33-126 only (L5593)
UNMARKED = {
    "unstated": "is buffered, but the manual does not say whether it can be saved in a sequence",
    "conflict": "has contradictory attributes in the manual",
    "unknown": "has no documented attributes",
}


@lru_cache(maxsize=None)
def version(text: str) -> tuple[int, ...]:
    return tuple(int(part) for part in re.findall(r"[0-9]+", str(text)))


def insert_at(span: Span) -> Span:
    return Span(span.file, span.line, span.column, span.line, span.column, span.start, span.start)


class Checker:
    def __init__(self, lowering: Lowering, profile: Profile, diags: Diagnostics):
        self.lowering = lowering
        self.profile = profile
        self.diags = diags
        self.cat = cat.load()
        low, high = profile.get("limits.addresses", [1, 16])
        self.addresses = (int(low), int(high))
        self.nesting = lowering.nesting
        self.memory: dict = {}  # sequence memory, for `mcc check --format json` and the editor
        self.case_policy = profile.get("x150.case", "warn")  # asked once, not for every command
        self.max_variable = int(self.cat.limit("variables", "max", 50))
        self.product_notes: dict[cat.Command, str | None] = {}  # see check_product

    def run(self) -> None:
        for unit in self.lowering.units:
            checkpoint()  # the editor server abandons a stale analysis here (compiler/cancel.py)
            self.check_unit(unit)
        self.check_saved()
        self.check_transfers()
        self.check_call_nesting()
        self.check_memory()

    # -- per command -------------------------------------------------------------------------------
    def check_unit(self, unit: Unit) -> None:
        device = unit.device()
        outside = [c for c in (unit.erase, unit.start) if c is not None]
        body = unit.commands + ([unit.end] if unit.end is not None else [])
        # Each check is called only for the commands it can concern (the tests it starts with),
        # in the same order: a program has tens of thousands of commands.
        case = self.case_policy != "ignore"
        products = self.profile.product in PRODUCT_NAMES
        low, high = self.addresses
        notes = self.product_notes
        for command in outside + body:
            info = command.info
            host = command.host
            if info is None and not host:
                continue
            # An upper-case text is its own canonical form (`canonical_case` upper-cases parts of it).
            if case and not host and command.text != command.text.upper():
                self.check_case(command)
            if not host:
                address = command.address
                if address is not None:  # nothing to say about an address in range on a command that takes one
                    if not (low <= address <= high and info.address != "none"):
                        self.check_address(command, device)
                elif info.address == "D":
                    self.check_address(command, device)
            # (a command whose note is known to be None has nothing to report)
            if products and info is not None and info.products is not None and notes.get(info, "") is not None:
                self.check_product(command)
            if info is not None and command.arg is not None:
                self.check_values(command)
        if not unit.is_sequence:
            return
        if unit.erase is None and unit.number is not None:
            self.missing_erase(unit)
        if unit.address is not None:
            for command in body:  # (nothing to say about a command for the sequence's own device)
                if command.info is not None and not command.host and command.address != unit.address:
                    self.check_device(command, unit)
        for command in unit.commands:
            if command.host or (command.info is not None and not command.buffered
                                and command.info.policy != "allow"):
                self.check_policy(command, unit)

    def check_case(self, command: st.Command) -> None:
        policy = self.case_policy
        if policy == "ignore" or command.host:
            return
        fixed = canonical_case(command)
        if fixed == command.text:
            return
        severity = Severity.ERROR if policy == "error" else None
        self.diags.add("X102", command.span, f"'{command.text}' is not upper case: the manual writes every command in "
                                             "upper case (L116, L126) and never says the controller accepts lower "
                                             f"case; write {fixed}",
                       severity=severity,
                       fix=Fix("write in upper case", (Edit(command.span, fixed),))
                       if not command.rejoined else None)

    def check_address(self, command: st.Command, device: int | None) -> None:
        info = command.info
        if command.host:
            return
        if command.address is not None:
            low, high = self.addresses
            if info.address == "none":
                self.diags.add("X118", command.address_span,
                               f"{command.mnemonic} cannot take a device address: it always resets every device "
                               "(L181, L5519); remove the address")
            elif not low <= command.address <= high:
                self.diags.add("X116", command.address_span,
                               f"device address {command.address} does not exist on the {self.product_name()}: "
                               f"addresses are {low}-{high} (X150: 1-16, X150E: 1-32, L124)")
        elif info.address == "D" and device is None:
            self.diags.add("X117", command.span,
                           f"{command.mnemonic} is device specific (it needs an address, L181): without one every "
                           f"device on the chain answers or acts; write 1{command.text} for device 1")

    def product_name(self) -> str:
        name = PRODUCT_NAMES.get(self.profile.product, self.profile.product)
        return f"{name} (software {self.profile.firmware})" if self.profile.firmware else name

    def check_product(self, command: st.Command) -> None:
        info = command.info
        if info is None:
            return
        if info not in self.product_notes:  # the same answer for every use of a command: found once
            self.product_notes[info] = self.product_note(info)
        message = self.product_notes[info]
        if message is not None:
            self.diags.add("X121", command.mnemonic_span or command.span, message)

    def product_note(self, info: cat.Command) -> str | None:
        """Why the target product or its software lacks the command, or None."""
        products = info.products
        key = self.profile.product
        if products is None or key not in PRODUCT_NAMES:
            return None
        if key not in products:
            have = ", ".join(f"{PRODUCT_NAMES[k]} v{v}" for k, v in products.items())
            return (f"{info.name} is not available on the {PRODUCT_NAMES[key]} (the manual lists it "
                    f"for {have}); remove it or select another profile")
        if self.profile.firmware and version(products[key]) > version(self.profile.firmware):
            return (f"{info.name} needs software v{products[key]} on the {PRODUCT_NAMES[key]}; the "
                    f"profile targets v{self.profile.firmware}")
        return None

    def check_values(self, command: st.Command) -> None:
        info = command.info
        arg = command.arg
        if arg is None or info is None:
            return
        kind = type(arg)
        if kind is st.Number:  # the most common argument, which names no variable
            if info.arg == "sequence":
                self.check_sequence_number(command, arg)
            elif info.arg in ("number", "int") and not info.in_range(arg.value):
                self.diags.add("X122", arg.span, f"{info.name}{arg.text} is out of range: {self.describe_range(info)}"
                                                 + (f" ({info.manual})" if info.manual else ""))
            return
        if kind is st.Pattern or kind is st.IoFunction:  # nothing to check in the value
            return
        if isinstance(arg, st.Fields):
            for spec, value, span in zip(info.fields, arg.values, arg.spans):
                if not spec.low <= value <= spec.high:
                    self.diags.add("X122", span, f"{info.name}: the {spec.name} {value} is outside {spec.low}-{spec.high}")
        elif isinstance(arg, st.Text):
            self.check_text(command, arg)
        elif isinstance(arg, st.Condition):
            self.check_condition(arg)
        for var in variables(arg) if isinstance(arg, NAMING_VARIABLES) else ():
            limit = self.max_variable
            if not 1 <= var.number <= limit:
                self.diags.add("X130", var.span, f"VAR{var.number} does not exist: the variables are VAR1-VAR{limit} "
                                                 "(L4573)")

    def describe_range(self, info: cat.Command) -> str:
        if info.values is not None:
            return "one of " + ", ".join(str(v) for v in info.values)
        parts = [str(low) if low == high else f"{low} to {high}" for low, high in info.intervals]
        special = f" (or {', '.join(str(s) for s in info.special)})" if info.special else ""
        return ", or ".join(parts) + (f" {info.entry.unit}" if info.entry.unit else "") + special

    def check_sequence_number(self, command: st.Command, arg: st.Number) -> None:
        info = command.info
        low, high = info.range or (1, 64)
        if not low <= arg.value <= high:
            zero = "; 0 selects none" if low == 0 else ""
            self.diags.add("X104", arg.span, f"sequence {arg.value} does not exist: {info.name} takes {low}-{high}{zero} "
                                             "(sequences are numbered 1-64, L4899)")

    def check_text(self, command: st.Command, arg: st.Text) -> None:
        text = arg.text
        lexical = self.cat.data.table("lexical")
        if command.mnemonic == '"':
            limit = int(self.cat.limit("quote_chars", default=50))
            low, high = QUOTE_ASCII
            bad = sorted({ch for ch in text if not low <= ord(ch) <= high})
            rule = "ASCII 33-126, no spaces; write _ for a space (L5593)"
        else:
            limit = int(self.cat.limit("dtxt_chars", default=42))
            illegal = set(lexical.get("dtxt_illegal", "; \\ ~").split())
            bad = sorted({ch for ch in text if ch in illegal or not (32 <= ord(ch) <= 126)})
            rule = "no ; \\ ~ and only printable ASCII (L1278-L1282)"
        if len(text) > limit:
            self.diags.add("X125", arg.span, f"{command.mnemonic} text is {len(text)} characters; the controller takes "
                                             f"{limit}: shorten it")
        if bad:
            shown = " ".join(repr(ch) for ch in bad)
            self.diags.add("X125", arg.span, f"{command.mnemonic} text contains {shown}: {rule}")

    def check_condition(self, cond: st.Condition) -> None:
        limit = self.cat.max_terms
        if len(cond.terms) > limit:
            self.diags.add("X111", cond.span, f"the condition has {len(cond.terms)} terms; the controller evaluates at "
                                              f"most {limit} joined by AND or OR (L2009): split it over nested IFs or "
                                              "a variable")
        for term in cond.terms:
            if isinstance(term, st.InputTerm) and not term.underscore:
                self.diags.add("X131", term.span,
                               f"IN{term.pattern.bits} has no '_', so it tests the dedicated inputs (LMT+ LMT- HOME "
                               f"AUX_IN STOP ENERGISE INDEX, L3778); for user inputs write IN_{term.pattern.bits}")

    # -- inside sequences ----------------------------------------------------------------------------
    def missing_erase(self, unit: Unit) -> None:
        start = unit.start
        prefix = start.address_text()
        erase = f"{prefix}XE{unit.number}"
        # Inside another definition (X106) an XE written before this XD would be stored in that
        # definition, not sent: no fix there (it would be offered again after every run).
        fix = None if unit.nested else Fix(f"insert {erase}", (Edit(insert_at(start.span), erase + " "),))
        self.diags.add("X126", start.span,
                       f"XD{unit.number} without {erase} first: the controller does not store a sequence whose "
                       f"number is already in use (L4904); send {erase} before it", fix=fix)

    def check_device(self, command: st.Command, unit: Unit) -> None:
        if unit.address is None or command.host:
            return
        if command.address is None:
            self.diags.add("X120", command.span,
                           f"{command.text} has no address inside a sequence for device {unit.address}: while device "
                           f"{unit.address} stores it, every other device on the chain executes it; write "
                           f"{unit.address}{command.text}",
                           fix=Fix(f"address it to device {unit.address}",
                                   (Edit(insert_at(command.span), str(unit.address)),)))
        elif command.address != unit.address:
            self.diags.add("X119", command.address_span,
                           f"{command.text} is for device {command.address}, inside the definition of sequence "
                           f"{unit.number} for device {unit.address}: define it in its own sequence for device "
                           f"{command.address}")

    def check_policy(self, command: st.Command, unit: Unit) -> None:
        where = f"sequence {unit.number}"
        if command.host:
            self.diags.add("X113", command.span, f"{command.text} is host data answering VARn=RSIN (L3604); it cannot be "
                                                 f"stored in {where}: send it while the sequence runs")
            return
        if command.buffered:
            return
        info = command.info
        policy = info.policy
        if policy in ("reject", "edit"):
            why = "never saved" if info.entry.get("seq") == "N" else "immediate"
            self.diags.add("X113", command.mnemonic_span or command.span,
                           f"{info.name} is {why}: between XD and XT it runs at download time instead of being "
                           f"stored in {where} (L171-L181); send it outside the sequence")
        elif policy == "b-prefix":
            at = insert_at(command.mnemonic_span or command.span)
            fixed = command.address_text() + "B" + command.text[len(command.address_text()):]
            self.diags.add("X114", command.mnemonic_span or command.span,
                           f"{info.name} is immediate: inside {where} only its buffered form is stored; write {fixed} "
                           "(the B prefix, L185)",
                           fix=Fix(f"write {fixed}", (Edit(at, "B"),)))
        elif policy in UNMARKED:
            self.diags.add("X115", command.mnemonic_span or command.span,
                           f"{info.name} {UNMARKED[policy]} ({info.manual}): check on the controller that {where} "
                           "keeps it, or send it before the sequence")

    # -- whole program ---------------------------------------------------------------------------------
    def check_saved(self) -> None:
        units = self.lowering.units
        last_definition = None
        for unit in units:
            if unit.is_sequence:
                last_definition = unit
        selections = [site for site in self.lowering.sites if site.kind == "handler" and site.number
                      and site.command.info.ir == "powerup"]
        anchor = None
        if last_definition is not None:
            anchor = (last_definition.start, f"sequence {last_definition.number} stays in volatile memory until SV "
                                             "(L4904)")
        if selections:
            site = selections[-1]
            anchor = (site.command, f"the power-up sequence selected by {site.command.text} is used after a power cycle "
                                    "only once saved with SV (L5117)")
        if anchor is None:
            return
        command, why = anchor
        # Is there an SV after the anchor? Read from the end back to it: the anchor is most often
        # the last definition, near the end of the file.
        saved = False
        for line in reversed(self.lowering.tree.lines):
            for other in reversed(line.commands):
                if other is command:
                    if saved:
                        return
                    break
                if other.info is not None and other.info.ir == "save":
                    saved = True
            else:
                continue
            break
        self.diags.add("X128", command.span, f"{why}: add SV (addressed, e.g. 1SV) after the definitions if the "
                                             "program must survive a power cycle")

    def check_transfers(self) -> None:
        for site in self.lowering.sites:
            number = site.number
            if not number or not 1 <= number <= 64:
                continue
            command = site.command
            if not site.targets:
                self.diags.add("X127", command.span,
                               f"sequence {number} is not defined in this file: {command.text} uses whatever sequence "
                               f"{number} is stored on the controller (define it here, or check it is downloaded)")
                continue
            if site.kind == "goto" and site.depth.get("IF", 0):
                self.check_goto_out_of_if(site)

    def check_goto_out_of_if(self, site: Site) -> None:
        depth = site.depth["IF"]
        for target in site.targets:
            nifs = self.lowering.leading_nifs.get(target, 0)
            if nifs < depth:
                needed = "NIF" if depth == 1 else f"{depth} NIFs"
                self.diags.add("X112", site.command.span,
                               f"{site.command.text} leaves {depth} open IF(...) behind; the controller keeps it open, "
                               f"so sequence {site.number} must begin with {needed} (L1794, L2024, L5079); add "
                               f"{needed} as its first command, or close the IF before jumping")

    def check_call_nesting(self) -> None:
        """Sequence calls nest at most 16 deep (L1750, L5140: X110). That the construct stacks are shared
        by a sequence and the sequences it calls is mcc's inference, reported as the warning X140."""
        limit = self.nesting
        kinds = tuple(OPENERS.values())
        local = self.lowering.max_depth
        entry: dict[str, dict[str, int]] = {}
        calls = [s for s in self.lowering.sites if s.kind == "call" and s.targets]
        by_routine: dict[str, list[Site]] = {}
        for site in calls:
            by_routine.setdefault(site.routine, []).append(site)
        called = {t for s in calls for t in s.targets}
        work = [r.name for r in self.lowering.module.routines if r.name not in called]
        for name in work:
            entry[name] = {k: 0 for k in kinds + ("call",)}
        reported: set[tuple[str, str]] = set()
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
                    self.report_nesting(site, target, merged, local.get(target, {}), reported)

    def report_nesting(self, site: Site, target: str, context: dict[str, int], inside: dict[str, int],
                       reported: set[tuple[str, str]]) -> None:
        limit = self.nesting
        if context["call"] > limit and (target, "call") not in reported:
            reported.add((target, "call"))
            self.diags.add("X110", site.command.span,
                           f"{site.command.text} nests sequence calls more than {limit} deep (through the calls of "
                           "this file; a sequence that calls itself never stops): the controller allows "
                           f"{limit} (L1750, L5140)")
        for kind, depth in inside.items():
            total = context.get(kind, 0) + depth
            if total > limit and (target, kind) not in reported:
                reported.add((target, kind))
                self.diags.add("X140", site.command.span,
                               f"{site.command.text} runs sequence {site.number}, which opens {kind} {depth} deep, "
                               f"while {context[kind]} are already open: {total} > {limit} if the controller "
                               "counts a called sequence's constructs with its caller's. This is inferred, not "
                               f"stated: the manual limits {kind} nesting to {limit} (L2011, L2332, L3441, L4849) "
                               "and sequence calls to 16 (L1750, L5140), but not the two together; move loops out "
                               "of the called sequence to be safe, or ignore X140 if your controller runs it")

    def stored_bytes(self, unit: Unit) -> int:
        """The bytes a sequence stores: each command in its canonical form (upper case, the device
        address in front, the B prefix on an immediate `*` command) and its delimiter, XT included
        (L241). The X150 backend writes sequences in the same form."""
        from mcc.compiler.x150.format import command_text  # format imports this module's canonical_case
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

    def check_memory(self) -> None:
        lowering = self.lowering
        store = int(self.profile.get("limits.sequence_store_bytes", self.cat.limit("sequence_store_bytes", default=8000)))
        buffer = int(self.profile.get("limits.command_buffer_bytes", self.cat.limit("command_buffer_bytes", default=2000)))
        ratio = float(self.profile.get("x150.buffer_warn_ratio", 0.9))
        latest: dict[tuple[int, int | None], tuple[Unit, int]] = {}
        for unit in lowering.units:
            if not unit.is_sequence or unit.start is None:
                continue
            size = self.stored_bytes(unit)
            latest[(unit.number or 0, unit.address)] = (unit, size)
            if size >= ratio * buffer:
                over = "more than" if size > buffer else "close to"
                self.diags.add("X124", unit.start.span,
                               f"sequence {unit.number} is {size} bytes, {over} the {buffer}-byte command buffer it is "
                               "downloaded through (L241, L4904): split it into sequences that call each other")
        per_device: dict[str, int] = {}
        for (_, address), (_, size) in latest.items():
            key = str(address) if address is not None else "*"
            per_device[key] = per_device.get(key, 0) + size
        self.memory = {"unit": "bytes", "used": max(per_device.values(), default=0), "budget": store,
                       "by_device": per_device, "command_buffer": buffer,
                       "largest_sequence": max((size for _, size in latest.values()), default=0)}
        store_ratio = float(self.profile.get("x150.store_warn_ratio", 0.9))
        devices = sorted({address for _, address in latest if address is not None})
        for device in devices or [None]:
            total = 0
            last = None
            who = f"device {device}" if device is not None else "each device"
            for (number, address), (unit, size) in sorted(latest.items(), key=lambda kv: kv[1][0].start.span.start):
                if address is not None and address != device:
                    continue
                total += size
                last = (number, unit)
                if total > store:
                    self.diags.add("X123", unit.start.span,
                                   f"with sequence {number} the sequences for {who} need {total} bytes; the sequence "
                                   f"store holds {store} (L4871, 1 byte per character and delimiter, L241): shorten "
                                   "or remove sequences")
                    break
            else:
                if last is not None and total > store_ratio * store:
                    number, unit = last
                    self.diags.add("X141", unit.start.span,
                                   f"the sequences for {who} need {total} of the {store} bytes of the sequence store "
                                   f"({100 * total / store:.1f} %, L4871): little room is left for changes; the "
                                   "count assumes 1 byte per character and delimiter (L241)")


NAMING_VARIABLES = (st.VarRef, st.VarStatement, st.Chain, st.Condition)  # the arguments `variables` reads
KEEP_CASE_ARGS = ("raw",)  # TX's free text (catalog argument class): sent to the display as written


def canonical_case(command: st.Command) -> str:
    """The command in upper case, except its text: quoted text (`DTXT"..."`, `"..."`) and the
    free text of TX are data the device shows as written (`1TX7,1,0,gap=` shows `gap=`). One
    definition for X102 and its fix and for `mcc fmt`, so that neither changes what is shown."""
    info = command.info
    return _canonical_case(command.text, info.arg if info is not None else "", command.mnemonic)


@lru_cache(maxsize=4096)
def _canonical_case(text: str, arg: str, mnemonic: str) -> str:
    """`canonical_case` of what it depends on (a program repeats its commands: found once each)."""
    if arg in KEEP_CASE_ARGS:
        end = text.upper().find(mnemonic) + len(mnemonic)
        return text[:end].upper() + text[end:] if end >= len(mnemonic) else text
    return upper_outside_quotes(text)


def upper_outside_quotes(text: str) -> str:
    if '"' not in text:  # most commands: nothing quoted
        return text.upper()
    out = []
    last = 0
    for match in QUOTED.finditer(text):
        out.append(text[last:match.start()].upper())
        out.append(match.group())
        last = match.end()
    out.append(text[last:].upper())
    return "".join(out)


def variables(arg) -> list[st.VarRef]:
    """Every VARn an argument names."""
    if isinstance(arg, st.VarRef):
        return [arg]
    if isinstance(arg, st.VarStatement):
        return [arg.var] + (variables(arg.value) if arg.value is not None else [])
    if isinstance(arg, st.Chain):
        return [o for o in [arg.first] + [op for _, op in arg.rest] if isinstance(o, st.VarRef)]
    if isinstance(arg, st.Condition):
        out = []
        for term in arg.terms:
            if isinstance(term, st.Comparison):
                out += [o for o in (term.left, term.right) if isinstance(o, st.VarRef)]
        return out
    return []


def run(lowering: Lowering, profile: Profile, diags: Diagnostics) -> dict:
    """Every whole-program check; returns the sequence memory used (empty when not measured)."""
    checker = Checker(lowering, profile, diags)
    checker.run()
    return checker.memory
