"""Values in force: which motion settings hold a known constant at each point of a program.

Several conversions need the settings in force where an operation runs, not only the operation
itself: an Arcus ramp time (`ACC=300`) is an acceleration only together with the speeds in force
(`(HSPD - LSPD) / 0.3 s`), and an MCode acceleration becomes an Arcus ramp time the same way. The
optimizer drops a setting already in force on every path, and lint finds a move before any speed
is set. All of them read this one forward data-flow analysis.

The state at a point maps `(param, axis)` to the constant in force; a key that is absent is not
known statically (never set, set from a variable, or different on two paths). How an axis's own
setting and the setting for every axis (`axis == "*"`) combine is the module's fact
(`Module.axis_sets`, docs/IR.md):

- by default a `*` setting is written into every axis. `(param, "*")` holds the value of every
  axis that has no key of its own, so an axis whose own value becomes unknown (set from a
  variable, different on two paths, set by a call) takes the `*` key with it: it would otherwise
  be read as the `*` value;
- for the parameters of `Module.axis_sets` (Arcus HSPDa/LSPDa/ACCa, L447-L457) the `*` setting
  and each axis's own are separate registers, and an axis runs with its own only once all of the
  set have been written for it. The state then also says, per axis and parameter, whether the
  register was written on every path (`(WRITTEN, param, axis)`) or on none (`(UNWRITTEN, param,
  axis)`; the first is kept for every module: whether the axis set its own value since the last
  `*` setting); `lookup` gives the axis's own value when its set is complete on every path, the `*`
  value when it is incomplete on every path, and nothing otherwise. Every state carries the
  module's rule as `(SETS, param)` keys, so `lookup` needs nothing else.

Across routines the analysis is context-insensitive: the commands sent outside any program run
first, in order, and the program's entry routine starts with what they leave (the simulator's
order); a subroutine starts with what holds at every one of its calls, a call removes whatever the subroutine (or anything it calls) may set, and an
event handler starts knowing nothing, since it can run at any time. Each block is visited a
bounded number of times (the lattice only loses keys), so the cost is linear in the program for
the graphs programs have.
"""

from __future__ import annotations

from typing import Iterator

from mcc.compiler import dialects, ir
from mcc.compiler.cfg import dataflow
from mcc.compiler.cfg.graph import BlockIndex

Key = tuple  # (param, axis), or (SETS, param), (WRITTEN, param, axis), (UNWRITTEN, param, axis)
State = dict[Key, ir.Const]

ALL = ir.ALL_AXES
SETS, WRITTEN, UNWRITTEN = "axis_sets", "written", "unwritten"
ONE = ir.Const(1)


# Settings a source dialect fixes for every axis, whatever the program does: X150 has no initial
# speed (its moves start from standstill, docs/dialects/x150.md), so a program written for it runs
# with an initial speed of 0 at every point.
FIXED: dict[str, State] = {
    d.name: {(ir.MotionParam.INITIAL_SPEED, ALL): ir.Const(0, ir.Unit.STEPS_PER_S)} for d in dialects.DIALECTS.values() if d.moves_from_standstill
}


def with_fixed_initial_speed(module: ir.Module, lowest: float) -> ir.Module:
    """For a target whose initial speed cannot be 0: a program from a dialect that fixes it at 0
    (X150 starts every move from standstill) sets the target's lowest initial speed (`lowest`, in
    the IR's steps/s) at the start of each routine that runs first, so that the device does not
    start moves at whatever initial speed it has stored. A copy; other programs are returned as they
    are."""
    if (ir.MotionParam.INITIAL_SPEED, ALL) not in FIXED.get(module.dialect, {}):
        return module
    copy = ir.copy_module(module)
    for routine in copy.routines:
        if routine.kind in (ir.RoutineKind.MAIN, ir.RoutineKind.IMMEDIATE) and routine.blocks:
            speed = ir.Const(lowest, ir.Unit.STEPS_PER_S)
            routine.blocks[0].ops.insert(0, ir.SetMotion(ir.MotionParam.INITIAL_SPEED, ALL, speed))
    return copy


# An acceleration and a ramp time give the same thing two ways: the one set last applies
# (docs/SIMULATOR.md, "Motion"), so setting one for every axis forgets the other.
RAMP_PAIRS = {ir.MotionParam.ACCEL: ir.MotionParam.ACCEL_TIME, ir.MotionParam.ACCEL_TIME: ir.MotionParam.ACCEL,
              ir.MotionParam.DECEL: ir.MotionParam.DECEL_TIME, ir.MotionParam.DECEL_TIME: ir.MotionParam.DECEL}
POWER_UP_PARAMS = (ir.MotionParam.INITIAL_SPEED, ir.MotionParam.MAX_SPEED, ir.MotionParam.ACCEL,
                   ir.MotionParam.DECEL)
MOTION_OPS = (ir.Move, ir.Arc, ir.Slew, ir.Home)
SETTING_READINGS = {p.value for p in POWER_UP_PARAMS}


def source_profile(module: ir.Module, target):
    """The built-in profile the module was compiled for, when it is not the target's own (None for
    the target's own profile, and for a profile not known by name here: a user's profile file, a
    hand-built module)."""
    from mcc.compiler.profiles import ProfileError, load

    if module.profile == target.name or not module.profile:
        return None
    try:
        return load(module.profile)
    except ProfileError:
        return None


