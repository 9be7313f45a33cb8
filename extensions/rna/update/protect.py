"""Files the user edited stay; files the user never touched follow the template.

Copier deletes every file the old version made and the new one does not, edited or
not, and never refreshes a user file (`_skip_if_exists`) once it exists. Here:

- a file the user had edited (its committed text differs from the old render) that the
  new answers no longer make is put back where it was and reported with the reason; the
  update fails until the user decides what becomes of it. When what is kept is a whole
  package's package.xml (the interfaces package of answers without interfaces), the
  folder gets a COLCON_IGNORE / CATKIN_IGNORE so the workspace still builds;
- a node's user file the user never edited gets the new starter code, so an untouched
  package stays equal to a fresh copy.
"""

from __future__ import annotations

import os
import posixpath

from .. import layout
from ..model import Package
from .project import Project, Render
from .summary import Report

BUILD_FILES = {"ament_python": "setup.py", "ament_cmake": "CMakeLists.txt", "catkin": "CMakeLists.txt"}
IGNORE_FILES = {1: "CATKIN_IGNORE", 2: "COLCON_IGNORE"}


def edited(project: Project, old: Render, path: str) -> bool:
    """The user changed this file (or made it): what was committed is not what the old version made."""
    before, generated = project.committed_content(path), old.content(path)
    if before is None:
        return False
    return generated is None or before.data is None or (before.kind, before.data) != (generated.kind, generated.data)


def refresh_untouched_starters(project: Project, old: Render, new: Render, user_files: set[str],
                               report: Report) -> None:
    """A user file never edited holds what a fresh copy would hold now."""
    for path in sorted(user_files & new.files):
        before = project.committed(path)
        if before is None or edited(project, old, path) or project.text(path) != before:
            continue
        if new.text(path) != before:
            project.write(path, new.text(path))  # listed as updated


def _in(package: Package, path: str) -> str:
    return posixpath.normpath(posixpath.join(package.dir, path))


def why_gone(path: str, old: Package | None, new: Package | None) -> str:
    """Why the new answers no longer make a file the old ones made, in the user's terms."""
    if old is None or new is None:
        return "the answers no longer make it"
    names = {node.name: node for node in new.nodes}
    for node in old.nodes:
        if path in {_in(old, node.user_file), _in(old, node.base_file), _in(old, node.config_file),
                    _in(old, node.test_file)}:
            if node.name not in names:
                return f"its node '{node.name}' is gone from the answers"
            if names[node.name].language != node.language:
                return f"node '{node.name}' is written in {names[node.name].language} now"
    if old.launch_format != new.launch_format and path == _in(old, old.launch_file):
        return (f"the launch file is {layout.LAUNCH_FORMAT_NAMES[new.launch_format]} now: move what you added into "
                f"{_in(new, new.launch_file)}")
    if old.interfaces_package and path.startswith(old.interfaces_package + "/"):
        if not new.definitions:
            return "the answers define no interfaces now"
        return f"the interfaces are built in {new.interfaces_home} now"
    if old.build_type != new.build_type and path.startswith(f"{old.dir}/") and "/" not in path[len(old.dir) + 1:]:
        return (f"the package is {new.build_type} now: move what you still need into "
                f"{_in(new, BUILD_FILES[new.build_type])}")
    if old.python_init_file and path == _in(old, old.python_init_file) and not new.python_dir:
        return "no Python node is left in the package"
    return "the answers no longer make it"


def keep_edited_files(project: Project, old: Render, new: Render, packages: tuple[Package | None, Package | None],
                      report: Report, skip: set[str] = frozenset()) -> None:
    """Put back each edited file the new answers no longer make (Copier deleted it); `skip`: carried elsewhere."""
    for path in sorted(old.files - new.files - skip):
        if not edited(project, old, path) or os.path.lexists(project.root / path):
            continue
        project.restore(path)
        report.kept.append((path, why_gone(path, *packages)))
        folder = posixpath.dirname(path)
        if posixpath.basename(path) == "package.xml" and not any(
                name.startswith(f"{folder}/") for name in new.files):
            generation = (packages[1] or packages[0]).ros if any(packages) else 2
            ignore = posixpath.join(folder, IGNORE_FILES[generation])
            project.write(ignore, "")
            report.notes.append(f"{ignore} written: {folder} is no package of these answers, so the "
                                "workspace leaves it out until you decide what becomes of it.")
