"""What a frontend returns for one source file: the text, the syntax tree, the IR and diagnostics.

It lives apart from the driver so that frontends depend on it without depending on the driver
(the layers are kept by tests/test_layers.py).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from mcc.compiler import ir
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.span import SourceFile


@dataclass
class Analysis:
    source: SourceFile
    tree: Any
    module: ir.Module | None
    diagnostics: Diagnostics
    # program memory against the target's budget, from the same model as the backend's listing
    # (X150 sequence bytes, Arcus assembly lines); filled by the frontend or by `measure_memory`
    memory: dict = field(default_factory=dict)