def with_source_power_up(module: ir.Module, target, lowest_initial: float = 0.0) -> ir.Module:
    """What a program relies on from its own product, made explicit for another: its power-up
    motion settings (`with_power_up`) and its inputs' polarity (`with_input_polarity`). Every
    backend calls it first; a module from the target's own or an unknown profile is returned as it
    is."""
    source = source_profile(module, target)
    if source is None:
        return module
    # a setting read back is resolved before the power-up values (`D=A` after `A=...` then sets D before
    # any motion, so D's power-up value is not needed) and again after (`D=A` reading a power-up value)
    module = with_power_up(with_settings_read(module), source, target, lowest_initial)
    return with_input_polarity(with_settings_read(module), source, target)


def with_settings_read(module: ir.Module) -> ir.Module:
    """A motion setting given the value of another read back (MCode `D=A` in the manual's applications, lexium-mcode.txt L7626;
    D sets the deceleration, L2270) is the constant in force there when the data
    flow knows it: a target that needs the value written (an X150 A, an Arcus ACC from the speeds)
    then writes it, as it writes `D=1000000`. Only between settings of the same unit; readings not
    known statically are left as they are (the backend refuses them). A copy; the module as it is
    when no setting reads another."""
    def reads_setting(op) -> bool:
        return isinstance(op, ir.SetMotion) and isinstance(op.value, ir.Status) \
            and op.value.meaning in SETTING_READINGS \
            and ir.PARAM_UNITS.get(ir.MotionParam(op.value.meaning)) == ir.PARAM_UNITS.get(op.param)

    if not any(reads_setting(op) for _, block in module.blocks() for op in block.ops):
        return module
    analysis = InForce(module)
    known: dict[tuple[int, int, int], ir.Const] = {}
    for r, routine in enumerate(module.routines):
        blocks = {id(block): b for b, block in enumerate(routine.blocks)}
        for block, index, op, state in analysis.walk(routine):
            if reads_setting(op):
                value = lookup(state, ir.MotionParam(op.value.meaning), op.value.axis or ALL)
                if value is not None:
                    known[(r, blocks[id(block)], index)] = value
    if not known:
        return module
    copy = ir.copy_module(module)
    for (r, b, index), value in known.items():
        op = copy.routines[r].blocks[b].ops[index]
        op.value = ir.Const(value.value, value.unit, op.value.span)
    return copy


def active_high(profile) -> bool:
    """Whether the product's inputs read active at a high level before a program sets otherwise
    (`[machine.inputs] active_high`; true without it: the input reads its level)."""
    return bool(profile.get("machine.inputs.active_high", True)) if profile is not None else True


def with_input_polarity(module: ir.Module, source, target) -> ir.Module:
    """For products whose inputs read with opposite polarity at power-up (an MCode I1 is low-active,
    lexium-mcode.txt L3500; an Arcus DI1 reads the level, arcus L1900-L1905): the reads of every
    input whose polarity the program does not set itself are inverted, so that the output tests
    the same electrical level as the source (`I1=1` becomes `DI1=0`). A polarity the program sets
    (MCode IS, X150 INL) is written by the backend or refused there. A copy; the module as it is
    when nothing differs."""
    if active_high(source) == active_high(target):
        return module
    module = with_bank_patterns(module, source)
    set_here = {op.index for _, b in module.blocks() for op in b.ops
                if isinstance(op, ir.Setting) and op.name == "input_active_high"}
    module, as_power_up = without_plain_levels(module, source, target)
    set_here -= as_power_up
    read = {n.index for _, b in module.blocks() for e in [*(x for op in b.ops for x in ir.op_exprs(op)),
                                                           *ir.term_exprs(b.terminator)]
            for n in ir.walk_expr(e) if isinstance(n, ir.Status) and n.meaning == "input"}
    read |= {i + 1 for _, b in module.blocks() for e in [*(x for op in b.ops for x in ir.op_exprs(op)),
                                                          *ir.term_exprs(b.terminator)]
             for n in ir.walk_expr(e) if isinstance(n, ir.InputMatch)
             for i, bit in enumerate(n.pattern.bits) if bit in "01"}
    flip = frozenset(n for n in read if n is not None and n not in set_here)
    if not flip:
        return module
    copy = ir.copy_module(module)
    for _, block in copy.blocks():
        block.ops[:] = [_flip_op(op, flip) for op in block.ops]
        if isinstance(block.terminator, ir.Branch):
            block.terminator.cond = _flip_expr(block.terminator.cond, flip)
    return copy


