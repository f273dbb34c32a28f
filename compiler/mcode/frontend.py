"""The MCode frontend: text → syntax tree → IR, with every MCode check."""

from __future__ import annotations

from mcc.compiler.cancel import checkpoint
from mcc.compiler.diagnostics import Diagnostics
from mcc.compiler.analysis import Analysis
from mcc.compiler import checks
from mcc.compiler.mcode import parser, preprocessor
from mcc.compiler.mcode.lower import Lowering
from mcc.compiler.profiles import Profile
from mcc.compiler.span import SourceFile


def analyze(source: SourceFile, profile: Profile) -> Analysis:
    diags = Diagnostics()
    directives = preprocessor.directive_lines(source)
    if directives:  # mcontrol preprocessor source: one M142, the file read without its directives
        text = preprocessor.blanked(source, directives)
        analysis = analyze_tree(text, parser.parse(text, Diagnostics()), profile, Diagnostics())
        preprocessor.report(source, directives, diags)
        return Analysis(source, analysis.tree, analysis.module, diags, statements=analysis.statements)
    tree = parser.parse(source, diags)
    return analyze_tree(source, tree, profile, diags)


def analyze_tree(source: SourceFile, tree, profile: Profile, diags: Diagnostics) -> Analysis:
    """Everything after parsing, on a tree the caller parsed (the editor server reuses the lines
    of the previous version that did not change: lsp/incremental.py)."""
    lowering = Lowering(tree, profile, diags)
    module = lowering.run()
    checkpoint()  # the editor server abandons a stale analysis here (compiler/cancel.py)
    checks.run(checks.Program("mcode", source, tree, lowering, profile), diags)  # compiler/checks/mcode/
    return Analysis(source, tree, module, diags, statements=[(line, res) for line, res, _ in lowering.resolved])
