"""Managed blocks that take the user's own lines into account.

package.xml and the build files hold blocks between `BEGIN rna-template` and `END
rna-template` markers that the template rewrites from the answers; the docs tell users
to add their own lines below the END marker. A package the user declared there and the
answers come to need too would then be declared twice, which catkin_pkg refuses
("The generic dependency on 'x' is redundant"). The rule here: what the user declares
outside the blocks is the user's, and the block leaves it out (only the dependency types
the user's lines do not already give stay in the block).

The other way round, a package the answers stop needing leaves the blocks; when the
user's own code still includes or imports it, the update says so.

And every package.xml is checked as catkin_pkg would, without it (Copier's Python does
not have it): well-formed, no dependency declared twice.
"""

from __future__ import annotations

import posixpath
import re
import xml.etree.ElementTree as ET

from .project import Project, Render
from .protect import edited
from .summary import Report

BLOCK = re.compile(r"^[^\n]*BEGIN rna-template[^\n]*\n.*?^[^\n]*END rna-template[^\n]*$", re.M | re.S)
DEPENDENCY = re.compile(r"^(?P<indent>[ \t]*)<(?P<tag>\w+)(?P<attrs>[^>]*)>\s*(?P<name>[\w.-]+)\s*</(?P=tag)>[ \t]*$")
# What each package.xml tag declares (format 3).
TYPES = {
    "depend": frozenset({"build", "build_export", "exec"}),
    "build_depend": frozenset({"build"}),
    "build_export_depend": frozenset({"build_export"}),
    "exec_depend": frozenset({"exec"}),
    "buildtool_depend": frozenset({"buildtool"}),
    "buildtool_export_depend": frozenset({"buildtool_export"}),
    "test_depend": frozenset({"test"}),
    "doc_depend": frozenset({"doc"}),
}
SPECIFIC = ("build_depend", "build_export_depend", "exec_depend")
IGNORE_MARKERS = ("COLCON_IGNORE", "CATKIN_IGNORE", "AMENT_IGNORE")


def split(text: str) -> list[tuple[bool, str]]:
    """The text as (inside a managed block?, piece) in order."""
    pieces, start = [], 0
    for match in BLOCK.finditer(text):
        pieces += [(False, text[start:match.start()]), (True, match[0])]
        start = match.end()
    return [*pieces, (False, text[start:])]


def declared(text: str, inside: bool | None = None) -> dict[str, set[str]]:
    """package -> the dependency types package.xml lines declare (inside/outside the blocks, or all)."""
    found: dict[str, set[str]] = {}
    for in_block, piece in split(text):
        if inside is not None and in_block != inside:
            continue
        for line in _without_comments(piece).splitlines():
            match = DEPENDENCY.match(line)
            if match and match["tag"] in TYPES:
                found.setdefault(match["name"], set()).update(TYPES[match["tag"]])
    return found


def _without_comments(text: str) -> str:
    return re.sub(r"<!--.*?-->", lambda m: "\n" * m[0].count("\n"), text, flags=re.S)


def package_xml_without_duplicates(text: str) -> tuple[str, list[str]]:
    """package.xml with each block line the user's own lines already declare left out (or narrowed)."""
    users = declared(text, inside=False)
    left_out: list[str] = []

    def narrowed(block: str) -> str:
        lines = []
        for line in block.split("\n"):
            match = DEPENDENCY.match(line)
            if not match or match["tag"] not in TYPES or match["name"] not in users:
                lines.append(line)
                continue
            remaining = TYPES[match["tag"]] - users[match["name"]]
            if remaining == TYPES[match["tag"]]:
                lines.append(line)
                continue
            left_out.append(match["name"])
            lines += [f"{match['indent']}<{tag}{match['attrs']}>{match['name']}</{tag}>"
                      for tag in SPECIFIC if TYPES[tag] <= remaining]
        return "\n".join(lines)

    merged = "".join(narrowed(piece) if inside else piece for inside, piece in split(text))
    return merged, left_out


