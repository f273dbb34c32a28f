"""What the envelope rules (G301-G304) share: the axes' envelope of `[tool.mcc.axes]` and the
profile's `[envelope]` (compiler/envelope/axes.py), and one run of the interval analysis of
compiler/envelope/intervals.py per file. Without an envelope there is no analysis and the rules
report nothing.
"""

from __future__ import annotations

from mcc.compiler.envelope.axes import AxisEnvelope, envelopes
from mcc.compiler.envelope.intervals import Analyzer, Result
from mcc.compiler.lint.rules import Context


def envelope_of(ctx: Context) -> dict[str, AxisEnvelope]:
    configured = getattr(ctx.settings, "axes", ()) or ()
    return ctx.shared("envelope", lambda: envelopes(ctx.profile, configured))


def analysis(ctx: Context) -> Result | None:
    found = envelope_of(ctx)
    if not found:
        return None
    return ctx.shared("envelope-analysis", lambda: Analyzer(ctx.module, found, ctx.profile.axes).run())


def line_of(op) -> int:
    return op.span.line if op.span else 0