def with_bank_patterns(module: ir.Module, source) -> ir.Module:
    """Every input read at once and compared with a number (Arcus `IF DI=255`, MCode `BR L,IN=5`)
    as the pattern of its inputs' logic states (`InputMatch`), which the polarity inversion above
    then turns into the target's: the bank holds the source product's `[machine.inputs] count`
    levels, input 1 in bit 0 (arcus-pmx-4ex-sa.txt L797, L1905; lexium-mcode.txt L3433-L3435), so
    `DI=255` is "inputs 1-8 at level 1" and the other product tests those inputs one by one (or
    refuses one it lacks) instead of its own bank, whose width and polarity differ. Done only where
    the program sets no input's polarity (the level is then the logic state, or its inverse for a
    low-active product); a copy, or the module itself when nothing is rewritten."""
    count = source.get("machine.inputs.count", 0) if source is not None else 0
    if not isinstance(count, int) or isinstance(count, bool) or not 0 < count <= 32:
        return module
    if any(isinstance(op, ir.Setting) and op.name == "input_active_high" for _, b in module.blocks() for op in b.ops):
        return module
    high = active_high(source)

    def pattern(compare) -> ir.Pattern | None:
        if not isinstance(compare, ir.Compare) or compare.op not in ("=", "!="):
            return None
        for bank, const in ((compare.left, compare.right), (compare.right, compare.left)):
            if isinstance(bank, ir.Status) and bank.meaning == "inputs" and bank.index is None \
                    and isinstance(const, ir.Const) and float(const.value).is_integer() \
                    and 0 <= const.value < 2 ** count:
                value = int(const.value)
                return ir.Pattern("".join(str((value >> n & 1) if high else 1 - (value >> n & 1))
                                          for n in range(count)), compare.span)
        return None

    def rewrite(cond):
        if cond is None:
            return cond
        found = pattern(cond)
        if found is not None:
            match = ir.InputMatch(found, cond.span)
            return match if cond.op == "=" else ir.Not(match, cond.span)
        if isinstance(cond, ir.Logic):
            left, right = rewrite(cond.left), rewrite(cond.right)
            return cond if left is cond.left and right is cond.right else ir.Logic(cond.op, left, right, cond.span)
        if isinstance(cond, ir.Not):
            inner = rewrite(cond.cond)
            return cond if inner is cond.cond else ir.Not(inner, cond.span)
        return cond

    fields = {ir.WaitInput: "cond", ir.Call: "cond"}
    if not any(rewrite(cond) is not cond for _, b in module.blocks()
               for cond in [*(getattr(op, fields[type(op)]) for op in b.ops if type(op) in fields),
                            getattr(b.terminator, "cond", None) if isinstance(b.terminator, ir.Branch) else None]):
        return module
    import copy as copying

    copy = ir.copy_module(module)
    for _, block in copy.blocks():
        for n, op in enumerate(block.ops):
            name = fields.get(type(op))
            if name is not None and getattr(op, name) is not None:
                new = rewrite(getattr(op, name))
                if new is not getattr(op, name):
                    op = copying.copy(op)
                    setattr(op, name, new)
                    block.ops[n] = op
        if isinstance(block.terminator, ir.Branch):
            block.terminator.cond = rewrite(block.terminator.cond)
    return copy


def without_plain_levels(module: ir.Module, source, target) -> tuple[ir.Module, set[int]]:
    """The input levels a program sets that need no statement on the target (issue 24): an input's
    level set to the source's own power-up polarity everywhere it is set (MCode `IS=1,0,0`, active
    low as at power-up, lexium-mcode.txt L3500) changes nothing, so the input reads as one the
    program does not set (its reads are inverted for the target); an input's level set to the
    target's polarity (`IS=1,0,1`, active high: what an Arcus DI reads, arcus-pmx-4ex-sa.txt
    L1900-L1905) before the program does anything else is the target's own reading, so its reads
    stay as they are. Returns the module without those settings (a copy) and the inputs of the
    first kind; anything else is left for the backend to write or refuse."""
    settings: dict[int, list[ir.Setting]] = {}
    for _, block in module.blocks():
        for op in block.ops:
            if isinstance(op, ir.Setting) and op.name == "input_active_high" and op.index is not None:
                settings.setdefault(op.index, []).append(op)
    if not settings:
        return module, set()
    first = _first_run(module)
    leading: set[int] = set()  # settings before anything else runs: the program's first statements
    if first is not None and first.entry is not None:
        for op in first.entry.ops:
            if not isinstance(op, (ir.Setting, ir.SetMotion)):  # neither reads an input
                break
            leading.add(id(op))
    ours, theirs = int(active_high(source)), int(active_high(target))
    power_up: set[int] = set()
    dropped: set[int] = set()
    for index, ops in settings.items():
        values = {op.value.value if isinstance(op.value, ir.Const) else None for op in ops}
        if values == {ours}:
            power_up.add(index)
            dropped.update(id(op) for op in ops)
        elif values == {theirs} and all(id(op) in leading for op in ops):
            dropped.update(id(op) for op in ops)
    if not dropped:
        return module, set()
    copy = ir.copy_module(module)
    for (_, block), (_, original) in zip(copy.blocks(), module.blocks()):
        block.ops[:] = [op for op, was in zip(block.ops, original.ops) if id(was) not in dropped]
    return copy, power_up


def _flip_op(op, flip: frozenset):
    import copy

    fields = {ir.Assign: "value", ir.SetOutput: "value", ir.WaitInput: "cond", ir.Call: "cond"}
    name = fields.get(type(op))
    if name is not None and getattr(op, name) is not None:
        new = _flip_expr(getattr(op, name), flip)
        if new is not getattr(op, name):
            op = copy.copy(op)
            setattr(op, name, new)
        return op
    if isinstance(op, ir.Print):
        items = tuple(_flip_expr(item, flip) for item in op.items)
        if any(a is not b for a, b in zip(items, op.items)):
            op = copy.copy(op)
            op.items = items
    return op


def _inverted(node, flip: frozenset) -> bool:
    return isinstance(node, ir.Status) and node.meaning == "input" and node.index in flip


