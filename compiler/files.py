"""What mcc reads and writes, and how: the one file policy every command follows.

Reading: only regular files are read. The kind of a path is checked with `os.stat` before it is
opened, and the file is opened non-blocking and checked again, so a FIFO is never waited on and a
device is never read (`mcc check /dev/zero` would otherwise read forever).

Writing: only regular files or new paths are written. A directory, FIFO, socket or device node as
the output is refused (as root, `-o /dev/null` would otherwise replace `/dev/null` with a regular
file). A symbolic link is written through: its target is replaced and the link stays a link. Every
write is atomic: the text goes to a temporary file in the target's directory, which then replaces
the target with `os.replace`; on any failure the temporary file is removed, so no half-written
file is ever left. A replaced file keeps its permissions (and, when allowed, its owner); a new one
gets the usual 0666 less the umask, not mkstemp's private 0600.

mcc works on text with "\\n" line ends (`SourceFile` folds CRLF and lone CR), but a file written
back by `--fix` or `mcc fmt` keeps its line ends (CRLF for files from Windows tools, CR for
device captures), its encoding (UTF-8 with or without BOM, or Latin-1 for old listings).

Every failure is a `FileError` carrying the path and a reason a user can act on; the commands turn
it into a diagnostic (G002 for reading, G006 for writing), never a traceback.
"""

from __future__ import annotations

import errno
import os
import stat
from dataclasses import dataclass

from mcc.compiler.span import normalise_newlines


class FileError(OSError):
    """A file that cannot be read or written, with the reason in words. An OSError, so that code
    written for `open` keeps working; `strerror` is the reason, `filename` the path."""

    def __init__(self, path: str, reason: str):
        super().__init__(f"{path}: {reason}")
        self.path = path
        self.reason = reason
        self.strerror = reason
        self.filename = path

    def __str__(self) -> str:
        return f"{self.path}: {self.reason}"


@dataclass(frozen=True)
class TextFile:
    text: str  # line ends folded to "\n"
    newline: str = "\n"
    encoding: str = "utf-8"
    bom: bool = False


PLAIN = TextFile("")  # how mcc writes a new file: UTF-8, "\n" line ends, no BOM


# kinds of files ------------------------------------------------------------------------------------

def kind_of(mode: int) -> str:
    """What a non-regular file is, in words ("a FIFO (named pipe)")."""
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISCHR(mode):
        return "a character device"
    if stat.S_ISBLK(mode):
        return "a block device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "a regular file" if stat.S_ISREG(mode) else "not a regular file"


def reason_of(exc: OSError) -> str:
    """The system's reason for an OSError, without the path (the message names it already)."""
    return (exc.strerror or str(exc)).rstrip(".")


def unreadable(path: str) -> str | None:
    """None when `path` is a regular file mcc may read (symlinks followed); else why not."""
    try:
        info = os.stat(path)
    except OSError as exc:
        return reason_of(exc)
    if stat.S_ISREG(info.st_mode):
        return None
    return f"it is {kind_of(info.st_mode)}, not a regular file; mcc reads only regular files"


def is_special(path: str) -> bool:
    """A path that exists but is neither a regular file nor a directory (FIFO, device, socket)."""
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return False
    return not (stat.S_ISREG(mode) or stat.S_ISDIR(mode))


# reading -------------------------------------------------------------------------------------------

def read_bytes(path: str) -> bytes:
    """The bytes of a regular file; FileError for anything else (checked before opening)."""
    problem = unreadable(path)
    if problem:
        raise FileError(path, problem)
    try:
        # O_NONBLOCK: should the path become a FIFO between the check and the open, the open
        # does not wait for a writer; fstat below then refuses it.
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as exc:
        raise FileError(path, reason_of(exc)) from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise FileError(path, f"it is {kind_of(info.st_mode)}, not a regular file; mcc reads only regular files")
        chunks = []
        while chunk := os.read(fd, 1 << 20):
            chunks.append(chunk)
        return b"".join(chunks)
    except OSError as exc:
        raise FileError(path, reason_of(exc)) from None
    finally:
        os.close(fd)


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
    return decode(read_bytes(path))


# writing -------------------------------------------------------------------------------------------

def encode(text: str, like: TextFile) -> bytes:
    if like.newline != "\n":
        text = text.replace("\n", like.newline)
    data = text.encode(like.encoding, errors="replace" if like.encoding == "latin-1" else "strict")
    return (b"\xef\xbb\xbf" + data) if like.bom else data


