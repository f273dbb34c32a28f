"""Whole-program checks of an MCode file: labels, user names, VI/VM, line length, a program that
runs on into a subroutine.

Per-statement checks (unknown commands, arguments, ranges, modes, products) happen while resolving
statements (resolve.py); these need the whole file.
"""

from __future__ import annotations

from mcc.compiler import ir
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.mcode import syntax as st
from mcc.compiler.mcode.lower import Lowering
from mcc.compiler.mcode.resolve import SHORT_USER_NAME, STRICT_USER_NAME, USER_NAME

# limits.label_rule -> (pattern, what it asks for)
NAME_RULES = {"strict": (STRICT_USER_NAME, "a letter then a letter or digit, exactly two characters"),
              "relaxed": (USER_NAME, "a letter followed by up to two letters or digits"),
              "short": (SHORT_USER_NAME, "a letter, alone or followed by a letter or digit")}
from mcc.compiler.span import SourceFile


def check_labels(lowering: Lowering, diags: Diagnostics) -> None:
    """Every BR, CL, EX, OE, trip (and BP, L, CP) target must be a label of this file or a known address."""
    labels = lowering.resolver.names.labels
    origins = {r.origin for r in lowering.module.routines if r.origin is not None}
    for key, node, command in lowering.label_refs:
        if isinstance(node, st.Number):
            if node.value not in origins:
                diags.add("M127", node.span, f"{command} {node.text}: no program starts at address {node.text} in "
                                             "this file; mcc cannot check this target")
            continue
        if key not in labels:
            if key in lowering.resolver.names.variables:
                diags.add("M129", node.span, f"{node.text} is a variable, not a label: {command} needs a label")
            else:
                diags.add("M106", node.span, f"label {node.text} is not defined: add `LB {node.text}` where "
                                             f"{command} should go, or fix the name")


def check_user_names(lowering: Lowering, diags: Diagnostics) -> None:
    """User names: two characters, a letter first, not a mnemonic; labels and variables share a table."""
    names = lowering.resolver.names
    cat = lowering.cat
    profile = lowering.profile
    pattern, rule = NAME_RULES.get(str(profile.get("limits.label_rule", "strict")), NAME_RULES["strict"])
    for kind, table in (("label", names.labels), ("variable", names.variables)):
        for key, node in table.items():
            if key == "SU" and kind == "label":
                continue
            if cat.is_reserved(key, profile.firmware) or key in cat.legacy:
                entry = cat.lookup(key) or cat.functions.get(key)
                what = f"the MCode {entry.kind} {key} ({entry.entry.title})" if entry else f"the command {key}"
                if entry is not None and entry.kind == "function" and entry.firmware:
                    targets = profile.firmware or "the newest"
                    what += (f" from firmware {entry.firmware} on (the profile targets {targets}; on older "
                             "firmware it is a plain name: use a profile with `firmware = \"5.0\"`, see docs/PROFILES.md)")
                diags.add("M104", node.span, f"{kind} name {node.text} is {what}: user names must not be "
                                             "MCode names; choose another")
            elif not pattern.match(node.text):
                diags.add("M103", node.span, f"{kind} name '{node.text}' is not a valid MCode name ({rule})")
    for key, node in names.variables.items():
        if key in names.labels:
            label = names.labels[key]
            diags.add("M122", node.span, f"{node.text} is both a variable and a label (line {label.span.line}); "
                                         "labels and variables share one name table, rename one")
    limit = int(profile.get("limits.user_names", 192))
    count = len(set(names.labels) | set(names.variables))
    if count > limit:
        node = list(names.variables.values())[-1] if names.variables else list(names.labels.values())[-1]
        diags.add("M116", node.span, f"{count} labels and variables: the device's name table holds {limit} "
                                     "(Error 31); reuse names or split the program")


def constant(expr) -> int | float | None:
    return expr.value if isinstance(expr, ir.Const) else None


