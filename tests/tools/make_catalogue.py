"""Write the catalogues of standard interface types: extensions/rna/catalogue/<distro>.json.

    tests/env python tests/tools/make_catalogue.py [DISTRO ...] [--source OWNER/NAME=GIT_DIR ...]

Each catalogue holds, for each standard interface package a distro has, its type names
per kind, read from the package's own definition files (msg/*.msg, srv/*.srv,
action/*.action), and says where each package came from and when it was made:

  jazzy, kilted    the distro's wheels (ros-<distro>-<name>), installed without their
                   dependencies into a throwaway venv; read from <venv>/share/<package>
  noetic           Debian 12's ros-<name> packages, installed with apt-get (as root);
                   read from /usr/share/<package>
  humble, rolling  the packages' source repositories, each a git repository (a clone or a
                   bare mirror) given with --source and read at the branch named after the
                   distro (or origin/<distro>), without checking it out

--source repositories also fill in, for any distro, the packages its wheels or Debian
lack (example_interfaces). With no DISTRO, all five catalogues are written.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import re
import subprocess
import sys
import tempfile
from collections.abc import Iterable
from pathlib import Path, PurePosixPath

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "extensions" / "rna" / "catalogue"
KINDS = ("msg", "srv", "action")
ROS2_PACKAGES = (
    "std_msgs", "std_srvs", "geometry_msgs", "sensor_msgs", "nav_msgs", "action_msgs",
    "diagnostic_msgs", "trajectory_msgs", "visualization_msgs", "shape_msgs", "stereo_msgs",
    "lifecycle_msgs", "test_msgs", "example_interfaces",
)
ROS1_PACKAGES = (
    "std_msgs", "std_srvs", "geometry_msgs", "sensor_msgs", "nav_msgs", "actionlib_msgs",
    "diagnostic_msgs", "trajectory_msgs", "visualization_msgs", "shape_msgs", "stereo_msgs",
    "actionlib_tutorials",
)
# Packages that generate another package's definitions as their own types (see its CMakeLists.txt).
BORROWED = {"test_msgs": "test_interface_files"}
WHEEL_DISTROS = ("jazzy", "kilted")
DEBIAN_DISTROS = ("noetic",)
DISTROS = ("humble", "jazzy", "kilted", "rolling", "noetic")


def log(message: str) -> None:
    print(f"[catalogue] {message}", file=sys.stderr, flush=True)


def types_of(paths: Iterable[str]) -> dict[str, list[str]]:
    """Type names per kind from file paths relative to a package's root.

    A type is a definition file in the folder of its kind: msg/Name.msg, srv/Name.srv,
    action/Name.action, or Name.idl there for the few types written in IDL only (test_msgs).
    """
    found: dict[str, set[str]] = {kind: set() for kind in KINDS}
    for path in map(PurePosixPath, paths):
        if len(path.parts) == 2 and path.parts[0] in KINDS and path.suffix in (f".{path.parts[0]}", ".idl"):
            found[path.parts[0]].add(path.stem)
    return {kind: sorted(names) for kind, names in found.items()}


def read_installed(share: Path, package: str) -> dict[str, list[str]] | None:
    """The types of an installed package (<prefix>/share/<package>), None if it is not there."""
    root = share / package
    if not root.is_dir():
        return None
    return types_of(path.relative_to(root).as_posix() for path in root.glob("*/*"))


def run(argv: list[str], **kwargs) -> subprocess.CompletedProcess[str]:
    return subprocess.run(argv, stdin=subprocess.DEVNULL, capture_output=True, text=True, **kwargs)


def from_wheels(distro: str, packages: Iterable[str]) -> dict[str, tuple[str, dict]]:
    """{package: (source, types)} for the packages that have a wheel for `distro`.

    ros-<distro>-<name> is a meta-package pinning the unprefixed wheel that holds the files.
    """
    found = {}
    with tempfile.TemporaryDirectory(prefix=f"catalogue-{distro}-") as scratch:
        venv = Path(scratch) / "venv"
        run([sys.executable, "-m", "venv", str(venv)], check=True)
        python = str(venv / "bin" / "python")
        pip = [python, "-m", "pip", "--disable-pip-version-check", "--no-input", "install", "-q", "--no-deps"]
        for package in packages:
            meta = f"ros-{distro}-{package.replace('_', '-')}"
            # Without dependencies: only the definition files under share/ are needed.
            result = run([*pip, meta])
            if result.returncode != 0:
                if "No matching distribution" not in result.stderr:
                    raise RuntimeError(f"pip install {meta} failed:\n{result.stderr}")
                log(f"{distro}: no wheel {meta}")
                continue
            pins = run([python, "-c", f"import importlib.metadata as m; print(*m.requires({meta!r}))"],
                       check=True).stdout.split()
            run([*pip, *pins], check=True)
            types = read_installed(venv / "share", package)
            if types is None:
                raise RuntimeError(f"{meta} ({' '.join(pins)}) installed no share/{package}")
            found[package] = (f"wheel {' '.join(pins)} (from {meta})", types)
    return found


def installed(deb: str) -> str | None:
    """The version of an installed Debian package, None if it is not installed."""
    status = run(["dpkg-query", "-W", "-f=${db:Status-Abbrev} ${Version}", deb]).stdout.split()
    return status[1] if status[:1] == ["ii"] else None


def from_debian(packages: Iterable[str]) -> dict[str, tuple[str, dict]]:
    """{package: (source, types)} from Debian's ros-<name> packages, installing missing ones."""
    wanted = {package: f"ros-{package.replace('_', '-')}" for package in packages}
    missing = [deb for deb in wanted.values() if installed(deb) is None]
    if missing and os.geteuid() == 0:
        run(["apt-get", "update"], check=True)
        if missing := [deb for deb in missing if run(["apt-cache", "show", deb]).returncode == 0]:
            env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
            run(["apt-get", "install", "-y", "--no-install-recommends", *missing], check=True, env=env)
    elif missing:
        log(f"noetic: installing Debian packages needs root; reading without {' '.join(missing)}")
    release = re.search(r'^PRETTY_NAME="?(.*?)"?$', Path("/etc/os-release").read_text(), re.M)
    found = {}
    for package, deb in wanted.items():
        version = installed(deb)
        types = read_installed(Path("/usr/share"), package)
        if version is None or types is None:
            log(f"noetic: no Debian package {deb}")
            continue
        found[package] = (f"{release.group(1) if release else 'Debian'} package {deb} {version}", types)
    return found


