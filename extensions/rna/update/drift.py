"""User files whose base class changed in a way their code depends on.

A node's user file is the user's once edited: the update never rewrites it. When the
answers change what that code builds on (the message type of a callback it overrides, a
callback it overrides that is gone: a build error in C++, dead code in Python; lifecycle,
component or diagnostics switched, the license its header states), or the template's base
file does (a name the user's code imports from it is gone; an executor that main() does not
spin the node on), the update says so in its summary and writes the new starter beside the
file, under a name no build tool or linter picks up, for the user to compare and port.
"""

from __future__ import annotations

import posixpath
import re

from ..model import Node, Package
from .project import Project, Render
from .protect import edited
from .summary import Report

# `driver.cpp.new-starter`: CMake builds the sources it is given, setuptools installs
# modules (*.py), and the linters (flake8, cpplint, uncrustify, copyright) go by extension.
STARTER_SUFFIX = ".new-starter"


def _node(package: Package, name: str) -> Node | None:
    return next((node for node in package.nodes if node.name == name), None)


def _endpoints(node: Node) -> dict[tuple, object]:
    return {(type(endpoint).__name__, getattr(endpoint, "role", None), endpoint.id): endpoint
            for endpoint in node.endpoints}


def _used(methods, code: str) -> list[str]:
    return [method for method in methods if method and re.search(rf"\b{re.escape(method)}\b", code)]


def reasons(old: Package, new: Package, name: str, code: str, was: str | None = None) -> list[str]:
    """What node `name`'s user code (`code`) must follow, one short line each (`was`: its name before)."""
    before, after = _node(old, was or name), _node(new, name)
    if before is None or after is None or before.language != after.language:
        return []  # a node gone or rewritten in another language: its file is kept (protect.py)
    found = []
    now = _endpoints(after)
    for key, endpoint in _endpoints(before).items():
        used = _used(endpoint.methods, code)
        if not used:
            continue
        changed = now.get(key)
        if changed is None and after.is_cpp:  # `override` of nothing no longer compiles
            found.append(f"the {endpoint.label} is no longer in the answers, and your code overrides "
                         f"{', '.join(used)}")
        elif changed is None:  # Python builds on, and the code the user wrote never runs: said all the same
            found.append(f"the {endpoint.label} is no longer in the answers: your {', '.join(used)} is never "
                         "called (move what it did, or delete it)")
        elif changed is not None and getattr(endpoint, "type", None) != getattr(changed, "type", None):
            found.append(f"the {endpoint.label} is {changed.type} now, not {endpoint.type}: "
                         f"port {', '.join(used)}")
    if before.lifecycle != after.lifecycle:
        found.append("it is a lifecycle node now" if after.lifecycle else "it is no longer a lifecycle node")
    if before.component != after.component:
        found.append("it is a component now" if after.component else "it is no longer a component")
    if before.diagnostics != after.diagnostics:
        found.append("it has a diagnostics updater now: fill in its status in on_diagnostics" if after.diagnostics
                     else "it no longer has a diagnostics updater")
    if old.license.spdx != new.license.spdx:
        found.append(f"the license is {new.license.spdx} now: its header still says {old.license.spdx}")
    return found


_DEFINED = re.compile(r"^(?:class|def) (\w+)", re.MULTILINE)


def base_reasons(before: Node, after: Node, code: str, old_base: str | None, new_base: str | None) -> list[str]:
    """What node `after`'s user code must follow from its base file: names it imports from the old
    base module that the new one no longer defines (Python), and an executor its main() would not spin on."""
    found = []
    if after.is_python and old_base and new_base:
        gone = sorted(set(_DEFINED.findall(old_base)) - set(_DEFINED.findall(new_base)))
        used = [name for name in gone if re.search(rf"\b{re.escape(name)}\b", code)]
        if used:
            found.append(f"{posixpath.basename(after.base_file)} no longer has {', '.join(used)}, which your code "
                         "uses: main() is a call of the base module's run() now")
    if (before.executor, before.threads) != (after.executor, after.threads) and not after.component:
        # What main() calls to spin the node on the executor its answers give it.
        call = f"{after.class_name}::spin(" if after.is_cpp else "run("
        if call not in code:
            found.append(f"it spins on a {after.executor.replace('_', '-')} executor now, which main() gets by "
                         f"calling {call})")
    return found


def port_edited_user_files(project: Project, old: Render, new: Render, packages: tuple[Package, Package],
                           report: Report, renamed: dict[str, str] | None = None) -> None:
    """Name each edited user file that must follow a change, with the new starter beside it.

    `renamed`: new node name -> old one (renames.py carried the file)."""
    old_package, new_package = packages
    renamed = renamed or {}
    for node in new_package.nodes:
        was = renamed.get(node.name, node.name)
        before = _node(old_package, was)
        if before is None or before.language != node.language:
            continue
        path = posixpath.normpath(posixpath.join(new_package.dir, node.user_file))
        source = posixpath.normpath(posixpath.join(old_package.dir, before.user_file))
        code = project.text(path)
        if code is None or path not in new.files or not edited(project, old, source):
            continue  # an untouched starter follows the template itself (protect.py)
        found = reasons(old_package, new_package, node.name, code, was)
        found += base_reasons(before, node, code, old.text(posixpath.normpath(posixpath.join(
            old_package.dir, before.base_file))), new.text(posixpath.normpath(posixpath.join(
                new_package.dir, node.base_file))))
        if found:
            starter = path + STARTER_SUFFIX
            project.write(starter, new.text(path))
            report.to_port.append((path, "; ".join(found) + f" (the new starter: {starter.rsplit('/', 1)[-1]})"))
