"""The cache of the code `dataclasses` compiles for mcc's classes (compiler/dataclass_code.py): a
class built from the cache is the class the builtin `exec` builds, a second process reads the
entry instead of compiling, and a damaged or foreign entry only means compiling again."""

from __future__ import annotations

import dataclasses
import subprocess
import sys
import types

import pytest

from mcc.compiler import dataclass_code

SOURCE = """
from dataclasses import dataclass, field

@dataclass
class Point:
    x: int
    y: int = 0
    tags: list = field(default_factory=list)

@dataclass(frozen=True)
class Frozen:
    name: str

@dataclass(eq=True, unsafe_hash=True)
class Hashed:
    a: int
    b: str = "b"
"""


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """A fresh, empty cache in tmp_path for this test."""
    monkeypatch.setattr(dataclass_code, "_directory_found", [str(tmp_path)])
    monkeypatch.setattr(dataclass_code, "_loaded", {})
    monkeypatch.setattr(dataclass_code, "_used", {})
    monkeypatch.setattr(dataclass_code, "_changed", set())
    return tmp_path


def define(name: str, monkeypatch) -> types.ModuleType:
    module = types.ModuleType(name)
    monkeypatch.setitem(sys.modules, name, module)
    exec(compile(SOURCE, name, "exec"), module.__dict__)
    return module


def behaviour(module: types.ModuleType) -> list:
    p, q = module.Point(1), module.Point(1, 0, [])
    frozen = module.Frozen("a")
    with pytest.raises(dataclasses.FrozenInstanceError):
        frozen.name = "b"
    return [repr(p), p == q, p != module.Point(2), repr(frozen), hash(module.Hashed(1)) == hash(module.Hashed(1)),
            module.Hashed(1) == module.Hashed(1, "b"), [f.name for f in dataclasses.fields(module.Point)]]


def test_classes_from_the_cache_behave_as_compiled_ones(cache, monkeypatch):
    assert dataclasses.exec is dataclass_code._exec  # installed by importing mcc.compiler
    first = define("mcc.cachetest", monkeypatch)
    assert dataclass_code._changed == {"mcc.cachetest"}
    dataclass_code._save()
    [entry] = cache.iterdir()
    assert entry.name.startswith("dataclass-mcc.cachetest.")
    monkeypatch.setattr(dataclass_code, "_loaded", {})  # as a new process: read the entry back
    second = define("mcc.cachetest", monkeypatch)
    assert not dataclass_code._changed  # nothing compiled
    plain = define("elsewhere.cachetest", monkeypatch)  # not an mcc module: the builtin exec
    assert "elsewhere.cachetest" not in dataclass_code._used
    assert behaviour(first) == behaviour(second) == behaviour(plain)


def test_a_damaged_entry_is_compiled_again(cache, monkeypatch):
    define("mcc.cachetest", monkeypatch)
    dataclass_code._save()
    [entry] = cache.iterdir()
    entry.write_bytes(b"\x00not marshal")
    monkeypatch.setattr(dataclass_code, "_loaded", {})
    module = define("mcc.cachetest", monkeypatch)
    assert dataclass_code._changed == {"mcc.cachetest"}
    assert module.Point(3).x == 3


def test_a_second_process_reads_the_cache(tmp_path):
    """The whole path: the first `mcc explain` writes the entries, the second compiles nothing."""
    probe = ("import sys\nfrom mcc.compiler import dataclass_code, codes\ncodes.registry()\n"
             "print(sorted(dataclass_code._changed))")
    env = {"MCC_CACHE_DIR": str(tmp_path), "PATH": "/usr/bin:/bin"}
    first = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, check=True)
    assert "mcc.compiler.codes" in first.stdout
    assert any(p.name.startswith("dataclass-mcc.compiler.codes.") for p in tmp_path.iterdir())
    second = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, check=True)
    assert second.stdout.strip() == "[]"
