"""Rebuilding X150's structured constructs from a routine's control-flow graph.

X150 has no labels: a sequence can only express its control flow with `Ln..N`, `IF(c)..ELSE..NIF`,
`WHILE(c)..NWHILE` and `REPEAT..UNTIL(c)`. This structurer walks the blocks in layout order and
recognises the shapes the X150 lowering produces (see lower.py), which are also what any
structured source gives:

- a loop head is a block some later block jumps back to; the last such block (the latch) says
  which loop it is: `Branch(%Lk != 0, head, exit)` an L loop (the counter `%Lk` is set just before
  the head), `Branch(c, exit, head)` a REPEAT..UNTIL(c), `Jump(head)` a WHILE whose head holds only
  `Branch(c, body, exit)`;
- any other Branch is an IF: the then-part runs from the next block up to the `otherwise` block;
  when the then-part's last block jumps past it, the blocks in between are the ELSE part;
- GotoRoutine, Return and End write XG, XRT and HALT; what follows them in layout order is kept.

A loop that runs back while its condition holds becomes REPEAT..UNTIL(NOT c), and a branch that
skips forward when c holds becomes IF(NOT c); the writer turns NOT into the conditions X150 has
(`NOT VAR1<5` is `VAR1>5 OR VAR1=5`) or reports X202. What does not fit (an irreducible graph, a
jump into the middle of a construct, a loop with two ways back) is reported by the caller as X201
and written flat, so nothing is lost silently.
"""

from __future__ import annotations

from dataclasses import dataclass

from mcc.compiler import ir

LOOP_PREFIX = "%L"
MAX_DEPTH = 200  # constructs nested deeper are not rebuilt (the controller allows 16; X110 says so)


@dataclass(slots=True)
class Step:
    """One thing to write: an operation, a construct keyword, or a transfer of control."""

    kind: str  # op | L | IF | ELSE | NIF | WHILE | NWHILE | REPEAT | UNTIL | N | term
    payload: object = None  # the op, the loop count, the condition, or the terminator
    span: object = None


class Unstructured(Exception):
    def __init__(self, message: str, span=None):
        super().__init__(message)
        self.message = message
        self.span = span


def is_counter(expr) -> bool:
    return isinstance(expr, ir.Var) and expr.name.startswith(LOOP_PREFIX)


def counter_test(term) -> str | None:
    """The counter of an L-loop latch `Branch(%Lk != 0, head, exit)`, else None."""
    if isinstance(term, ir.Branch) and isinstance(term.cond, ir.Compare) and term.cond.op == "!=" \
            and is_counter(term.cond.left) and isinstance(term.cond.right, ir.Const) and term.cond.right.value == 0:
        return term.cond.left.name
    return None


