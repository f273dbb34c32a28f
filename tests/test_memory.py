"""Program memory is reported by `mcc check` (so by lint and the editor), from the cost model of
`mcc compile`: Arcus assembly lines against the profile's budget and the Windows software's limit,
X150 sequence bytes against the sequence store."""

from __future__ import annotations

import json

from conftest import run_mcc
from mcc.compiler import driver, profiles


def arcus_program(loops: int) -> str:
    body = ["V1=0"]
    for _ in range(loops):  # 13 assembly lines per loop under the default h-estimate model
        body += ["WHILE V1<10", "IF DI1=1", "X1000Y2000", "ELSE", "V2=V2+1", "ENDIF", "V1=V1+1", "ENDWHILE"]
    return "\n".join(body + ["END"]) + "\n"


def codes(result) -> list[str]:
    return [d.code for d in result.diagnostics]


def test_check_reports_the_same_count_as_compile() -> None:
    text = arcus_program(20)
    checked = driver.check_file("p.prg", text=text)
    compiled = driver.compile_file("p.prg", text=text)
    assert checked.analysis.memory["used"] == compiled.listing.stats["asm_lines"] > 0
    assert checked.analysis.memory["budget"] == 3230


def test_near_the_windows_software_limit_is_a_warning_in_check() -> None:
    used = driver.check_file("p.prg", text=arcus_program(130)).analysis.memory["used"]
    assert 0.9 * 1785 < used <= 3230  # between the two limits
    result = driver.check_file("p.prg", text=arcus_program(130))
    assert codes(result) == ["A240"] and not result.has_errors
    assert "1785" in result.diagnostics[0].message


def test_the_windows_limit_can_be_switched_off(tmp_path) -> None:
    path = tmp_path / "host.toml"
    path.write_text('extends = "pmx-4ex-sa"\nname = "host"\n[arcus.cost]\ngui_limit = 0\n', encoding="utf-8")
    result = driver.check_file("p.prg", profile=profiles.load(str(path)), text=arcus_program(130))
    assert codes(result) == []


def test_over_the_budget_is_an_error_in_check_and_once_in_compile() -> None:
    text = arcus_program(260)
    assert codes(driver.check_file("p.prg", text=text)) == ["A201"]
    assert codes(driver.compile_file("p.prg", text=text)) == ["A201"]


def test_the_gui_profile_has_1785_as_its_budget() -> None:
    result = driver.check_file("p.prg", profile=profiles.load("pmx-4ex-sa-gui"), text=arcus_program(140))
    assert codes(result) == ["A201"]


def test_x150_sequence_bytes_in_check_json() -> None:
    text = "1XE3\n1XD3\n1A10\n1G\n1XT\n"
    result = driver.check_file("p.x150", text=text)
    compiled = driver.compile_file("p.x150", text=text)
    # check counts the program as written; compile counts what it writes, which may add the mode
    # commands a sequence needs at its start (MN, MPI): the same model, one byte per character
    assert result.analysis.memory["used"] == len("1A10\n1G\n1XT\n")
    assert compiled.listing.stats["sequence_bytes"] >= result.analysis.memory["used"]
    assert result.to_json()["memory"]["budget"] == 8000


def test_check_json_shows_memory(tmp_path) -> None:
    path = tmp_path / "p.prg"
    path.write_text(arcus_program(2), encoding="utf-8")
    out = json.loads(run_mcc("check", "--format", "json", str(path)).stdout)
    memory = out["files"][0]["memory"]
    assert memory["unit"] == "assembly lines" and memory["used"] > 0 and memory["budget"] == 3230


def x150_sequences(count: int, lines: int) -> str:
    out = []
    for n in range(1, count + 1):
        out += [f"1XE{n}", f"1XD{n}"] + ["1VAR1=VAR1+12345"] * lines + ["1XT"]
    return "\n".join(out) + "\n"


def test_x150_near_the_sequence_store_is_a_warning(tmp_path) -> None:
    near = driver.check_file("p.x150", text=x150_sequences(3, 150))
    assert 0.9 * 8000 < near.analysis.memory["used"] <= 8000
    assert [c for c in codes(near) if c in ("X123", "X141")] == ["X141"] and not near.has_errors
    path = tmp_path / "roomy.toml"
    path.write_text('extends = "x150-pdhx"\nname = "roomy"\n[x150]\nstore_warn_ratio = 0.99\n', encoding="utf-8")
    relaxed = driver.check_file("p.x150", profile=profiles.load(str(path)), text=x150_sequences(3, 150))
    assert "X141" not in codes(relaxed)
    over = driver.check_file("p.x150", text=x150_sequences(4, 150))
    assert "X123" in codes(over) and "X141" not in codes(over)


def test_arcus_memory_in_check_can_be_left_to_compile(tmp_path) -> None:
    path = tmp_path / "fast.toml"
    path.write_text('extends = "pmx-4ex-sa"\nname = "fast"\n[arcus.cost]\nin_check = false\n', encoding="utf-8")
    profile = profiles.load(str(path))
    text = arcus_program(260)
    checked = driver.check_file("p.prg", profile=profile, text=text)
    assert codes(checked) == [] and checked.analysis.memory == {}
    assert codes(driver.compile_file("p.prg", profile=profile, text=text)) == ["A201"]
