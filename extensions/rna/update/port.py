"""A ROS 1 package ported to ROS 2 by an update (`copier update -d ros_distro=<ROS 2 distro>`).

Copier renders the package for ROS 2 and deletes what only ROS 1 had; the template's
own files are then ROS 2's. This step carries what the user wrote, each file with the
rules of rna.port:

- each node's file (its user file, moved where ROS 2 keeps it): the user's code ported
  onto the ROS 2 starter (rna.port.code);
- the user's other code files of the package (Python modules of the ROS 1 Python package
  move to the ROS 2 one): the rules alone;
- the user's lines of CMakeLists.txt, package.xml (the package's and the interfaces
  package's) and the launch file: carried into the ROS 2 ones, rewritten, or commented
  out under a TODO(port) note where they name ROS 1 things no rule rewrites (rna.port.build);
- the user's own roslaunch files: ROS 2 XML launch files beside them;
- config files: the user's tuned values and lines, in `ros__parameters` form.

A node added to a package the template did not make is ported alone: the package's own
files are the user's (refusals.port_error makes sure they are ROS 2's already), and the
node's block in its build files is add_node.py's, run by the same update.

Every rewrite and every TODO(port) is listed in the summary; the ROS 1 package stays in
git history (the update needs a clean tree), which the summary says how to compare with.
"""

from __future__ import annotations

import dataclasses
import posixpath
import re

from .. import distros, layout
from ..catalogue import load as load_catalogue
from ..dialects import dialect
from ..model import Action, Node, Package, Service, Timer, Topic
from ..port import api, build, code, cpp, python
from . import config_merge, merge, renames
from .project import Project, Render
from .protect import edited
from .summary import Ported, Report

ROS1_DISTRO = distros.ROS1_DISTROS[0]  # whose catalogue says which ROS 1 types are messages, services, actions
CODE_SUFFIXES = (".py", ".cpp", ".h", ".hpp", ".cc", ".hh", ".hxx", ".cxx")


def porting(packages: tuple[Package | None, Package | None]) -> bool:
    old, new = packages
    return old is not None and new is not None and old.ros == 1 and new.ros == 2


def _in(package: Package, path: str) -> str:
    return posixpath.normpath(posixpath.join(package.dir, path))


def _node(package: Package, name: str) -> Node | None:
    return next((node for node in package.nodes if node.name == name), None)


def endpoint_kind(endpoint) -> str:
    """The name rna.port.api's tables give an endpoint's kind."""
    if isinstance(endpoint, Timer):
        return "timer"
    if isinstance(endpoint, Topic):
        return endpoint.role
    if isinstance(endpoint, Service):
        return f"service_{endpoint.role}"
    if isinstance(endpoint, Action):
        return f"action_{endpoint.role}"
    raise TypeError(endpoint)


def kinds(package: Package) -> dict[tuple[str, str], str]:
    """(package, type) -> msg, srv or action: the types ROS 1 knows (its catalogue, the package's own)."""
    known = {}
    catalogue = load_catalogue(ROS1_DISTRO) or {"packages": {}}
    for name, types in catalogue["packages"].items():
        for kind, type_names in types.items():
            for type_name in type_names:
                known.setdefault((name, type_name), kind)
    for interface in (interface for node in package.nodes for interface in node.interfaces):
        known[(interface.package, interface.name)] = interface.kind
    home = package.interfaces_home
    for definition in package.definitions:
        known[(home, definition.name)] = definition.kind
    return known


def python_context(old: Node, new: Node, package: Package) -> python.Context:
    """What the Python rules know of a node: its ROS 1 base class's API, and ROS 2's names of its types."""
    ros2_types = dialect(new)
    servers = {action.id: action for action in new.action_servers}
    results = tuple((action.id, ros2_types.type(servers[action.id].type) + ".Result")
                    for action in old.action_servers if action.id in servers)
    callbacks = tuple((callback.method.format(id=endpoint.id), callback) for endpoint in old.endpoints
                      for callback in api.callbacks("python") if callback.endpoint == endpoint_kind(endpoint))
    return python.Context(
        base_class=old.base_class_name, logger=old.name, parameters=frozenset(p.name for p in old.parameters),
        subscribers=frozenset(t.id for t in old.subscribers), timers=frozenset(t.id for t in old.timers),
        service_clients=frozenset(s.id for s in old.service_clients),
        action_clients=frozenset(a.id for a in old.action_clients), action_results=results,
        callbacks=callbacks, kinds=kinds(package))


