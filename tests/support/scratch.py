"""Where the suite writes its scratch files: in memory when the machine has room for them.

The suite writes tens of thousands of small files (packages, Copier's clones of the
template, colcon and catkin builds). On a virtual machine's disk each costs about
0.7 ms of system time: a run of the whole suite spent 5.6 of its 20 CPU-minutes in the
kernel on disk, 2.6 to 3 with its scratch in /dev/shm (docs/pages/reference/performance.md).
A run writes about 300 MB there; conftest.py removes them when the run passes.
"""

from __future__ import annotations

import os
import stat
import sys
import tempfile
from pathlib import Path

MEMORY = Path("/dev/shm")
ROOM_NEEDED = 4 * 2**30  # bytes: a run's 300 MB, and pip unpacking ROS 2's wheels (300 MB a distro), many times over


def memory_scratch(memory: Path = MEMORY, environ: os._Environ | dict = os.environ) -> Path | None:
    """The folder in memory to use for scratch files, or None to leave TMPDIR as it is.

    None when TMPDIR is already chosen, or when memory lacks the room or does not let
    programs run from it (colcon and catkin run what they build).
    """
    if environ.get("TMPDIR") or not sys.platform.startswith("linux"):
        return None
    try:
        found = os.statvfs(memory)
    except OSError:
        return None
    if found.f_flag & os.ST_NOEXEC or found.f_flag & os.ST_RDONLY or found.f_bavail * found.f_frsize < ROOM_NEEDED:
        return None
    return memory / folder_in_memory().name


def folder_in_memory(uid: int | None = None) -> Path:
    """The one folder in memory the suite's scratch files go to (per user)."""
    return MEMORY / f"rna-template-tests-{os.getuid() if uid is None else uid}"


def use_memory_for_scratch() -> Path | None:
    """Point TMPDIR (this process's and every one it starts) to memory when it has room."""
    folder = memory_scratch()
    if folder is None:
        return None
    try:
        folder.mkdir(mode=0o700, exist_ok=True)
        found = folder.lstat()
    except OSError:
        return None
    if not stat.S_ISDIR(found.st_mode) or found.st_uid != os.getuid() or found.st_mode & 0o077:
        return None  # not a private folder of this user's (a link, someone else's): stay on disk
    os.environ["TMPDIR"] = str(folder)
    tempfile.tempdir = None  # read TMPDIR again
    return folder
