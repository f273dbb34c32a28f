"""Reading and writing source files without disturbing what the user chose.

mcc works on text with "\\n" line ends (`SourceFile` folds CRLF and lone CR), but a file written
back by `--fix` or `mcc fmt` keeps its line ends (CRLF for files from Windows tools, CR for
device captures), its encoding (UTF-8 with or without BOM, or Latin-1 for old listings) and its
permissions, and it is replaced atomically: a temporary file in the same directory, then
`os.replace`, so an interrupted run never leaves half a program.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

from mcc.compiler.span import normalise_newlines


@dataclass(frozen=True)
class TextFile:
    text: str  # line ends folded to "\n"
    newline: str = "\n"
    encoding: str = "utf-8"
    bom: bool = False


PLAIN = TextFile("")  # how mcc writes a new file: UTF-8, "\n" line ends, no BOM


def decode(data: bytes) -> TextFile:
    bom = data.startswith(b"\xef\xbb\xbf")
    try:
        raw = data.decode("utf-8-sig")
        encoding = "utf-8"
    except UnicodeDecodeError:
        raw = data.decode("latin-1")
        encoding = "latin-1"
    newline = "\r\n" if "\r\n" in raw else "\r" if "\r" in raw else "\n"
    return TextFile(normalise_newlines(raw), newline, encoding, bom)


def read(path: str) -> TextFile:
    with open(path, "rb") as handle:
        return decode(handle.read())


def encode(text: str, like: TextFile) -> bytes:
    if like.newline != "\n":
        text = text.replace("\n", like.newline)
    data = text.encode(like.encoding, errors="replace" if like.encoding == "latin-1" else "strict")
    return (b"\xef\xbb\xbf" + data) if like.bom else data


def write_atomic(path: str, text: str, like: TextFile = PLAIN) -> None:
    """Replace (or create) `path` atomically; an existing file keeps its permissions, a new one
    gets the usual ones (0666 less the umask), not mkstemp's private 0600."""
    target = Path(path)
    data = encode(text, like)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=str(target.parent or Path(".")))
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
        if target.exists():
            shutil.copymode(target, tmp)
        else:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, target)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
