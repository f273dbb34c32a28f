"""The validation compares prints exactly: their characters and whether they end the line
(issue 23; docs/CROSS.md, "Prints"). Before, prints were compared with their line ends and
surrounding spaces stripped, so an MCode output that dropped a print's line end (bench/mutants.py
`mcode-print-newline`) validated equal."""

from __future__ import annotations

from mcc.sim.verify import check_translation

SOURCE = """VA N1=0
PG 100
LB MN
  N1=-7
  PR N1
  PR "done"
  E
PG
"""


def translate(text: str) -> str:
    return check_translation("prints.mxt", "mcode", SOURCE, text)


def test_the_same_prints_validate():
    """The same program with other spacing prints the same: nothing to report."""
    assert translate(SOURCE.replace("  ", "")) == ""


def test_a_dropped_line_end_is_a_difference():
    """`PR ...;` keeps the cursor on the line: the line end is not sent (lexium-mcode.txt L4895,
    L4906), so a print written with `;` where the source has none sends something else."""
    found = translate(SOURCE.replace("PR N1\n", "PR N1;\n"))
    assert "the source prints '-7\\n', the output '-7'" in found


def test_an_added_line_end_is_a_difference():
    source = SOURCE.replace("PR N1\n", "PR N1;\n")
    assert check_translation("prints.mxt", "mcode", source, SOURCE) != ""


def test_a_space_in_the_text_is_a_difference():
    """The host reads the characters sent: a text with a space more is another text (L4895)."""
    found = translate(SOURCE.replace('PR "done"', 'PR "done "'))
    assert "the source prints 'done\\n', the output 'done \\n'" in found
