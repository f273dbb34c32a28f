"""X150's #n steps a constant 1-255 commands (parker-x150.md L5548): a count held in a variable has
no X150 spelling, and the backend refuses it at its line. The refusal once raised a NameError
instead (an internal error, G001), which the handler test's examples did not reach: there the
step is in a sequence, refused earlier, since only the host sends # (L5548)."""

from __future__ import annotations

from ir_text import ir_from_text
from mcc.compiler import dialects, profiles


def test_a_step_count_known_only_at_run_time_is_refused_at_its_line():
    module = ir_from_text("""
        var V1: int32
        routine host (immediate)
        %1:
          step 1 V1  ; L3
          end  ; L4
    """, "x150")
    listing = dialects.get("x150").load_backend().emit(module, profiles.load("x150-pdhx"))
    errors = [d for d in listing.diagnostics if d.severity.value == "error"]
    assert [(d.code, d.span.line) for d in errors] == [("G003", 3)]
    assert "a count known only at run time" in errors[0].message