def write_target(path: str) -> str:
    """The file a write to `path` replaces: `path` itself, or the final target of a symlink."""
    return os.path.realpath(path) if os.path.islink(path) else path


def unwritable(path: str) -> str | None:
    """None when mcc may write `path` (a regular file, a symlink to one, or a new name in an
    existing directory); else why not, in words."""
    target = write_target(path)
    try:
        info = os.stat(target)
    except FileNotFoundError:
        info = None
    except NotADirectoryError:
        info = None  # reported below, for the parent
    except OSError as exc:
        return reason_of(exc)
    if info is not None:
        if not stat.S_ISREG(info.st_mode):
            return f"it is {kind_of(info.st_mode)}; mcc writes only regular files or new paths"
        if not info.st_mode & 0o222 or not os.access(target, os.W_OK):
            return "the file is read-only (no write permission)"
    parent = os.path.dirname(os.path.abspath(target))
    try:
        parent_info = os.stat(parent)
    except FileNotFoundError:
        return f"the directory {missing_part(parent)} does not exist"
    except NotADirectoryError:
        return f"{file_in(parent)} is a file, not a directory"
    except OSError as exc:
        return f"cannot use the directory {parent}: {reason_of(exc)}"
    if not stat.S_ISDIR(parent_info.st_mode):
        return f"{parent} is {kind_of(parent_info.st_mode)}, not a directory"
    if not os.access(parent, os.W_OK | os.X_OK):
        return f"no permission to create files in {parent}"
    return None


def missing_part(folder: str) -> str:
    """The first directory of `folder` that does not exist (the one the user has to create)."""
    probe = folder
    while not os.path.exists(os.path.dirname(probe)) and os.path.dirname(probe) != probe:
        probe = os.path.dirname(probe)
    return probe


def file_in(folder: str) -> str:
    """The part of `folder` that exists but is not a directory."""
    probe = folder
    while probe != os.path.dirname(probe):
        if os.path.exists(probe) and not os.path.isdir(probe):
            return probe
        probe = os.path.dirname(probe)
    return folder


def write_many(items: list[tuple[str, bytes]]) -> None:
    """Write several files all-or-nothing as far as the system allows: every target is checked,
    every temporary file written, and only then are they moved into place. FileError on failure,
    with nothing of the failed write left behind."""
    staged: list[tuple[str, str]] = []  # (temporary file, target)
    try:
        for path, data in items:
            problem = unwritable(path)
            if problem:
                raise FileError(path, problem)
            staged.append((stage(path, data), write_target(path)))
        for tmp, target in staged:
            try:
                os.replace(tmp, target)
            except OSError as exc:
                raise FileError(target, reason_of(exc)) from None
    finally:
        for tmp, _ in staged:
            if os.path.lexists(tmp):
                os.unlink(tmp)


def stage(path: str, data: bytes) -> str:
    """Write `data` to a temporary file next to the target of `path`, with the target's
    permissions; returns the temporary file's name."""
    target = write_target(path)
    folder = os.path.dirname(os.path.abspath(target))
    name = os.path.basename(target)
    try:
        import tempfile  # only when writing: a check never loads it (start-up, issue 26)

        fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=folder)
    except OSError as exc:
        raise FileError(path, f"cannot create a file in {folder}: {reason_of(exc)}") from None
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
        copy_mode(target, tmp)
    except OSError as exc:
        os.unlink(tmp)
        reason = "no space left on the device" if exc.errno == errno.ENOSPC else reason_of(exc)
        raise FileError(path, reason) from None
    except BaseException:
        os.unlink(tmp)
        raise
    return tmp


def copy_mode(target: str, tmp: str) -> None:
    try:
        info = os.stat(target)
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        return
    os.chmod(tmp, stat.S_IMODE(info.st_mode))
    if hasattr(os, "chown"):
        try:
            os.chown(tmp, info.st_uid, info.st_gid)
        except OSError:
            pass  # only root may give a file away; the permissions are kept all the same


def write_atomic(path: str, text: str, like: TextFile = PLAIN) -> None:
    """Replace (or create) `path` atomically with `text`, encoded like `like`."""
    write_many([(path, encode(text, like))])


def same_file(a: str, b: str) -> bool:
    """Whether two paths name the same file (links and hard links included)."""
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.abspath(write_target(a)) == os.path.abspath(write_target(b))
