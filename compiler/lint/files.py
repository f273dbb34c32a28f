"""Reading and writing source files: kept for callers of the lint package; the policy itself (only
regular files, atomic writes that keep line ends, encoding and permissions) is `mcc.compiler.files`."""

from __future__ import annotations

from mcc.compiler.files import PLAIN, FileError, TextFile, decode, encode, read, write_atomic

__all__ = ["PLAIN", "FileError", "TextFile", "decode", "encode", "read", "write_atomic"]
