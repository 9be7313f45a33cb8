"""A node renamed carries the user's files, tuned values and lines to its new name.

Copier sees a rename as a node removed and another added: the old node's files go (or
are kept, when edited), the new one starts from the starter, and the user's lines that
name the old executable (target_link_libraries(driver ...), a console script, a launch
remap) name something that no longer exists. A node answer that says what it was renamed
from (`renamed_from: driver`; the edit_nodes dialog writes it) makes the update carry:

- the user's node file, moved to the new name, the identifiers the template owns in it
  renamed (the class and its base class, the base module or header, the node's name as
  the starter wrote it), every other line as the user wrote it;
- the tuned config file, merged by parameter into the new node's config;
- the user's lines of the package's build files and launch file that name the old node
  (its target, executable, module, config file), renamed, then merged as any update;
- and the answer itself is consumed: the answers file records the new name only.
"""

from __future__ import annotations

import difflib
import os
import posixpath
import re
from collections.abc import Mapping

from ..configs import yaml_literal
from ..model import Node, Package
from . import config_merge, merge
from .project import Project, Render
from .protect import edited
from .summary import Report

# Files whose lines name a node's target, executable or module, by name.
BUILD_AND_LAUNCH = re.compile(r"(^|/)(CMakeLists\.txt|setup\.py|setup\.cfg|[^/]*\.launch(\.xml|\.py)?)$")


# --- rewriting text


def _mentions(line: str, old: Node) -> bool:
    return re.search(rf"\b({re.escape(old.name)}|{re.escape(old.class_name)})", line) is not None


def starter_lines(old_starter: str, new_starter: str, old: Node) -> dict[str, str]:
    """Lines of the old starter the new one writes otherwise because of the name: old line -> new line."""
    before, after = old_starter.split("\n"), new_starter.split("\n")
    pairs: dict[str, str] = {}
    for tag, i1, i2, j1, j2 in difflib.SequenceMatcher(None, before, after, autojunk=False).get_opcodes():
        if tag != "replace" or i2 - i1 != j2 - j1:
            continue
        for line, other in zip(before[i1:i2], after[j1:j2], strict=True):
            if line.strip() and _mentions(line, old) and pairs.get(line, other) == other:
                pairs[line] = other
    return pairs


def renamed_code(text: str, old: Node, new: Node, old_starter: str | None, new_starter: str | None) -> str:
    """The user's node file with what the template owns in it renamed, every other line kept."""
    pairs = starter_lines(old_starter, new_starter, old) if old_starter and new_starter else {}
    lines = [pairs.get(line, line) for line in text.split("\n")]
    result = "\n".join(lines)
    for before, after in ((old.base_class_name, new.base_class_name), (old.class_name, new.class_name),
                          (old.base_name, new.base_name)):
        result = re.sub(rf"\b{re.escape(before)}\b", after, result)
    # the node's name as a string literal: rospy.init_node('driver'), ros::init(..., "driver")
    return re.sub(rf"(['\"]){re.escape(old.name)}\1", lambda m: f"{m[1]}{new.name}{m[1]}", result)


def _target(old: str, package: str) -> re.Pattern:
    """The old node's name as a build or launch file names its target, executable, module or config."""
    prefixes = rf"\$\{{PROJECT_NAME\}}_|{re.escape(package)}_"
    return re.compile(rf"(?<![A-Za-z0-9_])((?:{prefixes})?){re.escape(old)}(?![A-Za-z0-9_])")


def _comment(line: str) -> bool:
    return line.lstrip().startswith(("#", "<!--"))


def renamed_lines(text: str, names: Mapping[str, str], package: str) -> str:
    """A build or launch file with each line (not a comment) naming an old node renamed."""
    lines = text.split("\n")
    for old, new in names.items():
        pattern = _target(old, package)
        lines = [line if _comment(line) else pattern.sub(rf"\g<1>{new}", line) for line in lines]
    return "\n".join(lines)


def still_named(text: str, names: Mapping[str, str], package: str) -> list[tuple[int, str]]:
    """(line number, old name) of each line outside a comment that names an old node."""
    found = []
    for number, line in enumerate(text.split("\n"), 1):
        for old in names:
            if not _comment(line) and _target(old, package).search(line):
                found.append((number, old))
    return found


# --- the step of the update


def _node(package: Package, name: str) -> Node | None:
    return next((node for node in package.nodes if node.name == name), None)


def _in(package: Package, path: str) -> str:
    return posixpath.normpath(posixpath.join(package.dir, path))


def carry_renamed_nodes(project: Project, old: Render, new: Render, packages: tuple[Package, Package],
                        names: Mapping[str, str], report: Report) -> set[str]:
    """Carry each renamed node's files and lines; returns the paths handled here (left alone by later steps)."""
    old_package, new_package = packages
    pairs = {before: after for after, before in names.items() if before != after
             and _node(old_package, before) and _node(new_package, after)}
    handled: set[str] = set()
    if not pairs:
        return handled
    # With the package renamed in the same update, its step has moved the build and launch
    # files already, and the node's file must have the package's name changed too.
    package_names = _package_names(old_package, new_package) if _package_renamed(packages) else {}
    for before, after in pairs.items():
        old_node, new_node = _node(old_package, before), _node(new_package, after)
        handled |= _carry_user_file(project, old, new, packages, old_node, new_node, report, package_names)
        handled |= _carry_config(project, old, new, packages, old_node, new_node, report)
    if package_names:
        handled |= _rename_in_moved_files(project, old, packages, pairs, package_names, report)
    else:
        handled |= _rename_in_build_and_launch_files(project, old, new, new_package, pairs, report)
    return handled


