"""Structured control flow (if/else chains, while loops, sequences) rebuilt from one routine's CFG.

Targets without GOTO (Arcus; later, perhaps, X150) cannot write a CFG as it is: they need nested
constructs. `structure(routine, ...)` turns a routine's blocks into a tree of those constructs that
a backend's writer prints in its own spelling. Nothing here knows a target's syntax; it reads and
builds `mcc.compiler.ir` only, and takes its orderings, dominators and loops from the analysis
library (`mcc.compiler.cfg`).

What it produces, a list of nodes executed in order (a sequence), each one of:

- `Simple(op)`: one IR operation, as the block held it;
- `IfNode(arms, orelse)`: `if c1: ... elif c2: ... else: ...`, the arms tested in order;
- `WhileNode(cond, body)`: test `cond`, run `body`, again while it holds (no break or continue:
  the only way out is the test, or an `EndNode`);
- `EndNode`: the program stops here (an `ir.End`, or another terminator the caller lists in `stops`:
  X150 also stops a routine with `GotoRoutine` (XG) and a `Return` (XRT) in the middle of it);
- `RepeatNode(body, until)`: run `body`, again until `until` holds (a loop tested at its end), made
  only when the caller passes `repeat=True` (targets with REPEAT..UNTIL or counted loops).

The routine's own end (`ir.Return`, `ir.FallOff`) is the end of the list; its span is returned as
`Structured.exit_span` for the writer's closing line.

How, in the spirit of Ramsey's "Beyond Relooper" (ICFP 2022) without `br` or `break`: a branch
becomes an if whose arms end at the branch's unique merge child in the dominator tree (or at the
enclosing follow); a loop (header = target of a back edge) becomes a while when its only exit is the
header's test. A loop left from one other place is first rewritten with a flag variable
(`f=1; while f=1 ... f=0`); a loop that exits at its header after some operations (a do-while) has
those operations copied before the while and at the end of its body, up to `max_copied` of them. A
block that only ENDs, with at most `tail_copy` operations, may be written twice. Anything else (an
irreducible graph, a loop with several exits, arms that meet at two places) makes the routine a
*dispatch loop*: `v = <entry>; while v != 0: if v = 1: ... elif v = 2: ...`, one arm per block, each
setting `v` to the number of the next block (0 for the routine's end). `Structured.fallback` then
says why, in words meant for the user's diagnostic ("a loop is left from several places").

What it assumes of the routine (the backend's legaliser establishes it first):

- the first block is the entry; every jump target is a block of the same routine (edges to other
  labels are ignored);
- terminators are `Jump`, `Branch`, `End` (stop), or `Return`/`FallOff`/None (the routine's end);
  others (`GotoRoutine`) are not expected: the legaliser rewrites them;
- a branch condition is an `ir.Compare` whose operator is one of = != < <= > >= (it may be negated
  to put the arms in order): AND, OR and NOT must already be computed into plain comparisons;
- operations never transfer control; they are carried into `Simple` nodes untouched, and the same
  op object may appear twice in the tree (copied loop tests and END blocks);
- the target can write `v = <integer>` assignments and `v = <integer>` / `v != 0` tests for the flag
  and dispatch variables the caller supplies, which the caller keeps apart from the program's own.

The routine passed in is not changed (loops are flagged on a copy). Labels of blocks this module
makes end in '%' like those of other compiler-made blocks.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Union

from mcc.compiler import ir
from mcc.compiler.cfg.loops import back_edges, latches, natural_loop, reducible
from mcc.compiler.cfg.dominators import DominatorTree
from mcc.compiler.cfg.graph import BlockIndex, all_paths_reach, depth_first, predecessors
from mcc.compiler.span import Span

EXIT = "%exit"  # the virtual node every routine end leads to
TAIL_COPY = 4  # operations of an END block the structurer may write twice rather than give up
# IF and WHILE blocks nested deeper than this are not rebuilt: the routine becomes a dispatch loop,
# which is flat, so neither this module nor a writer walking its tree recurses more than this deep.
MAX_NESTING = 64
NEGATE = {"=": "!=", "!=": "=", "<": ">=", ">=": "<", ">": "<=", "<=": ">"}
TRUE = ir.Compare("=", ir.Const(1), ir.Const(1))  # the test of an endless loop


class Unstructurable(Exception):
    """The CFG has no if/while form (the reason is the message)."""


def negate(cond):
    """The opposite condition: a comparison with the opposite operator; any other condition (a
    target that keeps AND, OR and input patterns, such as X150) wrapped in, or taken out of, `Not`."""
    if isinstance(cond, ir.Compare):
        return ir.Compare(NEGATE[cond.op], cond.left, cond.right, cond.span)
    if isinstance(cond, ir.Not):
        return cond.cond
    return ir.Not(cond, getattr(cond, "span", None))


# =============================================================================================
# The structured tree


@dataclass
class Simple:
    op: ir.Op


@dataclass
class IfNode:
    arms: list[tuple[ir.Compare, list]]  # the if arm, then the elif arms: (condition, body)
    orelse: list
    spans: list[Span | None]  # the if and elif tests
    else_span: Span | None = None
    end_span: Span | None = None


@dataclass
class WhileNode:
    cond: ir.Compare
    body: list
    span: Span | None = None
    end_span: Span | None = None


@dataclass
class EndNode:
    span: Span | None = None
    term: object = None  # the terminator that stops here (ir.End unless the caller passed `stops`)


@dataclass
class RepeatNode:
    """`body` runs, then again until `until` holds (only with `structure(..., repeat=True)`)."""

    body: list
    until: object  # an ir.Cond
    span: Span | None = None  # the loop's first block
    end_span: Span | None = None  # the test at its end


Node = Union[Simple, IfNode, WhileNode, EndNode, RepeatNode]


@dataclass
class Structured:
    """A routine as a tree, or as a dispatch loop when `fallback` (the reason) is set."""

    body: list
    exit_span: Span | None  # where the routine ends (its Return or FallOff), for the closing line
    fallback: str | None = None
    var: ir.Var | None = None  # the dispatch variable, set with `fallback`


def structure(routine: ir.Routine, flag: Callable[[int], ir.Var | None], dispatch_var: Callable[[], ir.Var],
              max_copied: int = 4, tail_copy: int = TAIL_COPY, stops: tuple = (ir.End,),
              repeat: bool = False) -> Structured:
    """The routine as a structured tree, or as a dispatch loop when it has none.

    `flag(depth)` is the loop flag for a loop nested `depth` loops deep (None when none is left,
    which makes the routine a dispatch loop); `dispatch_var()` is asked for the dispatch variable
    only when one is needed. Both must keep their values across the routine's operations, calls
    included. `stops` are the terminator kinds written in place as an `EndNode` (the routine does not
    go on after them); `repeat=True` makes loops tested at their end `RepeatNode`s instead of
    flagged whiles."""
    try:
        graph = flag_loops(routine, flag, max_copied, stops, repeat)  # rewrites a copy, if anything
        structurer = Structurer(routine, tail_copy, stops, repeat, graph)
        return Structured(structurer.run(), structurer.exit_span)
    except Unstructurable as why:
        var = dispatch_var()
        exit_span = next((b.terminator.span for b in routine.blocks
                          if isinstance(b.terminator, (ir.Return, ir.FallOff)) and not isinstance(b.terminator, stops)),
                         None)
        return Structured(dispatch(routine, var, stops), exit_span, str(why), var)


def copy_block(block: ir.Block) -> ir.Block:
    """A block whose terminator may be retargeted without touching the original."""
    term = block.terminator
    if isinstance(term, ir.Jump):
        term = ir.Jump(term.target, term.span)
    elif isinstance(term, ir.Branch):
        term = ir.Branch(term.cond, term.then, term.otherwise, term.span)
    return ir.Block(block.label, list(block.ops), term, block.span, block.named)


# =============================================================================================
# The graph


class Graph:
    """Reachability, dominators and loops of one routine's CFG (with a virtual exit node), from
    the analysis library (`mcc.compiler.cfg`): this class adds the structurer's view of a routine
    (which terminators end it, the virtual EXIT) and answers by label. The library computes over
    block numbers (`self.nodes`); the label-keyed answers the structurer asks for are built once."""

    def __init__(self, routine: ir.Routine, stops: tuple = (ir.End,)):
        self.stops = stops
        self._terminating: set[str] | None = None
        self.blocks = {b.label: b for b in routine.blocks}
        self.entry = routine.blocks[0].label if routine.blocks else EXIT
        self.succ: dict[str, list[str]] = {}
        ending: list[str] = []  # the blocks whose terminator stops the program
        for label, block in self.blocks.items():
            term = block.terminator
            if (isinstance(term, (ir.Return, ir.FallOff)) and not isinstance(term, stops)) or term is None:
                self.succ[label] = [EXIT]
            else:
                self.succ[label] = [t for t in ir.successors(term) if t in self.blocks]
                if isinstance(term, stops):
                    ending.append(label)
        self.succ[EXIT] = []
        nodes = self.nodes = BlockIndex.of(list(self.succ), self.succ.values())
        labels, size = nodes.labels, len(nodes.labels)
        walk = depth_first(nodes.number[self.entry], nodes.succ)
        rpo = self._rpo = walk.reverse_postorder
        self.order = [labels[n] for n in rpo]
        self._rank = [-1] * size
        for i, n in enumerate(rpo):
            self._rank[n] = i
        self._preds = predecessors(rpo, nodes.succ, size)
        self._tree = DominatorTree(rpo, self._preds, size)
        back = back_edges(rpo, nodes.succ, self._tree)
        self.headers = {labels[v] for _, v in back}
        self._latches = latches(rpo, nodes.succ, back)
        # each block's predecessors along forward (not back) edges, which IF merges and elifs count
        self._forward_in = [0] * size
        for u in rpo:
            for v in nodes.succ[u]:
                if (u, v) not in back:
                    self._forward_in[v] += 1
        self.reducible = reducible(walk, self._tree)
        self._ending = [nodes.number[label] for label in ending]
        self._bodies: dict[str, set[str]] = {}

    def rank(self, label: str) -> int:
        """The block's place in the reverse postorder (`order`)."""
        return self._rank[self.nodes.number[label]]

    def children(self, label: str) -> list[str]:
        """The block's children in the dominator tree, in reverse postorder."""
        labels = self.nodes.labels
        return [labels[n] for n in self._tree.children[self.nodes.number[label]]]

    def forward_preds(self, label: str) -> int:
        number = self.nodes.number.get(label)
        return self._forward_in[number] if number is not None else 0

    def loop_body(self, header: str) -> set[str]:
        """The natural loop of `header` (computed once per header: flag_loops and the structurer
        both ask; callers only read it)."""
        body = self._bodies.get(header)
        if body is None:
            number = self.nodes.number[header]
            labels = self.nodes.labels
            found = natural_loop(number, self._latches.get(number, ()), self._preds)
            body = self._bodies[header] = {labels[n] for n in found}
        return body

    def latches(self, header: str) -> list[str]:
        """The sources of the back edges to `header`, in reverse postorder."""
        labels = self.nodes.labels
        return [labels[n] for n in self._latches.get(self.nodes.number[header], ())]

    def terminating(self) -> set[str]:
        """Blocks from which every path ends at an END (never falls through to anything after).
        Computed once per graph (a graph is not changed once built); callers only read the set."""
        if self._terminating is None:
            labels = self.nodes.labels
            found = all_paths_reach(self._rpo, self.nodes.succ, self._preds, self._ending)
            self._terminating = {labels[n] for n in found}
        return self._terminating

    def exits(self, header: str, body: set[str], ends: set[str]) -> list[tuple[str, str]]:
        return [(u, v) for u in body for v in self.succ[u] if v not in body and v not in ends]

    def repeat_latch(self, header: str, body: set[str], ends: set[str]) -> str | None:
        """The block that ends a loop tested at its end: the one way back to `header`, a branch whose
        other arm is the loop's only exit (edges to blocks that END excepted); else None."""
        latches = self.latches(header)
        if len(latches) != 1:
            return None
        latch = latches[0]
        term = self.blocks[latch].terminator
        if not isinstance(term, ir.Branch) or header not in (term.then, term.otherwise) or term.then == term.otherwise:
            return None
        out = term.otherwise if term.then == header else term.then
        others = [edge for edge in self.exits(header, body, ends) if edge != (latch, out)]
        return latch if not others and out not in body else None


