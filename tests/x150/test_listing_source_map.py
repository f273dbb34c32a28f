"""The X150 listing maps every output line to its own source line.

For a program already in canonical form the backend writes the same lines back, so output line n
must come from source line n and from no other: XE, XD, L, ELSE, NIF, NWHILE, UNTIL and an XT after
an XG each have their own line in the source.
"""

from __future__ import annotations

import pytest

from mcc.compiler import driver

CANONICAL = {
    "loops-and-ifs": """\
1XE3
1XD3
1L5
1IF(IN_1)
1A10
1ELSE
1A20
1NIF
1N
1XG4
1XT
1XE4
1XD4
1A5
1XT
""",
    "while-repeat-empty-if": """\
1XE5
1XD5
1WHILE(VAR1<5)
1VAR1=VAR1+1
1NWHILE
1REPEAT
1A1
1UNTIL(VAR1>9)
1IF(VAR2=1)
1NIF
1XRT
1XT
1XR5
""",
}


@pytest.mark.parametrize("name", sorted(CANONICAL))
def test_each_output_line_maps_to_its_own_source_line(name: str) -> None:
    text = CANONICAL[name]
    result = driver.compile_file(f"{name}.x150", text=text, opt_level="O0")
    assert not result.has_errors, result.diagnostics
    listing = result.listing
    assert listing.text == text  # canonical input: the same lines come back
    for entry in listing.source_map():
        assert [line for _, line in entry["sources"]] == [entry["line"]], entry


def test_xe_without_a_source_xe_maps_to_the_xd() -> None:
    result = driver.compile_file("noxe.x150", text="1XD7\n1A1\n1XT\n", opt_level="O0")
    rows = [(line.text, sorted(s.line for s in line.sources)) for line in result.listing.lines]
    assert rows == [("1XE7", [1]), ("1XD7", [1]), ("1A1", [2]), ("1XT", [3])]
