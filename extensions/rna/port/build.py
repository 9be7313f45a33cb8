"""The user's lines of the build files and the launch file, carried from ROS 1 to ROS 2.

The template makes CMakeLists.txt, package.xml and the launch file afresh for ROS 2; the
user's own lines in the ROS 1 ones (what differs from the ROS 1 render) are carried into
them, each run after the line it followed (the marker that ends a managed block maps to
ROS 2's marker of the same block; a line inside a block goes after its end), and ported:

- CMake: catkin's install destinations and target names become ament's, catkin's
  variables leave the lists they were in, `find_package(catkin COMPONENTS ...)` becomes one
  `find_package()` a package, `CATKIN_DEPENDS` becomes `ament_export_dependencies()`;
- package.xml: each dependency named as ROS 2 names it (rna.port.dependencies);
- launch XML: roslaunch's attributes and substitutions become ROS 2's (`type` -> `exec`,
  `$(find pkg)` -> `$(find-pkg-share pkg)`, `<rosparam file>` -> `<param from>`...).

What names ROS 1 things and no rule ports is carried commented out under a
`TODO(port)` note (a ROS 1 command or element would stop the build or the launch).
Config files move to `ros__parameters` form (`ros2_config`).
"""

from __future__ import annotations

import difflib
import re
import textwrap
from collections.abc import Callable
from dataclasses import dataclass, field

from . import dependencies
from .rule import TODO, Rule

WIDTH = 99

RULES = (
    Rule("cmake.destinations", "CMake", "${CATKIN_PACKAGE_BIN_DESTINATION}, ..._LIB_, ..._SHARE_, ..._INCLUDE_",
         "lib/${PROJECT_NAME}, lib, share/${PROJECT_NAME}, include/${PROJECT_NAME}"),
    Rule("cmake.catkin_variables", "CMake", "${catkin_INCLUDE_DIRS}, ${catkin_LIBRARIES}, ${catkin_EXPORTED_TARGETS}",
         "(left out: a target links the ROS 2 packages it uses)"),
    Rule("cmake.targets", "CMake", "${PROJECT_NAME}_<node> (catkin's target of a node)", "<node>",
         "target_link_libraries() of a node's target with PRIVATE, as ament_cmake's"),
    Rule("cmake.find_package", "CMake", "find_package(catkin REQUIRED COMPONENTS a b)",
         "find_package(a REQUIRED), find_package(b REQUIRED), each named as in ROS 2"),
    Rule("cmake.exports", "CMake", "catkin_package(CATKIN_DEPENDS a b)", "ament_export_dependencies(a b)"),
    Rule("cmake.install_python", "CMake", "catkin_install_python(PROGRAMS f DESTINATION ...)",
         "install(PROGRAMS f DESTINATION lib/${PROJECT_NAME})"),
    Rule("cmake.testing", "CMake", "if(CATKIN_ENABLE_TESTING)", "if(BUILD_TESTING)"),
    Rule("cmake.todo", "CMake", "catkin_package(), add_message_files(), generate_messages(), add_rostest(), "
         "catkin_add_gtest(), catkin_add_nosetests(), catkin_python_setup()",
         "ament_export_*(), rosidl_generate_interfaces(), add_launch_test(), ament_add_gtest(), "
         "ament_add_pytest_test(), ament_python_install_package()", todo=True),
    Rule("xml.depend", "package.xml", "<depend>roscpp</depend> and every dependency tag",
         "<depend>rclcpp</depend>: the ROS 2 name (rna.port.dependencies)"),
    Rule("xml.todo", "package.xml", "a dependency ROS 2 has no counterpart of (dynamic_reconfigure...)",
         "what ROS 2 does instead", todo=True),
    Rule("launch.exec", "launch", '<node pkg="p" type="t" ns="n" required="true">',
         '<node pkg="p" exec="t" namespace="n" on_exit="shutdown">', "a node of the package: its ROS 2 executable"),
    Rule("launch.find", "launch", "$(find pkg)", "$(find-pkg-share pkg)"),
    Rule("launch.rosparam", "launch", '<rosparam command="load" file="f"/>', '<param from="f"/>'),
    Rule("launch.param", "launch", '<param name="n" value="v" type="t"/>', '<param name="n" value="v"/>'),
    Rule("launch.include", "launch", '<include file="$(find pkg)/launch/x.launch"/> of the package\'s own',
         '<include file="$(find-pkg-share pkg)/launch/x.launch.xml"/>', "the package's roslaunch files are ported too"),
    Rule("launch.set_parameter", "launch", '<param name="n" value="v"/> outside a <node>',
         '<set_parameter name="n" value="v"/>', "for every node the launch file starts after it"),
    Rule("launch.group", "launch", '<group ns="n">', '<group><push-ros-namespace namespace="n"/>'),
    Rule("launch.todo", "launch", "<include> of a ROS 1 launch file, <machine>, <test>, inline <rosparam>, "
         "textfile or command parameters", "ROS 2's launch actions", todo=True),
    Rule("config.ros__parameters", "config", "name: value (loaded by <rosparam> into the node)",
         "/**: ros__parameters: name: value (loaded by the launch file's <param from>)"),
)
BY_KEY = {rule.key: rule for rule in RULES}