def check_speeds(lowering: Lowering, diags: Diagnostics) -> None:
    """VI must stay below VM where both are constants (device Errors 22/23), in file order."""
    vi = lowering.cat.lookup("VI")
    vm = lowering.cat.lookup("VM")
    current = {ir.MotionParam.INITIAL_SPEED: (vi.entry.default if vi else 1000, None),
               ir.MotionParam.MAX_SPEED: (vm.entry.default if vm else 768000, None)}
    for _, block in lowering.module.blocks():
        for op in block.ops:
            if not isinstance(op, ir.SetMotion) or op.param not in current:
                continue
            value = constant(op.value)
            current[op.param] = (value, op)
            low, low_op = current[ir.MotionParam.INITIAL_SPEED]
            high, high_op = current[ir.MotionParam.MAX_SPEED]
            if low is None or high is None or low < high:
                continue
            other = high_op if op.param is ir.MotionParam.INITIAL_SPEED else low_op
            where = f" (set at line {other.span.line})" if other is not None and other.span else " (the default)"
            diags.add("M113", op.span, f"VI={low} is not below VM={high}{where}: the device refuses it "
                                       "(Error 22/23); VI must be less than VM")


def check_line_lengths(source: SourceFile, tree: st.SyntaxTree, lowering: Lowering, diags: Diagnostics) -> None:
    """The device buffers 64 characters per line, comments and spaces included (L626, L4897)."""
    limit = int(lowering.profile.get("limits.line_length", 64))
    policy = lowering.profile.get("mcode.comment_line_policy", "warn")
    comment_only = lowering.profile.get("mcode.comment_only_lines", "ignore")
    for line in tree.lines:
        text = source.line_text(line.number)
        if len(text) <= limit:
            continue
        stmt = line.statement
        body = text.strip() if stmt is None else source.text[stmt.span.start:stmt.span.end]
        span = source.line_span(line.number)
        if stmt is not None and len(body) > limit:
            diags.add("M109", stmt.span, f"this statement is {len(body)} characters; the device accepts {limit} per "
                                         "line (Error 20): shorten names or split the work over two statements")
        elif stmt is None and comment_only == "ignore":
            continue
        elif policy != "ignore" and len(text.strip()) > limit:
            severity = None if policy == "warn" else diags_error()
            diags.add("M110", span, f"the line is {len(text.strip())} characters with its comment; downloaders that "
                                    f"send comments overflow the {limit}-character buffer: shorten the comment "
                                    "or move it to its own line", severity=severity)


def diags_error():
    from mcc.compiler.diagnostics import Severity

    return Severity.ERROR


def check_fall_into_subroutine(lowering: Lowering, diags: Diagnostics) -> None:
    """The main (or SU) program runs past its last line into a subroutine or handler: its RT then
    returns with no call on the stack (L8489). Reported by `mcc check` (M323), not only by lint.

    The lowering joins one label's code to the next label's with a Jump carrying the span of the
    `LB` it runs into (the target block's own span); a written `BR` carries its own span."""
    module = lowering.module
    owner = {block.label: (routine, block) for routine in module.routines for block in routine.blocks}
    for routine in module.routines:
        if routine.kind not in (ir.RoutineKind.MAIN, ir.RoutineKind.POWERUP) or routine.entry is None:
            continue
        for block in reachable(routine):
            term = block.terminator
            if not isinstance(term, ir.Jump) or term.target not in owner:
                continue
            target_routine, target = owner[term.target]
            if target_routine is routine or target_routine.kind not in (ir.RoutineKind.SUBROUTINE,
                                                                        ir.RoutineKind.HANDLER):
                continue
            if term.span is None or term.span != target.span:
                continue  # a written BR into a subroutine is another matter (M302 and friends)
            diags.add("M323", term.span,
                      f"the program {routine.name} runs on into {target_routine.kind.value} {target.label} "
                      "without E: its RT returns with no call on the stack; end the program with E (or BR "
                      "back to its loop)")


def reachable(routine: ir.Routine) -> list[ir.Block]:
    """The routine's blocks reachable from its entry, in routine order."""
    blocks = {block.label: block for block in routine.blocks}
    seen = {routine.entry.label}
    todo = [routine.entry]
    while todo:
        for label in ir.successors(todo.pop().terminator):
            if label in blocks and label not in seen:
                seen.add(label)
                todo.append(blocks[label])
    return [block for block in routine.blocks if block.label in seen]
