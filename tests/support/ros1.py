"""The ROS 1 (Noetic-level) environment of the test suite, from Debian 12's own packages.

Debian ships ROS 1 as ordinary packages: no /opt/ros, no global setup.bash,
``ROS_DISTRO`` is ``Debian``. Two things matter on this machine:

* The ``python3`` first on PATH may be a pyenv interpreter without Debian's ROS
  modules, so every ROS command runs with /usr/bin first on PATH and catkin is
  told ``-DPYTHON_EXECUTABLE=/usr/bin/python3``.
* C++ nodes open their XML-RPC server on 0.0.0.0 even with ``ROS_IP`` set.
  To keep a test's traffic private, its master and nodes all run inside one
  network namespace made for the test (:func:`netns_prefix`), reached with
  ``nsenter``; inside it only a loopback interface exists.

Stdlib only; the pytest fixtures build on it.
"""

from __future__ import annotations

import contextlib
import fcntl
import itertools
import os
import shutil
import socket
import subprocess
import tempfile
import time
import warnings
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import urlsplit

from .processes import NodeProcess

PYTHON = "/usr/bin/python3"
# A process started from a shell's background job (`pytest &` in a script) inherits
# SIGINT ignored, and Python then never raises KeyboardInterrupt: rosmaster would
# ignore Ctrl-C. Running commands through this resets SIGINT to its default first.
SIGINT_DEFAULT = ("env", "--default-signal=INT")
SYSTEM_PATH = "/usr/local/sbin:/usr/sbin:/usr/bin:/sbin:/bin"

DEBIAN_PACKAGES = [
    # Toolchain.
    "g++", "make", "cmake",
    # Build system and core C++/Python client libraries.
    "catkin", "python3-catkin-pkg", "libroscpp-dev", "python3-rospy",
    "ros-message-generation", "ros-message-runtime",
    # Master, launch, rosout, command line tools, tests.
    "python3-rosmaster", "python3-roslaunch", "rosout", "rosbash", "rospack-tools",
    "python3-rosparam", "python3-rostopic", "python3-rosnode", "python3-rosservice",
    "python3-rostest", "librostest-dev", "catkin-lint",
    # What the generated lint tests run (nose runs them).
    "python3-nose", "python3-flake8", "cpplint",
    # actionlib.
    "libactionlib-dev", "python3-actionlib",
    "ros-actionlib-msgs", "libactionlib-msgs-dev", "python3-actionlib-msgs",
    # Nodes with `diagnostics: true`.
    "libdiagnostic-updater-dev", "python3-diagnostic-updater",
    # Interface packages: definitions, C++ headers, Python modules.
    *(
        form.format(name)
        for name in ("std-msgs", "std-srvs", "geometry-msgs", "sensor-msgs", "nav-msgs", "move-base-msgs",
                     "diagnostic-msgs")
        for form in ("ros-{}", "lib{}-dev", "python3-{}")
    ),
    # Private network namespaces: ip (netns add, lo up) and nsenter.
    "iproute2", "util-linux",
]

_BASH_NOISE = ("_", "PWD", "OLDPWD", "SHLVL")


class Ros1Unavailable(RuntimeError):
    """The ROS 1 tier cannot run on this machine (packages missing, no root...)."""


def missing_packages(packages: Sequence[str] = DEBIAN_PACKAGES) -> list[str]:
    """The packages of `packages` that dpkg does not list as installed."""
    if shutil.which("dpkg-query") is None:
        raise Ros1Unavailable("no dpkg-query: the ROS 1 tier needs Debian 12's packages")
    result = subprocess.run(
        ["dpkg-query", "-W", "-f=${Package} ${db:Status-Abbrev}\n", *packages],
        capture_output=True, text=True, check=False,
    )  # Exit code 1 just means some package is unknown to dpkg.
    installed = {
        line.split()[0] for line in result.stdout.splitlines() if line.split()[1:2] == ["ii"]
    }
    return [package for package in packages if package not in installed]


