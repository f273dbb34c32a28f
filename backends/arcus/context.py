"""What every pass of one compilation shares: the module and profile, the Arcus catalog, the
diagnostics, and the names given so far (V numbers for the program's variables, SUB numbers).

The passes run routine by routine, but these are decided once for the whole program: a variable
must get the same V number in every routine, and a GOSUB needs its subroutine's number before that
subroutine is compiled.
"""

from __future__ import annotations

import re
from functools import cached_property

from mcc.backends.arcus.convert import Axes, Scale
from mcc.backends.arcus.target import DEDICATED_INPUTS, DIALECT, Config
from mcc.backends.arcus.temporaries import Temps
from mcc.backends.input_setup import InputSetup
from mcc.compiler import in_force, ir
from mcc.compiler.arcus import catalog as arcus_catalog
from mcc.compiler.diagnostics import Diagnostics, Severity
from mcc.compiler.profiles import Profile
from mcc.compiler.span import Span

VARIABLE = re.compile(r"V([0-9]+)\Z", re.IGNORECASE)


class Context:
    def __init__(self, module: ir.Module, profile: Profile):
        self.module = module
        self.profile = profile
        self.config = Config.from_profile(profile)
        self.cat = arcus_catalog.load(profile.product)
        self.diags = Diagnostics()
        self.temps = Temps(self.config.temporaries)
        self.var_map: dict[str, str] = {}
        self.sub_numbers: dict[str, int] = {}
        self.entries = {r.blocks[0].label: r for r in module.routines if r.blocks}  # entry label -> routine
        self.reported: dict[int, object] = {}
        self.scale = Scale(module.steps_per_rev, profile.steps_per_rev)
        self.axes = Axes(module, self.config.axes)
        self._in_force: dict[int, in_force.State] | None = None
        self.input_setup = InputSetup(module, DEDICATED_INPUTS)  # MCode IS lines the PMX-4EX-SA needs no set-up for

    @cached_property
    def sets_accel(self) -> bool:
        """Whether any operation sets a constant acceleration or deceleration in steps/s^2: without
        one, no state of the in-force analysis holds one (it starts empty), and the legalizer's ramp
        questions that need one are answered without the analysis."""
        rates = (ir.MotionParam.ACCEL, ir.MotionParam.DECEL)
        return any(isinstance(op, ir.SetMotion) and op.param in rates and isinstance(op.value, ir.Const)
                   for _, block in self.module.blocks() for op in block.ops)

    @cached_property
    def plain_outputs(self) -> set[int]:
        """The outputs whose set-up the PMX-4EX-SA needs no statement for: set up as general outputs
        (what DO1-DO8 are, arcus-pmx-4ex-sa.txt L752), and, if given a level, active high (an Arcus
        output turned on sources VS, L357, L752) before the program does anything else, everywhere
        it is set. Another function or level is refused by the legalizer."""
        functions: dict[int, set] = {}
        levels: dict[int, list] = {}
        for _, block in self.module.blocks():
            for op in block.ops:
                if isinstance(op, ir.Setting) and op.index is not None:
                    if op.name == "output_function":
                        functions.setdefault(op.index, set()).add(
                            op.value.value if isinstance(op.value, ir.Text) else None)
                    elif op.name == "output_active_high":
                        levels.setdefault(op.index, []).append(op)
        leading: set[int] = set()
        first = next((r for kind in (ir.RoutineKind.IMMEDIATE, ir.RoutineKind.MAIN) for r in self.module.routines
                      if r.kind is kind and r.blocks), None)
        if first is not None:
            for op in first.blocks[0].ops:
                if not isinstance(op, (ir.Setting, ir.SetMotion)):
                    break
                leading.add(id(op))
        plain = set()
        for index in set(functions) | set(levels):
            if not 1 <= index <= 8 or functions.get(index, {"general"}) != {"general"}:
                continue
            if all(isinstance(op.value, ir.Const) and op.value.value == 1 and id(op) in leading
                   for op in levels.get(index, [])):
                plain.add(index)
        return plain

    @cached_property
    def settled_ops(self) -> set[int]:
        """The operations (by id) before which no move can still be running (`ir.settled_ops`)."""
        return ir.settled_ops(self.module)

    def in_force_before(self, op: ir.Op) -> in_force.State:
        """The motion settings in force just before `op` (constants known by data flow)."""
        if self._in_force is None:
            self._analysis = in_force.InForce(self.module)
            self._in_force = {}
            self._block_of = {id(o): block for _, block in self.module.blocks() for o in block.ops}
        found = self._in_force.get(id(op))
        if found is None:
            # The states of a block's operations, replayed once, when one of them is first asked
            # for: the legalizer asks for a few operations only (ramps, speeds, moves).
            block = self._block_of.get(id(op))
            if block is None:
                return {}
            state = self._analysis.at_entry(block.label)
            for o in block.ops:
                self._in_force[id(o)] = state
                state = self._analysis.after(state, o)
            found = self._in_force[id(op)]
        return found

    # diagnostics ------------------------------------------------------------------------------
    def file_span(self) -> Span:
        return Span(self.module.path or "<ir>", 1, 1, 1, 1, 0, 0)

    def span_of(self, op) -> Span:
        span = getattr(op, "span", None)
        return span if span is not None else self.file_span()

    def first_report(self, op) -> bool:
        """True the first time `op` is reported: one diagnostic per operation, however often it is met."""
        if id(op) in self.reported:
            return False
        self.reported[id(op)] = op  # kept alive so that its id is not reused
        return True

    def unsupported(self, op, why: str, code: str = "G003", severity_note: bool = False) -> None:
        """An operation that is not written (or not in full), once per operation."""
        if self.first_report(op):
            self.unsupported_at(getattr(op, "span", None), why, code, severity_note)

    def unsupported_at(self, span: Span | None, why: str, code: str = "G003", severity_note: bool = False) -> None:
        """Something not written that is no operation of the source (a jump, a condition, a routine)."""
        self.diags.add(code, span if span is not None else self.file_span(),
                       f"not written for the Arcus PMX-4EX-SA: {why}",
                       severity=Severity.WARNING if severity_note else None)

    # names -------------------------------------------------------------------------------------
    def var(self, var: ir.Var) -> ir.Var:
        """The Arcus variable for an IR variable: Vn stays, other names get the first free V number."""
        name = var.name.upper()
        if VARIABLE.match(name):
            return var if name == var.name else ir.Var(name, var.span)  # an IR value is never changed
        if name not in self.var_map:
            used = {int(VARIABLE.match(n.upper()).group(1)) for n in self.variable_names
                    if VARIABLE.match(n.upper())} | set(self.config.temporaries) | \
                   {int(v[1:]) for v in self.var_map.values()}
            low, high = self.config.variables
            free = next((i for i in range(low, high + 1) if i not in used), None)
            if free is None:
                self.diags.add("A205", self.span_of(var), f"no Arcus variable left for {var.name}: V{low}-V{high} "
                                                          "are all used or reserved")
                free = low
            self.var_map[name] = f"V{free}"
        return ir.Var(self.var_map[name], var.span)

    @cached_property
    def variable_names(self) -> set[str]:
        """Every variable name the program declares, writes or reads."""
        names = set(self.module.variables)
        for _, block in self.module.blocks():
            for op in block.ops:
                if isinstance(op, ir.Assign):
                    names.add(op.target.name)
                for expr in ir.op_exprs(op):
                    names.update(e.name for e in ir.walk_expr(expr) if isinstance(e, ir.Var))
            names.update(e.name for expr in ir.term_exprs(block.terminator) for e in ir.walk_expr(expr)
                         if isinstance(e, ir.Var))
        return names

    def number_subroutines(self) -> None:
        """SUB numbers: the source's own where the profile's range allows, the first free ones otherwise."""
        low, high = self.config.sub_range
        taken: set[int] = set()
        pending: list[ir.Routine] = []
        for routine in self.module.routines:
            if routine.kind is not ir.RoutineKind.SUBROUTINE:
                continue
            number = routine.number
            if number is not None and low <= number <= high and number not in taken:
                self.sub_numbers[routine.name] = number
                taken.add(number)
            else:
                pending.append(routine)
        candidates = (n for n in range(max(low, self.config.allocate_from), high + 1) if n not in taken)
        for routine in pending:
            number = next(candidates, None)
            if number is None:
                self.diags.add("A207", routine.span or self.file_span(),
                               f"no subroutine number left for {routine.name}: the profile allows {low}-{high}")
                continue
            self.sub_numbers[routine.name] = number
            taken.add(number)

    # the catalog -------------------------------------------------------------------------------
    def keyword_of(self, mnemonic: str) -> arcus_catalog.Keyword | None:
        match = self.cat.match(mnemonic.upper())
        return match.keyword if match is not None else None

    def register(self, ref: ir.DeviceRef) -> arcus_catalog.Keyword | None:
        if ref.dialect != DIALECT:
            return None
        return self.cat.lookup(ref.name, ref.axis, ref.index)