def _package_renamed(packages: tuple[Package, Package]) -> bool:
    return packages[0].name != packages[1].name and packages[0].target == "package"


def _carry_user_file(project, old, new, packages, old_node: Node, new_node: Node, report: Report,
                     package_names: Mapping[str, str]) -> set[str]:
    source, target = _in(packages[0], old_node.user_file), _in(packages[1], new_node.user_file)
    if not edited(project, old, source):
        return set()  # the starter: the new one follows the template
    if old_node.language != new_node.language:
        return set()  # another language: kept and named (protect.py)
    text = renamed_code(project.committed(source), old_node, new_node, old.text(source), new.text(target))
    if package_names:
        text = package_renamed_text(text, package_names, _suffix(target))
    project.restore(source, to=target)  # with its mode: an executable script stays one
    if not project.write(target, text, like=source):
        return set()
    project.remove(source)
    report.renamed.append((source, target))
    return {source, target}


def _carry_config(project, old, new, packages, old_node: Node, new_node: Node, report: Report) -> set[str]:
    source, target = _in(packages[0], old_node.config_file), _in(packages[1], new_node.config_file)
    mine, generated, fresh = project.committed(source), old.text(source), new.text(target)
    if mine is None or generated is None or fresh is None or mine == generated:
        return set()
    pairs = starter_lines(generated, fresh, old_node)
    mine = "\n".join(pairs.get(line, line) for line in mine.split("\n"))
    descriptions = (config_merge.descriptions_of(packages[0], source),
                    config_merge.descriptions_of(packages[1], target))
    merged = config_merge.merge(generated, mine, fresh, descriptions)
    if merged is None or not config_merge.write_merged(project, target, merged):
        return set()  # not YAML the merge reads: kept where it was and named (protect.py)
    project.remove(source)
    if (project.root / f"{source}.rej").exists():  # Copier's, for the file the rename moves
        project.remove(f"{source}.rej")
    report.renamed.append((source, target))
    report.merged.add(target)
    for name, (yours, theirs) in merged.conflicts.items():
        report.notes.append(f"{target}: you tuned {name} to {yaml_literal(yours)} and its default is now "
                            f"{yaml_literal(theirs)}: keep one.")
    return {source, target}


def _rename_in_build_and_launch_files(project, old, new, package: Package, pairs: Mapping[str, str],
                                      report: Report) -> set[str]:
    """The user's lines naming a renamed node: renamed in the user's text and the old render alike, then merged."""
    handled = set()
    folder = f"{package.dir}/" if package.dir != "." else ""
    for path in sorted(project.committed_files):
        if not path.startswith(folder) or not BUILD_AND_LAUNCH.search(path):
            continue
        mine, generated, fresh = project.committed(path), old.text(path), new.text(path)
        if mine is None or mine == generated:
            continue  # untouched: Copier's result is the new render
        if generated is None or fresh is None:  # the user's own file: said, not rewritten
            for number, name in still_named(mine, pairs, package.name):
                report.problems.append(f"{path}:{number} still names the node '{name}', renamed "
                                       f"'{pairs[name]}': rename it there.")
            continue
        ours, base = renamed_lines(mine, pairs, package.name), renamed_lines(generated, pairs, package.name)
        text, conflicted = merge.merge3(ours, base, fresh)
        if not project.write(path, text):
            continue
        rejected = project.root / f"{path}.rej"
        if rejected.exists():
            rejected.unlink()
        if not conflicted:
            project.resolve_in_index(path)
        if text != fresh:
            report.merged.add(path)
        if ours != mine:
            report.notes.append(f"{path}: your lines naming {', '.join(sorted(pairs))} now name "
                                f"{', '.join(pairs[name] for name in sorted(pairs))}.")
        handled.add(path)
    return handled


def _rename_in_moved_files(project, old, packages: tuple[Package, Package], pairs: Mapping[str, str],
                           package_names: Mapping[str, str], report: Report) -> set[str]:
    """The user's lines naming a renamed node, in the build and launch files the package's rename moved."""
    handled = set()
    for path in sorted(project.committed_files):
        target = package_path(path, package_names)
        if not path.startswith(f"{packages[0].dir}/") or not BUILD_AND_LAUNCH.search(target):
            continue
        mine, current = project.committed(path), project.text(target)
        if current is None or mine == old.text(path):
            continue  # untouched: the new render already names the new node
        if old.text(path) is None:  # the user's own file: said, not rewritten
            for number, name in still_named(current, pairs, packages[1].name):
                report.problems.append(f"{target}:{number} still names the node '{name}', renamed "
                                       f"'{pairs[name]}': rename it there.")
            continue
        text = renamed_lines(current, pairs, packages[1].name)
        if text != current and project.write(target, text):
            report.notes.append(f"{target}: your lines naming {', '.join(sorted(pairs))} now name "
                                f"{', '.join(pairs[name] for name in sorted(pairs))}.")
        handled.add(target)
    return handled


