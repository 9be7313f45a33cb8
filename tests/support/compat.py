"""Other Pythons, and the newest releases of the libraries extensions/patches/ changes, each
in a virtual environment of its own, for the compat tier (tests/test_compat.py).

Users install the newest Copier (and with it the newest Jinja, questionary and
prompt_toolkit) into whatever Python their system has: Ubuntu 24.04 brings 3.12, Debian 13
3.13. The suite's own environment (tests/env) is Python 3.11 with the pins of
tests/requirements.txt; here the same pins go into 3.12 and 3.13, and the newest releases
of the libraries the patches change, not the pins, into 3.11. The environments are kept in
the suite's cache folder (RNA_TEMPLATE_CACHE, as the ROS 2 ones), rebuilt when the
requirements change; the newest releases are asked for at every run. Standard library
only: it runs before any of it exists.
"""

from __future__ import annotations

import contextlib
import fcntl
import glob
import hashlib
import os
import re
import shutil
import subprocess
from collections.abc import Iterator
from pathlib import Path

from .generation import ROOT
from .ros2 import default_cache_root

REQUIREMENTS = ROOT / "tests" / "requirements.txt"
PYTHONS = ("3.12", "3.13")
# The libraries whose behaviour extensions/patches/ changes (questionary's is through prompt_toolkit).
NEWEST = ("copier", "copier-template-extensions", "jinja2", "questionary", "prompt-toolkit")
FAST_TIER = "not ros and not ros1 and not update and not browser and not compat"
# Variables of the suite's own run (its xdist worker, its test) that a run started from it must not see.
_OUTER = ("PYTEST_XDIST_WORKER", "PYTEST_XDIST_WORKER_COUNT", "PYTEST_XDIST_TESTRUNUID", "PYTEST_CURRENT_TEST",
          "PYTEST_ADDOPTS", "VIRTUAL_ENV")


class Unavailable(Exception):
    """This machine cannot set the environment up: the reason, and how to get what is missing."""


def find_python(version: str) -> Path | None:
    """An interpreter of `version` (e.g. "3.12") that runs: the newest pyenv one, or python3.12 on
    PATH (pyenv's shim of that name runs only where that version is selected)."""
    pyenv = Path(os.environ.get("PYENV_ROOT") or Path.home() / ".pyenv")
    installed = sorted(glob.glob(str(pyenv / "versions" / f"{version}.*" / "bin" / f"python{version}")),
                       key=lambda path: [int(part) for part in re.findall(r"\d+", Path(path).parents[1].name)])
    for candidate in [*reversed(installed), shutil.which(f"python{version}")]:
        if candidate and _runs_as(Path(candidate), version):
            return Path(candidate)
    return None


def _runs_as(interpreter: Path, version: str) -> bool:
    try:
        result = subprocess.run([str(interpreter), "-c", "import sys, venv; print('%d.%d' % sys.version_info[:2])"],
                                capture_output=True, text=True, timeout=60, check=False)
    except OSError:
        return False
    return result.returncode == 0 and result.stdout.strip() == version


def python(version: str) -> Path:
    """An interpreter of `version`, installed from Debian's or Ubuntu's packages when it is not
    here and the system has them (Debian 13 has 3.13, Ubuntu 24.04 3.12, Debian 12 neither)."""
    found = find_python(version)
    if found is None and os.geteuid() == 0 and shutil.which("apt-get"):
        packages = [f"python{version}", f"python{version}-venv"]
        policy = subprocess.run(["apt-cache", "policy", *packages], capture_output=True, text=True, check=False)
        if policy.stdout.count("Candidate:") == 2 and "Candidate: (none)" not in policy.stdout:
            subprocess.run(["apt-get", "install", "-y", "-qq", *packages], env={**os.environ,
                           "DEBIAN_FRONTEND": "noninteractive"}, capture_output=True, text=True, check=False)
            found = find_python(version)
    if found is None:
        raise Unavailable(f"no Python {version}: neither python{version} on PATH nor a pyenv version {version}.x, "
                          f"and this system's packages have no python{version} (Debian 13 and Ubuntu 24.04 have "
                          f"one of them; elsewhere `pyenv install {version}`)")
    return found