@dataclass
class Carried:
    text: str
    rewrites: list[str] = field(default_factory=list)  # `line N: before -> after`, N in the ROS 1 file
    todos: int = 0


@dataclass(frozen=True)
class Run:
    """Lines of the user's in a generated file: after the generated line `anchor` (-1: the top)."""

    anchor: int
    lines: tuple[str, ...]
    first: int  # the line number of its first line in the user's file (from 1)


def user_runs(mine: str, generated: str) -> list[Run]:
    """The user's runs of lines: added, or changed from the generated ones."""
    ours, base = mine.split("\n"), generated.split("\n")
    runs = []
    for tag, i1, _, j1, j2 in difflib.SequenceMatcher(None, base, ours, autojunk=False).get_opcodes():
        if tag in ("insert", "replace") and any(line.strip() for line in ours[j1:j2]):
            runs.append(Run(i1 - 1, tuple(ours[j1:j2]), j1 + 1))
    return runs


BLOCK_BEGIN = re.compile(r"BEGIN rna-template")
BLOCK_END = re.compile(r"END rna-template")


def _marker_role(line: str) -> str | None:
    """What a managed block's END marker ends, in words both generations share; None for other lines."""
    match = re.search(r"END rna-template(?::\s*(.*?))?\s*(?:-->)?\s*$", line)
    if not match:
        return None
    words = (match[1] or "").lower()
    for role in ("find_package", "targets", "tests", "dependencies", "nodes", "actions", "executables"):
        if role.rstrip("s") in words or (role == "find_package" and "packages to find_package" in words):
            return {"nodes": "launch", "actions": "launch"}.get(role, role)
    return words or "end"


def place(base: list[str], theirs: list[str], anchor: int, default: int) -> int:
    """Where a run that followed `base[anchor]` goes in `theirs`: the index of the line it follows."""
    index = anchor
    # Inside a managed block, the run goes after the block (the next update rewrites the block).
    depth = 0
    for line in base[:anchor + 1]:
        depth += bool(BLOCK_BEGIN.search(line)) - bool(BLOCK_END.search(line))
    if depth > 0:
        index = next((i for i in range(anchor + 1, len(base)) if BLOCK_END.search(base[i])), anchor)
    stripped = [line.strip() for line in theirs]
    while index >= 0:
        line = base[index].strip()
        role = _marker_role(line)
        if role is not None:
            found = [i for i, other in enumerate(theirs) if _marker_role(other) == role]
            if found:
                return found[0]
        elif len(line) > 3 and stripped.count(line) == 1:
            return stripped.index(line)
        index -= 1
    return default


def carry(mine: str, generated: str, fresh: str, port_run: Callable[[list[str], int], tuple[list[str], list[str], int]],
          default: Callable[[list[str]], int], at_end: Callable[[str], bool] = lambda line: False) -> Carried:
    """`fresh` with the user's runs of `mine` (against `generated`) ported by `port_run` and put in place.

    `port_run(lines, first_line)` -> (lines, rewrites, todos); `default(theirs)`: where a run
    with no anchor goes; `at_end(line)`: a ported line that belongs at the default place.
    """
    base, theirs = generated.split("\n"), fresh.split("\n")
    inserts: dict[int, list[str]] = {}
    result = Carried(fresh)
    for run in user_runs(mine, generated):
        lines, rewrites, todos = port_run(list(run.lines), run.first)
        result.rewrites += rewrites
        result.todos += todos
        where = place(base, theirs, run.anchor, default(theirs))
        kept = [line for line in lines if not at_end(line)]
        last = [line for line in lines if at_end(line)]
        if kept:
            inserts.setdefault(where, []).extend(kept)
        if last:
            inserts.setdefault(default(theirs), []).extend(last)
    out = []
    for index, line in enumerate(theirs):
        out.append(line)
        out += inserts.get(index, [])
    result.text = "\n".join(out)
    return result


