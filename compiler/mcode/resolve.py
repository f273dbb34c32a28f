"""Giving each MCode statement its meaning from the catalog, and the per-statement checks.

The grammar accepts any word at the head of a statement; here the word is matched against the
catalog (longest match, so `aPR` is party prefix `a` + `PR`, `PG1` is `PG 1` written without a
space), user names are told apart from commands, and the arguments are checked against the
catalog's argument list: count, kind (label, variable, condition, string) and constant ranges.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from mcc.compiler.diagnostics import Diagnostics, Edit, Fix
from mcc.compiler.mcode import catalog as cat
from mcc.compiler.mcode import syntax as st
from mcc.compiler.profiles import Profile
from mcc.compiler.suggest import close_matches

USER_NAME = re.compile(r"[A-Za-z][A-Za-z0-9]{0,2}\Z")
STRICT_USER_NAME = re.compile(r"[A-Za-z][A-Za-z0-9]\Z")
SHORT_USER_NAME = re.compile(r"[A-Za-z][A-Za-z0-9]?\Z")  # label_rule "short": one or two characters
GLUED = re.compile(r"([A-Za-z]{1,2})([0-9]+)\Z")
VALUE_TYPES = ("int", "number")


@dataclass
class Resolved:
    """What a statement's head turned out to be."""

    stmt: st.Statement
    command: cat.Command | None = None
    user: str = ""  # upper-case user name at the head (an assignment to a user variable)
    legacy: cat.Legacy | None = None
    party: str = ""
    args: list[st.Node] = field(default_factory=list)

    @property
    def name(self) -> str:
        return self.command.name if self.command else self.user


@dataclass
class Names:
    """User names of the program: labels (LB) and variables (VA), one shared table (L537)."""

    labels: dict[str, st.Name] = field(default_factory=dict)
    variables: dict[str, st.Name] = field(default_factory=dict)


def firmware_tuple(text: str) -> tuple[int, ...]:
    return tuple(int(part) for part in re.findall(r"\d+", text))


