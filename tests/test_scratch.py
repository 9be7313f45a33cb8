"""The suite's scratch files go to memory only where it is a tmpfs with room that runs programs."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import pytest
from support import scratch


class Found:
    """What os.statvfs says of a file system."""

    def __init__(self, free: int, flags: int = 0):
        self.f_bavail, self.f_frsize, self.f_flag = free // 4096, 4096, flags


@pytest.fixture
def memory(monkeypatch, tmp_path):
    """A stand-in /dev/shm whose free room and mount flags a test sets."""
    found = {"path": tmp_path, "free": 8 * 2**30, "flags": 0}
    real = os.statvfs
    monkeypatch.setattr(scratch.os, "statvfs",
                        lambda path: Found(found["free"], found["flags"]) if Path(path) == tmp_path else real(path))
    return found


def test_memory_with_room_is_used(memory):
    assert scratch.memory_scratch(memory["path"], environ={}) == memory["path"] / f"rna-template-tests-{os.getuid()}"


def test_a_chosen_tmpdir_is_kept(memory):
    assert scratch.memory_scratch(memory["path"], environ={"TMPDIR": "/var/tmp"}) is None


@pytest.mark.parametrize("flags", [os.ST_NOEXEC, os.ST_RDONLY], ids=["noexec", "read-only"])
def test_memory_that_cannot_run_or_keep_files_is_not_used(memory, flags):
    memory["flags"] = flags
    assert scratch.memory_scratch(memory["path"], environ={}) is None


def test_memory_without_room_is_not_used(memory):
    memory["free"] = scratch.ROOM_NEEDED - 1
    assert scratch.memory_scratch(memory["path"], environ={}) is None


def test_no_memory_folder_leaves_the_disk(tmp_path):
    assert scratch.memory_scratch(tmp_path / "missing", environ={}) is None


def test_a_folder_of_that_name_that_is_not_private_is_passed_over(monkeypatch, tmp_path):
    folder = tmp_path / "elsewhere"
    folder.mkdir(mode=0o755)
    monkeypatch.setattr(scratch, "memory_scratch", lambda: folder)
    monkeypatch.setenv("TMPDIR", "")  # recorded, so that what the test sets is undone
    monkeypatch.delenv("TMPDIR")
    assert scratch.use_memory_for_scratch() is None
    link = tmp_path / "link"
    link.symlink_to(tmp_path)
    monkeypatch.setattr(scratch, "memory_scratch", lambda: link)
    assert scratch.use_memory_for_scratch() is None
    assert "TMPDIR" not in os.environ


def test_a_private_folder_becomes_tmpdir(monkeypatch, tmp_path):
    folder = tmp_path / "private"
    monkeypatch.setattr(scratch, "memory_scratch", lambda: folder)
    monkeypatch.setenv("TMPDIR", "")  # recorded, so that what the test sets is undone
    monkeypatch.delenv("TMPDIR")
    monkeypatch.setattr(scratch.tempfile, "tempdir", None)
    assert scratch.use_memory_for_scratch() == folder
    assert os.environ["TMPDIR"] == str(folder)
    assert tempfile.gettempdir() == str(folder)
