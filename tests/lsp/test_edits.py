"""The whole-line edits formatting and "fix all" send: applied, they give the new text exactly,
in every shape of change, and fast on a long program of repeated lines."""

from __future__ import annotations

import random
import time


from lsp_client import apply_edits
from mcc.lsp.edits import line_edits


apply = apply_edits


def test_random_changes_give_the_new_text():
    rng = random.Random(25)
    words = ["H\n", "WAITX\n", "  MA 100\n", "V1=V1+1\r\n", "END\n", "X1000\r", ""]
    for _ in range(400):
        before = "".join(rng.choice(words) for _ in range(rng.randrange(0, 12)))
        after = "".join(rng.choice(words) for _ in range(rng.randrange(0, 12)))
        if rng.random() < 0.3:
            before, after = before.rstrip("\n"), after.rstrip("\r\n")
        assert apply(before, line_edits(before, after)) == after, (before, after)


def test_a_long_program_of_repeated_lines_is_diffed_at_once():
    lines = ["WAITX\n", "WAITY\n", "GOSUB 1\n", "DO1=1\n"] * 750
    before = "".join(lines)
    indented = "".join("  " + line if line.startswith("GOSUB") else line for line in lines)
    added = "NEW\n" + indented[:-6] + "LAST\n" + indented[-6:]
    for after in (indented, added):
        start = time.perf_counter()
        edits = line_edits(before, after)
        assert time.perf_counter() - start < 2.0  # the bench's 3,000-line Arcus program took 13 s to diff line by line with difflib
        assert apply(before, edits) == after