def _todo_lines(comment: str, text: str, indent: str = "") -> list[str]:
    """`text` as comment lines at `indent`: `# ...`, or `<!-- ... -->` each (`comment` "<!--")."""
    closing = " -->" if comment == "<!--" else ""
    if closing:
        text = text.removesuffix(" -->").replace("--", "- -")
    width = max(WIDTH - len(indent) - len(comment) - len(closing) - 1, 40)
    return [f"{indent}{comment} {line}{closing}" for line in textwrap.wrap(text, width, break_long_words=False,
                                                                           break_on_hyphens=False)]


# --- CMake

CMAKE_DESTINATIONS = {
    "CATKIN_PACKAGE_BIN_DESTINATION": "lib/${PROJECT_NAME}",
    "CATKIN_PACKAGE_LIB_DESTINATION": "lib",
    "CATKIN_PACKAGE_SHARE_DESTINATION": "share/${PROJECT_NAME}",
    "CATKIN_PACKAGE_INCLUDE_DESTINATION": "include/${PROJECT_NAME}",
    "CATKIN_PACKAGE_ETC_DESTINATION": "share/${PROJECT_NAME}",
    "CATKIN_GLOBAL_BIN_DESTINATION": "bin",
    "CATKIN_GLOBAL_LIB_DESTINATION": "lib",
    "CATKIN_GLOBAL_INCLUDE_DESTINATION": "include",
    "CATKIN_GLOBAL_SHARE_DESTINATION": "share",
}
CATKIN_VARIABLES = re.compile(r"\s*\$\{(?:catkin_INCLUDE_DIRS|catkin_LIBRARIES|catkin_EXPORTED_TARGETS|"
                              r"\$\{PROJECT_NAME\}_EXPORTED_TARGETS|[A-Za-z0-9_]+_generate_messages_cpp)\}")
CMAKE_TODO = {
    "catkin_package": "ament_export_dependencies(), ament_export_include_directories(), ament_export_targets()",
    "add_message_files": "rosidl_generate_interfaces() (the answers' interfaces make it)",
    "add_service_files": "rosidl_generate_interfaces() (the answers' interfaces make it)",
    "add_action_files": "rosidl_generate_interfaces() (the answers' interfaces make it)",
    "generate_messages": "rosidl_generate_interfaces() (the answers' interfaces make it)",
    "catkin_python_setup": "ament_python_install_package(${PROJECT_NAME})",
    "add_rostest": "add_launch_test() (launch_testing_ament_cmake)",
    "add_rostest_gtest": "add_launch_test() (launch_testing_ament_cmake)",
    "catkin_add_gtest": "ament_add_gtest() (ament_cmake_gtest)",
    "catkin_add_nosetests": "ament_add_pytest_test() (ament_cmake_pytest)",
    "catkin_lint": "ament_lint_auto",
}
ROS1_WORDS = re.compile(r"\b(catkin\w*|CATKIN\w*|roscpp|rospy|rostest|rosunit|genmsg|message_generation)\b")
REMOVED = "\0removed\0"  # a command that goes, with its line
EXPORT_KEYWORDS = ("CATKIN_DEPENDS", "DEPENDS", "INCLUDE_DIRS", "LIBRARIES", "CFG_EXTRAS")


@dataclass(frozen=True)
class CMakeContext:
    package: str
    nodes: tuple[str, ...]  # node targets: ${PROJECT_NAME}_<node> in ROS 1, <node> in ROS 2
    found: frozenset[str] = frozenset()  # packages the ROS 2 file finds already
    languages: tuple[str, ...] = ("cpp", "python")