# =============================================================================================
# Loops with a flag


def flag_loops(routine: ir.Routine, flag: Callable[[int], ir.Var | None], max_copied: int,
               stops: tuple = (ir.End,), repeat: bool = False) -> Graph:
    """Rewrites loops whose one exit is not the header's test into `f=1; WHILE f=1 ... f=0` form.

    The exit edge u -> e goes to a new block `f=0` that jumps to a new header testing f, whose false
    edge leads to e; entries to the old header go through a new block `f=1`. A loop that exits at its
    header but has operations there (a do-while, a condition computed into temporaries) is written
    with the operations copied before WHILE and at the end of the body when there are at most
    `max_copied` of them, with a flag otherwise. `flag(depth)` gives the flag of a loop nested in
    `depth` others. Raises Unstructurable when the graph is irreducible, a loop has several exits
    (the dispatch fallback handles those) or no flag is left. Returns the graph of the routine as
    it leaves (the structurer reads the same graph: it is not built twice). `routine` itself is not
    changed: the first rewrite copies its blocks."""
    counter = 0
    done: set[str] = set()
    copied = False
    while True:
        graph = Graph(routine, stops)
        if not graph.reducible:
            raise Unstructurable("the control-flow graph is irreducible (a loop is entered at two places)")
        ends = graph.terminating()
        loops = [(graph.loop_body(h), h) for h in graph.headers]
        loops.sort(key=lambda item: (len(item[0]), graph.rank(item[1])))
        target = None
        for body, header in loops:
            if header in done:
                continue
            exits = graph.exits(header, body, ends)
            term = graph.blocks[header].terminator
            clean = isinstance(term, ir.Branch) and len(exits) == 1 and exits[0][0] == header \
                and len(graph.blocks[header].ops) <= max_copied
            if not exits or clean or (repeat and graph.repeat_latch(header, body, ends) is not None):
                continue
            if len(exits) > 1:
                raise Unstructurable("a loop is left from several places")
            target = (header, body, exits[0])
            break
        if target is None:
            return graph
        header, body, (source, exit_label) = target
        depth = sum(1 for h in graph.headers if h != header and header in graph.loop_body(h))
        var = flag(depth)
        if var is None:
            raise Unstructurable("no temporary variable is left for a loop flag")
        counter += 1
        span = graph.blocks[header].span
        if not copied:
            # The first rewrite works on a copy of the blocks (the caller's routine stays as it
            # was: the dispatch fallback reads it); a routine with no loop to flag, the common
            # case, is not copied at all (issue 26: the copy was a pass over every block).
            routine = ir.Routine(routine.name, routine.kind, [copy_block(b) for b in routine.blocks],
                                 routine.span, routine.number)
            copied = True
        pre = ir.Block(f"{routine.name}.pre{counter}%", [ir.Assign(var, ir.Const(1), span)], span=span)
        test = ir.Block(f"{routine.name}.test{counter}%", span=span)
        leave = ir.Block(f"{routine.name}.leave{counter}%", [ir.Assign(var, ir.Const(0), span)], span=span)
        pre.terminator = ir.Jump(test.label, span)
        test.terminator = ir.Branch(ir.Compare("=", var, ir.Const(1)), header, exit_label, span)
        leave.terminator = ir.Jump(test.label, span)
        for block in routine.blocks:
            inside = block.label in body
            ir.retarget(block.terminator, header, test.label if inside else pre.label)
            if block.label == source:
                ir.retarget(block.terminator, exit_label, leave.label)
        entry_moved = routine.blocks[0].label == header
        routine.blocks.extend([test, leave])
        routine.blocks.insert(0 if entry_moved else len(routine.blocks), pre)
        done.add(test.label)
        done.add(header)


