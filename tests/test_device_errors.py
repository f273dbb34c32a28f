"""docs/DEVICE-ERRORS.md: every device error of the manuals (kept as data in tests/data/) has a row,
and every mcc code a row names is registered."""

from __future__ import annotations

import re

from conftest import ROOT
from mcc.compiler.codes import registry

TABLE = ROOT / "docs" / "DEVICE-ERRORS.md"
DATA = ROOT / "tests" / "data" / "device_errors.txt"
CODE = re.compile(r"\b[AGMX]\d{3}\b")


def rows() -> dict[str, list[str]]:
    found = {}
    for line in TABLE.read_text(encoding="utf-8").splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 4 and cells[0].startswith("`") and ":" in cells[0]:
            found[cells[0].strip("`")] = cells
    return found


def expected_ids() -> list[str]:
    lines = DATA.read_text(encoding="utf-8").splitlines()
    return [line.split(" ", 1)[0] for line in lines if line.strip() and not line.startswith("#")]


def test_every_device_error_has_a_row() -> None:
    table = rows()
    missing = [ident for ident in expected_ids() if ident not in table]
    assert not missing, f"no row in docs/DEVICE-ERRORS.md for {missing}"
    assert len(expected_ids()) == len(set(expected_ids())) > 100


def test_every_row_is_a_known_device_error() -> None:
    extra = set(rows()) - set(expected_ids())
    assert not extra, f"rows for errors not in tests/data/device_errors.txt: {sorted(extra)}"


def test_every_code_named_is_registered() -> None:
    known = {info.code for info in registry()}
    named = {code for cells in rows().values() for code in CODE.findall(cells[2] + " " + cells[3])}
    assert named and not named - known, sorted(named - known)


def test_a_row_either_names_a_code_or_says_why_not() -> None:
    for ident, (_, _, codes, why) in rows().items():
        assert CODE.search(codes) or (codes == "—" and why), ident
