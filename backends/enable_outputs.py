"""The Arcus enable outputs (`EO`, `EO1`-`EO4`) as the drive enable of a one-axis target.

The PMX-4EX-SA has an enable output per axis "to enable or disable the driver" (arcus-pmx-4ex-sa.txt
L748; its software's "Enable motor power" circles, L1000), and real programs start with `EO=1`
(issue 24). `EO=<mask>` sets them all, the first axis in bit 0 (L748, L2142); the frontend keeps it
as the setting `enable_outputs` (profile `[arcus] enable_outputs = "outputs"`), and `EOn=` as a
`DriveEnable` of the n-th axis. A target drive enables its own bridge: MCode `DE` (lexium-mcode.txt
L2362-L2378), X150 `ST0`/`ST1` (parker-x150.md L4010-L4031). So (decision, docs/CROSS.md, "Enable
outputs"):

- the mask becomes the enable of each axis the target drives, from that axis's bit: `EO=3` on a
  program of axis X is `DE=1`; the bits of axes the program never uses are the enables of drives
  the target does not have, and are left out (a program that uses those axes is refused at them);
- an `EOn` of an axis the program never moves is left out with warning G060, on its line;
- the enable of a program with no axis at all is the first axis's (bit 0), the target's drive.

Used by backends/mcode.py and backends/x150/writer.py; it reads the IR and the source's profile only.
"""

from __future__ import annotations

from mcc.compiler import ir

SOURCE_AXES = ("X", "Y", "Z", "U")  # the order of the mask's bits when the source profile names none


def source_axes(module: ir.Module) -> tuple[str, ...]:
    """The source product's axes in the order of the mask's bits (bit 0 first)."""
    from mcc.compiler.profiles import ProfileError, load

    try:
        axes = tuple(str(a) for a in load(module.profile).axes) if module.profile else ()
    except ProfileError:
        axes = ()
    return axes or SOURCE_AXES


def moved_axes(module: ir.Module) -> set[str]:
    """The axes any operation other than an enable names."""
    found: set[str] = set()
    for _, block in module.blocks():
        for op in block.ops:
            if isinstance(op, ir.DriveEnable) or (isinstance(op, ir.Setting) and op.name == "enable_outputs"):
                continue
            if isinstance(op, ir.Move):
                found.update(axis for axis, _ in op.targets)
            elif isinstance(op, ir.Arc):
                found.update(op.axes)
            elif getattr(op, "axis", "") not in ("", ir.ALL_AXES):
                found.add(op.axis)
    return found


def bit_of(module: ir.Module, axis: str) -> int | None:
    """The bit of `axis` in the source's enable mask (None: the mask has no bit for it)."""
    axes = source_axes(module)
    return axes.index(axis) if axis in axes else None


def enable_value(value: ir.Expr, bit: int) -> ir.Expr | None:
    """Bit `bit` of the mask `value` as 0 or 1: a number for a constant mask; for a mask computed at
    run time `(value & 2^bit) / 2^bit` (`value & 1` for bit 0); None for a constant outside 0-15."""
    if isinstance(value, ir.Const):
        number = value.value
        if not float(number).is_integer() or not 0 <= number <= 15:
            return None
        return ir.Const(int(number) >> bit & 1, ir.Unit.NONE, value.span)
    masked = ir.BinOp("&", value, ir.Const(1 << bit), value.span)
    return masked if bit == 0 else ir.BinOp("/", masked, ir.Const(1 << bit), value.span)


def undriven(module: ir.Module, op: ir.DriveEnable, driven: set[str]) -> bool:
    """Whether `op` enables the drive of an axis the program never moves and the target does not
    drive (`driven`: the source axes the target maps): left out with a warning."""
    return op.axis not in ("", ir.ALL_AXES) and op.axis not in driven and op.axis not in moved_axes(module)