# =============================================================================================
# Ifs and whiles


class Structurer:
    """Rebuilds if/elif/else and while from a reducible CFG whose loops all exit at their header."""

    def __init__(self, routine: ir.Routine, tail_copy: int = TAIL_COPY, stops: tuple = (ir.End,),
                 repeat: bool = False, graph: Graph | None = None):
        """`graph`: the routine's graph when the caller has it (built with the same `stops`)."""
        self.stops = stops
        self.repeat = repeat
        self.graph = graph if graph is not None else Graph(routine, stops)
        self.blocks = self.graph.blocks
        self.tail_copy = tail_copy
        self.emitted: set[str] = set()
        self.ends = self.graph.terminating()
        self.exit_span: Span | None = None
        self.depth = 0  # regions being built, one per enclosing IF arm or WHILE body

    def run(self) -> list:
        graph = self.graph
        if not graph.reducible:
            raise Unstructurable("the control-flow graph is irreducible")
        if graph.entry == EXIT:
            return []
        code = self.region(graph.entry, EXIT, frozenset(), frozenset())
        missing = [label for label in graph.order if label != EXIT and label not in self.emitted]
        if missing:
            raise Unstructurable(f"block {missing[0]} is reached from outside its IF or WHILE")
        return code

    def span(self, label: str) -> Span | None:
        block = self.blocks.get(label)
        return block.span if block is not None else None

    def leaves(self, arm: str, join: str) -> bool:
        """The arm ENDs on every path without ever reaching `join`."""
        if arm not in self.ends:
            return False
        seen = {arm}
        work = [arm]
        while work:
            label = work.pop()
            if label == join:
                return False
            for succ in self.graph.succ.get(label, ()):
                if succ not in seen:
                    seen.add(succ)
                    work.append(succ)
        return True

    def copyable(self, label: str) -> bool:
        """A short block that ENDs the program may be written twice (tail duplication)."""
        block = self.blocks[label]
        return isinstance(block.terminator, self.stops) and len(block.ops) <= self.tail_copy

    def is_test(self, label: str) -> bool:
        """A block that only tests (an elif): no operations, a branch, one way in."""
        block = self.blocks.get(label)
        return (block is not None and not block.ops and isinstance(block.terminator, ir.Branch)
                and label not in self.graph.headers and label not in self.emitted
                and self.graph.forward_preds(label) == 1)

    def join(self, label: str, follow: str) -> str:
        merges = [c for c in self.graph.children(label) if self.graph.forward_preds(c) >= 2]
        if not merges:
            return follow
        if len(merges) > 1:
            raise Unstructurable("a branch's paths meet at more than one place")
        return merges[0]

    def region(self, label: str | None, follow: str, forbidden: frozenset, active: frozenset,
               first: bool = False) -> list:
        if self.depth >= MAX_NESTING:
            raise Unstructurable(f"IF and WHILE blocks nest more than {MAX_NESTING} deep")
        self.depth += 1
        try:
            return self.sequence(label, follow, forbidden, active, first)
        finally:
            self.depth -= 1

    def sequence(self, label: str | None, follow: str, forbidden: frozenset, active: frozenset,
                 first: bool) -> list:
        out: list = []
        while label is not None and (label != follow or first):
            starting, first = first, False
            if label == EXIT:
                raise Unstructurable("a return from the middle of a routine")
            if label in forbidden and not starting:
                raise Unstructurable("a jump out of an IF or WHILE")
            if label in self.graph.headers and label not in active:
                code, label = self.loop(label, follow, forbidden, active)
                out += code
                continue
            if label in self.emitted and not self.copyable(label):
                raise Unstructurable("a block is reached from two structured places")
            self.emitted.add(label)
            block = self.blocks[label]
            out += [Simple(op) for op in block.ops]
            term = block.terminator
            if isinstance(term, ir.Jump):
                label = term.target
            elif isinstance(term, ir.Branch):
                label = self.branch(label, term, follow, forbidden, active, out)
            elif isinstance(term, self.stops):
                out.append(EndNode(term.span, term))
                label = None
            else:  # Return, FallOff: the routine's end
                self.exit_span = getattr(term, "span", None) or self.exit_span
                label = EXIT
                if follow != EXIT:
                    raise Unstructurable("a return from the middle of a routine")
        return out

    def branch(self, label: str, term: ir.Branch, follow: str, forbidden: frozenset, active: frozenset,
               out: list) -> str | None:
        if term.then == term.otherwise:
            return term.then
        join = self.join(label, follow)
        inner = (forbidden | {follow}) - {join}
        then, otherwise = term.then, term.otherwise
        cond = term.cond
        if join == follow and self.leaves(otherwise, join) and not self.leaves(then, join) and then != follow \
                and self.is_test(then):
            cond, then, otherwise = negate(cond), otherwise, then  # the ENDing arm first, as below
        if join == follow and self.leaves(then, join) and otherwise != follow and self.is_test(otherwise):
            # if a / END / elif b ...: keep the elif chain; its own merge point closes the whole if.
            join = self.join(otherwise, follow)
            inner = (forbidden | {follow}) - {join}
        elif join == follow:
            # One arm never comes back (it ENDs): keep it inside the if, go on with the other one.
            if self.leaves(then, join):
                out.append(self.if_node(cond, self.region(then, join, inner, active), [], term, None,
                                        self.span(otherwise)))
                return otherwise
            if self.leaves(otherwise, join):
                out.append(self.if_node(negate(cond), self.region(otherwise, join, inner, active), [], term, None,
                                        self.span(then)))
                return then
        then_code = self.region(then, join, inner, active)
        else_code = self.region(otherwise, join, inner, active)
        else_span = self.span(otherwise) if otherwise != join else None
        end_span = self.span(join) if join != follow else None
        out.append(self.if_node(cond, then_code, else_code, term, else_span, end_span))
        return join

    @staticmethod
    def if_node(cond: ir.Compare, then: list, orelse: list, term: ir.Branch, else_span: Span | None,
                end_span: Span | None = None) -> IfNode:
        if not then and orelse:
            cond, then, orelse = negate(cond), orelse, []
        if len(orelse) == 1 and isinstance(orelse[0], IfNode):  # else if ... -> elif
            inner = orelse[0]
            return IfNode([(cond, then)] + inner.arms, inner.orelse, [term.span] + inner.spans, inner.else_span,
                          end_span or inner.end_span)
        return IfNode([(cond, then)], orelse, [term.span], else_span if orelse else None, end_span)

    def loop(self, header: str, follow: str, forbidden: frozenset, active: frozenset) -> tuple[list, str | None]:
        graph = self.graph
        body = graph.loop_body(header)
        block = self.blocks[header]
        term = block.terminator
        leaving = [(u, v) for u in body for v in graph.succ[u] if v not in body]
        tested = [v for u, v in leaving if u == header and isinstance(term, ir.Branch)]
        others = [(u, v) for u, v in leaving if not (u == header and v in tested)]
        latch = graph.repeat_latch(header, body, self.ends) if self.repeat else None
        if latch is not None and (latch == header or all(v in self.ends for v in tested)):
            return self.repeat_loop(header, latch, follow, forbidden, active)
        # Edges to blocks that END are not exits: those blocks are written inside the loop.
        if len(tested) == 1 and all(v in self.ends for _, v in others):
            exit_label = tested[0]
        elif all(v in self.ends for _, v in leaving):  # endless loop: while 1=1
            code = self.region(header, header, (forbidden | {follow}) - {header}, active | {header}, first=True)
            return [WhileNode(TRUE, code, block.span)], None
        else:
            raise Unstructurable("a loop is left from the middle of its body")
        inside = term.otherwise if term.then == exit_label else term.then
        cond = term.cond if term.then == inside else negate(term.cond)
        self.emitted.add(header)
        pre = [Simple(op) for op in block.ops]
        code = self.region(inside, header, (forbidden | {follow, exit_label}) - {header}, active | {header})
        end_span = self.blocks[exit_label].span if exit_label in self.blocks else None
        return pre + [WhileNode(cond, code + list(pre), term.span, end_span)], exit_label


    def repeat_loop(self, header: str, latch: str, follow: str, forbidden: frozenset,
                    active: frozenset) -> tuple[list, str | None]:
        """A loop tested at its end: the body runs from the header to the latch, whose branch back
        becomes the loop's test (on the copy the structurer owns, the latch's branch is replaced by a
        jump to the header while the body is written)."""
        block = self.blocks[latch]
        term = block.terminator
        exit_label = term.otherwise if term.then == header else term.then
        until = negate(term.cond) if term.then == header else term.cond
        block.terminator = ir.Jump(header, term.span)
        try:
            code = self.region(header, header, (forbidden | {follow, exit_label}) - {header}, active | {header},
                               first=True)
        finally:
            block.terminator = term
        end_span = self.blocks[exit_label].span if exit_label in self.blocks else term.span
        return [RepeatNode(code, until, self.blocks[header].span, end_span)], exit_label


