"""rna-template's releases, recovered from what is committed.

Git tags do not travel with this repository: every clone starts without them. The
version history is kept in docs/CHANGELOG.md instead, by one rule:

    release X.Y.Z is the last commit before the one that added the heading
    `## X.Y.Z` to docs/CHANGELOG.md

Writing a version's heading closes that version: the commit that adds it (changing
nothing but the changelog) comes right after the release. So 0.1.0 is 38f734f, the
commit before the changelog first named it.

`tests/tools/tag-releases` (run by `tests/env`) turns the rule into tags vX.Y.Z, so
Copier finds the releases; the update tests use the rule directly.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

CHANGELOG = "docs/CHANGELOG.md"
VERSION_HEADING = re.compile(r"^## (\d+\.\d+\.\d+)(?: |$)", re.MULTILINE)


class ReleaseError(Exception):
    """A release the changelog names cannot be found in this clone's history."""


def changelog_versions(text: str) -> list[str]:
    """The versions the changelog has headings for, in the changelog's order (newest first)."""
    return VERSION_HEADING.findall(text)


def _git(repo: Path, *args: str, check: bool = True) -> subprocess.CompletedProcess:
    result = subprocess.run(["git", "-C", str(repo), *args], capture_output=True, text=True, check=False)
    if check and result.returncode != 0:
        raise ReleaseError(f"git {' '.join(args)} failed in {repo}: {result.stderr.strip()}")
    return result


def versions(repo: Path) -> list[str]:
    """The released versions, newest first, from the changelog as committed at HEAD."""
    return changelog_versions(_git(repo, "show", f"HEAD:{CHANGELOG}").stdout)


def release_commit(repo: Path, version: str) -> str:
    """The full hash of release `version` (the rule above)."""
    if _git(repo, "rev-parse", "--is-shallow-repository").stdout.strip() == "true":
        raise ReleaseError(f"{repo} is a shallow clone, so its releases cannot be found from the changelog's "
                           "history: run `git fetch --unshallow`")
    pattern = f"^## {re.escape(version)}( |$)"
    added = _git(repo, "log", "--reverse", "--format=%H", "-G", pattern, "HEAD", "--", CHANGELOG).stdout.split()
    if not added:
        raise ReleaseError(f"no commit in {repo} adds the heading '## {version}' to {CHANGELOG}")
    parent = _git(repo, "rev-parse", "-q", "--verify", f"{added[0]}^", check=False)
    if parent.returncode != 0:
        raise ReleaseError(f"the commit that adds '## {version}' to {CHANGELOG} ({added[0][:12]}) has no parent")
    return parent.stdout.strip()


def tag_name(version: str) -> str:
    return f"v{version}"


def following_version(version: str) -> str:
    """The patch release after `version` (1.2.3 -> 1.2.4): what unreleased work is, at the least."""
    major, minor, patch = (int(part) for part in version.split("."))
    return f"{major}.{minor}.{patch + 1}"


def missing_tags(repo: Path) -> list[str]:
    """The tags vX.Y.Z of the changelog's versions that this clone lacks."""
    return [tag_name(version) for version in versions(repo)
            if _git(repo, "rev-parse", "-q", "--verify", f"refs/tags/{tag_name(version)}", check=False).returncode]


def tag_releases(repo: Path) -> list[tuple[str, str]]:
    """Create the missing release tags (lightweight: no git identity needed); returns (tag, commit) pairs."""
    created = []
    for tag in reversed(missing_tags(repo)):  # oldest first
        commit = release_commit(repo, tag.removeprefix("v"))
        _git(repo, "tag", tag, commit)
        created.append((tag, commit))
    return created
