"""Moving an MCode program from one MCode product family to another (MDrivePlus -> Lexium MDrive).

`mcc compile --source-profile mdrive-plus --profile lmd-o prog.mxt` checks the program as an
MDrivePlus program and writes it for the Lexium drive. Most of MCode is the same on both ("Programs
not using I/O can generally be loaded onto the device and work without modification", application
note "Converting MDrive MCode to Lexium MCode"); what differs is converted here, on a copy of the
IR, from the two profiles' data, or refused with the line:

- I/O set-up: S1-S4 lowered to neutral input/output settings, which the Lexium writer spells IS/OS;
  the sink/source value has no Lexium statement (the Reference input's bias decides, by wiring):
  warning M203 on its line. An output on a point the target has no output for is refused (M202).
- the analog input: `machine.analog.counts` of each profile (1024 vs 4096): a reading becomes
  `I5/4` on the Lexium drive, the same number at the same voltage; the other way is refused.
- the encoder: `machine.encoder.counts_per_rev` (2048 vs 4000): reading the encoder counter or
  enabling encoder units (EE) where the counts differ is refused, as counts do not convert exactly.
- a command or register of the source family that the target does not have (OL, IL, an S1-S4
  set-up computed at run time) is refused, naming it.

The migrated program is then simulated against the source like every compile (docs/SIMULATOR.md).
"""

from __future__ import annotations

import dataclasses

from mcc.compiler import ir
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.mcode import catalog as cat
from mcc.compiler.mcode.lower import INPUT_TYPES, OUTPUT_TYPES
from mcc.compiler.profiles import Profile

DIALECT = "mcode"


def differs(source: Profile | None, target: Profile | None) -> bool:
    """Whether compiling from `source` to `target` is a migration between two MCode profiles."""
    return source is not None and target is not None and source.dialect == DIALECT == target.dialect \
        and source.name != target.name


def analog_counts(profile: Profile) -> int:
    return int(profile.get("machine.analog.counts", 0) or 0)


def encoder_counts(profile: Profile) -> int:
    """Encoder counts per revolution; 0 for a product without an encoder (`mcode.encoder = false`)."""
    if profile.get("mcode.encoder", True) is False:
        return 0
    return int(profile.get("machine.encoder.counts_per_rev", 0) or 0)


def migrate(module: ir.Module, source: Profile, target: Profile, diags: Diagnostics) -> ir.Module:
    """A copy of `module` for `target`'s family, with M202 for what cannot be converted and M203
    for what the user must do by wiring."""
    out = ir.copy_module(module)
    out.profile = target.name
    Migration(source, target, diags).run(out)
    return out