# =============================================================================================
# The fallback


def dispatch(routine: ir.Routine, var: ir.Var, stops: tuple = (ir.End,)) -> list:
    """while var!=0 with one if arm per basic block; var holds the next block's number (0: the end)."""
    graph = Graph(routine, stops)
    labels = [label for label in graph.order if label != EXIT]
    number = {label: i + 1 for i, label in enumerate(labels)}
    number[EXIT] = 0

    def goto(label: str, span: Span | None) -> Simple:
        return Simple(ir.Assign(var, ir.Const(number.get(label, 0)), span))

    arms = []
    spans = []
    for label in labels:
        block = graph.blocks[label]
        body: list = [Simple(op) for op in block.ops]
        term = block.terminator
        if isinstance(term, ir.Jump):
            body.append(goto(term.target, term.span))
        elif isinstance(term, ir.Branch):
            body.append(IfNode([(term.cond, [goto(term.then, term.span)])], [goto(term.otherwise, term.span)],
                               [term.span]))
        elif isinstance(term, stops):
            body.append(EndNode(term.span, term))
        else:
            body.append(goto(EXIT, getattr(term, "span", None)))
        arms.append((ir.Compare("=", var, ir.Const(number[label])), body))
        spans.append(block.span)
    start = Simple(ir.Assign(var, ir.Const(number.get(graph.entry, 0)), routine.span))
    if not arms:
        return []
    return [start, WhileNode(ir.Compare("!=", var, ir.Const(0)), [IfNode(arms, [], spans)], routine.span)]
