"""Fixtures shared by the tiers: a committed snapshot of the template, and generation helpers.

Tiers (pytest -m):
  (no mark)  fast: extension functions, questions, generated files checked statically
  ros        ROS 2 Kilted from PyPI wheels: colcon builds, nodes run in separate processes
  ros1       ROS 1 from Debian packages: catkin builds, node pairs run against a master
  update     copier update flows and merge-safety scenarios (copier and git only)

Outside CI a ROS tier that cannot set itself up is skipped with the reason; with
CI=true it fails instead, so a green CI run always means every tier ran.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "extensions"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

TEMPLATE_ITEMS = ("copier.yml", "template", "extensions")

# Answers that make a run independent of the machine (git identity, current year).
FIXED_ANSWERS = {
    "maintainer": "Ada Lovelace",
    "maintainer_email": "ada@example.com",
    "copyright_holder": "Ada Lovelace",
    "copyright_year": 2026,
}


def pytest_configure(config):
    config.addinivalue_line("markers", "ros: builds and runs generated ROS 2 packages (PyPI wheels)")
    config.addinivalue_line("markers", "ros1: builds and runs generated ROS 1 packages (Debian)")
    config.addinivalue_line("markers", "update: copier update flows and merge-safety scenarios")


def in_ci() -> bool:
    return os.environ.get("CI", "").lower() == "true"


def unavailable(reason: str):
    """Skip a ROS tier that cannot run here, except in CI, where that is a failure."""
    if in_ci():
        pytest.fail(f"CI=true and this tier cannot run: {reason}", pytrace=False)
    pytest.skip(reason)


def git(*args: str, cwd: Path) -> str:
    env = {**os.environ, "GIT_AUTHOR_NAME": "rna tests", "GIT_AUTHOR_EMAIL": "tests@example.com",
           "GIT_COMMITTER_NAME": "rna tests", "GIT_COMMITTER_EMAIL": "tests@example.com"}
    return subprocess.run(["git", *args], cwd=cwd, env=env, check=True, capture_output=True,
                          text=True).stdout


def snapshot_template(destination: Path, source: Path = ROOT) -> Path:
    """Copy the template (copier.yml, template/, extensions/) into a fresh, committed git repo."""
    destination.mkdir(parents=True, exist_ok=True)
    for item in TEMPLATE_ITEMS:
        path = source / item
        if path.is_dir():
            shutil.copytree(path, destination / item, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            shutil.copy2(path, destination / item)
    git("init", "-q", "-b", "main", cwd=destination)
    git("add", "-A", cwd=destination)
    git("commit", "-q", "-m", "template snapshot", cwd=destination)
    return destination


@pytest.fixture(scope="session")
def template_dir(tmp_path_factory) -> Path:
    """The template as it is in this working tree, committed in a private repo."""
    return snapshot_template(tmp_path_factory.mktemp("template"))


def generate(template: Path, destination: Path, answers: dict | None = None, **kwargs):
    """Run `copier copy` through its API with fixed machine-independent answers."""
    import copier

    data = {**FIXED_ANSWERS, **(answers or {})}
    return copier.run_copy(str(template), str(destination), data=data, defaults=True,
                           unsafe=True, quiet=True, vcs_ref="HEAD", **kwargs)


def add_node(template: Path, package: Path, answers: dict):
    """`copier copy` into an existing package: only the node's answers, the rest from its package.xml."""
    import copier

    copier.run_copy(str(template), str(package), data={"copyright_year": 2026, **answers}, defaults=True,
                    unsafe=True, quiet=True, vcs_ref="HEAD")


@pytest.fixture
def make_package(template_dir, copie, tmp_path):
    """Generate a package from answers with pytest-copie; returns the destination folder.

    `name` names the destination folder, for the answers whose defaults come from it.
    """

    def make(answers: dict | None = None, name: str | None = None) -> Path:
        if name:
            generate(template_dir, tmp_path / name, answers)
            return tmp_path / name
        result = copie.copy(extra_answers={**FIXED_ANSWERS, **(answers or {})}, template_dir=template_dir)
        if result.exit_code != 0:
            raise result.exception
        return result.project_dir

    return make


def answers_of(destination: Path) -> dict:
    return yaml.safe_load((destination / ".copier-answers.yml").read_text())
