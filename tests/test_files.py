"""The file policy (compiler/files.py): only regular files are read, only regular files or new
paths are written, atomically, all-or-nothing, through symlinks, keeping permissions.

Device nodes are never written: the refusal path is tested on a FIFO made with os.mkfifo, and on
/dev/null only when it is the character device it should be, checked untouched afterwards."""

from __future__ import annotations

import errno
import os
import stat
from pathlib import Path

import pytest

from mcc.compiler import files

ROOT_USER = hasattr(os, "geteuid") and os.geteuid() == 0


def leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".tmp"))


def test_a_fifo_is_never_opened_for_reading(tmp_path: Path) -> None:
    fifo = tmp_path / "p.mxt"
    os.mkfifo(fifo)
    with pytest.raises(files.FileError) as caught:
        files.read(str(fifo))  # would block forever if it were opened
    assert "FIFO" in caught.value.reason and caught.value.path == str(fifo)
    assert files.is_special(str(fifo)) and not files.is_special(str(tmp_path))


def test_reading_a_directory_or_a_missing_file_says_why(tmp_path: Path) -> None:
    with pytest.raises(OSError, match="directory"):
        files.read(str(tmp_path))
    with pytest.raises(OSError, match="No such file"):
        files.read(str(tmp_path / "missing.mxt"))


@pytest.mark.parametrize("kind", ["fifo", "directory"])
def test_special_targets_are_refused_and_untouched(tmp_path: Path, kind: str) -> None:
    target = tmp_path / "out.mxt"
    os.mkfifo(target) if kind == "fifo" else target.mkdir()
    before = os.stat(target)
    with pytest.raises(files.FileError, match="FIFO" if kind == "fifo" else "directory"):
        files.write_atomic(str(target), "MA 100\n")
    after = os.stat(target)
    assert (after.st_ino, after.st_mode) == (before.st_ino, before.st_mode)
    assert leftovers(tmp_path) == []


def test_dev_null_is_refused_and_untouched() -> None:
    null = "/dev/null"
    if not stat.S_ISCHR(os.stat(null).st_mode):
        pytest.skip("/dev/null is not a character device on this machine")
    before = os.stat(null)
    with pytest.raises(files.FileError, match="character device"):
        files.write_atomic(null, "MA 100\n")
    after = os.stat(null)
    assert stat.S_ISCHR(after.st_mode) and (after.st_ino, after.st_rdev) == (before.st_ino, before.st_rdev)


def test_symlinks_are_written_through(tmp_path: Path) -> None:
    real = tmp_path / "real.mxt"
    real.write_text("old\n")
    real.chmod(0o640)
    link = tmp_path / "link.mxt"
    link.symlink_to("real.mxt")
    files.write_atomic(str(link), "new\n")
    assert link.is_symlink() and os.readlink(link) == "real.mxt"
    assert real.read_text() == "new\n" and stat.S_IMODE(real.stat().st_mode) == 0o640
    dangling = tmp_path / "dangling.mxt"
    dangling.symlink_to("made.mxt")
    files.write_atomic(str(dangling), "made\n")
    assert dangling.is_symlink() and (tmp_path / "made.mxt").read_text() == "made\n"


def test_permissions_are_kept_and_new_files_get_the_umask(tmp_path: Path) -> None:
    path = tmp_path / "p.mxt"
    path.write_text("x\n")
    path.chmod(0o750)
    files.write_atomic(str(path), "y\n")
    assert stat.S_IMODE(path.stat().st_mode) == 0o750
    umask = os.umask(0o022)
    try:
        files.write_atomic(str(tmp_path / "new.mxt"), "z\n")
    finally:
        os.umask(umask)
    assert stat.S_IMODE((tmp_path / "new.mxt").stat().st_mode) == 0o644


@pytest.mark.parametrize("case, reason", [
    ("missing parent", "does not exist"),
    ("parent is a file", "plain is a regular file, not a directory"),
    ("read-only file", "read-only"),
])
def test_write_errors_say_why_and_leave_nothing(tmp_path: Path, case: str, reason: str) -> None:
    if case == "missing parent":
        target = tmp_path / "no" / "such" / "out.mxt"
    elif case == "parent is a file":
        (tmp_path / "plain").write_text("")
        target = tmp_path / "plain" / "out.mxt"
    else:
        target = tmp_path / "locked.mxt"
        target.write_text("keep\n")
        target.chmod(0o444)
    with pytest.raises(files.FileError, match=reason) as caught:
        files.write_atomic(str(target), "MA 100\n")
    assert caught.value.path == str(target)
    assert leftovers(tmp_path) == []
    if case == "read-only file":
        assert target.read_text() == "keep\n"
    if case == "missing parent":
        assert str(tmp_path / "no") in caught.value.reason and not (tmp_path / "no").exists()


@pytest.mark.skipif(ROOT_USER, reason="root may write anywhere")
def test_no_permission_in_the_directory(tmp_path: Path) -> None:
    folder = tmp_path / "locked"
    folder.mkdir()
    folder.chmod(0o555)
    try:
        with pytest.raises(files.FileError, match="permission"):
            files.write_atomic(str(folder / "out.mxt"), "x\n")
    finally:
        folder.chmod(0o755)


def test_a_full_disk_leaves_no_partial_file(tmp_path: Path, monkeypatch) -> None:
    target = tmp_path / "p.mxt"
    target.write_text("old\n")
    real_fdopen = os.fdopen

    class Full:
        def __init__(self, handle):
            self.handle = handle

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            self.handle.close()

        def write(self, data):
            self.handle.write(data[:3])
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "fdopen", lambda fd, mode: Full(real_fdopen(fd, mode)))
    with pytest.raises(files.FileError, match="no space left"):
        files.write_atomic(str(target), "new text\n")
    assert target.read_text() == "old\n" and leftovers(tmp_path) == []


def test_several_outputs_are_all_or_nothing(tmp_path: Path) -> None:
    first = tmp_path / "out.mxt"
    first.write_text("old\n")
    with pytest.raises(files.FileError):
        files.write_many([(str(first), b"new\n"), (str(tmp_path / "missing" / "out.lst"), b"listing\n")])
    assert first.read_text() == "old\n" and leftovers(tmp_path) == []


def test_same_file_sees_through_links(tmp_path: Path) -> None:
    real = tmp_path / "p.mxt"
    real.write_text("x\n")
    (tmp_path / "l.mxt").symlink_to(real)
    os.link(real, tmp_path / "h.mxt")
    assert files.same_file(str(real), str(tmp_path / "l.mxt")) and files.same_file(str(real), str(tmp_path / "h.mxt"))
    assert not files.same_file(str(real), str(tmp_path / "new.mxt"))
    assert files.same_file(str(tmp_path / "new.mxt"), str(tmp_path / "." / "new.mxt"))
