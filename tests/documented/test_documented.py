"""The manuals' own results (tests/documented/*.toml), run on `mcc sim` and on the virtual device.

Every case is a reply, position or output a vendor manual prints, with its manual line in the
case's `manual` key (lexium-mcode.txt, parker-x150.md, arcus-pmx-4ex-sa.txt). Each (case, target)
must give the manual's answer, or be listed in exceptions.toml with the reason mcc does not (yet):
"defect: ..." (mcc does something else; removed once fixed) or "the manual cannot be followed
because ...". A listed exception that now passes fails too, so the list cannot go stale.
docs/SIMULATOR.md ("Documented results") presents the same table.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import documented  # noqa: E402

CASES = documented.all_cases()
EXCEPTIONS = documented.exceptions()
RUNS = [(case, target) for case in CASES for target in case.targets]


@pytest.mark.parametrize(("case", "target"), RUNS, ids=[f"{c.id}-{t}" for c, t in RUNS])
def test_the_manual_s_result_is_reproduced_or_a_listed_exception(case, target):
    outcome = documented.run(case, target)
    reason = EXCEPTIONS.get((case.id, target))
    if reason is None:
        assert outcome.ok, (f"{case.id} ({case.manual}) on the {target}: the manual says "
                            f"{_expected(case)}; mcc: {outcome.got}")
    else:
        assert not outcome.ok, (f"{case.id} on the {target} now gives the manual's answer: remove it "
                                f"from tests/documented/exceptions.toml (listed as: {reason})")


def _expected(case) -> str:
    parts = []
    if case.prints is not None:
        parts.append(f"prints {case.prints!r}")
    if case.device is not None:
        parts.append(f"exchange {case.device!r}")
    if case.positions:
        parts.append(f"positions {case.positions!r}")
    if case.outputs:
        parts.append(f"outputs {case.outputs!r}")
    if case.variables:
        parts.append(f"variables {case.variables!r}")
    if case.output_order is not None:
        parts.append(f"output changes {case.output_order!r}")
    if case.duration is not None:
        parts.append(f"duration {case.duration} s ± {case.tolerance} s")
    return ", ".join(parts)


def test_every_case_checks_something_on_each_target():
    for case in CASES:
        assert case.manual.split()[0] in ("lexium-mcode.txt", "parker-x150.md", "arcus-pmx-4ex-sa.txt"), case.id
        assert " L" in case.manual, f"{case.id}: cite the manual line"
        for target in case.targets:
            assert target in documented.TARGETS, case.id
            checks = [case.prints is not None, bool(case.positions), bool(case.outputs), bool(case.variables),
                      case.output_order is not None, case.duration is not None]
            if target == "device":
                checks.append(bool(case.device) and any(reply for _c, reply in case.device))
            else:
                assert case.program.strip(), f"{case.id}: the simulator needs a program"
            assert any(checks), f"{case.id} checks nothing on the {target}"


def test_each_dialect_has_ten_hand_worked_programs_with_a_tight_duration():
    """Issue 22: at least 10 hand-worked programs per dialect, each with its duration worked out
    from the manual's ramp rules and an explicit tolerance of at most 1 ms (not a percentage)."""
    for dialect in documented.DIALECTS:
        cases = documented.load_handworked(dialect)
        assert len(cases) >= 10, f"handworked_{dialect}.toml has {len(cases)} programs"
        for case in cases:
            assert case.handworked and case.program.strip(), case.id
            assert case.duration is not None and 0 < case.tolerance <= 0.001, case.id
            assert case.positions or case.outputs or case.variables or case.prints is not None, case.id


def test_case_ids_are_unique_and_every_exception_names_a_case():
    ids = [case.id for case in CASES]
    assert len(ids) == len(set(ids))
    runs = {(case.id, target) for case, target in RUNS}
    for key, reason in EXCEPTIONS.items():
        assert key in runs, f"exceptions.toml lists {key}, which is no case run on that target"
        assert reason.startswith(("defect: ", "the manual cannot be followed because ")), key


def test_docs_present_the_exceptions_table():
    """docs/SIMULATOR.md shows the table generated from exceptions.toml (written by
    `bench/conformance_report.py --update-docs`); it must be the current one."""
    docs = (Path(__file__).resolve().parents[2] / "docs" / "SIMULATOR.md").read_text()
    table = docs.split("<!-- documented-exceptions:", 1)[1].split("<!-- end documented-exceptions -->", 1)[0]
    rows = [line for line in table.splitlines() if line.startswith("| ") and not line.startswith("| case |")]
    assert len(rows) == len(EXCEPTIONS), "run bench/conformance_report.py --update-docs"
    for (case_id, target), reason in EXCEPTIONS.items():
        assert any(row.startswith(f"| {case_id} | {target} |") and reason.replace("|", "/") in row for row in rows), (
            f"docs/SIMULATOR.md shows an old entry for {case_id} ({target}): run bench/conformance_report.py --update-docs")