class Structurer:
    def __init__(self, routine: ir.Routine, entries: dict[str, str] | None = None):
        self.routine = routine
        self.entries = entries or {}  # entry label of every other routine -> its name
        self.blocks = routine.blocks
        self.index = {block.label: i for i, block in enumerate(self.blocks)}
        self.counts: dict[str, object] = {}
        self.latches: dict[int, list[int]] = {}
        self.steps: list[Step] = []
        self.depth = 0
        for i, block in enumerate(self.blocks):
            for op in block.ops:
                if isinstance(op, ir.Assign) and is_counter(op.target) and not self.decrement(op):
                    self.counts.setdefault(op.target.name, op.value)
            for target in ir.successors(block.terminator):
                j = self.index.get(target)
                if j is not None and j <= i:
                    self.latches.setdefault(j, []).append(i)

    @staticmethod
    def decrement(op: ir.Assign) -> bool:
        value = op.value
        return isinstance(value, ir.BinOp) and is_counter(value.left) and value.left.name == op.target.name

    def run(self) -> list[Step]:
        """The steps of the whole routine; raises Unstructured when the graph has another shape."""
        self.region(0, len(self.blocks), None, None)
        return self.steps

    def at(self, label: str, span) -> int:
        if label not in self.index:
            raise Unstructured(f"a jump to '{label}', which is not a block of this routine", span)
        return self.index[label]

    # -- regions ------------------------------------------------------------------------------------
    def region(self, i: int, stop: int, exit_label: str | None, latch: int | None, skip_head: int = -1) -> None:
        """Write blocks [i, stop). `exit_label` is where the enclosing construct continues, `latch`
        the block whose terminator the enclosing loop writes itself."""
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise Unstructured(f"constructs nested more than {MAX_DEPTH} deep", self.blocks[min(i, stop - 1)].span)
        while i < stop:
            back = [j for j in self.latches.get(i, ()) if i <= j < stop]
            if back and i != skip_head:
                i = self.loop(i, back, stop)
                continue
            i = self.straight(i, stop, exit_label, latch)
        self.depth -= 1

    def ops(self, block: ir.Block) -> None:
        for op in block.ops:
            if isinstance(op, ir.Assign) and is_counter(op.target):
                continue  # the L count and its decrement are written as L n .. N
            self.steps.append(Step("op", op, op.span))

    def straight(self, i: int, stop: int, exit_label: str | None, latch: int | None) -> int:
        block = self.blocks[i]
        self.ops(block)
        if i == latch:
            return i + 1
        term = block.terminator
        span = getattr(term, "span", None) or block.span
        if isinstance(term, ir.Jump) and term.target not in self.index and term.target in self.entries:
            # a jump to the start of another routine (MCode BR across programs): XG, no return
            self.steps.append(Step("term", ir.GotoRoutine(self.entries[term.target], span), span))
            return i + 1
        if isinstance(term, ir.Jump):
            target = self.at(term.target, span)
            if target == i + 1 or (term.target == exit_label and i + 1 == stop):
                return i + 1
            raise Unstructured("a jump that no X150 construct expresses (X150 has no labels)", span)
        if isinstance(term, ir.Branch):
            return self.conditional(i, stop, term, span)
        if isinstance(term, (ir.GotoRoutine, ir.Return, ir.End)):
            self.steps.append(Step("term", term, span))
        return i + 1

    def conditional(self, i: int, stop: int, term: ir.Branch, span) -> int:
        then, other = self.at(term.then, span), self.at(term.otherwise, span)
        if other == i + 1 and then > other:  # `BR past, c` (MCode): IF(NOT c) around the blocks in between
            term = ir.Branch(ir.Not(term.cond, term.span), term.otherwise, term.then, term.span)
            then, other = other, then
        if then != i + 1 or other <= i or other > stop:
            raise Unstructured("a conditional branch that is not an IF(...) ... NIF", span)
        if then == other:
            self.steps += [Step("IF", term.cond, span), Step("NIF", None, self.closing_span(other, span))]
            return other
        last = self.blocks[other - 1].terminator
        join = other
        has_else = False
        if isinstance(last, ir.Jump) and last.target in self.index and self.index[last.target] > other:
            join = self.index[last.target]
            has_else = True
            if join > stop:
                raise Unstructured("an ELSE part that runs past its construct", span)
        join_label = self.blocks[join].label if join < len(self.blocks) else None
        self.steps.append(Step("IF", term.cond, span))
        self.region(then, other, join_label, None)
        if has_else:
            self.steps.append(Step("ELSE", None, getattr(last, "span", None) or span))
            self.region(other, join, join_label, None)
        self.steps.append(Step("NIF", None, self.closing_span(join, span)))
        return join

    def closing_span(self, join: int, span):
        """Where an IF ends: the block after NIF starts at the NIF (X150 lowering), else the jump into it."""
        if join < len(self.blocks) and self.blocks[join].span is not None:
            return self.blocks[join].span
        return getattr(self.blocks[join - 1].terminator, "span", None) or span

    def loop(self, head: int, back: list[int], stop: int) -> int:
        latch = max(back)
        if len(back) > 1:
            raise Unstructured("a loop with more than one way back to its start", self.blocks[latch].span)
        block = self.blocks[head]
        term = self.blocks[latch].terminator
        span = getattr(term, "span", None) or block.span
        after = latch + 1
        counter = counter_test(term)
        if counter is not None and term.then == block.label:
            self.expect(term.otherwise, after, span)
            self.steps.append(Step("L", self.counts.get(counter), block.span or span))
            self.region(head, after, None, latch, skip_head=head)
            self.steps.append(Step("N", None, span))
            return after
        if isinstance(term, ir.Branch) and counter is None and block.label in (term.then, term.otherwise):
            back_on_then = term.then == block.label  # loop while c (MCode `BR head, c`): UNTIL(NOT c)
            self.expect(term.otherwise if back_on_then else term.then, after, span)
            self.steps.append(Step("REPEAT", None, block.span))
            self.region(head, after, None, latch, skip_head=head)
            self.steps.append(Step("UNTIL", ir.Not(term.cond, term.span) if back_on_then else term.cond, span))
            return after
        test = block.terminator
        if isinstance(term, ir.Jump) and isinstance(test, ir.Branch) and not block.ops and latch > head:
            self.expect(test.then, head + 1, span)
            self.expect(test.otherwise, after, span)
            self.steps.append(Step("WHILE", test.cond, block.span))
            self.region(head + 1, after, block.label, latch)
            self.steps.append(Step("NWHILE", None, span))
            return after
        raise Unstructured("a loop that is not L..N, WHILE..NWHILE or REPEAT..UNTIL", span)

    def expect(self, label: str, index: int, span) -> None:
        if self.index.get(label) != index and not (index == len(self.blocks) and label not in self.index):
            raise Unstructured("a loop exit that does not continue right after the loop", span)


def flat_steps(routine: ir.Routine) -> list[Step]:
    """Every operation in layout order, for writing a routine that could not be structured."""
    steps = []
    for block in routine.blocks:
        for op in block.ops:
            if not (isinstance(op, ir.Assign) and is_counter(op.target)):
                steps.append(Step("op", op, op.span))
        if isinstance(block.terminator, (ir.GotoRoutine, ir.Return, ir.End)):
            steps.append(Step("term", block.terminator, block.terminator.span))
    return steps
