"""The cache of parsed data files (compiler/toml.load_data_file): the same table as parsing, a
changed file is read again, and a damaged or unusable cache only means parsing again."""

from __future__ import annotations

import os

from mcc.compiler import toml


def test_the_cached_table_is_the_parsed_one_and_follows_changes(tmp_path, monkeypatch):
    monkeypatch.setenv("MCC_CACHE_DIR", str(tmp_path / "cache"))
    data = tmp_path / "catalog.toml"
    data.write_text('[[entry]]\nname = "VM"\nrange = [1, 5000000]\n', encoding="utf-8")
    first = toml.load_data_file(data)
    assert first == {"entry": [{"name": "VM", "range": [1, 5000000]}]}
    assert len(list((tmp_path / "cache").iterdir())) == 1
    assert toml.load_data_file(data) == first  # read back from the cache
    data.write_text('[[entry]]\nname = "VI"\n', encoding="utf-8")
    os.utime(data, ns=(data.stat().st_atime_ns, data.stat().st_mtime_ns + 10_000_000))
    assert toml.load_data_file(data) == {"entry": [{"name": "VI"}]}


def test_a_damaged_cache_entry_is_parsed_again(tmp_path, monkeypatch):
    monkeypatch.setenv("MCC_CACHE_DIR", str(tmp_path / "cache"))
    data = tmp_path / "codes.toml"
    data.write_text('code = "M101"\n', encoding="utf-8")
    toml.load_data_file(data)
    [entry] = (tmp_path / "cache").iterdir()
    entry.write_bytes(b"\x00not marshal")
    assert toml.load_data_file(data) == {"code": "M101"}


def test_an_unwritable_or_disabled_cache_still_reads_the_file(tmp_path, monkeypatch):
    data = tmp_path / "profile.toml"
    data.write_text("a = 1\nwhen = 2026-11-27\n", encoding="utf-8")  # a date: marshal cannot hold it
    blocker = tmp_path / "file"
    blocker.write_text("", encoding="utf-8")
    monkeypatch.setenv("MCC_CACHE_DIR", str(blocker / "cache"))  # a directory under a file
    assert toml.load_data_file(data)["a"] == 1
    monkeypatch.setenv("MCC_CACHE_DIR", "")
    assert toml.cache_dir() is None
    assert toml.load_data_file(data)["a"] == 1
