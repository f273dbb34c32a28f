"""End-to-end: run the `mcc` command as a user does and check the CLI contract other tools rely on."""

from __future__ import annotations

import json

from conftest import SAMPLES, run_mcc

SAMPLE = str(SAMPLES / "mcode" / "pick_and_place.mxt")
BAD = "MA (100)\nMX 5\nVM=10\nVI=20\n"


def test_version_and_help():
    assert run_mcc("--version").stdout.startswith("mcc ")
    out = run_mcc("--help").stdout
    for word in ("check", "compile", "explain", "Exit codes"):
        assert word in out


def test_check_clean_sample_exits_zero():
    result = run_mcc("check", SAMPLE)
    assert result.returncode == 0, result.stdout
    assert "No problems found" in result.stdout


def test_check_json_shape(tmp_path):
    bad = tmp_path / "bad.mxt"
    bad.write_text(BAD)
    result = run_mcc("check", "--format", "json", str(bad), SAMPLE)
    assert result.returncode == 1
    data = json.loads(result.stdout)
    assert [f["path"] for f in data["files"]] == [str(bad), SAMPLE]
    first = data["files"][0]
    assert first["dialect"] == "mcode"
    diag = first["diagnostics"][0]
    assert set(diag) >= {"code", "severity", "kind", "message", "line", "column", "end_line", "end_column"}
    assert (diag["code"], diag["kind"], diag["line"], diag["column"]) == ("M001", "syntax", 1, 4)
    codes = [d["code"] for d in first["diagnostics"]]
    assert codes == ["M001", "M101", "M113", "M113"]  # VM=10 < default VI, then VI=20 >= VM
    assert data["files"][1]["diagnostics"] == []


def test_check_text_shows_location_line_and_caret(tmp_path):
    bad = tmp_path / "bad.mxt"
    bad.write_text(BAD)
    out = run_mcc("check", str(bad)).stdout
    assert f"{bad}:1:4: error[M001]" in out
    assert "    1 | MA (100)" in out
    assert "^" in out
    assert "Traceback" not in out


def test_dialect_from_extension_and_override(tmp_path):
    odd = tmp_path / "prog.txt"
    odd.write_text("MA 100\n")
    unknown = run_mcc("check", "--format", "json", str(odd))
    assert unknown.returncode == 1
    assert json.loads(unknown.stdout)["files"][0]["diagnostics"][0]["code"] == "G004"
    assert run_mcc("check", "--dialect", "mcode", str(odd)).returncode == 0


def test_usage_errors_exit_two(tmp_path):
    assert run_mcc("check").returncode == 2
    assert run_mcc("check", str(tmp_path / "missing.mxt")).returncode == 2
    assert run_mcc("check", "--format", "xml", SAMPLE).returncode == 2
    result = run_mcc("check", "--profile", "no-such-profile", SAMPLE)
    assert result.returncode == 2 and "unknown profile" in result.stderr


def test_compile_writes_output_listing_and_stats(tmp_path):
    out, lst = tmp_path / "out.mxt", tmp_path / "out.lst"
    result = run_mcc("compile", SAMPLE, "-o", str(out), "--listing", str(lst), "--format", "json")
    assert result.returncode == 0, result.stdout
    entry = json.loads(result.stdout)["files"][0]
    assert entry["output"] == str(out)
    assert entry["stats"]["lines"] == len(out.read_text().splitlines())
    assert entry["stats"]["longest_line"] <= 64
    assert out.read_text().startswith("VA NP=0\n")
    assert "; src 5" in lst.read_text()
    again = run_mcc("compile", str(out), "--format", "json")
    assert json.loads(again.stdout)["files"][0]["text"] == out.read_text()


def test_compile_prints_program_and_refuses_errors(tmp_path):
    printed = run_mcc("compile", SAMPLE)
    assert printed.returncode == 0
    assert "PG 1\n" in printed.stdout and "compiled" in printed.stderr
    bad = tmp_path / "bad.mxt"
    bad.write_text(BAD)
    out = tmp_path / "never.mxt"
    refused = run_mcc("compile", str(bad), "-o", str(out))
    assert refused.returncode == 1 and not out.exists()


def test_compile_to_dash_prints_the_program_and_writes_no_file(tmp_path):
    printed = run_mcc("compile", SAMPLE, "-o", "-", cwd=tmp_path)
    assert printed.returncode == 0 and "PG 1\n" in printed.stdout
    assert list(tmp_path.iterdir()) == []


def test_explain_known_and_unknown_codes():
    page = run_mcc("explain", "M106")
    assert page.returncode == 0
    assert "## Bad" in page.stdout and "## Good" in page.stdout
    assert run_mcc("explain", "Z999").returncode == 2
    assert "M001" in run_mcc("explain", "--list").stdout


def test_binary_and_empty_files_never_traceback(tmp_path):
    junk = tmp_path / "junk.mxt"
    junk.write_bytes(bytes(range(256)) * 4)
    empty = tmp_path / "empty.mxt"
    empty.write_text("")
    result = run_mcc("check", "--format", "json", str(junk), str(empty))
    assert "Traceback" not in result.stdout + result.stderr
    files = json.loads(result.stdout)["files"]
    assert all(d["kind"] != "internal" for f in files for d in f["diagnostics"])
    assert files[1]["diagnostics"] == []
