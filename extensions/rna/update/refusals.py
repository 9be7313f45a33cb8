"""Answer changes an update refuses before it writes anything.

Each check compares the answers being updated (the project's answers file) with the new
ones and returns the error to stop on: one line naming the question (or the file), the
rule and what to do instead.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from .. import distros
from ..answers import AnswerError

def switch_error(previous: Mapping, answers: Mapping) -> AnswerError | None:
    """A change from ROS 2 back to ROS 1, which no update makes.

    ROS 1 -> ROS 2 is a port (rna/update/port.py): the template's files are made for ROS 2
    and the user's code is carried over by documented rules. The other way round there is
    nothing to port to: ROS 1 reached its end of life. A build type change within ROS 2 is
    not refused either: the update makes it.
    """
    before, after = previous.get("ros_distro"), answers.get("ros_distro")
    if not before or not after or distros.generation(before) <= distros.generation(after):
        return None
    return AnswerError("ros_distro", (
        f"{after} is ROS 1 and this package is ROS 2 ({before}): an update ports ROS 1 to ROS 2, never back "
        f"(nothing was written). Keep ros_distro {before}"))


def port_error(previous: Mapping, answers: Mapping, package_xml: Mapping | None) -> AnswerError | None:
    """A node the template added to a package it did not make, ported while that package is catkin's.

    The package's own package.xml and CMakeLists.txt are the user's: the port carries the
    node's files and replaces the node's lines in them, so they must be ROS 2's already.
    """
    if previous.get("target") != "node" or distros.generation(previous.get("ros_distro")) != 1:
        return None
    if distros.generation(answers.get("ros_distro")) != 2 or (package_xml or {}).get("build_type") != "catkin":
        return None
    return AnswerError("ros_distro", (
        "the package this node was added to is still a catkin package (its package.xml): its package.xml and "
        "CMakeLists.txt are yours, so port them to ROS 2 (ament_cmake) first, then run this update to port the "
        "node (nothing was written)"))


def hand_edit_error(answers_file: str) -> str:
    """The answers file was edited by hand (resolve.edited_by_hand): Copier would take the
    edited answers for the package's old ones, render nothing new and exit 0."""
    return (f"{answers_file} was edited by hand (its answers no longer match the checksum the template wrote), "
            f"so this update would change nothing (nothing was written). Restore it as the last update left it "
            f"(git log -p {answers_file}), commit, and give the changed answers to the update instead: "
            f"copier update --trust --data question=value, or --data-file changes.yml")


def take_over_error(package, previous: Mapping, destination: Path) -> AnswerError | None:
    """A node the update adds whose source file is already there, written by the user.

    The template never rewrites a node's own file once it exists, so the new node would
    run the user's unrelated module (or fail to build against it). A file that builds on
    the node's base class is the node's own, kept from an earlier update: taken back.
    """
    before = {item.get("name") if isinstance(item, Mapping) else str(item)
              for item in (previous.get("nodes") or []) if item}
    for node in package.nodes:
        if node.name in before:
            continue
        path = Path(package.dir) / node.user_file
        try:
            text = (destination / path).read_text(encoding="utf-8", errors="replace")
        except OSError:
            continue
        if node.base_class_name not in text:
            return AnswerError("nodes", (
                f"node '{node.name}': {path} is already in the package and does not build on "
                f"{node.base_class_name}, so the new node would take over your file (nothing was written). "
                f"Give the node another name, or move your file first"))
    return None
