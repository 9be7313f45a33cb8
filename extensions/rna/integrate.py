"""Adding one node to a package the template did not make: the edits to its build files.

Each function takes a build file's text and returns it with the node's lines in a
block of their own (`BEGIN rna-template: node <name>` ... `END ...`), replacing that
block when it is already there, so running it again after `copier update` only
changes the node's lines. Text outside the blocks is left alone, except a catkin
package's find_package(catkin REQUIRED COMPONENTS ...) call, which gains the components
the node needs at its end, in the call's own layout. A catkin package without
catkin_python_setup() (scripts only) gets it in a block of its own for a Python node,
whose base class is a module of the package (setup.py, rendered by the template when
the package has none). Each returns `(new_text, [one line per change])`; a ValueError
says what the file lacks, so the user can add the lines by hand.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

from .dialects import dialect
from .dialects.lines import BREAK, SPLIT, fit_line


def _markers(comment: str, closing: str, node, indent: str = "") -> tuple[str, str]:
    return (f"{indent}{comment} BEGIN rna-template: node {node.name}{closing}",
            f"{indent}{comment} END rna-template: node {node.name}{closing}")


def _put_block(text: str, markers: tuple[str, str], block: list[str], anchor: re.Pattern,
               separator: str = "\n") -> str:
    """The block between its markers: in place of the old one, else where `anchor` matches."""
    begin, end = markers
    body = "\n".join([begin, *block, end]) + "\n"
    existing = re.compile(re.escape(begin) + r".*?" + re.escape(end) + r"\n", re.S)
    if existing.search(text):
        return existing.sub(lambda _: body, text, count=1)
    match = anchor.search(text)
    if not match:
        raise ValueError(f"found no place for the node's lines ({anchor.pattern})")
    # A new block gets a blank line after it, like the paragraphs around it.
    return text[:match.end()] + body + separator + text[match.end():]


def _outside_blocks(text: str) -> str:
    return re.sub(r"(#|<!--) BEGIN rna-template: node .*?(#|<!--) END rna-template: node [^\n]*",
                  "", text, flags=re.S)


def package_xml(text: str, package) -> tuple[str, list[str]]:
    """Declare the dependencies of the node that package.xml lacks."""
    node = package.nodes[0]
    declared = {element.text.strip() for element in ET.fromstring(_outside_blocks(text)).iter()
                if element.tag.endswith("depend") and element.text}
    wanted = [dependency for dependency in package.dependencies if dependency.name not in declared]
    block = [f"  <{d.tag}>{d.name}</{d.tag}>" for d in wanted]
    new = _put_block(text, _markers("<!--", " -->", node, "  "), block,
                     re.compile(r"\n(?=  <export>|</package>)"))
    return new, [f"package.xml: declares {d.name} ({d.tag})" for d in wanted]


def ament_cmake_lists(text: str, package) -> tuple[str, list[str]]:
    """The node's find_package(), target and install lines, before the tests and ament_package()."""
    node = package.nodes[0]
    block = []
    if node.is_cpp:
        block += [f"find_package({dependency} REQUIRED)" for dependency in node.dependencies]
        block += [f"add_executable({node.name} src/{node.name}.cpp)",
                  f"target_include_directories({node.name} PRIVATE include)",
                  f"target_link_libraries({node.name} PRIVATE {' '.join(dialect(node).cmake_targets)})",
                  f"install(TARGETS {node.name} DESTINATION lib/${{PROJECT_NAME}})"]
    else:
        if not re.search(r"^\s*ament_python_install_package\(", _outside_blocks(text), re.M):
            block += ["find_package(ament_cmake_python REQUIRED)", "ament_python_install_package(${PROJECT_NAME})"]
        block += [f"install(PROGRAMS {package.name}/{node.name}.py",
                  f"  DESTINATION lib/${{PROJECT_NAME}} RENAME {node.name})"]
    block.append(f"install(FILES config/{node.name}.yaml DESTINATION share/${{PROJECT_NAME}}/config)")
    new = _put_block(text, _markers("#", "", node), block,
                     re.compile(r"\n(?=if\(BUILD_TESTING\)|ament_package\()"))
    return new, [f"CMakeLists.txt: builds and installs {node.executable} and config/{node.name}.yaml"]


# The call itself, not one a comment quotes (catkin_create_pkg's comments do).
CATKIN_FIND = re.compile(r"^[ \t]*find_package\(\s*catkin\s+REQUIRED\b(?P<rest>[^)]*)\)", re.M)
PYTHON_SETUP_MARKERS = ("# BEGIN rna-template: the nodes' Python package (setup.py)",
                        "# END rna-template: the nodes' Python package")


def catkin_components(call: str) -> list[str]:
    """The components a find_package(catkin REQUIRED [COMPONENTS ...]) call names."""
    words = re.sub(r"#[^\n]*", "", CATKIN_FIND.match(call)["rest"]).split()
    return words[1:] if words[:1] == ["COMPONENTS"] else words


