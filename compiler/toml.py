"""TOML loading for the catalogs, profiles and configuration (tomllib, or tomli before 3.11).

The catalogs and profiles mcc ships are read by every process, and parsing them was a fifth of
what a small `mcc check` cost as a whole process (issue 26). `load_data_file` keeps the parsed
table in the user's cache directory as `marshal` data keyed by the file's path, size and time of
change, so a process reads it back in a fraction of the parse; anything wrong with the cache (no
directory, no permission, a damaged entry, a value marshal cannot hold) only means parsing again.

Start-up cost (issue 26): the TOML parser is imported only when a file is parsed (a process whose
data files are all cached never imports it), and an entry is named by a CRC-32 of its key (zlib)
rather than a SHA-256 (hashlib loads OpenSSL: about 5 ms of a small `mcc check`); the entry holds
its whole key, so two keys with the same CRC only mean parsing again.
"""

from __future__ import annotations

import marshal
import os
import sys
import zlib
from pathlib import Path

CACHE_VERSION = 2


def _tomllib():
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover
        import tomli as tomllib
    return tomllib


def __getattr__(name: str):
    """`TOMLDecodeError`, imported with the parser on first use."""
    if name == "TOMLDecodeError":
        return _tomllib().TOMLDecodeError
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def loads(text: str) -> dict:
    return _tomllib().loads(text)


def cache_dir() -> Path | None:
    """Where parsed data files are kept: $MCC_CACHE_DIR, else the platform's user cache directory;
    None when caching is off (MCC_CACHE_DIR set to an empty string)."""
    chosen = os.environ.get("MCC_CACHE_DIR")
    if chosen is not None:
        return Path(chosen) if chosen else None
    if sys.platform == "win32":
        base = os.environ.get("LOCALAPPDATA") or str(Path.home() / "AppData" / "Local")
    else:
        base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "mcc"


def load_data_file(path: Path) -> dict:
    """The table of the TOML file `path`, read back from the cache when the file has not changed."""
    try:
        stat = path.stat()
    except OSError:
        stat = None
    directory = cache_dir()
    entry = None
    if stat is not None and directory is not None:
        key = f"{path.resolve()}|{stat.st_size}|{stat.st_mtime_ns}|{CACHE_VERSION}|{sys.version_info[:2]}"
        entry = directory / f"toml-{path.stem}-{zlib.crc32(key.encode()):08x}.marshal"
        try:
            stored_key, data = marshal.loads(entry.read_bytes())
            if stored_key == key:
                return data
        except (OSError, EOFError, ValueError, TypeError):
            pass
    data = loads(path.read_text(encoding="utf-8"))
    if entry is not None:
        store(entry, key, data)
    return data


def store(entry: Path, key: str, data: dict) -> None:
    """Write one cache entry, its key and table, atomically (a concurrent reader sees the old entry
    or the new one)."""
    try:
        blob = marshal.dumps((key, data))
    except ValueError:  # a value marshal cannot hold (a TOML date): this file is simply not cached
        return
    try:
        entry.parent.mkdir(parents=True, exist_ok=True)
        partial = entry.with_suffix(f".{os.getpid()}.tmp")
        partial.write_bytes(blob)
        os.replace(partial, entry)
    except OSError:
        pass
