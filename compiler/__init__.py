"""compiler

Importing it routes the code that `dataclasses` compiles for mcc's classes through a per-user
cache (compiler/dataclass_code.py): start-up of a small `mcc check`, issue 26.
"""

from mcc.compiler import dataclass_code as _dataclass_code

_dataclass_code.install()
