"""Applying fixes: the edits of several diagnostics at once, never two that touch the same text.

As in ruff, fixes are applied in rounds: each round takes the fixes whose edits do not overlap an
already accepted one, applies them, and the file is checked again (a fix may make another finding
appear or disappear), until no fix applies. A round that comes back to a text already seen, or
rounds that do not settle within MAX_ROUNDS, stop with G008 and the file is left unchanged.

A fix is *safe* only when it provably keeps what the program does: `fix_is_safe` compares the
program before and after (see there). A rule marks a fix safe when it means it to be; the engine
still proves it on the actual file before applying it, and a marked-safe fix that fails the proof
is treated as unsafe (applied only with `--unsafe-fixes`, shown by `--diff --unsafe-fixes`).
Unsafe fixes are applied in rounds of their own, after the safe ones have settled, so that the
proof of a safe fix is never mixed with a change that is allowed to alter the program.
"""

from __future__ import annotations

import dataclasses
import difflib
from dataclasses import dataclass, field
from typing import Callable

from mcc.compiler.diagnostics import Diagnostic, Edit, Fix

MAX_ROUNDS = 8  # overlapping fixes need a round each; more than this means a fix repeats itself


def applicable(diagnostics: list[Diagnostic], unsafe: bool) -> list[Fix]:
    return [d.fix for d in diagnostics if d.fix is not None and d.fix.edits and (d.fix.safe or unsafe)]


def apply(text: str, fixes: list[Fix]) -> tuple[str, int]:
    """Apply the fixes that do not conflict; (new text, number of fixes applied)."""
    taken: list[tuple[int, int]] = []
    edits: list[Edit] = []
    count = 0
    for fix in sorted(fixes, key=lambda f: min(e.span.start for e in f.edits)):
        ranges = [(e.span.start, e.span.end) for e in fix.edits]
        if any(not 0 <= a <= b <= len(text) for a, b in ranges):
            continue  # a span that does not fit this text: never guess
        if any(overlaps(r, t) for r in ranges for t in taken):
            continue
        taken += ranges
        edits += fix.edits
        count += 1
    for edit in sorted(edits, key=lambda e: (e.span.start, e.span.end), reverse=True):
        text = text[:edit.span.start] + edit.text + text[edit.span.end:]
    return text, count


def overlaps(a: tuple[int, int], b: tuple[int, int]) -> bool:
    """Ranges overlap, or are the same insertion point (their order would be arbitrary)."""
    if a[0] == a[1] or b[0] == b[1]:
        return a[0] == b[0] or b[0] < a[0] < b[1] or a[0] < b[0] < a[1]
    return a[0] < b[1] and b[0] < a[1]


def unified_diff(path: str, before: str, after: str) -> str:
    lines = difflib.unified_diff(before.splitlines(keepends=True), after.splitlines(keepends=True),
                                 fromfile=f"a/{path}", tofile=f"b/{path}")
    out = []
    for line in lines:
        out.append(line if line.endswith("\n") else line + "\n\\ No newline at end of file\n")
    return "".join(out)


# proving fixes safe -------------------------------------------------------------------------------

@dataclass
class Version:
    """One text of the file being fixed, with what mcc makes of it (computed on first use)."""

    path: str
    text: str
    dialect: str | None
    profile: object | None = None
    _result: object | None = field(default=None, repr=False)

    @property
    def result(self):
        if self._result is None:
            from mcc.compiler import driver

            self._result = driver.compile_file(self.path, self.dialect, None, self.profile, self.text, verify=False)
        return self._result

    @property
    def compiled(self) -> str | None:
        """The device-ready program, or None when the text has errors (nothing is compiled)."""
        result = self.result
        if result.has_errors or result.listing is None:
            return None
        return result.listing.text

    @property
    def module(self):
        analysis = self.result.analysis
        return analysis.module if analysis is not None else None

    @property
    def errors(self) -> list[str]:
        """The codes of the errors, in order: what `mcc check` would reject the text for."""
        return sorted(d.code for d in self.result.diagnostics if d.severity.value == "error")