def _flip_expr(expr, flip: frozenset):
    """`expr` reading each input of `flip` inverted (the same object when it reads none)."""
    if not any(_inverted(n, flip) or isinstance(n, ir.InputMatch) for n in ir.walk_expr(expr)):
        return expr
    if _inverted(expr, flip):
        return ir.BinOp("-", ir.Const(1), expr, expr.span)
    if isinstance(expr, ir.Compare):
        for status, const, other in ((expr.left, expr.right, "right"), (expr.right, expr.left, "left")):
            if _inverted(status, flip) and isinstance(const, ir.Const) and const.value in (0, 1) \
                    and expr.op in ("=", "!="):
                turned = ir.Const(1 - const.value, const.unit, const.span)
                left, right = (status, turned) if other == "right" else (turned, status)
                return ir.Compare(expr.op, left, right, expr.span)
        return ir.Compare(expr.op, _flip_expr(expr.left, flip), _flip_expr(expr.right, flip), expr.span)
    if isinstance(expr, ir.Truth):
        if _inverted(expr.expr, flip):
            return ir.Compare("=", expr.expr, ir.Const(0), expr.span)
        return ir.Truth(_flip_expr(expr.expr, flip), expr.span)
    if isinstance(expr, ir.InputMatch):
        bits = "".join({"0": "1", "1": "0"}.get(b, b) if i + 1 in flip else b
                       for i, b in enumerate(expr.pattern.bits))
        return expr if bits == expr.pattern.bits else ir.InputMatch(ir.Pattern(bits, expr.pattern.span), expr.span)
    if isinstance(expr, ir.Logic):
        return ir.Logic(expr.op, _flip_expr(expr.left, flip), _flip_expr(expr.right, flip), expr.span)
    if isinstance(expr, ir.Not):
        return ir.Not(_flip_expr(expr.cond, flip), expr.span)
    if isinstance(expr, ir.BinOp):
        return ir.BinOp(expr.op, _flip_expr(expr.left, flip), _flip_expr(expr.right, flip), expr.span)
    if isinstance(expr, ir.UnOp):
        return ir.UnOp(expr.op, _flip_expr(expr.operand, flip), expr.span)
    if isinstance(expr, ir.Func):
        return ir.Func(expr.name, tuple(_flip_expr(a, flip) for a in expr.args), expr.span)
    return expr


def with_power_up(module: ir.Module, source, target, lowest_initial: float = 0.0) -> ir.Module:
    """For a conversion between products that power up with different motion settings (their
    profiles' `[machine.defaults]`, compiler/profiles.py `power_up`): the source's power-up values
    are written at the start of the program, where the target's differ, so that a program that
    relies on its controller's defaults moves the same on the other one (an MCode axis that sets
    nothing runs at VM 768000 steps/s, an X150 axis at 1 rev/s). They go at the start of the routine
    that runs first (the first IMMEDIATE routine, else the entry routine), in a new first block when
    something jumps back to that start, so that the jump does not set them again; a setting that block already makes before
    any motion is not repeated. A copy; the module is returned as it is when nothing differs or the
    program neither moves nor reads a speed. A setting the source dialect fixes (FIXED: X150's
    standstill starts) is left to `with_fixed_initial_speed`, one the target fixes cannot be written; an initial speed below the target's
    lowest (`lowest_initial`, in the IR's steps/s) is written at that lowest, as there."""
    from mcc.compiler.profiles import power_up

    if not _uses_motion(module):
        return module
    # a module that does not state its step size is taken at the target's (as the backends write it
    # and the validation compares it, sim/verify.py _stated_steps)
    ours = power_up(source, module.steps_per_rev or target.steps_per_rev)
    ratio = module.steps_per_rev / target.steps_per_rev if module.steps_per_rev > 0 and target.steps_per_rev > 0 \
        else 1.0
    theirs = {name: value * ratio for name, value in power_up(target, target.steps_per_rev).items()}
    fixed = {param for param, _ in [*FIXED.get(module.dialect, {}), *FIXED.get(target.dialect, {})]}
    ours["initial_speed"] = max(ours["initial_speed"], lowest_initial)
    differ = [p for p in POWER_UP_PARAMS if p not in fixed
              and abs(ours[p.value] - theirs[p.value]) > 1e-9 * max(1.0, abs(ours[p.value]))]
    if not differ:
        return module
    copy = ir.copy_module(module)
    first = _first_run(copy)
    if first is None or first.entry is None:
        return module
    covered = _set_before_motion(first.entry, _motion_axes(copy))
    if {ir.MotionParam.ACCEL, ir.MotionParam.DECEL} & (set(differ) - covered):
        # a ramp written for every axis is converted with the speeds in force for every axis (an Arcus
        # ACC is a time): speeds the program sets only for its own axes do not cover them
        covered -= {ir.MotionParam.INITIAL_SPEED, ir.MotionParam.MAX_SPEED} - _set_before_motion(first.entry, set())
    differ = [p for p in differ if p not in covered]
    if not differ:
        return module
    ops = [ir.SetMotion(p, ALL, ir.Const(_number(ours[p.value]), ir.PARAM_UNITS[p])) for p in differ]
    entry = first.entry
    if not any(entry.label in ir.successors(b.terminator) for _, b in copy.blocks()):
        entry.ops[:0] = ops  # nothing jumps back to the start: the settings run once there
        return copy
    label = "%power_up"
    while any(b.label == label for _, b in copy.blocks()):
        label += "_"
    first.blocks.insert(0, ir.Block(label, ops, ir.Jump(entry.label), entry.span))
    return copy


def _number(value: float) -> int | float:
    return int(value) if float(value).is_integer() else value


def _uses_motion(module: ir.Module) -> bool:
    for _, block in module.blocks():
        for op in block.ops:
            if isinstance(op, MOTION_OPS):
                return True
            for expr in ir.op_exprs(op):
                if any(isinstance(n, ir.Status) and n.meaning in SETTING_READINGS for n in ir.walk_expr(expr)):
                    return True
    return False


def _first_run(module: ir.Module) -> ir.Routine | None:
    """The routine the program starts with: the commands sent before it, else its main routine."""
    for kind in (ir.RoutineKind.IMMEDIATE, ir.RoutineKind.MAIN, ir.RoutineKind.POWERUP):
        for routine in module.routines:
            if routine.kind is kind and routine.blocks:
                return routine
    return None


def _motion_axes(module: ir.Module) -> set[str]:
    """The axes the module moves (`*` included when a motion names every axis)."""
    return _axes(module, MOTION_OPS, keep_all=True)


