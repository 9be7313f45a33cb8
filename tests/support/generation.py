"""Generating packages: the template committed in a scratch repository, and `copier copy` from it.

The one way the tests make a package (`generate`, or `add_node` into a package the
template did not make), with answers that do not depend on the machine. Answer sets
are the YAML files of docs/examples, read with `example()`.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "docs" / "examples"
TEMPLATE_ITEMS = ("copier.yml", "template", "extensions")
ANSWERS_FILE = ".copier-answers.yml"

# Answers that make a run independent of the machine (git identity, current year).
FIXED_ANSWERS = {
    "maintainer": "Ada Lovelace",
    "maintainer_email": "ada@example.com",
    "copyright_holder": "Ada Lovelace",
    "copyright_year": 2026,
}

# The variants the tiers check file by file and lint: an example answers file each.
VARIANTS = {
    "python": "robot_brain_python",
    "cpp": "robot_brain_cpp",
    "mixed": "mixed_languages",
    "lifecycle": "lifecycle_nodes",
    "component": "camera_components",
    "ros1": "robot_ros1",
}

GIT_IDENTITY = {
    "GIT_AUTHOR_NAME": "rna tests", "GIT_AUTHOR_EMAIL": "tests@example.com",
    "GIT_COMMITTER_NAME": "rna tests", "GIT_COMMITTER_EMAIL": "tests@example.com",
}


def subprocess_env() -> dict[str, str]:
    """The environment of every git and copier subprocess: a git identity, no colours."""
    return {**os.environ, **GIT_IDENTITY, "NO_COLOR": "1", "GIT_CONFIG_NOSYSTEM": "1"}


def copier_installed_by_pipx() -> dict[str, str]:
    """The environment of a Copier on the user's PATH (pipx's way), not one that came through
    tests/env, whose messages name that script instead (rna/terminal.py, copier_command)."""
    return {key: value for key, value in os.environ.items() if key != "RNA_TEMPLATE_ENV"}


def copy_counted(instrumentation: str, template: Path, destination: Path, answers: dict,
                 env: dict[str, str] | None = None) -> object:
    """`copier copy` of the template's HEAD in a Python process of its own, after `instrumentation`
    (code that wraps what it counts into a JSON-able `counted`); returns `counted` at exit."""
    script = textwrap.dedent(instrumentation) + textwrap.dedent("""
        import atexit, json, sys
        atexit.register(lambda: print("COUNTED " + json.dumps(counted)))
        from copier._cli import CopierApp
        CopierApp.run(["copier", *sys.argv[1:]])
    """)
    data = destination.parent / "answers.yml"
    data.write_text(json.dumps(answers))
    result = subprocess.run([sys.executable, "-c", script, "copy", "--trust", "--defaults", "--quiet",
                             "--vcs-ref", "HEAD", "--data-file", str(data), str(template), str(destination)],
                            env={**subprocess_env(), **(env or {})}, capture_output=True, text=True, timeout=120,
                            check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    line = next(line for line in result.stdout.splitlines() if line.startswith("COUNTED "))
    return json.loads(line.removeprefix("COUNTED "))


def tree(root: Path) -> dict[str, tuple[bytes, bool]]:
    """Every file under `root` (`.git` aside), by relative path: its bytes and whether it is executable."""
    return {str(path.relative_to(root)): (path.read_bytes(), os.access(path, os.X_OK))
            for path in sorted(root.rglob("*")) if path.is_file() and ".git" not in path.relative_to(root).parts}


def differences(left: dict, right: dict) -> list[str]:
    """The paths where two trees differ (a file only in one, other bytes, another executable bit)."""
    return sorted(name for name in left.keys() | right.keys() if left.get(name) != right.get(name))


def git(*args: str, cwd: Path, check: bool = True) -> subprocess.CompletedProcess:
    result = subprocess.run(["git", *args], cwd=cwd, env=subprocess_env(), capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"git {' '.join(args)} failed in {cwd}:\n{result.stdout}{result.stderr}")
    return result


def example(name: str, **changes) -> dict:
    """The answers of docs/examples/<name>.yml, with `changes` on top."""
    return {**yaml.safe_load((EXAMPLES / f"{name}.yml").read_text()), **changes}


def examples() -> list[str]:
    return sorted(path.stem for path in EXAMPLES.glob("*.yml"))


# Complete answers for unit tests of the model (what Copier's defaults would fill in).
VALID = {**FIXED_ANSWERS, **example("robot_driver")}


def copy_template(destination: Path, source: Path = ROOT) -> Path:
    """Copy the template (copier.yml, template/, extensions/) into `destination`, a plain folder."""
    destination.mkdir(parents=True, exist_ok=True)
    for item in TEMPLATE_ITEMS:
        path = source / item
        if path.is_dir():
            shutil.copytree(path, destination / item, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            shutil.copy2(path, destination / item)
    return destination


def snapshot_template(destination: Path, source: Path = ROOT) -> Path:
    """Copy the template (copier.yml, template/, extensions/) into a fresh, committed git repo."""
    copy_template(destination, source)
    git("init", "-q", "-b", "main", cwd=destination)
    git("add", "-A", cwd=destination)
    git("commit", "-q", "-m", "template snapshot", cwd=destination)
    return destination


def generate(template: Path, destination: Path, answers: dict | None = None, **kwargs):
    """`copier copy` through its API with machine-independent answers; returns Copier's worker."""
    import copier

    data = {**FIXED_ANSWERS, **(answers or {})}
    return copier.run_copy(str(template), str(destination), data=data, defaults=True,
                           unsafe=True, quiet=True, vcs_ref="HEAD", **kwargs)


def add_node(template: Path, package: Path, answers: dict):
    """`copier copy` into an existing package: only the node's answers, the rest from its package.xml."""
    import copier

    return copier.run_copy(str(template), str(package), data={"copyright_year": 2026, **answers},
                           defaults=True, unsafe=True, quiet=True, vcs_ref="HEAD")


def answers_of(destination: Path) -> dict:
    return yaml.safe_load((destination / ANSWERS_FILE).read_text())