def declaration(text: str, method: str) -> str | None:
    """The declaration of `method` in a C++ starter or base header, without `virtual` and `override`."""
    match = re.search(rf"^[ \t]*((?:virtual\s+)?[\w:<>,&*\s]*?\b{re.escape(method)}\s*\()", text, re.M)
    if not match:
        return None
    masked = cpp.mask(text)
    end = cpp.closing(masked, match.end() - 1)
    if end < 0:
        return None
    return re.sub(r"^virtual\s+", "", text[match.start(1):end + 1].strip())


def cpp_context(old: Node, new: Node, package: Package, new_starter: str, new_base: str) -> cpp.Context:
    """What the C++ rules know of a node: its ROS 1 base class's API, ROS 2's declarations of its callbacks."""
    ros1_types, ros2_types = dialect(old), dialect(new)
    callbacks = []
    for endpoint in old.endpoints:
        for callback in api.callbacks("cpp"):
            if callback.endpoint != endpoint_kind(endpoint):
                continue
            method = callback.method.format(id=endpoint.id)
            found = declaration(new_starter, method) or declaration(new_base, method)
            if found:
                callbacks.append((method, callback, found))
    constructor = re.search(rf"explicit\s+{re.escape(new.class_name)}\s*\(.*?\)\s*\n\s*:\s*"
                            rf"{re.escape(new.base_class_name)}\s*\(\s*options\s*\)", new_starter, re.S)
    return cpp.Context(
        class_name=old.class_name, base_class=old.base_class_name, logger=old.name,
        parameters=tuple((p.name, api.CPP_PARAMETER_ACCESSORS[p.type.name]) for p in old.parameters),
        publishers=frozenset(t.id for t in old.publishers), subscribers=frozenset(t.id for t in old.subscribers),
        timers=frozenset(t.id for t in old.timers),
        service_clients=tuple((s.id, ros2_types.type(s.type)) for s in new.service_clients),
        action_clients=frozenset(a.id for a in old.action_clients),
        action_servers=tuple((a.id, ros2_types.type(a.type)) for a in new.action_servers),
        action_types=frozenset(ros1_types.alias_names[a.type] for a in old.actions),
        callbacks=tuple(callbacks), constructor=constructor[0] if constructor else "", kinds=kinds(package),
        headers=((old.base_file.removeprefix("include/"), new.base_file.removeprefix("include/")),))


def _rewrite_lines(result: code.NodePort) -> tuple[str, ...]:
    return tuple(f"line {r.line}: {r.before} -> {r.after}" if r.after else f"line {r.line}: {r.before} (removed)"
                 for r in sorted(result.rewrites, key=lambda r: r.line))


def _settled(project: Project, *paths: str) -> None:
    """Copier's leftovers of a file this step wrote: its .rej, its conflict in the index."""
    for path in paths:
        rejected = project.root / f"{path}.rej"
        if rejected.exists():
            rejected.unlink()
        project.resolve_in_index(path)


