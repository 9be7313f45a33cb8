"""Releases recovered from the changelog (support/releases.py, tests/tools/tag-releases)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from support.generation import ROOT, git
from support.releases import (
    ReleaseError, changelog_versions, following_version, release_commit, tag_releases, versions,
)

TAG_RELEASES = ROOT / "tests" / "tools" / "tag-releases"


def commit(repo: Path, message: str, changelog: str | None = None, code: str | None = None) -> str:
    if changelog is not None:
        (repo / "docs").mkdir(exist_ok=True)
        (repo / "docs" / "CHANGELOG.md").write_text(changelog)
    if code is not None:
        (repo / "copier.yml").write_text(code)
    git("add", "-A", cwd=repo)
    git("commit", "-q", "--allow-empty", "-m", message, cwd=repo)
    return git("rev-parse", "HEAD", cwd=repo).stdout.strip()


@pytest.fixture
def history(tmp_path) -> tuple[Path, dict[str, str]]:
    """A repository released twice the way this one is: the heading comes right after the release."""
    repo = tmp_path / "repo"
    repo.mkdir()
    git("init", "-q", "-b", "main", cwd=repo)
    unreleased, first, second = "## Unreleased\n", "## 1.0.0 (2026-01-01)\n- a\n", "## 1.1.0 (2026-02-01)\n- c\n"
    commits = {"start": commit(repo, "start", f"# Changelog\n\n{unreleased}- a\n", "a")}
    commits["1.0.0"] = commit(repo, "feature b", code="b")
    commit(repo, "Release 1.0.0", f"# Changelog\n\n{first}")
    commits["1.1.0"] = commit(repo, "feature c", f"# Changelog\n\n{unreleased}- c\n\n{first}", "c")
    commit(repo, "Release 1.1.0", f"# Changelog\n\n{second}\n{first}")
    commit(repo, "feature d", f"# Changelog\n\n{unreleased}- d\n\n{second}\n{first}", "d")
    return repo, commits


def run_tool(repo: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(TAG_RELEASES), str(repo)], capture_output=True, text=True,
                          timeout=60, check=False)


def test_changelog_versions_are_the_version_headings():
    text = "## Unreleased\n### 9.9.9\n## 1.10.0 (2026-03-01)\n## 1.2.3\nsee ## 0.0.1\n## 1.0.0rc1\n"
    assert changelog_versions(text) == ["1.10.0", "1.2.3"]


def test_the_following_version_is_the_next_patch_release():
    assert [following_version(v) for v in ("0.2.0", "1.9.9", "0.10.0")] == ["0.2.1", "1.9.10", "0.10.1"]


def test_a_release_is_the_commit_before_its_heading(history):
    repo, commits = history
    assert versions(repo) == ["1.1.0", "1.0.0"]
    assert release_commit(repo, "1.0.0") == commits["1.0.0"]
    assert release_commit(repo, "1.1.0") == commits["1.1.0"]
    with pytest.raises(ReleaseError, match="no commit .* adds the heading '## 2.0.0'"):
        release_commit(repo, "2.0.0")


def test_this_repository_has_its_releases():
    """0.1.0 was tagged at 38f734f before tags stopped travelling; the rule finds the same commit."""
    assert "0.1.0" in versions(ROOT) and "0.2.0" in versions(ROOT)
    assert release_commit(ROOT, "0.1.0") == "38f734fa7da355bbf4453f1ac6b7f8e8f9e21476"


def test_tag_releases_creates_the_missing_tags_once_and_quietly(history):
    repo, commits = history
    git("tag", "v1.0.0", commits["1.0.0"], cwd=repo)  # one tag the clone already has
    first = run_tool(repo)
    assert first.returncode == 0, first.stderr
    assert first.stderr == f"tag-releases: tagged v1.1.0 ({commits['1.1.0'][:7]}) from docs/CHANGELOG.md\n"
    assert git("rev-parse", "v1.1.0^{commit}", cwd=repo).stdout.strip() == commits["1.1.0"]
    assert git("rev-parse", "v1.0.0^{commit}", cwd=repo).stdout.strip() == commits["1.0.0"]
    again = run_tool(repo)
    assert (again.returncode, again.stdout, again.stderr) == (0, "", "")


def test_a_shallow_clone_says_what_to_fetch(history, tmp_path):
    repo, _ = history
    shallow = tmp_path / "shallow"
    subprocess.run(["git", "clone", "-q", "--depth", "1", f"file://{repo}", str(shallow)], check=True)
    with pytest.raises(ReleaseError, match="shallow clone"):
        tag_releases(shallow)
    result = run_tool(shallow)
    assert result.returncode == 1 and "git fetch --unshallow" in result.stderr
    assert git("tag", "-l", cwd=shallow).stdout == ""


def test_the_tags_made_are_listed_in_lines_of_79_columns_each_tag_whole():
    import importlib.machinery
    import importlib.util

    loader = importlib.machinery.SourceFileLoader("tag_releases", str(TAG_RELEASES))
    tool = importlib.util.module_from_spec(importlib.util.spec_from_loader("tag_releases", loader))
    loader.exec_module(tool)
    tags = [f"v0.{minor}.{patch} (74249d5)" for minor in range(4) for patch in range(3)]
    lines = tool.tagged_lines(tags).splitlines()
    assert all(len(line) <= 79 for line in lines) and len(lines) > 1
    assert " ".join(lines).split() == tool.tagged_lines(tags, width=10_000).split()
    assert all(line.rstrip(",").endswith(")") or line.endswith("docs/CHANGELOG.md") for line in lines)
