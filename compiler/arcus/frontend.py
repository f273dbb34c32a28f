"""The Arcus frontend: text → syntax tree → IR, with every Arcus check."""

from __future__ import annotations

from mcc.compiler import checks
from mcc.compiler.arcus import parser
from mcc.compiler.arcus.lower import Lowering
from mcc.compiler.cancel import checkpoint
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.analysis import Analysis
from mcc.compiler.profiles import Profile
from mcc.compiler.span import SourceFile


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
    checks.run(checks.Program("arcus", source, tree, lowering, profile), diags)  # compiler/checks/arcus/
    return Analysis(source, tree, module, diags)