def port_node_files(project: Project, old: Render, new: Render, packages: tuple[Package, Package],
                    report: Report, renamed: dict[str, str]) -> set[str]:
    """Each node's edited file, ported onto the ROS 2 starter where ROS 2 keeps it."""
    old_package, new_package = packages
    handled = set()
    for node in new_package.nodes:
        before = _node(old_package, renamed.get(node.name, node.name))
        if before is None or before.language != node.language:
            continue  # a node gone, or rewritten in another language: kept and named (protect.py)
        source, target = _in(old_package, before.user_file), _in(new_package, node.user_file)
        old_starter, new_starter = old.text(source), new.text(target)
        if not edited(project, old, source) or old_starter is None or new_starter is None:
            continue  # the starter: the new one follows the template (Copier, protect.py)
        mine = project.committed(source)
        if mine is None:
            continue  # not text: kept as it is
        if before.name != node.name:  # renamed in this update: the class, base and node name, as renames does
            mine, old_starter = (renames.renamed_code(text, before, node, None, None) for text in (mine, old_starter))
        if node.is_python:
            context = python_context(before, node, old_package)
            if before.name != node.name:
                context = dataclasses.replace(context, base_class=node.base_class_name, logger=node.name)
            result = code.port_python(mine, old_starter, new_starter, context)
        else:
            base = new.text(_in(new_package, node.base_file)) or ""
            context = cpp_context(before, node, old_package, new_starter, base)
            if before.name != node.name:
                header = renames.renamed_code(before.base_file.removeprefix("include/"), before, node, None, None)
                context = dataclasses.replace(context, class_name=node.class_name, base_class=node.base_class_name,
                                              logger=node.name,
                                              headers=((header, node.base_file.removeprefix("include/")),))
            result = code.port_cpp(mine, old_starter, new_starter, context)
        _settled(project, source, target)
        # in the user's encoding and line ends; a conflict as --conflict says (markers, or a .rej file)
        if not merge.write_conflicted(project, target, result.text, like=source):
            continue
        if source != target:
            project.remove(source)
        report.ported.append(Ported(target, source, _rewrite_lines(result), result.todos))
        handled |= {source, target}
    return handled


def _languages(package: Package) -> tuple[str, ...]:
    return tuple(language for language, nodes in (("cpp", package.cpp_nodes), ("python", package.python_nodes))
                 if nodes) or ("cpp", "python")


def _carried(project: Project, old: Render, new: Render, source: str, target: str, report: Report,
             carry, renamed=None) -> set[str]:
    """A generated file the user edited, carried by `carry(mine, generated, fresh)` from `source` to `target`;
    `renamed(text)` first names the nodes the update renames by their new names, in the user's text and
    the old render alike."""
    mine, generated, fresh = project.committed(source), old.text(source), new.text(target)
    if mine is None or generated is None or fresh is None or mine == generated:
        return set()
    if renamed is not None:
        mine, generated = renamed(mine), renamed(generated)
    result = carry(mine, generated, fresh)
    if not project.write(target, result.text, like=source):
        return set()
    if source != target:
        project.remove(source)
    _settled(project, source, target)
    report.ported.append(Ported(target, source, tuple(result.rewrites), result.todos))
    return {source, target}


def _new_names(packages: tuple[Package, Package], renamed: dict[str, str]) -> dict[str, str]:
    """Old name -> new name of each node this update renames (`renamed`: new name -> old name)."""
    old_package, new_package = packages
    return {before: after for after, before in renamed.items() if before != after
            and _node(old_package, before) is not None and _node(new_package, after) is not None}


def _renaming(packages: tuple[Package, Package], renamed: dict[str, str]):
    """What names the renamed nodes by their new names in a build or launch file's lines (rna.update.renames)."""
    names = _new_names(packages, renamed)
    if not names:
        return None
    return lambda text: renames.renamed_lines(text, names, packages[0].name)


def port_build_files(project: Project, old: Render, new: Render, packages: tuple[Package, Package],
                     report: Report, renamed: dict[str, str] | None = None) -> set[str]:
    """The user's lines of CMakeLists.txt and package.xml (the package's, its interfaces package's)."""
    old_package, new_package = packages
    names = _new_names(packages, renamed or {})
    handled = set()
    folders = [(old_package.dir, new_package.dir, True)]
    if old_package.interfaces_package and new_package.interfaces_package:
        folders.append((old_package.interfaces_package, new_package.interfaces_package, False))
    languages = _languages(new_package)
    for old_folder, new_folder, nodes in folders:
        cmake, xml = (posixpath.normpath(posixpath.join(folder, name)) for folder, name in
                      ((old_folder, "CMakeLists.txt"), (old_folder, "package.xml")))
        new_cmake = posixpath.normpath(posixpath.join(new_folder, "CMakeLists.txt"))
        fresh = new.text(new_cmake) or ""
        context = build.CMakeContext(
            old_package.name, tuple(names.get(node.name, node.name) for node in old_package.cpp_nodes) if nodes else (),
            frozenset(re.findall(r"find_package\(\s*([\w-]+)", fresh)), languages)
        handled |= _carried(project, old, new, cmake, new_cmake, report,
                            lambda mine, generated, fresh, context=context: build.carry_cmake(mine, generated, fresh,
                                                                                              context),
                            _renaming(packages, renamed or {}) if nodes else None)
        handled |= _carried(project, old, new, xml, posixpath.normpath(posixpath.join(new_folder, "package.xml")),
                            report, lambda mine, generated, fresh: build.carry_package_xml(mine, generated, fresh,
                                                                                          languages))
    return handled


