"""The X150 frontend: text → syntax tree → IR, with every X150 check (docs/dialects/x150.md)."""

from __future__ import annotations

from mcc.compiler.cancel import checkpoint
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.analysis import Analysis
from mcc.compiler.profiles import Profile
from mcc.compiler.span import SourceFile
from mcc.compiler.x150 import checks, parser
from mcc.compiler.x150.lower import Lowering


def analyze(source: SourceFile, profile: Profile) -> Analysis:
    diags = Diagnostics()
    tree = parser.parse(source, diags)
    return analyze_tree(source, tree, profile, diags)


def analyze_tree(source: SourceFile, tree, profile: Profile, diags: Diagnostics) -> Analysis:
    """Everything after parsing, on a tree the caller parsed (the editor server reuses the lines
    of the previous version that did not change: lsp/incremental.py)."""
    lowering = Lowering(tree, profile, diags)
    module = lowering.run()
    checkpoint()  # the editor server abandons a stale analysis here (compiler/cancel.py)
    memory = checks.run(source, lowering, profile, diags)
    return Analysis(source, tree, module, diags, memory)
