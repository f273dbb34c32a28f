"""Input set-up that a target needs none of (issue 24, "Cross-compilation of real programs").

MCode assigns a function and an active level to each of its general I/O lines (`IS=4,1,1`: input 4
is the home switch, active high; lexium-mcode.txt L6936-L6959). The X150 and the PMX-4EX-SA have the
home and limit switches on inputs of their own ("the HOME input", parker-x150.md L3841; "+limit,
-limit, home, and alarm inputs for each axis", arcus-pmx-4ex-sa.txt L333), and the PMX-4EX-SA's DI1-DI8
are general inputs with no function to choose. A set-up that only says "this line is the home (limit,
general) input" therefore has nothing to say on those targets: the switch is wired to the target's own
input, whose level is a property of the wiring (X150 links 15/17, L2064-L2068; Arcus POX from the
host, L700-L704), not of the program.

A general line keeps its number on the PMX-4EX-SA (DIn), so its function needs no statement; its
level does, when the program reads the line. Otherwise the set-up of a line is dropped only when every function the program gives
it is one the target has without set-up and the program never reads the line as an input itself
(it reads a switch, if at all, through the neutral home_switch/limit readings, which do not depend
on the MCode line): on the target the same line number would be another input. Everything else stays
for the backend to write or refuse with its line. The translation is still simulated against its
source (--verify), so a dropped set-up that changed what the program does would be refused (S010).
"""
from __future__ import annotations

from mcc.compiler import ir


def _reads_inputs(module: ir.Module) -> set[int] | None:
    """The input lines the program reads (conditions, expressions, input handlers); None when it
    reads every line at once (a bank read or a pattern), so that no line is known unread."""
    lines: set[int] = set()
    for _, block in module.blocks():
        exprs = [e for op in block.ops for e in ir.op_exprs(op)] + list(ir.term_exprs(block.terminator))
        for op in block.ops:
            if isinstance(op, ir.SetHandler) and op.event == "input":
                if op.args and isinstance(op.args[0], ir.Const):
                    lines.add(int(op.args[0].value))
                else:
                    return None
        for expr in exprs:
            for node in ir.walk_expr(expr):
                if isinstance(node, ir.InputMatch):
                    return None
                if isinstance(node, ir.Status) and node.meaning in ("inputs", "input_levels"):
                    return None
                if isinstance(node, ir.Status) and node.meaning == "input":
                    if node.index is None:
                        return None
                    lines.add(node.index)
    return lines


def _functions(module: ir.Module) -> dict[int, set[str]]:
    """Every function the program gives each input line (a line may be set up more than once)."""
    found: dict[int, set[str]] = {}
    for _, block in module.blocks():
        for op in block.ops:
            if isinstance(op, ir.Setting) and op.name == "input_function" and op.index is not None:
                value = op.value.value if isinstance(op.value, ir.Text) else "?"
                found.setdefault(op.index, set()).add(value)
    return found


class InputSetup:
    """Decides, once per module, which input_function / input_active_high settings a target writes
    as nothing: `dedicated` are the input functions the target has on inputs of its own, with no
    set-up in the program (its backend says which)."""

    def __init__(self, module: ir.Module, dedicated: frozenset[str]):
        self.dedicated = dedicated
        self.functions = _functions(module)
        self.read = _reads_inputs(module)

    def needs_none(self, op: ir.Op) -> bool:
        if not isinstance(op, ir.Setting) or op.index is None or not self.dedicated:
            return False
        if op.name not in ("input_function", "input_active_high"):
            return False
        functions = self.functions.get(op.index)
        if not functions or not functions <= self.dedicated:
            return False  # a line the target sets up (or no function known): written or refused
        if op.name == "input_function" and functions == {"general"}:
            return True  # the target's input of that number is a general input already
        # the program never reads the line itself: on the target the line would be another input
        return self.read is not None and op.index not in self.read
