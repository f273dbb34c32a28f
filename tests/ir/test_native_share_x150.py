"""The share of X150 operations that stay `Native` (issue 8's target: at most 10 %), measured on
the project's X150 samples and golden inputs. The bound only tightens as more of X150 gets a
neutral meaning; what is left is listed in docs/dialects/x150.md ("Limitations")."""

from __future__ import annotations

from collections import Counter

from ir_programs import lowered, program_files
from mcc.compiler import ir

BOUND = 0.25  # measured 24.8 % when the D/G/mode data flow landed; the target is 0.10


def share(dialect: str) -> tuple[float, Counter]:
    total = 0
    natives: Counter = Counter()
    for path in program_files(dialect):
        module = lowered(path, dialect)
        if module is None:
            continue
        for _, block in module.blocks():
            for op in block.ops:
                total += 1
                if isinstance(op, ir.Native):
                    natives[op.mnemonic] += 1
    return sum(natives.values()) / max(total, 1), natives


def test_x150_native_share_stays_under_its_bound():
    value, natives = share("x150")
    print(f"x150 Native share: {value:.1%}; most common: {natives.most_common(8)}")
    assert value <= BOUND
    # what has a neutral meaning does not stay Native (a G whose mode depends on the path stays, X140,
    # with its mode commands; an addressed T in a stream mixing devices keeps its address)
    assert not {"D", "H", "MPI", "MC", "TRIP", "PZ", "O", "HALT", '"'} & set(natives)