def _set_before_motion(block: ir.Block, axes: set[str]) -> set[ir.MotionParam]:
    """The settings `block` gives a constant, for every axis that moves, before anything moves."""
    seen: dict[ir.MotionParam, set[str]] = {}
    for op in block.ops:
        if isinstance(op, MOTION_OPS) or isinstance(op, (ir.Call, ir.Native)):
            break
        if isinstance(op, ir.SetMotion) and isinstance(op.value, ir.Const):
            # a ramp time set before any motion replaces the acceleration too (Arcus ACC)
            for param in (op.param, RAMP_PAIRS.get(op.param)):
                if param is not None:
                    seen.setdefault(param, set()).add(op.axis)
    return {p for p, set_for in seen.items() if ALL in set_for or (axes and axes <= set_for)}


def lookup(state: State, param: ir.MotionParam, axis: str) -> ir.Const | None:
    """The constant in force for `param` on `axis` (the value a move of that axis runs with), or
    None when it is not known statically."""
    if axis != ALL and (SETS, param) in state:
        members = [k[1] for k in state if len(k) == 2 and k[0] == SETS]
        if all((WRITTEN, m, axis) in state for m in members):
            return state.get((param, axis))
        if any((UNWRITTEN, m, axis) in state for m in members):
            return state.get((param, ALL))
        return None  # complete on some paths only
    found = state.get((param, axis))
    if found is None and axis != ALL:
        found = state.get((param, ALL))
    return found


def redundant(state: State, op: ir.Op) -> bool:
    """Whether `op` sets a value already in force everywhere it writes (so removing it changes
    nothing on the device): the register itself for a parameter of an axis set (writing it again
    leaves the set as complete as it was), every axis for a `*` setting otherwise."""
    if not isinstance(op, ir.SetMotion) or not isinstance(op.value, ir.Const):
        return False
    value = op.value
    if (SETS, op.param) in state:
        current = state.get((op.param, op.axis))
        return current is not None and _same(current, value)
    if op.axis != ALL:
        current = lookup(state, op.param, op.axis)
        return current is not None and _same(current, value)
    current = state.get((op.param, ALL))
    return current is not None and _same(current, value) and all(
        _same(v, value) for k, v in state.items() if len(k) == 2 and k[0] is op.param)


def meet(a: State | None, b: State, sets: frozenset = frozenset()) -> State:
    if a is None:
        return dict(b)
    out = {k: v for k, v in a.items() if k in b and _same(b[k], v)}
    # an axis's own value lost on one path would otherwise be read as the `*` value
    lost = {k[0] for state in (a, b) for k in state
            if len(k) == 2 and k[1] != ALL and k not in out and isinstance(k[0], ir.MotionParam) and k[0] not in sets}
    for param in lost:
        out.pop((param, ALL), None)
    return out


def _same(a: ir.Const, b: ir.Const) -> bool:
    return a.value == b.value and a.unit == b.unit


def transfer(state: State, op: ir.Op, clobbers: dict[str, frozenset[Key]], sets: frozenset = frozenset()) -> None:
    """Update `state` in place for one operation; `sets` is the module's `axis_sets`."""
    if isinstance(op, ir.SetMotion):
        param, axis = op.param, op.axis
        if axis != ALL:  # the axis's own register is written (whatever its value)
            state[(WRITTEN, param, axis)] = ONE
            state.pop((UNWRITTEN, param, axis), None)
        if param in sets:  # separate registers: a `*` write leaves the axes' own as they are
            pass
        elif axis == ALL:  # written into every axis: no axis has a value of its own any more
            for key in [k for k in state if k[0] is param or (k[0] == WRITTEN and k[1] is param)]:
                del state[key]
        elif not isinstance(op.value, ir.Const):
            state.pop((param, ALL), None)  # the axis is unknown: not the `*` value either
        if isinstance(op.value, ir.Const):
            state[(param, axis)] = op.value
        else:
            state.pop((param, axis), None)
        other = RAMP_PAIRS.get(param)
        if other is not None and axis == ALL:  # whichever of accel / accel_time is set last applies
            for key in [k for k in state if len(k) == 2 and k[0] is other]:
                del state[key]
        elif other is not None and other not in sets:  # on this axis: its own of the other is replaced,
            state.pop((other, axis), None)  # and the `*` one, which it would otherwise be read as
            state.pop((other, ALL), None)
    elif isinstance(op, ir.Native):
        state.clear()  # a command only its own dialect knows may change any setting
    elif isinstance(op, ir.Call):
        for param, axis in clobbers.get(op.routine, frozenset()):
            if axis == ALL and param not in sets:  # (or a command that may write anything: Native)
                for other in [k for k in state if k[0] is param or (k[0] in (WRITTEN, UNWRITTEN) and k[1] is param)]:
                    del state[other]
            elif axis == ALL:  # a `*` write, or a command that may write anything (Native)
                for other in [k for k in state if k[0] is param or (k[0] == UNWRITTEN and k[1] is param)]:
                    del state[other]
            elif param in sets:
                state.pop((param, axis), None)
                state.pop((UNWRITTEN, param, axis), None)  # it may have been written
            else:
                state.pop((param, axis), None)
                state.pop((param, ALL), None)
                state.pop((UNWRITTEN, param, axis), None)


