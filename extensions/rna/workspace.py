"""Interfaces that already exist on disk, found without a ROS installation.

The destination and the workspace around it (the nearest `src` folder above it, or
its parent folder) are searched for packages (a package.xml) and their
msg/*.msg, srv/*.srv and action/*.action files, so that the questions can offer
them by their full names.
"""

from __future__ import annotations

import os
import re
import xml.etree.ElementTree as ET
from pathlib import Path

from . import files, layout

_SKIP = {"build", "install", "log", "devel", "node_modules", "__pycache__"}
_NAME = re.compile(r"<name>\s*([^<\s]+)\s*</name>")
KIND_FOLDERS = ("msg", "srv", "action")


def workspace_roots(destination: Path) -> list[Path]:
    """Where to look: the destination, and the workspace source folder around it."""
    destination = Path(destination).resolve()
    roots = [destination]
    for ancestor in destination.parents:
        if ancestor.name == "src":
            roots.append(ancestor)
            break
    else:
        roots.append(destination.parent)
    return roots


def _packages(root: Path, depth: int = 4):
    """(package name, folder) of every package.xml under root, not descending into packages."""
    if not root.is_dir():
        return
    for current, folders, names in os.walk(root):
        level = len(Path(current).relative_to(root).parts)
        folders[:] = [f for f in folders if not f.startswith(".") and f not in _SKIP] if level < depth else []
        if "package.xml" in names:
            folders[:] = []
            match = _NAME.search(files.text(Path(current), "package.xml") or "")
            if match:
                yield match[1], Path(current)


def files_in_the_way(destination: Path, package: str, node: str, ros: int, languages) -> list[str]:
    """The files of a node, in any of `languages`, that are already in the package `destination`
    (a node added to a package must not land on them)."""
    return [path for language in languages for path in layout.node_files(package, node, ros, language)
            if (destination / path).exists()]


def find_interfaces(destination: Path, limit: int = 200) -> list[str]:
    """Full names (pkg/msg/Name) of the interfaces on disk around `destination`, sorted."""
    found: set[str] = set()
    for root in workspace_roots(destination):
        for package, folder in _packages(root):
            for kind in KIND_FOLDERS:
                for path in (folder / kind).glob(f"*.{kind}"):
                    found.add(f"{package}/{kind}/{path.stem}")
                    if len(found) >= limit:
                        return sorted(found)
    return sorted(found)


def read_package(folder: Path) -> dict | None:
    """What a node added to the package in `folder` needs from its package.xml, or None."""
    manifest = files.text(Path(folder), "package.xml")
    if manifest is None:
        return None
    try:
        root = ET.fromstring(manifest)  # text: its declared encoding was read already
    except ET.ParseError:
        return None

    def text(tag: str) -> str:
        element = root.find(tag)
        return (element.text or "").strip() if element is not None else ""

    buildtools = {element.text.strip() for element in root.iter("buildtool_depend") if element.text}
    build_type = root.findtext("export/build_type") or ("catkin" if "catkin" in buildtools else "ament_cmake")
    maintainer = root.find("maintainer")
    return {
        "name": text("name"),
        "description": " ".join(text("description").split()),
        "license": text("license"),
        "maintainer": (maintainer.text or "").strip() if maintainer is not None else "",
        "maintainer_email": maintainer.get("email", "") if maintainer is not None else "",
        "build_type": build_type.strip(),
        "ros_distro": "noetic" if build_type.strip() == "catkin" else "jazzy",
    }