def with_components(call: str, missing: list[str]) -> str:
    """The user's find_package(catkin ...) call with `missing` added before its `)`, in its own
    style: on its line when it is one line (or when `)` ends a line of components), else one a
    line, indented as the components above."""
    body = call[:-1]
    if not re.search(r"\bCOMPONENTS\b", re.sub(r"#[^\n]*", "", body)):
        missing = ["COMPONENTS", *missing]
    lines = body.split("\n")
    if len(lines) == 1 or lines[-1].strip():
        return body + " " + " ".join(missing) + ")"
    above = [line for line in lines[1:-1] if line.strip() and not line.lstrip().startswith("#")]
    indent = re.match(r"[ \t]*", above[-1])[0] if above else "  "
    return "\n".join(lines[:-1]) + "\n" + "".join(f"{indent}{name}\n" for name in missing) + lines[-1] + ")"


def catkin_cmake_lists(text: str, package) -> tuple[str, list[str]]:
    """The components find_package(catkin) lacks, appended to the user's call; a Python node's
    catkin_python_setup() in a block of its own when the package has none; then the node's
    target and install lines."""
    node = package.nodes[0]
    explained = []
    find = CATKIN_FIND.search(text)
    if not find:
        raise ValueError("it has no find_package(catkin REQUIRED COMPONENTS ...) call")
    components = catkin_components(find[0])
    missing = [dep.name for dep in package.dependencies if dep.name not in components]
    if missing:
        text = text[:find.start()] + with_components(find[0], missing) + text[find.end():]
        explained.append(f"CMakeLists.txt: find_package(catkin) also finds {', '.join(missing)}")
    if node.is_cpp:
        target = f"${{PROJECT_NAME}}_{node.name}"
        block = [f"add_executable({target} src/{node.name}.cpp)",
                 f'set_target_properties({target} PROPERTIES OUTPUT_NAME {node.name} PREFIX "")',
                 f"target_include_directories({target} PRIVATE include ${{catkin_INCLUDE_DIRS}})",
                 f"add_dependencies({target} ${{${{PROJECT_NAME}}_EXPORTED_TARGETS}} ${{catkin_EXPORTED_TARGETS}})",
                 f"target_link_libraries({target} ${{catkin_LIBRARIES}})",
                 f"install(TARGETS {target} RUNTIME DESTINATION ${{CATKIN_PACKAGE_BIN_DESTINATION}})"]
    else:
        # The node's base class is a module of the package's Python package (src/<package>/),
        # which setup.py installs; catkin_python_setup() must come before catkin_package().
        if not re.search(r"^\s*catkin_python_setup\(\s*\)", text, re.M):
            text = _put_block(text, PYTHON_SETUP_MARKERS, ["catkin_python_setup()"],
                              re.compile(re.escape(CATKIN_FIND.search(text)[0]) + r"[^\n]*\n\n?"))
            explained.append("CMakeLists.txt: catkin_python_setup() installs the Python package of setup.py")
        block = [f"catkin_install_python(PROGRAMS scripts/{node.executable}",
                 "  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})"]
    block.append(f"install(FILES config/{node.name}.yaml DESTINATION ${{CATKIN_PACKAGE_SHARE_DESTINATION}}/config)")
    new = _put_block(text, _markers("#", "", node), block, re.compile(r"^catkin_package\([^)]*\)\n\n?", re.M))
    return new, [*explained, f"CMakeLists.txt: builds and installs {node.executable} and config/{node.name}.yaml"]


def catkin_setup_py(text: str, package) -> tuple[str, list[str]]:
    """A catkin package's setup.py must install the Python package the node's base class is in."""
    if not re.search(rf"""['"]{re.escape(package.name)}['"]""", text) or "src" not in text:
        raise ValueError(f"its setup.py does not install the Python package {package.name} from src/, where the "
                         f"node's base class is: add packages=['{package.name}'], package_dir={{'': 'src'}}")
    return text, []


def setup_py(text: str, package) -> tuple[str, list[str]]:
    """The node's console script and config file, in an ament_python setup.py."""
    node = package.nodes[0]
    # Long names take two lines each, as the template's own setup.py spells them (flake8's 99 columns).
    entry = fit_line(f"            '{node.name} = {SPLIT}{package.name}.{node.name}:main',", "python", inside=True)
    text = _put_block(text, _markers("#", "", node, " " * 12), entry,
                      re.compile(r"""['"]console_scripts['"]\s*:\s*\[\s*\n"""), separator="")
    data = fit_line(f"        ('share/{package.name}/config',{BREAK} ['config/{node.name}.yaml']),", "python",
                    inside=True)
    text = _put_block(text, _markers("#", " (config)", node, " " * 8), data,
                      re.compile(r"data_files\s*=\s*\[\s*\n"), separator="")
    return text, [f"setup.py: installs the {node.name} executable and config/{node.name}.yaml"]