def environment(interpreter: Path, newest: bool = False) -> Path:
    """A virtual environment of `interpreter` with tests/requirements.txt installed; with
    `newest`, the newest releases of the libraries the patches change (NEWEST) instead of the
    pins (and the newest of what they need), asked for again at every call."""
    requirements = REQUIREMENTS.read_text()
    if newest:
        requirements = "".join(line for line in requirements.splitlines(keepends=True)
                               if _requirement_name(line) not in NEWEST)
    digest = hashlib.sha256(f"{requirements}\0{os.path.realpath(interpreter)}\0{newest}".encode()).hexdigest()[:16]
    root = default_cache_root()
    root.mkdir(parents=True, exist_ok=True)
    venv = root / f"compat-{'newest' if newest else Path(interpreter).name}-{digest}"
    stamp = venv / ".rna-template-ready"
    with _exclusive(root / f"{venv.name}.lock"):
        if not stamp.is_file():
            _run([str(interpreter), "-m", "venv", "--clear", str(venv)], "making the environment")
            pinned = venv / "requirements.txt"
            pinned.write_text(requirements)
            _run([*_pip(venv), "install", "-r", str(pinned)], "installing tests/requirements.txt")
            stamp.write_text(requirements)
        if newest:
            _run([*_pip(venv), "install", "--upgrade", "--upgrade-strategy", "eager", *NEWEST],
                 f"installing the newest {', '.join(NEWEST)}")
    return venv


def versions(venv: Path, names: tuple[str, ...] = NEWEST) -> dict[str, str]:
    script = "import importlib.metadata as m, sys; print(' '.join(m.version(n) for n in sys.argv[1:]))"
    result = subprocess.run([str(venv / "bin" / "python"), "-c", script, *names], capture_output=True, text=True,
                            check=True)
    return dict(zip(names, result.stdout.split(), strict=True))


def env_of(venv: Path, **extra: str) -> dict[str, str]:
    """The environment of a run in `venv`: its commands first on PATH, nothing of the suite's own run."""
    env = {key: value for key, value in os.environ.items() if key not in _OUTER}
    env["PATH"] = f"{venv / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    env["VIRTUAL_ENV"] = str(venv)
    return {**env, **extra}


def pytest_in(venv: Path, arguments: list[str], basetemp: Path, timeout: float,
              **extra: str) -> subprocess.CompletedProcess:
    """pytest in `venv` on this repository's tests, one process, its scratch under `basetemp`."""
    return subprocess.run([str(venv / "bin" / "python"), "-m", "pytest", "-q", "-p", "no:cacheprovider",
                           "--basetemp", str(basetemp), *arguments],
                          cwd=ROOT, env=env_of(venv, **extra), stdin=subprocess.DEVNULL, capture_output=True,
                          text=True, timeout=timeout, check=False)


def _requirement_name(line: str) -> str:
    return re.split(r"[=<>!~\[;\s#]", line.strip(), maxsplit=1)[0].lower().replace("_", "-")


def _pip(venv: Path) -> list[str]:
    return [str(venv / "bin" / "python"), "-m", "pip", "--disable-pip-version-check", "--no-input", "-q"]


def _run(argv: list[str], what: str) -> None:
    result = subprocess.run(argv, capture_output=True, text=True, timeout=1200, check=False,
                            stdin=subprocess.DEVNULL)
    if result.returncode != 0:
        raise Unavailable(f"{what} failed ({' '.join(argv)}):\n{(result.stdout + result.stderr)[-3000:]}")


@contextlib.contextmanager
def _exclusive(lock: Path) -> Iterator[None]:
    with lock.open("a") as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        yield