class InForce:
    """The analysis of one module: entry states per block, replayed per operation on demand."""

    def __init__(self, module: ir.Module, defaults: State | None = None):
        self.module = module
        self.sets = frozenset(module.axis_sets)
        self.fixed = {**FIXED.get(module.dialect, {}), **{(SETS, param): ONE for param in self.sets}}
        self.clobbers = _clobbers(module)
        self.defaults = {**dict(defaults or {}), **self.fixed, **self._unwritten()}
        self.entry: dict[str, State] = {}
        self.reached: set[str] = set()  # the blocks some path from a routine's start reaches
        self._solve()

    def at_entry(self, label: str) -> State:
        return {**self.entry.get(label, {}), **self.fixed}

    def _unwritten(self) -> State:
        """At power-up no axis has written its own set: the registers of the axes the program
        writes, unless what runs before the program (commands sent first, a power-up routine) may."""
        params = self.sets or tuple(ir.MotionParam)
        axes = _axes(self.module)
        early = set().union(*(self.clobbers.get(r.name, frozenset()) for r in self.module.routines
                              if r.kind in (ir.RoutineKind.IMMEDIATE, ir.RoutineKind.POWERUP)))
        if any(axis == ALL and param in params for param, axis in early):
            return {}
        return {(UNWRITTEN, param, axis): ONE for param in params for axis in axes if (param, axis) not in early}

    def after(self, state: State, op: ir.Op) -> State:
        """The state in force after `op`, given `state` before it (a new dictionary)."""
        state = dict(state)
        transfer(state, op, self.clobbers, self.sets)
        if self.fixed:
            state.update(self.fixed)
        return state

    def walk(self, routine: ir.Routine) -> Iterator[tuple[ir.Block, int, ir.Op, State]]:
        """Every operation of `routine` with the state in force just before it."""
        for block in routine.blocks:
            state = self.at_entry(block.label)
            for index, op in enumerate(block.ops):
                yield block, index, op, state
                state = self.after(state, op)

    def _solve(self) -> None:
        starts: dict[str, State | None] = {}
        for routine in self.module.routines:
            if routine.kind in (ir.RoutineKind.MAIN, ir.RoutineKind.IMMEDIATE, ir.RoutineKind.POWERUP):
                starts[routine.name] = dict(self.defaults)
            elif routine.kind is ir.RoutineKind.HANDLER:
                starts[routine.name] = dict(self.fixed)
            else:
                starts[routine.name] = None  # met from its calls
        starts.update(self._after_immediate())
        # Iterate: routine entries depend on call sites, call sites on routine entries.
        for _ in range(len(self.module.routines) + 2):
            calls: dict[str, State | None] = {}
            for routine in self.module.routines:
                start = starts.get(routine.name)
                if start is None:
                    start = {}
                self._solve_routine(routine, start, calls)
            changed = False
            for routine in self.module.routines:
                if routine.kind is ir.RoutineKind.SUBROUTINE:
                    new = calls.get(routine.name) or {}
                    if new != starts.get(routine.name):
                        starts[routine.name] = new
                        changed = True
            if not changed:
                break

    def _after_immediate(self) -> dict[str, State]:
        """The starts of the routines that run after the commands sent outside any program.

        The immediate stretches run first, in the order they were sent, then the program's entry
        routine (the first main program, else the power-up routine), as the simulator runs a module
        (sim/interpreter.py; MCode settings before `PG` are in force when the program runs,
        lexium-mcode.txt L510-L512; X150 buffered commands run in sequential order, L177). So each
        stretch starts with what the one before it leaves, and the entry routine with what the last
        one leaves: an MCode `VI=500` or an Arcus `HSPDX=...` sent before the program is in force in
        it (issue 23: MCode -> Arcus refused, G003, for want of them). What a stretch leaves does
        not depend on what its subroutines start with (a call removes what they may set), so one pass
        in order is exact. A stretch that never reaches its end (an End, a loop) leaves nothing known."""
        immediate = [r for r in self.module.routines if r.kind is ir.RoutineKind.IMMEDIATE and r.blocks]
        if not immediate:
            return {}
        starts: dict[str, State] = {}
        state: State = dict(self.defaults)
        for routine in immediate:
            starts[routine.name] = state
            exits: list[State] = []
            self._solve_routine(routine, state, {}, exits)
            left: State | None = None
            for found in exits:
                left = meet(left, found, self.sets)
            state = {**(left or {}), **self.fixed}
        entry = next((r for kind in (ir.RoutineKind.MAIN, ir.RoutineKind.POWERUP) for r in self.module.routines
                      if r.kind is kind and r.blocks), None)
        if entry is not None:
            starts[entry.name] = state
        self.entry = {}
        self.reached = set()
        return starts

    def _solve_routine(self, routine: ir.Routine, start: State, calls: dict[str, State | None],
                       exits: list[State] | None = None) -> None:
        """The state at each block's entry (`self.entry`); with `exits`, the states the routine
        ends with where it runs off its end or returns are appended to it."""
        if not routine.blocks:
            return
        index = BlockIndex.of_routine(routine)
        blocks = routine.blocks
        sets, clobbers = self.sets, self.clobbers

        def through(node: int, entry: State) -> State:
            block = blocks[node]
            state = dict(entry)
            for op in block.ops:
                if isinstance(op, ir.Call):
                    calls[op.routine] = meet(calls.get(op.routine), state, sets)
                transfer(state, op, clobbers, sets)
            if exits is not None and isinstance(block.terminator, (ir.FallOff, ir.Return, type(None))):
                exits.append(dict(state))
            return state

        # first in, first out, as this analysis always ran: its meet is not a lattice's (a `*`
        # setting is dropped where an axis's own was lost), so the order of visits is kept
        states = dataflow.solve(None, index.succ, {0: dict(start)}, through,
                                lambda old, new: meet(old, new, sets))
        for number, block in enumerate(blocks):
            state = states.get(number)
            self.entry[block.label] = state or {}
            if state is not None:
                self.reached.add(block.label)