ROS1_LAUNCH = ".launch"  # roslaunch's files; ROS 2 reads XML ones named *.launch.xml


def launch_context(project: Project, packages: tuple[Package, Package],
                   renamed: dict[str, str] | None = None) -> build.LaunchContext:
    """The package's nodes' executables and launch files, ROS 1's -> ROS 2's (a renamed node's: its new one)."""
    old_package, new_package = packages
    names = _new_names(packages, renamed or {})
    executables = tuple((ros1, next(n.executable for n in new_package.nodes
                                    if n.name == names.get(node.name, node.name)))
                        for node in old_package.nodes
                        if any(n.name == names.get(node.name, node.name) for n in new_package.nodes)
                        # a renamed node's as the user wrote it, and as its lines renamed name it
                        for ros1 in dict.fromkeys((node.executable, renames.renamed_lines(
                            node.executable, names, old_package.name))))
    launch = f"{_in(old_package, 'launch')}/"
    files = {path[len(launch):]: path[len(launch):] + ".xml" for path in project.committed_files
             if path.startswith(launch) and path.endswith(ROS1_LAUNCH) and "/" not in path[len(launch):]}
    files[posixpath.basename(old_package.launch_file)] = posixpath.basename(new_package.launch_file)
    return build.LaunchContext(new_package.name, executables, new_package.launch_format,
                               tuple(sorted(files.items())))


def port_launch_file(project: Project, old: Render, new: Render, packages: tuple[Package, Package],
                     report: Report, renamed: dict[str, str] | None = None) -> set[str]:
    """The user's lines of the roslaunch file, in the ROS 2 launch file."""
    old_package, new_package = packages
    if old_package.target == "node":
        return set()
    context = launch_context(project, packages, renamed)
    return _carried(project, old, new, _in(old_package, old_package.launch_file),
                    _in(new_package, new_package.launch_file), report,
                    lambda mine, generated, fresh: build.carry_launch(mine, generated, fresh, context),
                    _renaming(packages, renamed or {}))


def port_own_launch_files(project: Project, old: Render, packages: tuple[Package, Package],
                          report: Report, renamed: dict[str, str] | None = None) -> set[str]:
    """The user's own roslaunch files in the package's launch/, as ROS 2 XML launch files beside it."""
    old_package, _ = packages
    if old_package.target == "node":
        return set()
    context = launch_context(project, packages, renamed)
    launch = f"{_in(old_package, 'launch')}/"
    handled = set()
    for path in sorted(project.committed_files):
        if not path.startswith(launch) or not path.endswith(ROS1_LAUNCH) or path in old.files:
            continue
        target = path + ".xml"
        if (project.root / target).exists():
            continue
        mine = project.committed(path)
        if mine is None:
            continue  # not text: left as it is
        renaming = _renaming(packages, renamed or {})
        result = build.port_launch_file(renaming(mine) if renaming else mine, context)
        if not project.write(target, result.text, like=path):
            continue
        project.remove(path)
        report.ported.append(Ported(target, path, tuple(result.rewrites), result.todos))
        handled |= {path, target}
    return handled


