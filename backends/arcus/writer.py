"""Pass 4: the structured routines as Arcus statements, one canonical statement per line.

The layout is the main program (the setup lines first), END, then one SUB ... ENDSUB block per
subroutine. Each statement also carries the pseudo-instructions it expands to (its "natural"
assembly rows) and which other statements they jump to, because only the writer knows the shape of
what it writes (an ELSEIF first jumps to ENDIF, then tests); costmodel.py prices and numbers them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mcc.backends.arcus.context import Context
from mcc.backends.arcus.target import HOME_KEYWORDS, MOTION_IR
from mcc.backends.structure import EndNode, IfNode, Simple, WhileNode
from mcc.compiler import ir
from mcc.compiler.arcus import catalog as arcus_catalog
from mcc.compiler.span import Span

OPCODES = {"+": "ADD", "-": "SUB", "*": "MUL", "/": "DIV", "%": "MOD", "&": "AND", "|": "OR", "<<": "SHL",
           ">>": "SHR", "~": "NOT"}


@dataclass
class Stmt:
    """One line of the output and the assembly lines it costs."""

    text: str
    key: str  # cost key (catalog name, V, V_OP; a move lists its axes)
    spans: tuple[Span, ...]
    rows: list[tuple[str, str]] = field(default_factory=list)  # (opcode, operands) of the natural expansion
    jumps: dict[str, int] = field(default_factory=dict)  # placeholder -> statement index
    cost: int = 0
    address: int = 0


class Writer:
    """Flattens structured routines into statements, in program order."""

    def __init__(self, ctx: Context):
        self.ctx = ctx
        self.stmts: list[Stmt] = []
        cat = ctx.cat
        self.by_ir = {k.ir: k for k in cat.keywords if k.ir and k.kind not in (arcus_catalog.ASCII_ONLY,)}
        self.homes = {int(k.get("home_mode")): k for k in cat.keywords
                      if k.ir == "home" and k.get("home_mode") is not None}

    def program(self, main: list, subs: list[tuple[ir.Routine, list, Span | None]],
                programs: list[tuple[ir.Routine, list, Span | None]] = ()) -> list[Stmt]:
        """The main program, END unless it ends with one, then each subroutine as SUB n ... ENDSUB.
        With `programs` (PRG n, n >= 1: products that run several programs at once) the main
        program is written as PRG 0 and each other program as PRG n ... END before the subroutines."""
        if programs:
            self.add("PRG 0", "PRG", None, [("ENTRY", "PRG 0")])
        self.flatten(main)
        if not main or not isinstance(main[-1], EndNode):
            self.add("END", "END", None, [("HALT", "")])
        for routine, code, _ in programs:
            self.add(f"PRG {routine.number}", "PRG", routine.span, [("ENTRY", f"PRG {routine.number}")])
            self.flatten(code)
            if not code or not isinstance(code[-1], EndNode):
                self.add("END", "END", None, [("HALT", "")])
        for routine, code, end_span in subs:
            number = self.ctx.sub_numbers.get(routine.name)
            if number is None:
                continue  # no SUB number left: A207 is already reported and the output is refused
            self.add(f"SUB {number}", "SUB", routine.span, [("ENTRY", f"SUB {number}")])
            self.flatten(code)
            self.add("ENDSUB", "ENDSUB", end_span, [("RET", "")])
        return self.stmts

    # statements ------------------------------------------------------------------------------------
    def add(self, text: str, key: str, span: Span | None, rows: list[tuple[str, str]],
            jumps: dict[str, int] | None = None) -> int:
        self.stmts.append(Stmt(text, key, (span,) if span is not None else (), rows, jumps or {}))
        return len(self.stmts) - 1

    def flatten(self, nodes: list) -> None:
        for node in nodes:
            if isinstance(node, Simple):
                self.simple(node.op)
            elif isinstance(node, EndNode):
                self.add("END", "END", node.span, [("HALT", "")])
            elif isinstance(node, WhileNode):
                head = self.add(f"WHILE {self.cond_text(node.cond)}", "WHILE", node.span,
                                [("TEST", self.cond_text(node.cond)), ("JF", "{after}")])
                self.flatten(node.body)
                tail = self.add("ENDWHILE", "ENDWHILE", node.end_span or node.span, [("JMP", "{head}")],
                                {"head": head})
                self.stmts[head].jumps["after"] = tail + 1
            else:
                self.if_(node)

    def if_(self, node: IfNode) -> None:
        tests: list[int] = []
        exits: list[int] = []
        for i, (cond, body) in enumerate(node.arms):
            text = self.cond_text(cond)
            span = node.spans[i] if i < len(node.spans) else None
            if i == 0:
                index = self.add(f"IF {text}", "IF", span, [("TEST", text), ("JF", "{next}")])
            else:
                index = self.add(f"ELSEIF {text}", "ELSEIF", span,
                                 [("JMP", "{end}"), ("TEST", text), ("JF", "{next}")])
                exits.append(index)
                self.stmts[tests[-1]].jumps["next"] = index
            tests.append(index)
            self.flatten(body)
        if node.orelse:
            index = self.add("ELSE", "ELSE", node.else_span or node.spans[0], [("JMP", "{end}")])
            exits.append(index)
            self.stmts[tests[-1]].jumps["next"] = index
            self.flatten(node.orelse)
        end = self.add("ENDIF", "ENDIF", node.end_span or node.spans[0], [("NOP", "")])
        if "next" not in self.stmts[tests[-1]].jumps:
            self.stmts[tests[-1]].jumps["next"] = end
        for index in exits:
            self.stmts[index].jumps["end"] = end

    def simple(self, op: ir.Op) -> None:
        """One operation as one statement (WAIT on every axis is one per axis), by its handler in
        `WRITE_METHODS`. The legaliser (legalize.py) has refused or rewritten every operation the
        table lacks, so one reaching here without a handler is mcc's mistake: an internal error, never
        a statement dropped silently."""
        method = WRITE_METHODS.get(type(op))
        if method is None:
            raise AssertionError(f"the Arcus writer has no handler for {type(op).__name__}: the legaliser "
                                 "should have rewritten or refused it")
        method(self, op)

    def _assign(self, op: ir.Assign) -> None:
        value, target, text = op.value, op.target.name, self.text
        if isinstance(value, ir.BinOp):
            rows = [("LOAD", text(value.left)), (OPCODES[value.op], f"{text(value.right)} -> {target}")]
            self.add(f"{target}={text(value)}", "V_OP", op.span, rows)
        elif isinstance(value, ir.UnOp):
            rows = [("LOAD", text(value.operand)), ("NOT", f"-> {target}")]
            self.add(f"{target}={text(value)}", "V_OP", op.span, rows)
        else:
            self.add(f"{target}={text(value)}", "V", op.span, [("LET", f"{target} <- {text(value)}")])

    def _set_motion(self, op: ir.SetMotion) -> None:
        keyword = self.by_ir[MOTION_IR[op.param]]
        name = keyword.spell(op.axis if op.axis != ir.ALL_AXES else "")
        self.write(name, keyword.name, op.value, op.span)

    def _move(self, op: ir.Move) -> None:
        parts = "".join(f"{axis}{self.text(value)}" for axis, value in op.targets)
        rows = [("MOVE", f"{axis} <- {self.text(value)}") for axis, value in op.targets]
        self.add(parts, " ".join(axis for axis, _ in op.targets), op.span, rows)

    def _arc(self, op: ir.Arc) -> None:
        keyword = self.by_ir["arc" if op.angle is not None else "circle"]
        suffix = "P" if op.clockwise else "N"
        operands = [self.text(c) for c in op.center] + ([self.text(op.angle)] if op.angle is not None else [])
        name = keyword.spell(suffix=suffix)
        rows = [("ARG", v) for v in operands] + [(name, "")]
        self.add(f"{name}{':'.join(operands)}", keyword.name, op.span, rows)

    def _slew(self, op: ir.Slew) -> None:
        self.bare(self.by_ir["jog"], op.span, axis=op.axis, direction=op.direction)

    def _home(self, op: ir.Home) -> None:
        self.bare(self.homes[HOME_KEYWORDS[op.method]], op.span, axis=op.axis, direction=op.direction)

    def _stop(self, op: ir.Stop) -> None:
        keyword = self.by_ir["stop" if op.ramp else "abort"]
        self.bare(keyword, op.span, axis=op.axis if op.axis != ir.ALL_AXES else "")

    def _wait_motion(self, op: ir.WaitMotion) -> None:
        for axis in (self.ctx.config.axes if op.axis == ir.ALL_AXES else (op.axis,)):
            self.bare(self.by_ir["wait_motion"], op.span, axis=axis)

    def _delay(self, op: ir.Delay) -> None:
        self.write("DELAY", "DELAY", op.duration, op.span)

    def _set_output(self, op: ir.SetOutput) -> None:
        keyword = self.ctx.cat.lookup("DO", index=op.index)
        self.write(keyword.spell(index=op.index), keyword.name, op.value, op.span)

    def _set_position(self, op: ir.SetPosition) -> None:
        keyword = self.by_ir["position"]
        self.write(keyword.spell(op.axis), keyword.name, op.value, op.span)

    def _call(self, op: ir.Call) -> None:
        number = self.ctx.sub_numbers.get(op.routine)
        if number is None:
            return  # the legaliser reported the call to a subroutine without a number
        self.add(f"GOSUB {number}", "GOSUB", op.span, [("CALL", "{sub%d}" % number)])

    def _native(self, op: ir.Native) -> None:
        keyword = self.ctx.keyword_of(op.mnemonic)
        key = keyword.name if keyword is not None else op.mnemonic
        if op.args:
            self.write(op.mnemonic, key, op.args[0], op.span, form=op.form or "=")
        else:
            self.add(op.mnemonic, key, op.span, [("EXEC", op.mnemonic)])

    def write(self, name: str, key: str, value: ir.Expr, span: Span | None, form: str = "=") -> None:
        self.add(f"{name}{form}{self.text(value)}", key, span, [("SET", f"{name} <- {self.text(value)}")])

    def bare(self, keyword: arcus_catalog.Keyword, span: Span | None, axis: str = "", direction: int = 0) -> None:
        name = keyword.spell(axis, direction=direction)
        self.add(name, keyword.name, span, [("EXEC", name)])

    # values --------------------------------------------------------------------------------------------
    def text(self, value: ir.Expr) -> str:
        if isinstance(value, ir.Const):
            return str(int(value.value))
        if isinstance(value, ir.Var):
            return value.name
        if isinstance(value, ir.DeviceRef):
            keyword = self.ctx.register(value)
            if keyword is None:
                return value.name
            return keyword.spell(value.axis if value.axis != ir.ALL_AXES else "", value.index)
        if isinstance(value, ir.UnOp):
            return f"~{self.text(value.operand)}"
        if isinstance(value, ir.BinOp):
            return f"{self.text(value.left)}{value.op}{self.text(value.right)}"
        return "?"

    def cond_text(self, cond: ir.Compare) -> str:
        return f"{self.text(cond.left)}{cond.op}{self.text(cond.right)}"


# One handler per operation of the table (compiler/ir_ops.py) that reaches the writer; the legaliser
# rewrites the others into these or refuses them at their line (tests/ir/test_handlers.py).
WRITE_METHODS = {
    ir.Assign: Writer._assign,
    ir.SetMotion: Writer._set_motion,
    ir.Move: Writer._move,
    ir.Arc: Writer._arc,
    ir.Slew: Writer._slew,
    ir.Home: Writer._home,
    ir.Stop: Writer._stop,
    ir.WaitMotion: Writer._wait_motion,
    ir.Delay: Writer._delay,
    ir.SetOutput: Writer._set_output,
    ir.SetPosition: Writer._set_position,
    ir.Call: Writer._call,
    ir.Native: Writer._native,
}