def _axes(module: ir.Module, kinds: tuple = (), keep_all: bool = False) -> set[str]:
    """Every axis an operation of the module names (of `kinds` only, when given)."""
    axes: set[str] = set()
    for _, block in module.blocks():
        for op in block.ops:
            if kinds and not isinstance(op, kinds):
                continue
            if isinstance(op, ir.Move):
                axes.update(axis for axis, _ in op.targets)
            elif isinstance(op, ir.Arc):
                axes.update(op.axes)
            elif getattr(op, "axis", None) is not None and (op.axis or keep_all):
                axes.add(op.axis)
    if not keep_all:
        axes.discard(ALL)
    return axes


def _clobbers(module: ir.Module) -> dict[str, frozenset[Key]]:
    """For each routine, the settings it or anything it calls may change (a fixpoint over calls)."""
    direct: dict[str, set[Key]] = {}
    callees: dict[str, set[str]] = {}
    for routine in module.routines:
        keys: set[Key] = set()
        called: set[str] = set()
        for block in routine.blocks:
            for op in block.ops:
                if isinstance(op, ir.SetMotion):
                    keys.add((op.param, op.axis))
                elif isinstance(op, ir.Native):
                    keys |= {(param, ALL) for param in ir.MotionParam}
                elif isinstance(op, ir.Call):
                    called.add(op.routine)
            if isinstance(block.terminator, ir.GotoRoutine):
                called.add(block.terminator.routine)
        direct[routine.name] = keys
        callees[routine.name] = called
    result = {name: set(keys) for name, keys in direct.items()}
    changed = True
    while changed:
        changed = False
        for name, called in callees.items():
            for callee in called:
                extra = result.get(callee, set()) - result[name]
                if extra:
                    result[name] |= extra
                    changed = True
    return {name: frozenset(keys) for name, keys in result.items()}


class Unresolved(Exception):
    """A setting whose effect depends on the path that reaches it, where a conversion between the
    two rules of `Module.axis_sets` needs to know it statically; `span` is the setting's."""

    def __init__(self, message: str, span):
        super().__init__(message)
        self.span = span


def without_axis_sets(module: ir.Module) -> ir.Module:
    """The module rewritten for a target where an axis's own setting applies at once and a `*`
    setting reaches every axis (MCode, X150): what each axis runs with is written where it changes.

    - an own setting that leaves the axis's set incomplete on every path changes nothing the axis
      runs with and is dropped (Arcus `HSPDX` alone, L447-L449);
    - the one that completes the set writes the whole set, its values as the registers hold them;
    - a `*` setting is written, then each axis whose own set is complete gets its own value back.

    Raises `Unresolved` where the set is complete on some paths only, or a register's value is not
    known. A copy; a module without axis sets is returned as it is."""
    sets = tuple(module.axis_sets)
    if not sets:
        return module
    copy = ir.copy_module(module)
    copy.axis_sets = ()
    analysis = InForce(module)
    axes = sorted(_axes(module))
    written: dict[str, set] = {}
    for keys in analysis.clobbers.values():
        for param, axis in keys:
            if param in sets and axis != ALL:
                written.setdefault(axis, set()).add(param)
    able = [axis for axis in axes if written.get(axis, set()) >= set(sets)]  # others never complete
    replaced: dict[int, list[ir.Op]] = {}
    for routine in module.routines:
        for _, _, op, before in analysis.walk(routine):
            if not isinstance(op, ir.SetMotion) or op.param not in sets:
                continue
            after = analysis.after(before, op)
            if op.axis == ALL:
                ops: list[ir.Op] = [op]
                for axis in able:
                    if _complete(after, sets, axis) is None:
                        raise Unresolved(f"axis {axis}'s own speeds are complete on some paths to this setting only, "
                                         "so whether it applies to that axis is known only at run time", op.span)
                    if _complete(after, sets, axis):
                        ops.append(ir.SetMotion(op.param, axis, _register(after, op.param, axis, op), op.span))
                replaced[id(op)] = ops
                continue
            state = _complete(after, sets, op.axis) if op.axis in able else False
            if state is None:
                raise Unresolved(f"axis {op.axis}'s own speeds are complete on some paths only, so whether this "
                                 "setting applies is known only at run time", op.span)
            if not state:
                replaced[id(op)] = []  # the axis runs with the global settings: nothing changes
            elif not _complete(before, sets, op.axis):  # this one completes the set: all of it applies now
                replaced[id(op)] = [op if param is op.param else
                                    ir.SetMotion(param, op.axis, _register(after, param, op.axis, op), op.span)
                                    for param in sets]
    for original, (_, block) in zip(module.blocks(), copy.blocks()):
        ops = []
        for old, new in zip(original[1].ops, block.ops):
            ops.extend(replaced.get(id(old), [new]))
        block.ops[:] = ops
    return copy


def _complete(state: State, sets: tuple, axis: str) -> bool | None:
    """Whether `axis`'s own set is complete on every path (True), on none (False), or unknown."""
    if all((WRITTEN, param, axis) in state for param in sets):
        return True
    if any((UNWRITTEN, param, axis) in state for param in sets):
        return False
    return None


def _register(state: State, param: ir.MotionParam, axis: str, op: ir.Op) -> ir.Const:
    found = state.get((param, axis))
    if found is None:
        raise Unresolved(f"axis {axis}'s own {param.value.replace('_', ' ')} is not known here (set from a "
                         "variable or different on two paths), and the conversion must write it", op.span)
    return found


RATES = (ir.MotionParam.ACCEL, ir.MotionParam.DECEL)
TIMES = (ir.MotionParam.ACCEL_TIME, ir.MotionParam.DECEL_TIME)


