"""Stating IR as text in tests, as MLIR's FileCheck tests do (docs/IR.md, "Writing an IR test").

    module = ir_from_text('''
        routine main (main)
        %1:
          V1 = 2 + 3  ; L1
          end
    ''')

The text is `mcc ir`'s text form (compiler/ir_read.py reads it); the module line may be left out,
the helper then writes one for `dialect` with the profile its samples lower with. `ir_text(module)` prints a
module back without the module line, so an expected result reads as the input does."""

from __future__ import annotations

import textwrap

from mcc.compiler import ir
from mcc.compiler.ir_print import to_text
from mcc.compiler.ir_read import read_text

HEADERS = {
    "arcus": "module arcus profile=pmx-4ex-sa steps_per_rev=0",
    "mcode": "module mcode profile=lmd-c steps_per_rev=51200",
    "x150": "module x150 profile=x150-pdhx steps_per_rev=4000",
}


def ir_from_text(text: str, dialect: str = "arcus", path: str = "test.ir") -> ir.Module:
    """The module `text` states (indentation common to every line removed)."""
    body = textwrap.dedent(text).strip("\n") + "\n"
    if not body.startswith("module "):
        body = f"{HEADERS[dialect]}\n{body}"
    return read_text(body, path)


def ir_text(module: ir.Module) -> str:
    """`module`'s text form without its module line, ready to compare with a dedented expectation."""
    return to_text(module).split("\n", 1)[1].lstrip("\n")


def expected(text: str) -> str:
    return textwrap.dedent(text).strip("\n") + "\n"