# --- the package renamed

CODE_SUFFIXES = {".py": "#", ".cfg": "#", ".txt": "#", ".cmake": "#", ".yaml": "#", ".yml": "#",
                 ".cpp": "//", ".cc": "//", ".cxx": "//", ".hpp": "//", ".h": "//", ".hh": "//", ".hxx": "//",
                 ".xml": "<!--", ".launch": "<!--"}


def _package_names(old: Package, new: Package) -> dict[str, str]:
    """Old name -> new name of the package, and of its interfaces package."""
    names = {old.name: new.name}
    if old.interfaces_package and new.interfaces_package:
        names[old.interfaces_package] = new.interfaces_package
    return names


def package_path(path: str, names: Mapping[str, str]) -> str:
    """Where a file of the old package goes: each folder or file named after the package renamed."""
    parts = []
    for part in path.split("/"):
        for old, new in sorted(names.items(), key=lambda item: -len(item[0])):
            if part == old or part.startswith(f"{old}."):
                part = new + part[len(old):]
                break
        parts.append(part)
    return "/".join(parts)


def package_renamed_text(text: str, names: Mapping[str, str], suffix: str) -> str:
    """A file's text with each word naming the package renamed, outside comment lines."""
    comment = CODE_SUFFIXES.get(suffix)
    if comment is None:
        return text
    alternatives = "|".join(re.escape(old) for old in sorted(names, key=len, reverse=True))
    pattern = re.compile(rf"(?<![A-Za-z0-9_])({alternatives})(?![A-Za-z0-9_])")
    lines = text.split("\n")
    return "\n".join(line if line.lstrip().startswith(comment) else pattern.sub(lambda m: names[m[1]], line)
                     for line in lines)


def _suffix(path: str) -> str:
    name = posixpath.basename(path)
    return ".txt" if name == "CMakeLists.txt" else posixpath.splitext(name)[1]


def _move(project: Project, path: str, target: str) -> bool:
    """Move a file as it is (bytes and mode), unless the target is taken; whether it moved."""
    source, destination = project.root / path, project.root / target
    if not (source.is_file() or source.is_symlink()) or os.path.lexists(destination):
        return False
    destination.parent.mkdir(parents=True, exist_ok=True)
    os.replace(source, destination)
    project.remove(path)  # the folders it leaves empty
    return True


def carry_renamed_package(project: Project, old: Render, new: Render, packages: tuple[Package, Package],
                          report: Report) -> set[str]:
    """The user's files of a renamed package moved to the new folders, the lines naming it renamed and merged."""
    old_package, new_package = packages
    if old_package.name == new_package.name or old_package.target != "package":
        return set()
    names = _package_names(old_package, new_package)
    folders = tuple(f"{name}/" for name in names)
    handled: set[str] = set()
    for path in sorted(project.committed_files):
        if not path.startswith(folders):
            continue
        target = package_path(path, names)
        generated, fresh, suffix = old.text(path), new.text(target), _suffix(path)
        mine = project.committed(path)
        if generated is None and (suffix not in CODE_SUFFIXES or mine is None):
            if _move(project, path, target):  # the user's own file, as it is (maps, meshes, notes, links...)
                handled |= {path, target}
            continue
        if generated is not None and mine == generated:
            continue  # untouched: Copier made the new one, or no longer makes it
        if generated is not None and fresh is None:
            continue  # edited, and the new answers do not make it: kept and named (protect.py)
        ours = package_renamed_text(mine, names, suffix)
        if generated is None:  # the user's own file: renamed where it names the package
            text, conflicted = ours, False
            if fresh is not None and fresh != ours:
                text, conflicted = merge.merge3(ours, "", fresh)
        else:
            text, conflicted = merge.merge3(ours, package_renamed_text(generated, names, suffix), fresh)
        project.restore(path, to=target)  # with its mode
        if not project.write(target, text, like=path):
            continue
        project.remove(path)
        if (project.root / f"{path}.rej").exists():
            project.remove(f"{path}.rej")
        if not conflicted:
            project.resolve_in_index(target)
        handled |= {path, target}
    for old_name, new_name in names.items():
        if any(path.startswith(f"{old_name}/") for path in handled):
            report.renamed.append((f"{old_name}/", f"{new_name}/"))
    if handled:
        report.notes.append(
            f"The package is {new_package.name} now: your files moved with it and your lines naming "
            f"{' and '.join(names)} name {' and '.join(names.values())} (comment lines left as written). "
            f"Rename it where this project does not reach: other packages' package.xml and find_package(), "
            f"your scripts and `ros2 launch`/`roslaunch` commands, and rebuild the workspace from clean.")
    return handled
