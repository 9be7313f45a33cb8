"""Answer changes an update refuses before it writes anything.

Each check compares the answers being updated (the project's answers file) with the new
ones and returns the error to stop on: one line naming the question (or the file), the
rule and what to do instead.
"""

from __future__ import annotations

import subprocess
from collections.abc import Mapping
from pathlib import Path

from .. import distros, files
from ..answers import FIRST_COPY, AnswerError

def switch_error(previous: Mapping, answers: Mapping) -> AnswerError | None:
    """A change from ROS 2 back to ROS 1, which no update makes (or a port that renames the package).

    ROS 1 -> ROS 2 is a port (rna/update/port.py): the template's files are made for ROS 2
    and the user's code is carried over by documented rules. The other way round there is
    nothing to port to: ROS 1 reached its end of life. A build type change within ROS 2 is
    not refused either: the update makes it.
    """
    before, after = previous.get("ros_distro"), answers.get("ros_distro")
    if not before or not after or distros.generation(before) < distros.generation(after):
        return port_rename_error(previous, answers)
    if distros.generation(before) == distros.generation(after):
        return None
    return AnswerError("ros_distro", (
        f"{after} is ROS 1 and this package is ROS 2 ({before}): an update ports ROS 1 to ROS 2, never back "
        f"(nothing was written). Keep ros_distro {before}"))


def port_rename_error(previous: Mapping, answers: Mapping) -> AnswerError | None:
    """A package renamed in the update that ports it to ROS 2.

    The port carries the user's files where the package is, and the rename moves them where it
    goes: together, the user's own files would stay behind in the old folder. Nodes may be
    renamed in a port (rna/update/port.py), the package in an update of its own.
    """
    before, after = previous.get("package_name"), answers.get("package_name")
    if not before or not after or before == after or previous.get("target", "package") != "package":
        return None
    if distros.generation(previous.get("ros_distro")) != 1 or distros.generation(answers.get("ros_distro")) != 2:
        return None
    return AnswerError("package_name", (
        f"the update that ports {before} to ROS 2 keeps its name: rename it to {after} in an update of its own, "
        "before or after the port (nothing was written)"))


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


def first_copy_error(given: Mapping) -> AnswerError | None:
    """An update given one of the first copy's ways to the nodes (`-d node_publishers=...`).

    Those questions fill in `nodes` on a first copy; the answers file records `nodes`, and an
    update changes the nodes there. Taken as given, the answer would change nothing.
    """
    question = next((question for question in FIRST_COPY if question in given), None)
    if question is None:
        return None
    return AnswerError(question, (
        f"{question} is a question of the first copy, which it helps fill in 'nodes'; this package records its "
        "nodes in 'nodes', so an update changes them there (nothing was written): copier update --trust asks "
        "for them, or give them all: --data-file nodes.yml, with nodes: [...] as the answers file holds them"))


def undecodable_name(project: Path) -> str | None:
    """The first file in the project (git's view) whose name is not UTF-8, or None."""
    listed = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"], cwd=project,
                            capture_output=True, check=False).stdout
    for name in listed.split(b"\0"):
        try:
            name.decode("utf-8")
        except UnicodeDecodeError:
            return name.decode("utf-8", "backslashreplace")
    return None


def name_error(name: str) -> str:
    """Copier's update fails half-way on a file name that is not UTF-8 (it has written the new
    version by then); the template stops it first."""
    return (f"the file {name} has a name that is not UTF-8, on which copier update fails half-way (nothing was "
            "written): rename it (git mv, to a UTF-8 name), commit, and update again")


def copy_over_error(answers_file: str) -> str:
    """`copier recopy`, or `copier copy`, into a package the template made (its answers file is
    there): Copier renders the package afresh over the user's files, without the update's
    merge, and replaces the lines the user added to the files the template shares with them."""
    return (f"this folder holds a package the template made ({answers_file}): copier recopy and copier copy render "
            "it afresh over your files and would replace the lines you added to package.xml, the build files, "
            "the launch and config files and the README (nothing was written). Use copier update --trust, which "
            "merges them; to start again from the answers, copy into an empty folder and move your code across")


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
        content = files.read(destination, str(path))
        if content is None:
            continue
        if node.base_class_name not in (content.text or ""):
            return AnswerError("nodes", (
                f"node '{node.name}': {path} is already in the package and does not build on "
                f"{node.base_class_name}, so the new node would take over your file (nothing was written). "
                f"Give the node another name, or move your file first"))
    return None
