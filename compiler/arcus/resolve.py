"""Giving each Arcus statement its meaning from the catalog, and the per-statement checks.

The grammar accepts any word at the head of a statement, glued to a number or a sign. Here the
word is matched against the catalog (longest match of the entries' `pattern`s), the glued pieces
are told apart (`X1000` is axis X with target 1000, `XV10` axis X with variable V10, `DO7` output
bit 7, `ARCP0` the ARC keyword with suffix P and first operand 0) and the statement is checked
against what the catalog says of the keyword: its form, what it may read or write, literal-only
operands, ranges. The result is a `Resolved` statement the lowering turns into IR.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from mcc.compiler.arcus import catalog as cat
from mcc.compiler.arcus import syntax as st
from mcc.compiler.diagnostics import Diagnostics, Severity
from mcc.compiler.profiles import Profile
from mcc.compiler.span import Span
from mcc.compiler.suggest import close_matches

VALUE = re.compile(r"([+-]?)([0-9]+)\Z")
VARIABLE = re.compile(r"V([0-9]+)\Z")

# Shapes of a resolved statement.
MOVE, BARE, CONTROL, WRITE, ASSIGN, COLON, NUMBERED, CONDITION = (
    "move", "bare", "control", "write", "assign", "colon", "number", "condition")


@dataclass
class Target:
    """One axis of a move statement."""

    axis: str
    value: st.Node  # a Number or a Ref to a variable
    span: Span


@dataclass
class RefInfo:
    """What a name used as a value is."""

    match: cat.Match
    spelled: str

    @property
    def keyword(self) -> cat.Keyword:
        return self.match.keyword

    @property
    def is_variable(self) -> bool:
        return self.keyword.form == "expression"


@dataclass
class Resolved:
    line: st.Line
    stmt: st.Statement
    shape: str = ""  # "" when the statement could not be understood
    keyword: cat.Keyword | None = None
    match: cat.Match | None = None
    targets: list[Target] = field(default_factory=list)
    operands: list[st.Node] = field(default_factory=list)
    number: int | None = None
    number_span: Span | None = None
    value: st.Node | None = None
    valid: bool = True  # False: the statement's shape is known but it has an error

    @property
    def span(self) -> Span:
        return self.stmt.span

    @property
    def name(self) -> str:
        return self.keyword.name if self.keyword else ""

    @property
    def spelled(self) -> str:
        m = self.match
        return m.keyword.spell(m.axis, m.index, m.direction, m.suffix) if m else ""


def sub_span(part: st.Part, begin: int, end: int) -> Span:
    """The span of characters begin..end of `part.key` (word, then sign, then number)."""

    first, i = _offset(part, begin)
    last, j = _offset(part, max(begin, end - 1))
    j += 1 if end > begin else 0
    return Span(first.file, first.line, first.column + i, last.line, last.column + j, first.start + i, last.start + j)


def _offset(part: st.Part, i: int) -> tuple[Span, int]:
    """The piece (word, sign, number) holding character i of `part.key`, and i within it; past the
    end, the last piece and its length."""
    length = len(part.word)
    if i < length:
        return part.word_span, i
    i -= length
    last = part.word_span, length
    if part.sign_span is not None:
        length = len(part.sign)
        if i < length:
            return part.sign_span, i
        i -= length
        last = part.sign_span, length
    if part.number_span is not None:
        length = len(part.number)
        if i < length:
            return part.number_span, i
        last = part.number_span, length
    return last


class Resolver:
    def __init__(self, profile: Profile, diags: Diagnostics):
        self.cat = cat.load(profile.product)
        self.profile = profile
        self.diags = diags
        self._refs: dict[str, RefInfo | None] = {}
        self._variable_limits = (self.cat.limit("variables.min", -2147483648),
                                 self.cat.limit("variables.max", 2147483647))
        rng = profile.get("arcus.subroutines") or [self.cat.limit("subroutines.first", 0),
                                                   self.cat.limit("subroutines.last", 31)]
        self.sub_range = (int(rng[0]), int(rng[1]))
        self.gosub_zero = str(profile.get("arcus.gosub_zero", "warn"))
        # the product's variables, axes and concurrent programs (its profile; docs/dialects/arcus.md, "Family")
        variables = profile.get("arcus.variables") or [self.cat.limit("variables.first", 0),
                                                       self.cat.limit("variables.last", 63)]
        self.variables = (int(variables[0]), int(variables[1]))
        self.axes = tuple(a for a in profile.axes if a in ("X", "Y", "Z", "U")) or ("X", "Y", "Z", "U")
        self.programs = int(profile.get("arcus.programs", 0) or 0)
        self.product = (profile.title or profile.product).split(" (")[0]

    # entry point -----------------------------------------------------------------------------
    def resolve(self, line: st.Line) -> Resolved:
        stmt = line.statement
        res = Resolved(line, stmt)
        if isinstance(stmt, st.Command):
            self.command(res, stmt)
        elif isinstance(stmt, st.Assignment):
            self.assignment(res, stmt)
        elif isinstance(stmt, st.Conditional):
            self.conditional(res, stmt)
        return res

    # keyword lookup ---------------------------------------------------------------------------
    def head(self, part: st.Part) -> cat.Match | None:
        """The keyword a part starts with, reporting unknown, host-only and foreign words."""
        match = self.cat.match(part.key)
        if self.foreign(part, match):
            return None
        if match is None:
            self.unknown(part)
            return None
        keyword = match.keyword
        if keyword.kind == cat.ASCII_ONLY:
            self.host_command(part, match)
            return None
        if keyword.kind == cat.OTHER_PRODUCT:
            self.other_product(part, keyword)
            return None
        if match.axis and not self.check_axis(match.axis, part.word_span, match.keyword.spell(
                match.axis, match.index, match.direction, match.suffix)):
            return None
        return match

    def check_axis(self, axis: str, span: Span, what: str) -> bool:
        """The axis letter is one of the product's (A129)."""
        if axis in self.axes:
            return True
        have = ", ".join(self.axes)
        self.diags.add("A129", span, f"{what}: the {self.product} has {'axis' if len(self.axes) == 1 else 'axes'} "
                                     f"{have}, not {axis} (profile {self.profile.name}): write the statement for "
                                     f"{'that axis' if len(self.axes) == 1 else 'one of them'}, or choose the "
                                     "profile of the controller the program is for")
        return False

    def foreign(self, part: st.Part, match: cat.Match | None) -> bool:
        """A statement of another product of the family that reads longer than any of this
        product's (PRG on the PMX-4EX-SA, EO1 on the ACE-SDE): reported once (A121)."""
        other = self.cat.match_elsewhere(part.key)
        if other is None or (match is not None and match.end >= other.end):
            return False
        self.other_product(part, other.keyword)
        return True

    def other_product(self, part: st.Part, keyword: cat.Keyword) -> None:
        """A statement of another controller of the family (A121), named with the products that have it."""
        products = ", ".join(p.upper() for p in (keyword.entry.products or ()))
        if keyword.name == "PRG":
            advice = (f"the {self.product} runs one program: remove the PRG line and put the program before "
                      "END, its subroutines after")
        else:
            advice = f"the {self.product} (profile {self.profile.name}) does not have it"
        self.diags.add("A121", part.word_span, f"{keyword.name} ({keyword.entry.title}) is a {products} statement: "
                                               f"{advice}")

    def unknown(self, part: st.Part) -> None:
        key = part.key
        stems = [k for k in self.cat.stems(key) if k.kind not in (cat.ASCII_ONLY, cat.OTHER_PRODUCT)]
        if stems and (len(stems[0].stem) > 1 or key == stems[0].stem):
            keyword = stems[0]
            self.diags.add("A122", part.span,
                           f"'{part.word}{part.sign}{part.number}' is not a complete {keyword.name} statement: "
                           f"write {keyword.usage} (e.g. {keyword.example})")
            return
        near = close_matches(part.word.upper(), self.cat.names(), n=3, cutoff=0.6)
        hint = f"; did you mean {' or '.join(near)}?" if near else ""
        self.diags.add("A101", part.word_span, f"unknown keyword '{part.word}'{hint}")

    def host_command(self, part: st.Part, match: cat.Match) -> None:
        keyword = match.keyword
        instead = keyword.get("standalone")
        if instead:
            spelled = instead.replace("<axis>", match.axis or "<axis>")
            if match.index is not None:
                spelled = spelled.replace("<n>", str(match.index))
            if match.axis and "<axis>" not in instead and spelled.isalpha():
                spelled += match.axis  # HSX -> HSPDX
            advice = f"in a standalone program write {spelled}"
        else:
            advice = "a standalone program has no equivalent; a host sends it over USB or RS-485"
        self.diags.add("A102", part.span,
                       f"{part.key} ({keyword.entry.title}) is an ASCII host command, not a standalone "
                       f"statement: {advice}")

    def ref(self, ref: st.Ref) -> RefInfo | None:
        """A name used as a value, without reporting (see `check_ref`)."""
        key = ref.part.key
        try:
            return self._refs[key]  # the answer per spelling, computed once (nothing changes a RefInfo)
        except KeyError:
            pass
        match = self.cat.match(key)
        info = None
        if match is not None and match.end == len(key) and match.keyword.kind not in (cat.ASCII_ONLY,
                                                                                      cat.OTHER_PRODUCT):
            keyword = match.keyword
            info = RefInfo(match, keyword.spell(match.axis, match.index, match.direction, match.suffix))
        self._refs[key] = info
        return info

    # command statements ------------------------------------------------------------------------
    def command(self, res: Resolved, cmd: st.Command) -> None:
        first = cmd.parts[0]
        match = self.head(first)
        if match is None:
            return
        keyword = match.keyword
        res.keyword, res.match = keyword, match
        leftover = first.key[match.end:]
        form = keyword.form
        if form == "glued":
            self.move(res, cmd)
        elif form == "colon":
            self.colon(res, cmd, leftover)
        elif form == "number":
            self.numbered(res, cmd, leftover)
        elif form == "bare":
            if leftover:
                self.diags.add("A122", sub_span(first, match.end, len(first.key)),
                               f"unexpected '{leftover}' after {res.spelled}: write {keyword.usage}")
                return
            if self.single(cmd, res.spelled):
                res.shape = CONTROL if keyword.kind == "control" else BARE
        elif form == "write":
            self.diags.add("A122", first.span,
                           f"{first.key} is not a statement by itself: set it with '=' ({keyword.example}); "
                           + ("read it in an expression" if keyword.readable else "it cannot be read"))
        else:  # operand, expression
            what = "a variable" if form == "expression" else "read-only"
            self.diags.add("A122", first.span,
                           f"{first.key} is {what}: use it in an expression or a condition "
                           f"(e.g. V1={first.key}, IF {first.key}=1)" + (f", or set it: {first.key}=1" if form == "expression" else ""))

    def single(self, cmd: st.Command, what: str) -> bool:
        """The statement is one part and nothing else (one statement per line)."""
        extra = cmd.parts[1:]
        if extra:
            span = extra[0].span.to(extra[-1].span)
            self.diags.add("A125", span, f"'{extra[0].key}' after {what}: one statement per line "
                                         "(put it on a line of its own)")
            return False
        if cmd.colon:
            self.diags.add("A122", cmd.colon[0].span, f"{what} takes no ':' operands")
            return False
        return True

    def move(self, res: Resolved, cmd: st.Command) -> None:
        seen: dict[str, Span] = {}
        ok = True
        for part in cmd.parts:
            key = part.key
            match = self.cat.match(key)
            if match is None or match.keyword.form != "glued":
                self.diags.add("A125", part.span,
                               f"'{key}' in a move: a move line holds only axis targets (X, Y, Z, U); "
                               "put other statements on their own lines")
                ok = False
                continue
            axis = match.keyword.name
            if not self.check_axis(axis, part.word_span, f"{axis} in a move"):
                ok = False
                continue
            text = key[match.end:]
            span = sub_span(part, match.end, len(key)) if text else part.span
            value: st.Node | None = None
            if (m := VALUE.match(text)) is not None:
                value = st.Number(("-" if m.group(1) == "-" else "") + m.group(2), span)
                self.check_range(value, match.keyword, f"{axis} target")
            elif VARIABLE.match(text):
                ref = st.Ref(st.Part("V", sub_span(part, match.end, match.end + 1), number=text[1:],
                                     number_span=sub_span(part, match.end + 1, len(part.key))))
                value = ref
                self.check_variable(ref)
            else:
                self.diags.add("A122", part.span,
                               f"{axis} needs a target: a number or a variable glued to it (e.g. {axis}1000, {axis}V10)")
                ok = False
                continue
            if axis in seen:
                self.diags.add("A126", part.span, f"axis {axis} appears twice in this move (first at column "
                                                  f"{seen[axis].column}); name each axis once")
                ok = False
            seen[axis] = part.span
            res.targets.append(Target(axis, value, part.span))
        if cmd.colon:
            self.diags.add("A122", cmd.colon[0].span, "a move takes no ':' operands")
            ok = False
        if ok:
            res.shape = MOVE

    def colon(self, res: Resolved, cmd: st.Command, leftover: str) -> None:
        keyword = res.keyword
        first = cmd.parts[0]
        if not self.single(st.Command(cmd.parts, [], cmd.span), res.spelled):
            return
        operands: list[st.Node] = []
        if leftover:
            span = sub_span(first, res.match.end, len(first.key))
            if (m := VALUE.match(leftover)) is not None:
                operands.append(st.Number(("-" if m.group(1) == "-" else "") + m.group(2), span))
            elif VARIABLE.match(leftover):
                operands.append(st.Ref(st.Part("V", span, number=leftover[1:])))
            else:
                self.diags.add("A122", span, f"unexpected '{leftover}' after {res.spelled}: write {keyword.usage}")
                return
        operands += cmd.colon
        count = int(keyword.get("operand_count", len(operands)))
        if len(operands) != count:
            where = operands[0].span.to(operands[-1].span) if operands else first.span
            self.diags.add("A122", where, f"{res.spelled} takes {count} operands separated by ':', not "
                                          f"{len(operands)} (e.g. {keyword.example})")
            return
        ok = True
        for operand in operands:
            if not isinstance(operand, st.Number):
                self.diags.add("A118", operand.span,
                               f"{res.spelled} operands must be numbers written out: the manual documents "
                               "no variables or expressions here")
                ok = False
        if ok:
            res.operands = operands
            res.shape = COLON

    def numbered(self, res: Resolved, cmd: st.Command, leftover: str) -> None:
        """GOSUB n, SUB n. A bad number still gives the statement its shape (with `valid` False), so
        that the block structure around a broken SUB line is matched without follow-on errors."""
        first = cmd.parts[0]
        name = res.keyword.name
        extra = cmd.parts[1:]
        res.shape, res.valid = NUMBERED, False
        if not leftover and extra and len(extra) == 1 and (info := self.ref(st.Ref(extra[0]))) is not None \
                and info.is_variable:
            self.diags.add("A118", extra[0].span, f"{name} takes a subroutine number written out "
                                                  f"(e.g. {name} 1), not a variable: calls are fixed")
            return
        if not leftover:
            self.diags.add("A122", first.span, f"{name} needs a subroutine number (e.g. {name} 1)")
            return
        if not self.single(cmd, name):
            return
        span = sub_span(first, res.match.end, len(first.key))
        m = VALUE.match(leftover)
        if m is None:
            self.diags.add("A122", span, f"{name} needs a subroutine number (e.g. {name} 1), not '{leftover}'")
            return
        number = int(leftover)
        res.number, res.number_span, res.valid = number, span, True
        if name == "PRG":
            if not 0 <= number < self.programs or m.group(1):
                self.diags.add("A104", span, f"PRG {leftover}: the {self.product} runs programs 0-{self.programs - 1} "
                                             f"(profile {self.profile.name}, arcus.programs = {self.programs})")
                res.valid = False
            return
        low, high = self.sub_range
        if not low <= number <= high or m.group(1):
            self.diags.add("A104", span, f"{name} {leftover}: subroutine numbers are {low}-{high} "
                                         "(SUB 0-31, L2627; see `mcc explain A104` for the GOSUB 1-32 conflict)")
            res.valid = False
        elif name == "GOSUB" and number == 0 and self.gosub_zero != "ignore":
            severity = Severity.ERROR if self.gosub_zero == "error" else None
            self.diags.add("A105", span, "GOSUB 0: the manual numbers GOSUB targets from 1 (L2180); SUB 0 "
                                         "exists, but use 1-31 to be safe", severity=severity)

    # assignments --------------------------------------------------------------------------------
    def assignment(self, res: Resolved, stmt: st.Assignment) -> None:
        target = stmt.target
        match = self.cat.match(target.key)
        if match is not None and match.end != len(target.key):
            if self.foreign(target, match):
                return
            leftover = target.key[match.end:]
            sibling = self.cat.lookup(match.keyword.name, index=0)
            if leftover.isdigit() and sibling is not None and sibling.index_range:
                low, high = sibling.index_range
                self.diags.add("A119", target.span, f"{target.key}: {sibling.entry.title.lower()} numbers are "
                                                    f"{sibling.name}{low}-{sibling.name}{high}")
            elif leftover[:1].isalpha():
                self.unknown(target)
            else:
                self.diags.add("A122", sub_span(target, match.end, len(target.key)),
                               f"unexpected '{leftover}' after {match.keyword.spell(match.axis, match.index)}")
            return
        match = self.head(target)
        if match is None:
            return
        keyword = match.keyword
        res.keyword, res.match, res.value = keyword, match, stmt.value
        form = keyword.form
        if keyword.name == "SR" and match.index is not None and match.index >= self.programs:
            self.diags.add("A119", target.span, f"{target.key}: the {self.product} runs programs 0-{self.programs - 1} "
                                                f"(profile {self.profile.name}, arcus.programs = {self.programs})")
            return
        if form == "expression":
            if self.check_variable(st.Ref(target)):
                self.check_expression(stmt.value, res.spelled)
                res.shape = ASSIGN
        elif form == "write":
            if self.check_written_value(stmt.value, keyword, res.spelled):
                res.shape = WRITE
        elif form == "operand":
            self.diags.add("A123", target.span, f"{res.spelled} ({keyword.entry.title}) can be read (V1={res.spelled}) "
                                                "but not set")
        elif form == "glued":
            self.diags.add("A122", target.span, f"a move is written without '=': {keyword.name}1000 or "
                                                f"{keyword.name}V10")
        else:
            self.diags.add("A122", stmt.span, f"{res.spelled} takes no '=' value: write {keyword.usage}")

    def check_variable(self, ref: st.Ref) -> bool:
        info = self.ref(ref)
        if info is None or not info.is_variable:
            return False
        low, high = self.variables
        if not low <= info.match.index <= high:
            self.diags.add("A103", ref.span, f"{ref.part.key}: the {self.product} has {high - low + 1} variables, "
                                             f"V{low}-V{high} (profile {self.profile.name}, arcus.variables)")
            return False
        return True

    def check_written_value(self, value: st.Node, keyword: cat.Keyword, spelled: str) -> bool:
        if isinstance(value, st.Number):
            self.check_range(value, keyword, spelled)
            return True
        if isinstance(value, st.Ref):
            info = self.check_ref(value, "value")
            if info is None:
                return False
            if not info.is_variable:
                self.diags.add("A117", value.span, f"{spelled}= takes a number or a variable: copy "
                                                   f"{info.spelled} into a variable first (V1={info.spelled}, "
                                                   f"{spelled}=V1)")
                return False
            if keyword.literal_only:
                self.diags.add("A118", value.span, f"{spelled}= takes a number written out (e.g. "
                                                   f"{keyword.example}): the manual documents no variable here")
                return False
            return self.check_variable(value)
        self.diags.add("A117", value.span, f"{spelled}= takes a number or a variable, not an expression: compute "
                                           f"it into a variable first (V1=..., then {spelled}=V1)")
        return False

    def check_expression(self, value: st.Node, spelled: str) -> None:
        """V<n>=<arg>, V<n>=<arg><op><arg> or V<n>=~<arg> (L2675-L2677)."""
        count = st.operator_count(value)
        if count > 1:
            self.diags.add("A117", value.span,
                           f"{count} operators in one assignment: the controller evaluates one per statement "
                           f"(L2675); split it, e.g. V1=V2*3 then {spelled}=V1+V4")
        for node in st.walk(value):
            if isinstance(node, st.Number):
                self.check_number(node)
            elif isinstance(node, st.Ref):
                info = self.check_ref(node, "value")
                if info is None or info.is_variable or count == 0:
                    continue
                if not info.keyword.in_operation:
                    self.diags.add("A124", node.span,
                                   f"{info.spelled} can only be copied into a variable (V1={info.spelled}), not "
                                   "used in an operation: copy it first, then compute with the variable")

    def check_ref(self, ref: st.Ref, role: str) -> RefInfo | None:
        """A name read as a value: it must exist and be readable. `role`: value | condition."""
        info = self.ref(ref)
        if info is None:
            match = self.cat.match(ref.part.key)
            if self.foreign(ref.part, match):
                pass
            elif match is not None and match.end == len(ref.part.key):
                self.head(ref.part)  # host-only or other-product: reported there
            elif match is not None and (sibling := self.cat.lookup(match.keyword.name, index=0)) is not None \
                    and sibling.index_range and ref.part.key[match.end:].isdigit():
                low, high = sibling.index_range
                self.diags.add("A119", ref.span, f"{ref.part.key}: {sibling.entry.title.lower()} numbers are "
                                                 f"{sibling.name}{low}-{sibling.name}{high}")
            else:
                self.unknown(ref.part)
            return None
        keyword = info.keyword
        if info.is_variable:
            return info if self.check_variable(ref) else None
        if info.match.axis and not self.check_axis(info.match.axis, ref.span, info.spelled):
            return None
        if not keyword.readable:
            self.diags.add("A124", ref.span, f"{info.spelled} ({keyword.entry.title}) cannot be read in a "
                                             "standalone program")
            return None
        if role == "condition" and not keyword.in_condition:
            self.diags.add("A124", ref.span, f"{info.spelled} cannot be tested directly: copy it into a variable "
                                             f"first (V1={info.spelled}, then IF V1=...)")
            return None
        return info

    def check_number(self, node: st.Number) -> None:
        low, high = self._variable_limits
        if not low <= node.value <= high:
            self.diags.add("A119", node.span, f"{node.text} does not fit in a 32-bit variable ({low} to {high})")

    def check_range(self, node: st.Number, keyword: cat.Keyword, what: str) -> None:
        value = node.value
        allowed = keyword.get("write_values")
        rng = keyword.range
        if isinstance(allowed, list) and value not in allowed:
            self.diags.add("A119", node.span, f"{what}={value}: allowed values are "
                                              f"{', '.join(str(v) for v in allowed)}")
            return
        if rng is not None and not rng[0] <= value <= rng[1]:
            unit = f" {keyword.unit}" if keyword.unit and len(keyword.unit) < 12 else ""
            if keyword.get("range_check", "error") == "warn":
                self.diags.add("A120", node.span, f"{what}={value}{unit} is outside the documented range "
                                                  f"{rng[0]}-{rng[1]}{unit}; check it on the machine")
            else:
                self.diags.add("A119", node.span, f"{what}={value}{unit} is outside the range {rng[0]} to "
                                                  f"{rng[1]}{unit}")
            return
        warn = keyword.get("warn_range")
        if isinstance(warn, list) and not warn[0] <= value <= warn[1]:
            self.diags.add("A120", node.span, f"{what} {value} is outside the 28-bit range {warn[0]} to "
                                              f"{warn[1]} of the position comparator (L773)")

    # conditions ---------------------------------------------------------------------------------
    def conditional(self, res: Resolved, stmt: st.Conditional) -> None:
        res.keyword = self.cat.lookup(stmt.keyword)
        res.shape = CONDITION
        cond = stmt.condition
        if cond.more:
            op = cond.more[0][0]
            self.diags.add("A116", cond.span,
                           f"{stmt.keyword} takes one comparison; '{op}' joins two (L2046): nest two IFs, or "
                           "compute a flag into a variable and test the flag")
        comparison = cond.first
        if comparison.chained:
            self.diags.add("A116", comparison.span,
                           f"{stmt.keyword} takes one comparison <value> <op> <value>, not a chain (L2046)")
        for side in (comparison.left, comparison.right):
            if st.operator_count(side) > 0:
                self.diags.add("A117", side.span, f"{stmt.keyword} compares plain values: compute "
                                                  "the expression into a variable first (V1=..., then "
                                                  f"{stmt.keyword} V1...)")
            for node in st.walk(side):
                if isinstance(node, st.Ref):
                    self.check_ref(node, "condition")
                elif isinstance(node, st.Number):
                    self.check_number(node)
