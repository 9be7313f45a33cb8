"""What git says about the user and the destination, for defaults and messages (git may be missing)."""

from __future__ import annotations

import subprocess


def user_settings() -> dict[str, str]:
    """The user's `user.*` git settings (user.name, user.email), the last value of each (as
    `git config --get` reads it), from one git process; {} without git."""
    try:
        result = subprocess.run(["git", "config", "-z", "--get-regexp", r"^user\."], capture_output=True,
                                text=True, timeout=5, check=False)
    except (OSError, subprocess.SubprocessError):
        return {}
    settings = {}
    for entry in result.stdout.split("\0"):
        key, _, value = entry.partition("\n")
        if key:
            settings[key] = value.strip()
    return settings


def in_work_tree(path) -> bool:
    """Whether `path` is inside a git work tree (`copier update` needs one)."""
    try:
        result = subprocess.run(["git", "-C", str(path), "rev-parse", "--is-inside-work-tree"],
                                capture_output=True, text=True, timeout=5, check=False)
    except (OSError, subprocess.SubprocessError):
        return False
    return result.stdout.strip() == "true"
