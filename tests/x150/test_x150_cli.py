"""End to end: the mcc command on X150 files, as a user runs it."""

from __future__ import annotations

import json
import sys
import time

from conftest import ROOT, SAMPLES, run_mcc

SAMPLE = str(SAMPLES / "x150" / "03_part_sorter.x150")


def test_check_sample_and_json(tmp_path):
    result = run_mcc("check", "--format", "json", SAMPLE)
    assert result.returncode == 0, result.stdout
    data = json.loads(result.stdout)["files"][0]
    assert data["dialect"] == "x150"
    assert all(d["severity"] != "error" for d in data["diagnostics"])


def test_check_reports_syntax_and_semantic_errors(tmp_path):
    bad = tmp_path / "bad.x150"
    bad.write_text('1XE1\n1XD1\n1C\nDTXT"OPEN\n1XT\n')
    result = run_mcc("check", "--format", "json", str(bad))
    assert result.returncode == 1
    found = [(d["code"], d["kind"], d["line"]) for d in json.loads(result.stdout)["files"][0]["diagnostics"]]
    assert ("X113", "semantic", 3) in found and ("X001", "syntax", 4) in found


def test_profile_option(tmp_path):
    prog = tmp_path / "servo.x150"
    prog.write_text("20CPG50\n")
    assert run_mcc("check", str(prog)).returncode == 1
    assert run_mcc("check", "--profile", "x150e-bdhxe", str(prog)).returncode == 0


def test_compile_writes_the_program_and_the_listing(tmp_path):
    out, lst = tmp_path / "out.x150", tmp_path / "out.lst"
    result = run_mcc("compile", SAMPLE, "-o", str(out), "--listing", str(lst), "--format", "json")
    assert result.returncode == 0, result.stdout
    entry = json.loads(result.stdout)["files"][0]
    assert entry["stats"]["sequence_budget"] == 8000 and entry["stats"]["sequences"] == 3
    assert "3XE31\n3XD31\n" in out.read_text()
    assert "; src" in lst.read_text() and "bytes of sequence memory" in lst.read_text()
    again = run_mcc("compile", str(out), "--format", "json")
    assert json.loads(again.stdout)["files"][0]["text"] == out.read_text()


def test_explain_an_x150_code():
    page = run_mcc("explain", "X112")
    assert page.returncode == 0 and "## Bad" in page.stdout and "NIF" in page.stdout


def test_ten_thousand_commands_check_quickly():
    sys.path.insert(0, str(ROOT / "bench"))
    import bench_x150
    from mcc.compiler import profiles
    from mcc.compiler.span import SourceFile
    from mcc.compiler.x150 import frontend

    text = bench_x150.generate(10_000)
    profile = profiles.load("x150-pdhx")
    frontend.analyze(SourceFile("warm.x150", text[:500]), profile)
    start = time.perf_counter()
    analysis = frontend.analyze(SourceFile("big.x150", text), profile)
    elapsed = time.perf_counter() - start
    assert len(list(analysis.tree.commands())) >= 10_000
    assert elapsed < 5.0, f"10,000 commands took {elapsed:.2f} s"  # ~0.5 s on a quiet machine