def cmake_without_duplicates(text: str) -> tuple[str, list[str]]:
    """CMakeLists.txt with each block line that repeats one of the user's lines (find_package) left out."""
    def normal(line: str) -> str:
        return " ".join(line.split())

    users = {normal(line) for inside, piece in split(text) if not inside for line in piece.splitlines()}
    left_out: list[str] = []

    def narrowed(block: str) -> str:
        lines = []
        for line in block.split("\n"):
            if line.lstrip().startswith("find_package(") and normal(line) in users:
                left_out.append(normal(line))
            else:
                lines.append(line)
        return "\n".join(lines)

    return "".join(narrowed(piece) if inside else piece for inside, piece in split(text)), left_out


def package_xml_problems(text: str) -> list[str]:
    """Why catkin_pkg would refuse this package.xml (the checks an update can break), or []."""
    try:
        root = ET.fromstring(text)  # text: the declared encoding was read already (rna/files.py)
    except ET.ParseError as error:
        return [f"it is not well-formed XML ({error})"]
    tags: dict[str, list[str]] = {}
    for element in root:
        if element.tag in TYPES and (element.text or "").strip():
            tags.setdefault(element.text.strip(), []).append(element.tag)
    problems = []
    for name, found in tags.items():
        others = [tag for tag in found if tag in SPECIFIC]
        if "depend" in found and (others or found.count("depend") > 1):
            again = ", ".join(f"<{tag}>" for tag in others) or "<depend>"
            problems.append(f"{name} is declared by <depend> and again by {again}")
    return problems


CPP_SUFFIXES = (".cpp", ".hpp", ".h", ".cc", ".hh", ".hxx", ".cxx")
CODE_SUFFIXES = (*CPP_SUFFIXES, ".py")


def uses(text: str, package: str, suffix: str) -> bool:
    """Whether code in a C++ or Python file includes or imports `package`."""
    name = re.escape(package)
    if suffix in CPP_SUFFIXES:
        return re.search(rf"^\s*#\s*include\s*[<\"]{name}/", text, re.M) is not None
    if suffix == ".py":
        return re.search(rf"^\s*(?:from|import)\s+{name}(?:\.|\s|$)", text, re.M) is not None
    return False


# --- the steps of the update


def leave_out_user_declarations(project: Project, new: Render, report: Report) -> None:
    """Every generated package.xml and CMakeLists.txt: block lines the user's own lines repeat leave the block."""
    for path in sorted(new.files):
        name = posixpath.basename(path)
        text = project.text(path)
        if name not in ("package.xml", "CMakeLists.txt") or text is None or "<<<<<<< " in text:
            continue
        fixed, left_out = (package_xml_without_duplicates if name == "package.xml" else cmake_without_duplicates)(text)
        if left_out:
            project.write(path, fixed)
            report.notes.append(f"{path}: the managed block leaves out {', '.join(left_out)}: your own lines "
                                "below its END marker declare it.")


def dropped_but_used(project: Project, old: Render, report: Report) -> None:
    """A package that left package.xml while the user's own code still includes or imports it is named."""
    for path in sorted(p for p in project.committed_files if posixpath.basename(p) == "package.xml"):
        before, after = project.committed(path), project.text(path)
        if after is None or "<<<<<<< " in after:
            continue
        dropped = set(declared(before or "")) - set(declared(after))
        if not dropped:
            continue
        folder = posixpath.dirname(path)
        for file in sorted(project.committed_files):
            suffix = posixpath.splitext(file)[1]
            if suffix not in CODE_SUFFIXES or not file.startswith(f"{folder}/" if folder else "") \
                    or not edited(project, old, file):
                continue  # not code, not in this package, or not the user's
            text = project.text(file)
            for package in sorted(dropped):
                if text is not None and uses(text, package, suffix):
                    report.problems.append(
                        f"{package} is no longer a dependency in {path} (the answers stopped using it), but your "
                        f"{file} still {'imports' if suffix == '.py' else 'includes'} it: declare it below the END "
                        "marker there (and find_package() it), or stop using it.")


def unreadable_package_xml(project: Project, report: Report) -> None:
    """Every package.xml the workspace would read is one catkin_pkg and colcon read."""
    for path in sorted(p for p in project.current_files() if posixpath.basename(p) == "package.xml"):
        folder = posixpath.dirname(path)
        text = project.text(path) or ""
        if "<<<<<<< " in text or any((project.root / folder / marker).exists() for marker in IGNORE_MARKERS):
            continue  # a conflict, listed as such; or a folder the workspace leaves out
        report.problems += [f"{path} would not build: {problem}." for problem in package_xml_problems(text)]
