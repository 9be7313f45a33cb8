"""Run by Copier after it wrote a node into a package the template did not make.

Copier writes the node's own files (base class, your class, config file) and never
touches the package's build files. This script makes the smallest changes that get
the node built and installed: the node's lines go into blocks marked
`BEGIN/END rna-template: node <name>` in package.xml and CMakeLists.txt or setup.py
(rna/integrate.py), and each change is printed. Run again by `copier update`, it
replaces only those blocks. When a file lacks what an edit needs, it says what to add
by hand and exits 1.
"""

from __future__ import annotations

import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))
import patches  # noqa: E402 - next to this file

with patches.template_modules(Path(__file__).resolve().parent):
    from rna import build_package, files, integrate  # the template's own package, next to this file


def main(project: Path, answers_file: str) -> int:
    if not (project / "package.xml").is_file():
        return 0  # a copy Copier renders for its own comparison during an update
    package = build_package(yaml.safe_load(files.text(project, answers_file, owned=True) or "{}"))
    edits = [("package.xml", integrate.package_xml)]
    if package.build_type == "ament_python":
        edits.append(("setup.py", integrate.setup_py))
    elif package.build_type == "catkin":
        edits.append(("CMakeLists.txt", integrate.catkin_cmake_lists))
        if package.python_nodes:
            edits.append(("setup.py", integrate.catkin_setup_py))
    else:
        edits.append(("CMakeLists.txt", integrate.ament_cmake_lists))
    failed = False
    for name, edit in edits:
        try:
            content = files.read(project, name, owned=True)
            if content is None or content.text is None:
                raise ValueError("it is not a text file" if content is not None else "there is none")
            new, explained = edit(content.text, package)
            if new == content.text:
                continue
            files.write(project, name, new, like=content)
        except (ValueError, ET.ParseError) as error:  # files.NotWritable is a ValueError
            print(f"rna-template: could not add the {package.nodes[0].name} node to {name}: {error}. "
                  "Add its build lines by hand (docs/pages/how-to/node-in-an-existing-package.md shows them).",
                  file=sys.stderr)
            failed = True
            continue
        for line in explained:
            print(f"rna-template: {line}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), sys.argv[2]))
