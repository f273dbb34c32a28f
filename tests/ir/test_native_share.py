"""The share of `Native` operations in the IR of each dialect's samples and golden programs.

Issue 8: `Native` is only for what no other dialect has, at most 10 % of the operations. The test
prints the share (run pytest with -s to see it) and asserts it for the dialects whose lowering
is converted (the set only grows). The manuals' examples are measured the same way by
`../shared/tools/conformance`; the tests never read them.
"""

from __future__ import annotations

from collections import Counter

import pytest

from ir_programs import lowered, program_files
from mcc.compiler import ir

LIMIT = 0.10
SHARE_KEPT: set[str] = {"arcus"}


def native_share(dialect: str) -> tuple[int, int, Counter]:
    total = native = 0
    mnemonics: Counter = Counter()
    for path in program_files(dialect):
        module = lowered(path, dialect)
        if module is None:
            continue
        for _, block in module.blocks():
            for op in block.ops:
                total += 1
                if isinstance(op, ir.Native):
                    native += 1
                    mnemonics[op.mnemonic] += 1
    return native, total, mnemonics


@pytest.mark.parametrize("dialect", sorted(SHARE_KEPT))
def test_native_operations_are_at_most_a_tenth(dialect: str) -> None:
    native, total, mnemonics = native_share(dialect)
    assert total > 0
    share = native / total
    print(f"{dialect}: {native} of {total} operations are Native ({share:.1%}): {dict(mnemonics)}")
    assert share <= LIMIT, mnemonics.most_common(10)