class Migration:
    def __init__(self, source: Profile, target: Profile, diags: Diagnostics):
        self.source, self.target, self.diags = source, target, diags
        self.source_cat = cat.for_profile(source)
        self.target_cat = cat.for_profile(target)
        self.analog = (analog_counts(source), analog_counts(target))
        self.output_points: set[int | None] = set()
        self.encoder = (encoder_counts(source), encoder_counts(target))
        self.where = f"{target.title or target.name} (profile '{target.name}')"

    def refuse(self, span, what: str) -> None:
        self.diags.add("M202", span, f"{what}: the program cannot be moved to {self.where}; change the line "
                                     f"by hand, or compile for profile '{self.source.name}'")

    def run(self, module: ir.Module) -> None:
        self.output_points = {op.index for _, block in module.blocks() for op in block.ops
                              if isinstance(op, ir.Setting) and op.name == "output_function"}
        for _, block in module.blocks():
            for index, op in enumerate(block.ops):
                block.ops[index] = self.op(op)
            block.terminator = self.exprs_of(block.terminator)

    def op(self, op):
        if isinstance(op, ir.Native):
            self.native(op)
        elif isinstance(op, ir.Setting):
            self.setting(op)
        return self.exprs_of(op)

    def native(self, op: ir.Native) -> None:
        name = op.mnemonic.upper()
        if op.dialect != DIALECT or not name or self.target_cat.lookup(name) is not None:
            return
        command = self.source_cat.lookup(name)
        if command is not None and command.ir == "io_setup":
            self.refuse(op.span, f"{name} with values computed at run time: the target sets an input up with IS "
                                 "and an output with OS, so the function must be a number here")
        else:
            title = f" ({command.entry.title})" if command is not None else ""
            self.refuse(op.span, f"{name}{title} has no equivalent on the target")

    def setting(self, op: ir.Setting) -> None:
        if op.name == "encoder_enable" and self.encoder_differs() and not is_zero(op.value):
            self.refuse(op.span, f"encoder units (EE): {self.encoder_counts_text()}, so positions and speeds in "
                                 "counts do not convert exactly")
        if op.name == "output_function" and op.index is not None and f"O{op.index}" not in self.target_cat.commands:
            self.refuse(op.span, f"I/O point {op.index} as an output: the target has no output {op.index}")
        if op.name in ("input_function", "output_function") and self.target_cat.io_setup == "point":
            self.point_setting(op)
        if op.name == "io_sourcing" and self.target_cat.io_setup != "point":
            kind = "sourcing" if isinstance(op.value, ir.Const) and op.value.value == 1 else "sinking"
            self.diags.add("M203", op.span, f"I/O point {op.index} is set {kind} here; on {self.where} sinking or "
                                            "sourcing is set by the bias of the Reference input (wiring), not by "
                                            "the program: wire it so")

    def point_setting(self, op: ir.Setting) -> None:
        """A Lexium IS/OS on a family whose I/O points are either inputs or outputs (S1-S4): the
        function must be one S<n> has, and one point cannot be both."""
        command = self.target_cat.lookup(f"S{op.index}")
        if command is None:
            self.refuse(op.span, f"setting up {'input' if op.name == 'input_function' else 'output'} {op.index}: "
                                 "the target's I/O points are S1-S4")
            return
        table = INPUT_TYPES if op.name == "input_function" else OUTPUT_TYPES
        number = next((n for n, name in table.items() if isinstance(op.value, ir.Text) and name == op.value.value), None)
        allowed = command.forms()[0].args[0].values if command.forms() else None
        if number is not None and allowed is not None and number not in allowed:
            self.refuse(op.span, f"function {number} ({op.value.value}): the target's S{op.index} has no such function")
        if op.index in self.output_points and op.name == "input_function":
            self.refuse(op.span, f"input {op.index} and output {op.index} are two pins of the source but one I/O "
                                 f"point (S{op.index}) of the target")

    def encoder_differs(self) -> bool:
        return bool(self.encoder[0]) and self.encoder[0] != self.encoder[1]

    def encoder_counts_text(self) -> str:
        target = f"{self.encoder[1]} on '{self.target.name}'" if self.encoder[1] else \
            f"'{self.target.name}' has no encoder"
        return f"{self.encoder[0]} counts per revolution on '{self.source.name}', {target}"

    # expressions ---------------------------------------------------------------------------------
    def exprs_of(self, node):
        """`node` (an operation, terminator or expression) with its readings converted: the same
        object when nothing changed, else a copy (expressions are shared between modules)."""
        if isinstance(node, ir.Status):
            return self.status(node)
        if isinstance(node, ir.DeviceRef):
            self.device_ref(node)
            return node
        if isinstance(node, tuple):
            new = tuple(self.exprs_of(v) for v in node)
            return node if all(a is b for a, b in zip(new, node)) else new
        if not is_ir(node):
            return node
        changes = {}
        for field in dataclasses.fields(node):
            value = getattr(node, field.name)
            new = self.exprs_of(value)
            if new is not value:
                changes[field.name] = new
        return dataclasses.replace(node, **changes) if changes else node

    def device_ref(self, node: ir.DeviceRef) -> None:
        if node.dialect == DIALECT and self.target_cat.lookup(node.name) is None:
            command = self.source_cat.lookup(node.name)
            title = f" ({command.entry.title})" if command is not None else ""
            self.refuse(node.span, f"reading {node.name}{title}: the target has no such register")

    def status(self, node: ir.Status):
        if node.meaning == "analog" and all(self.analog) and self.analog[0] != self.analog[1]:
            source, target = self.analog
            if target % source == 0:  # the same reading at the same voltage: the target's counts / ratio
                return ir.BinOp("/", node, ir.Const(target // source, ir.Unit.NONE, node.span), node.span)
            self.refuse(node.span, f"reading the analog input: {source} counts on '{self.source.name}', {target} "
                                   f"on '{self.target.name}', and the target's reading cannot give the source's "
                                   "exactly")
        if node.meaning == "input" and node.index in self.output_points and self.source_cat.io_setup == "point" \
                and self.target_cat.io_setup != "point":
            self.refuse(node.span, f"reading I{node.index}, the level of I/O point {node.index}, which the program sets "
                                   f"up as an output: on the target, input {node.index} is another pin than output "
                                   f"{node.index}")
        if node.meaning == "encoder" and self.encoder_differs():
            self.refuse(node.span, f"reading the encoder counter: {self.encoder_counts_text()}, which do not "
                                   "convert exactly")
        return node


def is_ir(value) -> bool:
    """An IR operation, terminator or expression (not a span, not a block)."""
    return dataclasses.is_dataclass(value) and not isinstance(value, type) and \
        type(value).__module__ == ir.__name__ and not isinstance(value, (ir.Block, ir.Routine))


def is_zero(value) -> bool:
    return isinstance(value, ir.Const) and value.value == 0