class Resolver:
    def __init__(self, profile: Profile, diags: Diagnostics):
        self.cat = cat.for_profile(profile)
        self.profile = profile
        self.diags = diags
        self.names = Names()
        self.product = profile.product
        self.firmware = firmware_tuple(profile.firmware)

    # heads --------------------------------------------------------------------------------------
    def resolve(self, stmt: st.Statement) -> Resolved:
        res = Resolved(stmt, party=stmt.party, args=list(stmt.args))
        if stmt.form == "number":
            return res
        word = stmt.head.text
        upper = word.upper()
        commands = self.cat.commands
        if upper in commands:
            res.command = commands[upper]
        elif upper in self.cat.legacy:
            res.legacy = self.cat.legacy[upper]
        elif self.cat.family and upper in (lexium := cat.load().commands) and upper not in self.names.variables:
            res.command = lexium[upper]  # a Lexium command the older family lacks: M114 names the products
        elif len(upper) == 3 and upper[1:] in commands and not stmt.party and word[0].isalnum() \
                and upper not in self.names.variables:
            res.party, res.command = word[0], commands[upper[1:]]
        elif (m := GLUED.match(word)) and m.group(1).upper() in commands and upper not in self.names.variables:
            res.command = commands[m.group(1).upper()]
            head_len = len(m.group(1))
            span = stmt.head.span
            number_span = type(span)(span.file, span.line, span.column + head_len, span.end_line,
                                     span.end_column, span.start + head_len, span.end)
            res.args.insert(0, st.Number(m.group(2), number_span))
            fix = Fix("insert a space", (Edit(type(span)(span.file, span.line, span.column + head_len, span.line,
                                                          span.column + head_len, span.start + head_len,
                                                          span.start + head_len), " "),))
            self.diags.add("M124", stmt.head.span,
                           f"'{word}' reads as '{m.group(1)} {m.group(2)}': put a space between the command and "
                           "its value", fix=fix)
        elif USER_NAME.match(word):
            res.user = upper
        return res

    # statement checks ---------------------------------------------------------------------------
    def check(self, res: Resolved, in_program: bool) -> bool:
        """Check one statement; False when it is unusable (unknown head, wrong kind).

        A message names what the user wrote: when the head was read as something else (`Pos` as
        the command OS addressed to the party-mode device P), every diagnostic of the statement
        starts by saying so, rather than speaking of a command the user never typed (issue 24)."""
        before = len(self.diags.items)
        ok = self.check_head(res, in_program)
        if res.party and not res.stmt.party and res.command is not None:
            word = res.stmt.head.text
            lead = f"'{word}' reads as {res.command.name} addressed to the party-mode device {res.party}"
            rule = str(self.profile.get("limits.label_rule", "strict"))
            pattern = {"relaxed": USER_NAME, "short": SHORT_USER_NAME}.get(rule, STRICT_USER_NAME)
            if pattern.match(word):
                lead += f" (if {word} is a variable of yours, declare it first: `VA {word}`)"
            else:
                lead += f" ({word} cannot be a variable: a name of this product has at most "\
                        f"{2 if rule != 'relaxed' else 3} characters, L550)"
            for diag in self.diags.items[before:]:
                if not diag.message.startswith(f"'{word}'"):
                    diag.message = f"{lead}: {diag.message}"
        return ok

    def check_head(self, res: Resolved, in_program: bool) -> bool:
        stmt = res.stmt
        if stmt.form == "number":
            return True
        if res.legacy is not None and self.cat.family:
            legacy = res.legacy  # a command of the older family that its catalog variant does not have
            self.diags.add("M102", stmt.head.span,
                           f"{legacy.name} ({legacy.summary.rstrip('.')}) is not in mcc's catalog of the "
                           f"{self.cat.products.get(self.cat.family, self.cat.family)} family: no public source "
                           "gives its form (docs/dialects/mcode.md); mcc cannot check or convert it")
            return False
        if res.legacy is not None:
            legacy = res.legacy
            self.diags.add("M102", stmt.head.span,
                           f"{legacy.name} is an {legacy.family} command ({legacy.summary.rstrip('.')}); "
                           f"Lexium products do not have it: use {self.lexium_equivalent(res)} (a program for that "
                           "family: check it with `--profile mdrive-plus`, move it with `mcc compile "
                           "--source-profile mdrive-plus`)")
            return False
        if res.command is None:
            return self.check_user_statement(res)
        command = res.command
        kind = command.kind
        if kind == cat.RESERVED:
            self.diags.add("M130", stmt.head.span, f"{command.name} is a reserved name with no function; "
                                                    "it cannot be used as a command, label or variable")
            return False
        if kind in (cat.FUNCTION, cat.OPERATOR):
            self.diags.add("M101", stmt.head.span, f"{command.name} is a math function: use it inside an "
                                                    f"expression, e.g. F1={command.name} F2")
            return False
        if kind == cat.FACTORY_LABEL:
            self.diags.add("M101", stmt.head.span, f"{command.name} is a label name: write `LB {command.name}`")
            return False
        self.check_product(res)
        self.check_mode(res, in_program)
        if kind == cat.KEYWORD:
            self.diags.add("M120", stmt.head.span,
                           f"{command.name} is a keyword that only reports a value: read it with `PR {command.name}`")
            return False
        if kind in (cat.VARIABLE, cat.FLAG):
            return self.check_write(res)
        return self.check_args(res)

    def lexium_equivalent(self, res: Resolved) -> str:
        legacy = res.legacy
        args = res.args
        if legacy.io_point is not None and legacy.io_point <= 4 and args and isinstance(args[0], st.Number):
            function = args[0].value
            active = args[1].text if len(args) > 1 and isinstance(args[1], st.Number) else "0"
            setup = "IS" if isinstance(function, int) and function < 16 else "OS"
            return f"`{setup}={legacy.io_point},{args[0].text},{active}`"
        return legacy.lexium

    def check_user_statement(self, res: Resolved) -> bool:
        stmt = res.stmt
        word = stmt.head.text
        if not res.user:
            self.unknown(stmt.head)
            return False
        if res.user in self.names.labels and res.user not in self.names.variables:
            self.diags.add("M129", stmt.head.span, f"{word} is a label, not a variable: a label cannot be set")
            return False
        if res.user not in self.names.variables:
            if stmt.form == "bare" and not self.near_commands(word):
                self.unknown(stmt.head, also=f" (to name this place in the program write `LB {word}`)")
            elif stmt.form == "bare":  # `END`: a command misspelt (E), not a label (issue 24)
                self.unknown(stmt.head)
            elif stmt.form == "command":  # `MX 2000` reads as a mistyped command
                self.unknown(stmt.head)
            else:
                self.diags.add("M117", stmt.head.span,
                               f"{word} is not declared: declare it with `VA {word}` before use")
            return False
        if stmt.form == "bare":
            self.diags.add("M121", stmt.head.span, f"{word} alone does nothing: set it with `{word}=<value>` "
                                                    f"or read it with `PR {word}`")
            return False
        if len(res.args) != 1:
            self.diags.add("M118", stmt.span, f"a variable takes one value, not {len(res.args)}")
            return False
        self.check_value(res.args[0], "int")
        return True

    def near_commands(self, text: str) -> list[str]:
        """Up to three names close to `text`, those with its first letter first."""
        choices = list(self.cat.commands) + list(self.names.variables)
        word = text.upper()
        near = close_matches(word, choices, n=12, cutoff=0.5)
        return sorted(near, key=lambda c: (c[:1] != word[:1], near.index(c)))[:3]

    def unknown(self, head: st.Name, also: str = "") -> None:
        near = self.near_commands(head.text)
        hint = f"; did you mean {' or '.join(near)}?" if near else ""
        self.diags.add("M101", head.span, f"unknown command '{head.text}'{also}{hint}")

    def check_product(self, res: Resolved) -> None:
        command = res.command
        products = command.products
        if products and self.product not in products:
            names = ", ".join(self.cat.products.get(p, p) for p in products)
            self.diags.add("M114", res.stmt.head.span,
                           f"{command.name} is not available on {self.cat.products.get(self.product, self.product)} "
                           f"(profile '{self.profile.name}'); it exists on: {names}")
        elif command.firmware and self.firmware and self.firmware < firmware_tuple(command.firmware):
            self.diags.add("M115", res.stmt.head.span,
                           f"{command.name} needs firmware {command.firmware} or later; the profile targets "
                           f"{self.profile.firmware}")

    def check_mode(self, res: Resolved, in_program: bool) -> None:
        command = res.command
        if in_program and command.mode == "immediate":
            self.diags.add("M111", res.stmt.head.span,
                           f"{command.name} is an immediate-mode command: it cannot be stored in a program "
                           "(move it outside PG … PG)")
        elif not in_program and command.mode == "program":
            self.diags.add("M112", res.stmt.head.span,
                           f"{command.name} only works inside a program: put it between `PG <address>` and `PG`")

    def check_write(self, res: Resolved) -> bool:
        command, stmt = res.command, res.stmt
        if stmt.form == "bare" and not res.args:  # `LT1000` has its value glued on (M124): a write
            self.diags.add("M121", stmt.head.span,
                           f"{command.name} alone does nothing: set it with `{command.name}=<value>` or read it with "
                           f"`PR {command.name}`")
            return False
        if not command.writable:
            self.diags.add("M107", stmt.head.span,
                           f"{command.name} ({command.entry.title}) is read-only: it can be read (PR {command.name}, "
                           "conditions, expressions) but not set")
            return False
        if command.forms():
            return self.check_args(res)
        if len(res.args) != 1:
            self.diags.add("M118", stmt.span, f"{command.name} takes one value, not {len(res.args)}")
            return False
        value = res.args[0]
        if self.check_value(value, "number" if command.is_float else "int"):
            self.check_range(value, command.entry.range, command.values, command.name, command.entry.unit)
        return True

    # arguments ----------------------------------------------------------------------------------
    def select_form(self, res: Resolved) -> cat.Form | None:
        forms = res.command.forms()
        if not forms:
            return None
        if len(forms) == 1 or not res.args:
            return forms[0]
        first = constant_value(res.args[0])
        for form in forms:
            if form.select is None or first is None or form.select[0] <= first <= form.select[1]:
                return form
        allowed = ", ".join(f"{f.select[0]}-{f.select[1]}" if f.select[0] != f.select[1] else f"{f.select[0]}"
                            for f in forms if f.select)
        self.diags.add("M108", res.args[0].span,
                       f"{res.command.name}: first value {first} is out of range (allowed: {allowed})")
        return None

    def check_args(self, res: Resolved) -> bool:
        command, stmt = res.command, res.stmt
        form = self.select_form(res)
        if form is None and command.forms():
            return False  # the selecting value was out of range, already reported
        args = res.args
        specs = form.args if form else ()
        if not specs:
            if args:
                self.diags.add("M118", args[0].span.to(args[-1].span),
                               f"{command.name} takes no arguments")
                return False
            return True
        repeat = specs[-1].repeat
        required = sum(1 for s in specs if not s.optional and not s.repeat)
        if len(args) < required or (len(args) > len(specs) and not repeat):
            expected = f"{required}" if required == len(specs) and not repeat else \
                f"{required} to {len(specs)}" if not repeat else f"at least {required}"
            where = args[0].span.to(args[-1].span) if args else stmt.span
            usage = "; ".join(command.entry.syntax[:2])
            self.diags.add("M118", where, f"{command.name} takes {expected} argument{'s' if expected != '1' else ''}, "
                                          f"not {len(args)}" + (f" (syntax: {usage})" if usage else ""))
            return False
        ok = True
        for i, arg in enumerate(args):
            spec = specs[min(i, len(specs) - 1)]
            ok = self.check_arg(command, spec, arg) and ok
        return ok

    def check_arg(self, command: cat.Command, spec: cat.Arg, arg: st.Node) -> bool:
        kind = spec.type
        if kind in VALUE_TYPES:
            if self.check_value(arg, kind):
                self.check_range(arg, spec.range, spec.values, f"{command.name} {spec.name}", spec.unit)
                return True
            return False
        if kind == "target":
            if isinstance(arg, st.Name) or isinstance(arg, st.Number) and isinstance(arg.value, int):
                return True
            return self.wrong(arg, f"{command.name} needs a label or an address here")
        if kind == "condition":
            if isinstance(arg, (st.String, st.Juxtaposed)):
                return self.wrong(arg, "a condition compares two values, e.g. I1=1 or Q1<10")
            if isinstance(arg, st.Comparison):
                return self.check_value(arg.left, "int") & self.check_value(arg.right, "int")
            return self.check_value(arg, "int")
        if kind == "variable":
            if isinstance(arg, st.Name):
                upper = arg.key
                command_ref = self.cat.commands.get(upper)
                if upper in self.names.variables:
                    return True
                if command_ref and command_ref.writable and command.name in ("IC", "DC") \
                        and not self.cat.steppable(command_ref):
                    self.diags.add("M140", arg.span,
                                   f"{arg.text} is a mode or configuration {command_ref.kind} ({command_ref.entry.title}): "
                                   f"{command.name} of it is refused with Error 26 (L3375); set it with "
                                   f"`{arg.text}=value`")
                    return False
                if command_ref and command_ref.writable:
                    return True
                if command_ref is not None:
                    self.diags.add("M107", arg.span, f"{arg.text} is read-only and cannot be changed by {command.name}")
                    return False
                self.diags.add("M117", arg.span, f"{arg.text} is not declared: declare it with `VA {arg.text}`")
                return False
            return self.wrong(arg, f"{command.name} needs a variable name here")
        if kind == "name":
            target = arg.left if isinstance(arg, st.Comparison) and arg.op == "=" else arg
            if isinstance(target, st.Name):
                if target is not arg:
                    self.check_value(arg.right, "int")
                return True
            return self.wrong(arg, f"{command.name} needs a name here, e.g. {command.name} Q1")
        if kind == "string":
            if isinstance(arg, st.String):
                return True
            return self.wrong(arg, f"{command.name} needs text in double quotes here")
        if kind == "item":
            return self.check_item(arg)
        return True  # "keyword" and anything the catalog adds later: accepted

    def check_item(self, arg: st.Node) -> bool:
        if isinstance(arg, st.String):
            return True
        if isinstance(arg, st.Juxtaposed):
            fix = Fix("insert the comma", (Edit(type(arg.first.span)(
                arg.first.span.file, arg.first.span.end_line, arg.first.span.end_column, arg.first.span.end_line,
                arg.first.span.end_column, arg.first.span.end, arg.first.span.end), ","),))
            self.diags.add("M123", arg.span, "PR items are separated by commas: a comma is missing after the text",
                           fix=fix)
            return self.check_item(arg.second)
        if isinstance(arg, st.Name):
            command = self.cat.commands.get(arg.key)
            if command is not None and command.kind == cat.KEYWORD:
                return True
        return self.check_value(arg, "int")

    def wrong(self, arg: st.Node, message: str) -> bool:
        self.diags.add("M119", arg.span, message)
        return False

    def check_value(self, node: st.Node, kind: str) -> bool:
        """An arithmetic value: numbers, readable names, operators, functions."""
        if isinstance(node, st.Number):
            return True
        if isinstance(node, st.Name):
            return self.check_read(node)
        if isinstance(node, st.Unary):
            return self.check_value(node.operand, kind)
        if isinstance(node, st.Binary):
            if node.op == "!":
                self.diags.add("M126", node.span, "'!' is bitwise NOT and takes one value: write R1=!R2, "
                                                  "not R1=R2!R3")
                return False
            return self.check_value(node.left, kind) & self.check_value(node.right, kind)
        if isinstance(node, st.FuncCall):
            command = self.cat.functions.get(node.name)
            if command is not None and command.entry.get("arity", 1) != 0:
                self.check_product_of(command, node.span)
            else:
                functions = " ".join(sorted(n for n, f in self.cat.functions.items() if f.entry.get("arity", 1)))
                self.diags.add("M119", node.span, f"{node.name} is not an MCode function ({functions}), so "
                                                  "two values stand side by side: put an operator between them")
                self.check_value(node.operand, kind)
                return False
            return self.check_value(node.operand, kind)
        if isinstance(node, st.Comparison):
            self.diags.add("M119", node.span, "a comparison is only allowed as the condition of BR or CL")
            return False
        if isinstance(node, (st.String, st.Juxtaposed)):
            self.diags.add("M119", node.span, "text in quotes is only allowed in PR and DN")
            return False
        return True

    def check_product_of(self, command: cat.Command, span) -> None:
        if command.firmware and self.firmware and self.firmware < firmware_tuple(command.firmware):
            self.diags.add("M115", span, f"{command.name} needs firmware {command.firmware} or later; the profile "
                                         f"targets {self.profile.firmware}")

    def check_read(self, name: st.Name) -> bool:
        upper = name.key
        if upper in self.names.variables:
            return True
        command = self.cat.commands.get(upper) or self.cat.target_function(upper, self.profile.firmware)
        if command is not None:
            if command.kind == cat.FUNCTION and command.entry.get("arity", 1) == 0:
                return True  # PI: a constant
            if command.kind == cat.FUNCTION:
                self.diags.add("M119", name.span, f"{command.name} is the {command.entry.title.lower()} function "
                                                  f"from firmware {command.firmware} on (the profile targets "
                                                  f"{self.profile.firmware or 'the newest'}): it needs a value, "
                                                  f"`{command.name} P`; for a program written for older firmware "
                                                  "use a profile with its `firmware` (docs/PROFILES.md)")
                return False
            if command.kind in (cat.VARIABLE, cat.FLAG, cat.KEYWORD) and command.readable:
                return self.check_read_available(command, name)
            if command.kind in (cat.VARIABLE, cat.FLAG):
                self.diags.add("M119", name.span, f"{command.name} is write-only and cannot be read")
                return False
            self.diags.add("M119", name.span, f"{command.name} is a {command.kind}, not a value")
            return False
        if upper in self.names.labels:
            self.diags.add("M129", name.span, f"{name.text} is a label, not a value")
            return False
        self.diags.add("M117", name.span, f"{name.text} is not declared: declare it with `VA {name.text}`")
        return False

    def check_read_available(self, command: cat.Command, name: st.Name) -> bool:
        """Reading a variable or flag the product or firmware lacks is Error 37 too, like writing it."""
        products = command.products
        if products and self.product not in products:
            names = ", ".join(self.cat.products.get(p, p) for p in products)
            self.diags.add("M114", name.span,
                           f"{command.name} cannot be read on {self.cat.products.get(self.product, self.product)} "
                           f"(profile '{self.profile.name}'): the device answers Error 37; it exists on: {names}")
            return False
        if command.firmware and self.firmware and self.firmware < firmware_tuple(command.firmware):
            self.diags.add("M115", name.span, f"{command.name} needs firmware {command.firmware} or later; the "
                                              f"profile targets {self.profile.firmware}")
            return False
        return True

    def check_range(self, node: st.Node, rng, values, what: str, unit: str) -> None:
        value = constant_value(node)
        if value is None:
            return
        if values and value not in values:
            shown = ", ".join(str(v) for v in values[:24])
            self.diags.add("M108", node.span, f"{what}: {format_number(value)} is not one of the allowed values ({shown})")
        elif rng and not (rng[0] <= value <= rng[1]):
            suffix = f" {unit}" if unit else ""
            self.diags.add("M108", node.span, f"{what}: {format_number(value)} is out of range "
                                              f"({format_number(rng[0])} to {format_number(rng[1])}{suffix})")


def constant_value(node: st.Node) -> int | float | None:
    if isinstance(node, st.Number):
        return node.value
    if isinstance(node, st.Unary) and node.op == "-" and isinstance(node.operand, st.Number):
        return -node.operand.value
    return None


def format_number(value) -> str:
    return f"{value:,}".replace(",", " ") if isinstance(value, int) and abs(value) >= 100000 else str(value)
