"""A per-user cache of the code that `dataclasses` compiles for mcc's dataclasses (issue 26).

The `dataclasses` module writes each generated method of a class (`__init__`, `__repr__`,
`__eq__`, `__hash__`, the frozen `__setattr__` ...) as Python source and compiles it with `exec`,
in every process. mcc defines about a hundred dataclasses on the path of a small `mcc check`, and
compiling their 400 methods was about a fifth of that whole process (measured with
`bench/bench_startup.py`; docs/PERFORMANCE.md "Start-up").

`install()` gives the `dataclasses` module its own `exec` (a module global, found before the
builtin): for a class defined in an `mcc` module it runs the code object that
`compile(source, "<string>", "exec")` made of that same source text in an earlier process, kept as
`marshal` data per defining module in the cache directory of `compiler/toml.py`
($MCC_CACHE_DIR; `MCC_CACHE_DIR=` turns it off). The text is the key, so a changed class only
compiles its new text; what runs is exactly what the builtin would have compiled and run. Classes
of other packages go to the builtin unchanged. The entries are written when the process ends, and
only for a module that compiled something new; a missing, unwritable or damaged file only means
compiling again (docs/decisions/0020-dataclass-code-cache.md).
"""

from __future__ import annotations

import atexit
import builtins
import marshal
import os
import sys

_VERSION = sys.version  # marshal'd code belongs to one interpreter build
_loaded: dict[str, dict[str, object]] = {}  # module -> {source: code}, read from the cache
_used: dict[str, dict[str, object]] = {}  # module -> {source: code}, run in this process
_changed: set[str] = set()  # modules that compiled a text the cache did not have


_directory_found: list[str | None] = []  # the cache directory, looked up once per process


def _directory() -> str | None:
    if not _directory_found:
        from mcc.compiler.toml import cache_dir

        found = cache_dir()
        _directory_found.append(None if found is None else str(found))
    return _directory_found[0]


def _entry(directory: str, module: str) -> str:
    tag = sys.implementation.cache_tag or "python"
    return os.path.join(directory, f"dataclass-{module}.{tag}.marshal")


def _cached(module: str) -> dict[str, object]:
    found = _loaded.get(module)
    if found is None:
        found = {}
        directory = _directory()
        if directory is not None:
            try:
                with open(_entry(directory, module), "rb") as handle:
                    version, table = marshal.loads(handle.read())
                if version == _VERSION and isinstance(table, dict):
                    found = table
            except (OSError, EOFError, ValueError, TypeError):
                pass
        _loaded[module] = found
    return found


def _exec(source, globals=None, locals=None, /):
    """`exec` for the `dataclasses` module: a cached code object for the source texts of mcc's
    classes, the builtin for everything else."""
    module = globals.get("__name__", "") if isinstance(globals, dict) else ""
    if not isinstance(source, str) or not module.startswith("mcc."):
        return builtins.exec(source, globals, locals)
    code = _cached(module).get(source)
    if code is None:
        # dont_inherit: compiled as the builtin `exec` in dataclasses.py compiles it, without the
        # __future__ flags of this module
        code = compile(source, "<string>", "exec", dont_inherit=True)
        _changed.add(module)
    _used.setdefault(module, {})[source] = code
    return builtins.exec(code, globals, locals)


def _save() -> None:
    """Write the entries of the modules that compiled something new: the texts this process used
    (so a changed class's old text does not stay in the file)."""
    if not _changed:
        return
    directory = _directory()
    if directory is None:
        return
    for module in _changed:
        entry = _entry(directory, module)
        partial = f"{entry}.{os.getpid()}.tmp"
        try:
            os.makedirs(directory, exist_ok=True)
            with open(partial, "wb") as handle:
                handle.write(marshal.dumps((_VERSION, _used[module])))
            os.replace(partial, entry)
        except (OSError, ValueError):
            try:
                os.unlink(partial)
            except OSError:
                pass
    _changed.clear()


def install() -> None:
    """Route the `dataclasses` module's `exec` through the cache (once per process)."""
    import dataclasses

    if getattr(dataclasses, "exec", None) is _exec:
        return
    dataclasses.exec = _exec  # a module global: found before the builtin by `_create_fn`
    atexit.register(_save)