@contextlib.contextmanager
def apt_lock() -> Iterator[None]:
    """One apt-get at a time among the test processes (it fails at once on a lock another holds)."""
    with (Path(tempfile.gettempdir()) / "rna-template-apt.lock").open("a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        yield


def install_packages(packages: Sequence[str]) -> None:
    """`apt-get update`, then install `packages` without recommends. Root only."""
    if os.geteuid() != 0:
        raise Ros1Unavailable(
            f"installing Debian packages needs root; install them by hand: {' '.join(packages)}"
        )
    env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
    for argv in (
        ["apt-get", "update"],
        ["apt-get", "install", "-y", "--no-install-recommends", *packages],
    ):
        # File descriptor 2, not sys.stderr: pytest may have replaced the latter.
        subprocess.run(argv, env=env, stdin=subprocess.DEVNULL, stdout=2, stderr=2, check=True)


def _tail(text: str, lines: int = 60) -> str:
    return "\n".join(text.splitlines()[-lines:])


@dataclass
class Ros1Environment:
    """A machine with the ROS 1 packages installed; builds and environments for tests."""

    installed: list[str] = field(default_factory=list)  # what ensure_environment installed
    install_seconds: float = 0.0

    def env(self, master_port: int, ros_home: Path) -> dict[str, str]:
        """Environment for catkin, ROS tools and nodes talking to a master on 127.0.0.1."""
        env = {
            key: value for key, value in os.environ.items()
            if not key.startswith(("ROS", "PYTHON", "PYENV", "CMAKE_PREFIX_PATH", "CATKIN"))
            and key not in ("VIRTUAL_ENV", "LD_LIBRARY_PATH", "PKG_CONFIG_PATH")
        }
        ros_home.mkdir(parents=True, exist_ok=True)
        env.update(
            PATH=f"{SYSTEM_PATH}:{os.environ.get('PATH', '')}",  # Debian's python3 first
            ROS_MASTER_URI=f"http://127.0.0.1:{master_port}",
            ROS_IP="127.0.0.1",
            ROS_HOME=str(ros_home),
            ROS_PYTHON_VERSION="3",
            PYTHONUNBUFFERED="1",
            ROSCONSOLE_STDOUT_LINE_BUFFERED="1",
            LANG="C.UTF-8",
        )
        return env

    def workspace_env(self, devel_dir: Path, base_env: Mapping[str, str]) -> dict[str, str]:
        """`base_env` as `source <devel_dir>/setup.bash` leaves it.

        Sourcing for real (rather than computing the paths) also runs the env hooks
        of every package, and the script's own logic stays catkin's business.
        """
        script = devel_dir / "setup.bash"
        if not script.is_file():
            raise AssertionError(f"{script} does not exist: did catkin_make run?")
        result = subprocess.run(
            ["/bin/bash", "--norc", "--noprofile", "-c", 'source "$1" && exec env -0', "bash",
             str(script)],
            env=dict(base_env), stdin=subprocess.DEVNULL, capture_output=True, check=False,
        )
        if result.returncode != 0:
            stderr = result.stderr.decode(errors="replace")
            raise AssertionError(f"sourcing {script} failed:\n{stderr}")
        env = dict(
            item.split("=", 1) for item in result.stdout.decode().split("\0") if "=" in item
        )
        for key in _BASH_NOISE:  # set by bash itself, not by setup.bash
            if key in base_env:
                env[key] = base_env[key]
            else:
                env.pop(key, None)
        return env

    def catkin_make(
        self, workspace: Path, env: Mapping[str, str], *args: str, timeout: float = 900
    ) -> subprocess.CompletedProcess[str]:
        """Run `catkin_make` in `workspace`; raise AssertionError with the log tail on failure."""
        result = subprocess.run(
            # -C: catkin_make takes the workspace from $PWD, not from its working directory.
            ["catkin_make", "-C", str(workspace), "-j2", f"-DPYTHON_EXECUTABLE={PYTHON}", *args],
            cwd=workspace, env=dict(env), stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=timeout,
            check=False,
        )
        if result.returncode != 0:
            raise AssertionError(
                f"catkin_make in {workspace} exited with {result.returncode}:\n"
                f"{_tail(result.stdout)}"
            )
        return result

    def catkin_lint(self, paths: Path | Sequence[Path], env: Mapping[str, str]) -> tuple[int, str]:
        """Run `catkin_lint -W2` on the packages at or under `paths`: (exit code, output)."""
        paths = [paths] if isinstance(paths, Path) else paths
        result = subprocess.run(
            ["catkin_lint", "-W2", "--offline", *map(str, paths)],
            env=dict(env), stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT, text=True, timeout=120, check=False,
        )
        return result.returncode, result.stdout


def ensure_environment(install: bool) -> Ros1Environment:
    """Check, and with `install` first install, everything the ROS 1 tier needs."""
    missing = missing_packages()
    environment = Ros1Environment()
    if missing and install:
        # pytest-xdist workers set up at once: one installs, the others wait and find it done
        # (apt-get fails at once on the lock another one holds).
        with apt_lock():
            missing = missing_packages()
            if missing:
                start = time.monotonic()
                install_packages(missing)
                environment.installed, environment.install_seconds = missing, time.monotonic() - start
        missing = missing_packages()
    if missing:
        raise Ros1Unavailable(f"missing Debian packages: {' '.join(missing)}")
    try:
        socket.gethostbyname("localhost")
    except OSError as error:  # roslaunch and rostest need it
        raise Ros1Unavailable(f"'localhost' does not resolve (/etc/hosts): {error}") from None
    return environment


def free_port() -> int:
    """A TCP port free on 127.0.0.1 right now (the kernel picks it)."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


_netns_names = itertools.count()


def _ip(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["ip", *args], capture_output=True, text=True, check=False,
                          stdin=subprocess.DEVNULL, env={**os.environ, "PATH": SYSTEM_PATH})


def _remove_stale_namespaces() -> None:
    """Delete namespaces left by test runs that were killed (their pid is gone)."""
    for line in _ip("netns", "list").stdout.splitlines():
        name = line.split(" ", 1)[0]
        pid = name.split("-")[2] if name.startswith("rna-test-") else ""
        if pid.isdigit() and not Path(f"/proc/{pid}").exists():
            _ip("netns", "delete", name)


@contextlib.contextmanager
def netns_prefix() -> Iterator[list[str]]:
    """Yield an argv prefix that runs a command in a fresh private network namespace.

    Every command started with the same prefix shares that namespace, whose only
    interface is loopback: a master and its nodes can talk on 127.0.0.1, nothing
    outside can reach them and they cannot collide with other tests' ports.
    `nsenter` and `env` exec the command, so the process started is the node
    itself and SIGINT reaches it (with its default disposition, see SIGINT_DEFAULT).
    Where namespaces cannot be made (not root, no CAP_SYS_ADMIN), this warns and
    yields SIGINT_DEFAULT alone: the test still runs, on the shared 127.0.0.1.
    """
    name = f"rna-test-{os.getpid()}-{next(_netns_names)}"
    if os.geteuid() != 0:
        warnings.warn("not root: no private network namespace, ROS uses the shared loopback", stacklevel=2)
        yield [*SIGINT_DEFAULT]
        return
    _remove_stale_namespaces()
    added = _ip("netns", "add", name)
    if added.returncode != 0:
        warnings.warn(f"ip netns add failed ({added.stderr.strip()}): using the shared loopback", stacklevel=2)
        yield [*SIGINT_DEFAULT]
        return
    try:
        up = _ip("-n", name, "link", "set", "lo", "up")
        if up.returncode != 0:
            raise Ros1Unavailable(f"cannot bring up lo in namespace {name}: {up.stderr.strip()}")
        yield ["nsenter", f"--net=/run/netns/{name}", *SIGINT_DEFAULT]
    finally:
        _ip("netns", "delete", name)


_PROBE = "import sys, xmlrpc.client; xmlrpc.client.ServerProxy(sys.argv[1]).getPid('/probe')"


@contextlib.contextmanager
def master(
    env: Mapping[str, str],
    log_path: Path,
    prefix: Sequence[str] = SIGINT_DEFAULT,
    timeout: float = 20.0,
) -> Iterator[NodeProcess]:
    """Run a private `rosmaster --core` on the port of env's ROS_MASTER_URI.

    `prefix` (from netns_prefix) runs it inside the test's namespace; readiness
    is probed from inside it as well (an XML-RPC getPid call). Stopped with SIGINT.
    """
    uri = env["ROS_MASTER_URI"]
    port = str(urlsplit(uri).port)
    process = NodeProcess([*prefix, "rosmaster", "--core", "-p", port], env=env, log_path=log_path)
    try:
        deadline = time.monotonic() + timeout
        while subprocess.run([*prefix, PYTHON, "-c", _PROBE, uri], env=dict(env),
                             stdin=subprocess.DEVNULL, capture_output=True).returncode != 0:
            if process.popen.poll() is not None or time.monotonic() > deadline:
                raise AssertionError(f"rosmaster at {uri} did not answer:\n{process.tail()}")
            time.sleep(0.1)
        yield process
        code = process.interrupt()
        if code != 0:
            raise AssertionError(f"rosmaster exited with {code} on SIGINT:\n{process.tail()}")
    finally:
        process.close()