def with_axis_sets(module: ir.Module, sets: tuple, problems: list | None = None) -> ir.Module:
    """The module rewritten for a target whose axes use their own settings only as a complete set
    (`sets`, the target's `Module.axis_sets`: Arcus HSPDa, LSPDa and ACCa, L447-L457), from a
    module where an axis's own setting applies at once and a `*` setting reaches every axis.

    Every setting is written as it is. Before each motion of an axis that sets any of its own
    somewhere, the members of its set that it did not set itself on every path are written with the
    values the axis runs with there (its ramp: the program's ramp times when it sets any, else its
    accelerations), so that the target's axis runs with its own complete set exactly as the source's
    runs with its mix of own and `*` values; the ones a register already holds are then left out.

    Raises `Unresolved` when a value the set needs is not known at the motion (or adds it to
    `problems` and goes on without that value, when a list is given). A copy, still under
    the source's rule (the fills change nothing there); a module that has axis sets already, or
    sets nothing of one axis's own, is returned as it is."""
    sets = tuple(sets)
    if not sets or module.axis_sets:
        return module
    ramps = TIMES if any(isinstance(op, ir.SetMotion) and op.param in TIMES
                         for _, block in module.blocks() for op in block.ops) else RATES
    # the target's ramp register (Arcus ACC) is one: the program's ramp time or its acceleration
    members = tuple(p for p in sets if p not in TIMES) + (ramps[:1] if any(p in TIMES for p in sets) else ())
    group = set(sets) | set(RATES)
    analysis = InForce(module)
    own_axes = sorted({axis for keys in analysis.clobbers.values() for param, axis in keys
                       if param in group and axis != ALL})
    fixed = FIXED.get(module.dialect, {})
    inserted: dict[int, list[ir.Op]] = {}
    called = set().union(*analysis_calls(module).values()) if module.routines else set()
    for routine in module.routines:
        if routine.kind is ir.RoutineKind.SUBROUTINE and routine.name not in called:
            continue  # no program path runs it (a host may, knowing nothing of what is in force): as written
        for block, _, op, state in analysis.walk(routine):
            if block.label not in analysis.reached:
                continue  # never runs: it needs nothing
            fills: list[ir.Op] = []
            for axis in _moved(op, own_axes):
                if all((UNWRITTEN, param, axis) in state for param in group):
                    continue  # no setting of its own on any path: it runs with the `*` ones on both
                for param in members:
                    if (WRITTEN, param, axis) in state:
                        continue  # the axis set it itself on every path since any `*` setting: in its set already
                    value = lookup(state, param, axis)
                    if (param, ALL) in fixed:  # the value the target writes for it (with_fixed_initial_speed)
                        value = next((o.value for _, b in module.blocks() for o in b.ops if isinstance(o, ir.SetMotion)
                                      and o.param is param and o.axis == ALL and isinstance(o.value, ir.Const)), value)
                    if value is None:
                        problem = Unresolved(
                            f"the target uses axis {axis}'s own speeds only with its own initial speed, maximum "
                            f"speed and ramp all set, and the {param.value.replace('_', ' ')} axis {axis} runs with "
                            "here is not known: set it before this line", getattr(op, "span", None))
                        if problems is None:
                            raise problem
                        problems.append(problem)
                        break  # one report per axis and operation
                    fills.append(ir.SetMotion(param, axis, value, getattr(op, "span", None)))
            if fills:
                inserted[id(op)] = fills
    copy = ir.copy_module(module)  # the source's rule still holds: the fills change nothing there
    if not inserted:
        return copy
    added: set[int] = set()
    for original, (_, block) in zip(module.blocks(), copy.blocks()):
        ops = []
        for old, new in zip(original[1].ops, block.ops):
            fills = inserted.get(id(old), [])
            added.update(id(f) for f in fills)
            ops.extend(fills)
            ops.append(new)
        block.ops[:] = ops
    registers = ir.copy_module(copy)  # the same operations, read as the target's registers
    registers.axis_sets = tuple(group)
    check = InForce(registers)
    kept = {id(a): b for (_, a), (_, b) in zip(_ops(copy), _ops(registers))}
    needless_ids = {id(op) for routine in registers.routines for _, _, op, state in check.walk(routine)
                    if redundant(state, op)}
    needless = {key for key, twin in kept.items() if key in added and id(twin) in needless_ids}
    for _, block in copy.blocks():
        block.ops[:] = [op for op in block.ops if id(op) not in needless]
    return copy


def _ops(module: ir.Module):
    """Every (block, operation) of the module in order."""
    for _, block in module.blocks():
        for op in block.ops:
            yield block, op


def analysis_calls(module: ir.Module) -> dict[str, set[str]]:
    """The routines each routine calls or continues in."""
    calls: dict[str, set[str]] = {}
    for routine in module.routines:
        found = calls.setdefault(routine.name, set())
        for block in routine.blocks:
            found.update(op.routine for op in block.ops if isinstance(op, ir.Call))
            if isinstance(block.terminator, ir.GotoRoutine):
                found.add(block.terminator.routine)
    return calls


def _moved(op: ir.Op, axes: list[str]) -> list[str]:
    """The axes among `axes` that `op` sets moving (or stops on a ramp)."""
    if isinstance(op, ir.Move):
        named = [axis for axis, _ in op.targets]
    elif isinstance(op, ir.Arc):
        named = list(op.axes)
    elif isinstance(op, (ir.Slew, ir.Home)) or (isinstance(op, ir.Stop) and op.ramp):
        named = [op.axis]
    else:
        return []
    return [axis for axis in axes if axis in named or ALL in named]