def fix_is_safe(before: Version, after: Version) -> bool:
    """Whether `after` provably does what `before` does, so the change may be applied as safe.

    - When `before` compiles, `after` must compile to the identical device program.
    - When `before` has errors (nothing can be compiled), the IR of both must be equal, positions
      ignored, as `mcc fmt` requires, and the errors must be the same codes: a statement with an
      error is left out of the IR, so deleting or rewriting it would look like no change at all.
      A fix that removes an error is therefore never safe: it changes a program the device would
      reject, or run in a way mcc cannot tell, into one it accepts. A text that does not even
      lower is never proved.

    The integrator adds the simulator here: once `mcc.sim` exists, the traces of `before` and
    `after` (the same inputs, the same run) must be equal as well.
    """
    old = before.compiled
    if old is not None:
        return after.compiled == old
    if before.module is None or after.module is None:
        return False
    from mcc.compiler.ir_compare import equivalent

    return before.errors == after.errors and equivalent(before.module, after.module)


def key(fix: Fix) -> tuple:
    return fix.description, tuple((e.span.start, e.span.end, e.text) for e in fix.edits)


def as_unsafe(diagnostics: list[Diagnostic], keys: set[tuple]) -> list[Diagnostic]:
    """The diagnostics, with the fixes in `keys` marked unsafe (they failed the proof)."""
    for diag in diagnostics:
        if diag.fix is not None and diag.fix.safe and key(diag.fix) in keys:
            diag.fix = dataclasses.replace(diag.fix, safe=False,
                                           description=f"{diag.fix.description} (would change the compiled program)")
    return diagnostics


def apply_proven(before: Version, candidates: list[Fix], make: Callable[[str], Version]) -> tuple[str, int, set]:
    """Apply the candidates that keep the program's meaning: (text, fixes applied, keys of the
    candidates that failed the proof). All together first; when that fails, the candidates are
    halved until the ones that fail are found (a compile per half, not per fix)."""
    text = before.text
    passing: list[Fix] = []
    failing: set = set()

    def prove(group: list[Fix]) -> None:
        new_text, applied = apply(text, group)
        if applied and new_text != text and fix_is_safe(before, make(new_text)):
            passing.extend(group)
        elif len(group) == 1:
            failing.add(key(group[0]))
        elif len(group) > 1:
            middle = len(group) // 2
            prove(group[:middle])
            prove(group[middle:])

    prove(candidates)
    if not passing:
        return text, 0, failing
    new_text, count = apply(text, passing)
    if len(passing) < len(candidates) and not fix_is_safe(before, make(new_text)):
        new_text, count = apply(text, passing[:1])  # each part is fine, not all together: one per round
    return new_text, count, failing


@dataclass
class FixRun:
    text: str
    diagnostics: list[Diagnostic]
    fixed: int = 0
    error: str = ""  # why the fixes were abandoned (G008), the text then being the original


def fix_until_stable(text: str, diagnostics: list[Diagnostic], relint: Callable[[str], list[Diagnostic]],
                     make: Callable[[str], Version], unsafe: bool) -> FixRun:
    """Apply fixes round after round until none applies: safe ones (proved by `fix_is_safe`),
    then, if asked, unsafe ones. `relint(text)` gives the diagnostics of a text, `make(text)` its
    Version."""
    original, diags = text, diagnostics
    seen = {text}
    fixed = 0
    for round_number in range(MAX_ROUNDS + 1):
        current = make(text)
        safe = [d.fix for d in diags if d.fix is not None and d.fix.edits and d.fix.safe]
        new_text, count, failed = apply_proven(current, safe, make) if safe else (text, 0, set())
        if count == 0 and unsafe:
            others = [d.fix for d in diags if d.fix is not None and d.fix.edits
                      and (not d.fix.safe or key(d.fix) in failed)]
            new_text, count = apply(text, others)
        if count == 0 or new_text == text:
            return FixRun(text, as_unsafe(diags, failed), fixed)
        if round_number == MAX_ROUNDS:
            codes = sorted({d.code for d in diags if d.fix is not None and d.fix.edits})
            return FixRun(original, diagnostics, 0,
                          f"the fixes did not settle after {MAX_ROUNDS} rounds (still fixing: {', '.join(codes)})")
        if new_text in seen:
            return FixRun(original, diagnostics, 0, "the fixes come back to a text they already produced")
        seen.add(new_text)
        text, fixed = new_text, fixed + count
        diags = relint(text)
    raise AssertionError("unreachable: the last round returns")