def from_git(repository: str, git_dir: str, distro: str, packages: Iterable[str]) -> dict[str, tuple[str, dict]]:
    """{package: (source, types)} from a git repository at the branch named after `distro`."""
    git = ["git", "--git-dir", git_dir] if Path(git_dir, "HEAD").is_file() else ["git", "-C", git_dir]
    for ref in (distro, f"origin/{distro}"):
        commit = run([*git, "rev-parse", "--verify", "-q", f"{ref}^{{commit}}"])
        if commit.returncode == 0:
            break
    else:
        log(f"{distro}: {repository} has no branch {distro}")
        return {}
    commit = commit.stdout.strip()
    date = run([*git, "log", "-1", "--format=%cs", commit], check=True).stdout.strip()
    files = run([*git, "ls-tree", "-r", "--name-only", commit], check=True).stdout.splitlines()
    found = {}
    for manifest in (path for path in files if PurePosixPath(path).name == "package.xml"):
        text = run([*git, "show", f"{commit}:{manifest}"], check=True).stdout
        package = re.search(r"<name>\s*(\S+?)\s*</name>", text).group(1)
        if package in packages:
            root = PurePosixPath(manifest).parent
            inside = (PurePosixPath(path).relative_to(root).as_posix() for path in files
                      if PurePosixPath(path).is_relative_to(root))
            source = f"{repository} branch {ref} commit {commit} ({date})"
            found[package] = (source, types_of(inside))
    return found


def merged(*entries: tuple[str, dict]) -> tuple[str, dict]:
    """One package's (source, types) made of several sources' definitions."""
    sources = "; ".join(source for source, _ in entries)
    return sources, {kind: sorted({name for _, types in entries for name in types[kind]}) for kind in KINDS}


def catalogue(distro: str, sources: dict[str, str]) -> dict:
    packages = ROS1_PACKAGES if distro in DEBIAN_DISTROS else ROS2_PACKAGES
    if distro in WHEEL_DISTROS:
        found = from_wheels(distro, packages)
    elif distro in DEBIAN_DISTROS:
        found = from_debian(packages)
    else:
        found = {}
    in_git: dict[str, tuple[str, dict]] = {}
    for repository, git_dir in sources.items():  # the first repository holding a package wins
        in_git = {**from_git(repository, git_dir, distro, [*packages, *BORROWED.values()]), **in_git}
    for host, lender in BORROWED.items():
        lent = in_git.pop(lender, None)
        if host in in_git and lent:
            in_git[host] = merged(in_git[host], lent)
        elif host in in_git:  # its list would be short: better none
            log(f"{distro}: leaving out {host}, whose {lender} definitions no --source holds")
            del in_git[host]
    found.update({package: entry for package, entry in in_git.items() if package in packages and package not in found})
    if lacking := [package for package in packages if package not in found]:
        log(f"{distro}: no source for {', '.join(lacking)}")
    if not found:
        raise RuntimeError(f"{distro}: found none of the packages (humble and rolling need --source)")
    return {
        "distro": distro,
        "generated": datetime.date.today().isoformat(),
        "tool": "tests/tools/make_catalogue.py",
        "sources": {package: found[package][0] for package in sorted(found)},
        "packages": {package: found[package][1] for package in sorted(found)},
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("distros", nargs="*", metavar="DISTRO",
                        help=f"distros to write ({', '.join(DISTROS)}); all when none")
    parser.add_argument("--source", action="append", default=[], metavar="OWNER/NAME=GIT_DIR",
                        help="a source repository by its name and a git directory holding it")
    parser.add_argument("--out", type=Path, default=OUT, help="folder to write into")
    args = parser.parse_args()
    if unknown := set(args.distros) - set(DISTROS):
        parser.error(f"unknown distro {', '.join(sorted(unknown))}: choose from {', '.join(DISTROS)}")
    sources = dict(source.split("=", 1) for source in args.source)
    args.out.mkdir(parents=True, exist_ok=True)
    for distro in args.distros or DISTROS:
        data = catalogue(distro, sources)
        path = args.out / f"{distro}.json"
        path.write_text(json.dumps(data, indent=1) + "\n")
        log(f"{distro}: wrote {path} ({len(data['packages'])} packages)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