def cmake_pieces(text: str) -> list[tuple[str, str]]:
    """("command", text) for each command (across lines), ("other", text) for what lies between."""
    pieces, position, index = [], 0, 0
    command = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\s*\(")
    while index < len(text):
        char = text[index]
        if char == "#":
            end = text.find("\n", index)
            index = len(text) if end < 0 else end
            continue
        match = command.match(text, index) if (index == 0 or not (text[index - 1].isalnum()
                                                                 or text[index - 1] == "_")) else None
        if not match:
            index += 1
            continue
        depth, cursor, quote = 0, match.end() - 1, False
        while cursor < len(text):
            c = text[cursor]
            if quote:
                quote = not (c == '"' and text[cursor - 1] != "\\")
            elif c == '"':
                quote = True
            elif c == "#":
                newline = text.find("\n", cursor)
                cursor = len(text) - 1 if newline < 0 else newline
            elif c == "(":
                depth += 1
            elif c == ")":
                depth -= 1
                if depth == 0:
                    break
            cursor += 1
        if depth != 0:
            break  # unbalanced: the rest is kept as it is
        if position < index:
            pieces.append(("other", text[position:index]))
        pieces.append(("command", text[index:cursor + 1]))
        index = position = cursor + 1
    if position < len(text):
        pieces.append(("other", text[position:]))
    return pieces


def _commented(text: str, todo: str) -> list[str]:
    lines = text.split("\n")
    indent = re.match(r"\s*", lines[0])[0]
    return _todo_lines("#", f"{TODO}: {todo}", indent) + [f"{indent}# {line.strip()}" if line.strip() else line
                                                          for line in lines]


def port_cmake_command(text: str, context: CMakeContext) -> tuple[str, list[str], str | None]:
    """(the command as ROS 2's, the rules it used, a TODO when it stays ROS 1's and is commented out)."""
    match = re.match(r"([A-Za-z_][A-Za-z0-9_]*)(\s*\()(.*)\)$", text, re.S)
    name, opening, args = match[1], match[2], match[3]
    lower = name.lower()
    used: list[str] = []
    if lower in CMAKE_TODO:
        return text, used, CMAKE_TODO[lower]
    if lower == "find_package":
        words = args.split()
        if words and words[0] == "catkin":
            components = [w for w in words[words.index("COMPONENTS") + 1:]] if "COMPONENTS" in words else []
            lines, missing = [], []
            for component in components:
                if component.startswith("${"):
                    continue
                names = dependencies.ros2_names(component, context.languages)
                if names is None:
                    missing.append(component)
                    continue
                lines += [f"find_package({n} REQUIRED)" for n in names if n not in context.found]
            if missing:
                return text, used, f"{', '.join(missing)}: {dependencies.note(missing[0])}"
            return "\n".join(lines), ["cmake.find_package"], None
        if words:
            names = dependencies.ros2_names(words[0], context.languages)
            if names is None:
                return text, used, f"{words[0]}: {dependencies.note(words[0])}"
            if names != (words[0],):
                rest = " ".join(words[1:])
                return "\n".join(f"find_package({n}{' ' + rest if rest else ''})" for n in names), [
                    "cmake.find_package"], None
    if lower == "catkin_install_python":
        name, used = "install", ["cmake.install_python"]
    new_args = args
    for variable, value in CMAKE_DESTINATIONS.items():
        if "${" + variable + "}" in new_args:
            new_args = new_args.replace("${" + variable + "}", value)
            used.append("cmake.destinations")
    without = CATKIN_VARIABLES.sub("", new_args)
    if without != new_args:
        new_args = without
        used.append("cmake.catkin_variables")
    for node in context.nodes:
        renamed = re.sub(rf"(?<![\w$}}])(?:\$\{{PROJECT_NAME\}}|{re.escape(context.package)})_{re.escape(node)}\b",
                         node, new_args)
        if renamed != new_args:
            new_args = renamed
            used.append("cmake.targets")
    words = new_args.split()
    if lower == "set_target_properties" and words and words[0] in context.nodes:
        return "", ["cmake.targets"], None  # ROS 2 names the target after the node
    if lower in ("target_link_libraries", "add_dependencies", "include_directories",
                 "target_include_directories") and len(words) <= (0 if lower == "include_directories" else 1):
        own = words and words[0] not in context.nodes
        if lower == "target_link_libraries" and own and "${catkin_LIBRARIES}" in args:
            return text, used, (f"{words[0]} linked catkin's libraries: link what it uses of ROS 2 "
                                f"(target_link_libraries({words[0]} PRIVATE rclcpp::rclcpp ${{<package>_TARGETS}}))")
        return "", used, None  # nothing left but catkin's
    if lower == "target_link_libraries" and words and words[0] in context.nodes and len(words) > 1 and words[1] not in (
            "PRIVATE", "PUBLIC", "INTERFACE"):
        new_args = re.sub(rf"^(\s*{re.escape(words[0])})", r"\1 PRIVATE", new_args, count=1)
        used.append("cmake.targets")
    if lower == "if" and "CATKIN_ENABLE_TESTING" in new_args:
        new_args = new_args.replace("CATKIN_ENABLE_TESTING", "BUILD_TESTING")
        used.append("cmake.testing")
    ported = f"{name}{opening}{new_args})"
    if ROS1_WORDS.search(ported):
        return text, used, "no rule ports it: write it for ament_cmake"
    return ported, list(dict.fromkeys(used)), None


def port_cmake_lines(lines: list[str], first: int, context: CMakeContext) -> tuple[list[str], list[str], int]:
    text = "\n".join(lines)
    out: list[str] = []
    rewrites: list[str] = []
    todos = 0
    line = first
    for kind, piece in cmake_pieces(text):
        number = line
        line += piece.count("\n")
        if kind == "other":
            out.append(piece)
            continue
        ported, used, todo = port_cmake_command(piece, context)
        if todo:
            out.append("\n".join(_commented(piece, todo)))
            todos += 1
        elif ported == "":
            out.append(REMOVED)
            rewrites.append(f"line {number}: {' '.join(piece.split())} (removed)")
        elif ported != piece:
            out.append(ported)
            rewrites.append(f"line {number}: {' '.join(piece.split())} -> {' '.join(ported.split()) or '(removed)'}")
        else:
            out.append(piece)
    carried = [line for line in "".join(out).split("\n") if line.strip() != REMOVED]
    # catkin_package()'s keyword lines, carried alone (the user changed one of the template's)
    result = []
    for index, text_line in enumerate(carried):
        words = text_line.split()
        if words and words[0] in EXPORT_KEYWORDS and not text_line.lstrip().startswith("#"):
            if words[0] == "CATKIN_DEPENDS":
                names = [n for w in words[1:] if not w.startswith("${")
                         for n in (dependencies.ros2_names(w, context.languages) or ())]
                if names:
                    result.append(f"ament_export_dependencies({' '.join(names)})")
                    rewrites.append(f"line {first + index}: {' '.join(words)} -> {result[-1]}")
                continue
            result += _commented(text_line, "ament_export_include_directories() / ament_export_targets()")
            todos += 1
            continue
        result.append(text_line)
    return result, rewrites, todos


def cmake_default(theirs: list[str]) -> int:
    """A run with no place of its own goes before ament_package() (after the tests' block)."""
    for index in range(len(theirs) - 1, -1, -1):
        if theirs[index].strip().startswith("ament_package("):
            return max(index - 1, 0)
    return len(theirs) - 1


def carry_cmake(mine: str, generated: str, fresh: str, context: CMakeContext) -> Carried:
    return carry(mine, generated, fresh, lambda lines, first: port_cmake_lines(lines, first, context), cmake_default,
                 at_end=lambda line: line.startswith("ament_export_dependencies("))


# --- package.xml

DEPENDENCY = re.compile(r"^(?P<indent>[ \t]*)<(?P<tag>\w*depend)(?P<attrs>[^>]*)>\s*(?P<name>[\w.-]+)\s*</(?P=tag)>"
                        r"(?P<rest>.*)$")


def port_package_xml_lines(lines: list[str], first: int, languages: tuple[str, ...]) -> tuple[list[str], list[str],
                                                                                             int]:
    out, rewrites, todos = [], [], 0
    for offset, line in enumerate(lines):
        match = DEPENDENCY.match(line)
        if not match:
            out.append(line)
            continue
        name, tag = match["name"], match["tag"]
        if tag == "buildtool_depend" and name == "catkin":
            rewrites.append(f"line {first + offset}: {line.strip()} -> (removed: ament_cmake's is the template's)")
            continue
        names = dependencies.ros2_names(name, languages)
        if names is None:
            out += _todo_lines("<!--", f"{TODO}: {name}: {dependencies.note(name)} -->", match["indent"])
            out.append(f"{match['indent']}<!-- {line.strip()} -->")
            todos += 1
            continue
        if names == (name,):
            out.append(line)
            continue
        new = [f"{match['indent']}<{tag}{match['attrs']}>{n}</{tag}>{match['rest']}" for n in names]
        out += new
        rewrites.append(f"line {first + offset}: {line.strip()} -> {' '.join(n.strip() for n in new)}")
    return out, rewrites, todos


def package_xml_default(theirs: list[str]) -> int:
    for index, line in enumerate(theirs):
        if line.strip() in ("<export>", "</package>"):
            return max(index - 1, 0)
    return len(theirs) - 1


def carry_package_xml(mine: str, generated: str, fresh: str, languages: tuple[str, ...]) -> Carried:
    return carry(mine, generated, fresh, lambda lines, first: port_package_xml_lines(lines, first, languages),
                 package_xml_default)


# --- launch files (roslaunch XML -> ROS 2 XML)

LAUNCH_TODO_ELEMENTS = re.compile(r"<(machine|test)\b")


@dataclass(frozen=True)
class LaunchContext:
    package: str
    executables: tuple[tuple[str, str], ...] = ()  # (ROS 1 executable, ROS 2 one) of the package's nodes
    launch_format: str = "xml"
    launch_files: tuple[tuple[str, str], ...] = ()  # (ROS 1 launch file, ROS 2 one) of the package: launch/x.launch


def _element_end(lines: list[str], start: int) -> int:
    """The index of the line an element starting on lines[start] ends on."""
    tag = re.search(r"<([\w-]+)", lines[start])[1]
    depth = 0
    for index in range(start, len(lines)):
        depth += len(re.findall(rf"<{tag}\b", lines[index]))
        depth -= len(re.findall(rf"</{tag}>", lines[index]))
        depth -= len(re.findall(r"/>", lines[index])) if index == start or depth > 0 else 0
        if depth <= 0:
            return index
    return len(lines) - 1


def _launch_line(line: str, context: LaunchContext, in_node: bool = False) -> tuple[str, list[str], str | None]:
    used = []
    new = line
    if "$(find " in new:
        new = re.sub(r"\$\(find ", "$(find-pkg-share ", new)
        used.append("launch.find")
    node = re.search(r"<node\b", new)
    package = re.search(r'\bpkg="([^"]*)"', new)
    if node and package and package[1] != context.package:
        names = dependencies.ros2_names(package[1])
        if names and names[0] != package[1]:  # rviz is rviz2 (package and executable)
            renamed = new.replace(f'pkg="{package[1]}"', f'pkg="{names[0]}"').replace(
                f'type="{package[1]}"', f'type="{names[0]}"')
            new, used = renamed, used + ["launch.exec"]
    if node:
        def executable(match: re.Match) -> str:
            value = match[2]
            package = re.search(r'\bpkg="([^"]*)"', new)
            if package and package[1] == context.package:
                value = dict(context.executables).get(value, value)
            return f'{match[1]}exec="{value}"'
        replaced = re.sub(r'(\s)type="([^"]*)"', executable, new)
        replaced = re.sub(r'(\s)ns="', r'\1namespace="', replaced)
        replaced = re.sub(r'(\s)required="true"', r'\1on_exit="shutdown"', replaced)
        if replaced != new:
            new, used = replaced, used + ["launch.exec"]
        if re.search(r'\s(machine|clear_params)="', new):
            return line, used, "machine and clear_params have no ROS 2 counterpart"
    rosparam = re.match(r'^(\s*)<rosparam\s+command="load"\s+file="([^"]*)"\s*/>\s*$', new)
    if rosparam:
        new, used = f'{rosparam[1]}<param from="{rosparam[2]}"/>', used + ["launch.rosparam"]
    elif "<rosparam" in new:
        return line, used, "<param from=\"file.yaml\"/> in a <node>, or <set_parameter>"
    if re.search(r"<param\b", new):
        if re.search(r'\s(textfile|binfile|command)="', new):
            return line, used, "value=\"$(command '...')\" for a command's output"
        without = re.sub(r'\s+type="[^"]*"', "", new)
        if without != new:
            new, used = without, used + ["launch.param"]
    group = re.match(r'^(\s*)<group\s+ns="([^"]*)"\s*>\s*$', new)
    if group:
        new = f'{group[1]}<group>\n{group[1]}  <push-ros-namespace namespace="{group[2]}"/>'
        used.append("launch.group")
    include = re.search(r'<include\s+file="([^"]*)"', new)
    own = f"$(find-pkg-share {context.package})/"
    launch_files = {f"launch/{ros1}": f"launch/{ros2}" for ros1, ros2 in context.launch_files}
    if include and include[1].startswith(own) and include[1][len(own):] in launch_files:
        ported = own + launch_files[include[1][len(own):]]
        new, used = new.replace(include[1], ported), used + ["launch.include"]
    elif include and include[1].endswith(".launch"):
        return line, used, "include the package's ROS 2 launch file ($(find-pkg-share pkg)/launch/x.launch.xml)"
    if not in_node and re.search(r"<param\b", new):
        new, used = re.sub(r"<param\b", "<set_parameter", new), used + ["launch.set_parameter"]
    if LAUNCH_TODO_ELEMENTS.search(new):
        return line, used, "ROS 2 launch has no <machine> or <test> (launch_testing tests)"
    return new, list(dict.fromkeys(used)), None


def port_launch_lines(lines: list[str], first: int, context: LaunchContext) -> tuple[list[str], list[str], int]:
    if context.launch_format != "xml":
        todo = (f"your lines of the ROS 1 launch file: write them in this {context.launch_format} launch file "
                "(ROS 2's XML launch files read them nearly as they are)")
        return _todo_lines("#", f"{TODO}: {todo}") + [f"# {line}" for line in lines], [], 1
    out, rewrites, todos = [], [], 0
    index, in_node = 0, 0
    while index < len(lines):
        line = lines[index]
        new, used, todo = _launch_line(line, context, in_node > 0)
        masked = re.sub(r"<!--.*?-->", "", line)
        in_node += len(re.findall(r"<node\b(?![^>]*/>)", masked)) - masked.count("</node>")
        if todo:
            end = _element_end(lines, index) if re.search(r"<[\w-]+", line) else index
            indent = re.match(r"\s*", line)[0]
            element = "\n".join(lines[index:end + 1]).replace("--", "- -")
            out += _todo_lines("<!--", f"{TODO}: {todo} -->", indent)
            out += [f"{indent}<!--", *element.split("\n"), f"{indent}-->"]
            todos += 1
            index = end + 1
            continue
        if new != line:
            rewrites.append(f"line {first + index}: {line.strip()} -> {' '.join(new.split())}")
        out += new.split("\n")
        if "launch.group" in used:  # the group's end stays </group>
            pass
        index += 1
    return out, rewrites, todos


def port_launch_file(text: str, context: LaunchContext) -> Carried:
    """A roslaunch file of the user's own, as a ROS 2 XML launch file."""
    lines, rewrites, todos = port_launch_lines(text.split("\n"), 1, LaunchContext(
        context.package, context.executables, "xml", context.launch_files))
    return Carried("\n".join(lines), rewrites, todos)


def launch_default(theirs: list[str]) -> int:
    for index in range(len(theirs) - 1, -1, -1):
        if theirs[index].strip() in ("</launch>", "]", "return LaunchDescription(["):
            return max(index - 1, 0)
    return len(theirs) - 1


def carry_launch(mine: str, generated: str, fresh: str, context: LaunchContext) -> Carried:
    return carry(mine, generated, fresh, lambda lines, first: port_launch_lines(lines, first, context),
                 launch_default)


# --- config files

def ros2_config(text: str, head: int) -> str:
    """A ROS 1 config file (`name: value` lines) in `ros__parameters` form, its comments kept.

    Its first `head` lines (the template's heading comment, as many lines as ROS 2's has
    before `/**:`) stay at the top, as far as they are comments; the rest moves under
    `/**: ros__parameters:`, four columns deeper. `{}` (no parameters) becomes ROS 2's
    `ros__parameters: {}`.
    """
    lines = text.split("\n")
    top = 0
    while top < min(head, len(lines)) and lines[top].lstrip().startswith("#"):
        top += 1
    body = lines[top:]
    if [line.strip() for line in body if line.strip()] == ["{}"]:
        return "\n".join([*lines[:top], "/**:", "  ros__parameters: {}", *(line for line in body if not line.strip())])
    return "\n".join([*lines[:top], "/**:", "  ros__parameters:",
                      *(("    " + line) if line.strip() else line for line in body)])