def port_config_files(project: Project, old: Render, new: Render, packages: tuple[Package, Package],
                      report: Report, renamed: dict[str, str] | None = None) -> set[str]:
    """Each tuned config file in `ros__parameters` form, the user's values, lines and comments kept
    (a renamed node's in its new name's file)."""
    old_package, new_package = packages
    handled = set()
    for node in new_package.nodes:
        before = _node(old_package, (renamed or {}).get(node.name, node.name))
        if before is None:
            continue
        source, target = _in(old_package, before.config_file), _in(new_package, node.config_file)
        mine, generated, fresh = project.committed(source), old.text(source), new.text(target)
        if mine is None or generated is None or fresh is None or mine == generated:
            continue
        head = next((index for index, line in enumerate(fresh.split("\n")) if line.startswith("/**:")), 0)
        ours, base = build.ros2_config(mine, head), build.ros2_config(generated, head)
        text, conflicted = merge.merge3(ours, base, fresh)
        _settled(project, source, target)  # Copier's leftovers go before this step writes its own .rej
        if conflicted:
            descriptions = (config_merge.descriptions_of(old_package, source),
                            config_merge.descriptions_of(new_package, target))
            merged = config_merge.merge(base, ours, fresh, descriptions)
            if merged is not None:
                config_merge.write_merged(project, target, merged)
                text = None
        if text is not None:
            merge.write_conflicted(project, target, text)
        report.ported.append(Ported(target, None, ("its parameters under /**: ros__parameters:",), 0))
        handled |= {source, target}
    return handled


def port_own_code(project: Project, old: Render, new: Render, packages: tuple[Package, Package],
                  report: Report) -> set[str]:
    """The user's own code files in the package: Python modules of the ROS 1 Python package move to the
    ROS 2 one; each is rewritten by the rules (no base class here)."""
    old_package, new_package = packages
    folder = f"{old_package.dir}/" if old_package.dir != "." else ""
    old_python = _in(old_package, layout.python_package_dir(old_package.name, 1)) + "/"
    new_python = _in(new_package, layout.python_package_dir(new_package.name, 2)) + "/"
    context = python.Context(logger=new_package.name, kinds=kinds(old_package))
    handled = set()
    for path in sorted(project.committed_files):
        if not path.startswith(folder) or path in old.files or not path.endswith(CODE_SUFFIXES):
            continue
        target = path
        if path.startswith(old_python) and new_package.python_dir and path.endswith(".py"):
            target = new_python + path[len(old_python):]
            if (project.root / target).exists() and target not in handled:
                report.problems.append(f"{path} stays where it was: {target} is the template's now.")
                continue
        text = project.committed(path)
        if text is None:
            continue
        if path.endswith(".py"):
            result = code.port_other_python(text, context)
        else:
            result = code.port_other_cpp(text, cpp.Context(logger=new_package.name, kinds=context.kinds))
        if result.text == text and target == path:
            continue
        if target != path:
            project.restore(path, to=target)
            project.remove(path)
        if not project.write(target, result.text, like=path):
            continue
        report.ported.append(Ported(target, path, _rewrite_lines(result), result.todos))
        handled |= {path, target}
    return handled


def port_package(project: Project, old: Render, new: Render, packages: tuple[Package, Package], report: Report,
                 renamed: dict[str, str] | None = None) -> set[str]:
    """ROS 1 -> ROS 2: the user's files carried and ported; returns the paths handled here."""
    if not porting(packages):
        return set()
    renamed = renamed or {}
    handled = port_node_files(project, old, new, packages, report, renamed)
    if packages[0].target == "package":  # a node's own package is the user's: only the node is ported
        handled |= port_own_code(project, old, new, packages, report)
        handled |= port_build_files(project, old, new, packages, report, renamed)
    handled |= port_launch_file(project, old, new, packages, report, renamed)
    handled |= port_own_launch_files(project, old, packages, report, renamed)
    handled |= port_config_files(project, old, new, packages, report, renamed)
    names = _new_names(packages, renamed)
    if names and packages[0].target == "package":
        report.notes.append(f"Your lines of the build and launch files naming {', '.join(sorted(names))} "
                            f"name {', '.join(names[name] for name in sorted(names))}, as the nodes are renamed.")
    report.review = "git add -A . && git diff --staged -M HEAD"
    report.notes.append(
        f"Ported from ROS 1: the ROS 1 package is your last commit. Compare each file with it: "
        f"{report.review} (-M pairs a moved file with the file it was).")
    return handled
