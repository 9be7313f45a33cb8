"""Migration to 0.2.0, run by `copier update` from an older version, after the update.

0.2.0 names a catkin package's C++ targets `${PROJECT_NAME}_<node>` (output name
still `<node>`), so that two packages with a node of the same name build in one
catkin workspace. The managed block follows by itself; this renames the old target
in the user's own CMake lines outside the blocks (target_link_libraries(<node> ...)
and the like), which would otherwise name a target that no longer exists.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rna import build_package, files  # noqa: E402 - the template's own package, next to this file

TARGET_COMMANDS = ("add_dependencies", "install", "set_target_properties", "target_compile_definitions",
                   "target_compile_features", "target_compile_options", "target_include_directories",
                   "target_link_libraries", "target_link_options", "target_sources")
_BLOCK = re.compile(r"# BEGIN rna-template.*?# END rna-template[^\n]*", re.S)


def rename_targets(text: str, nodes: list[str]) -> tuple[str, list[str]]:
    """`text` with the old target names replaced outside the managed blocks."""
    changes = []
    pieces = _BLOCK.split(text)
    blocks = _BLOCK.findall(text)
    for index, piece in enumerate(pieces):
        for node in nodes:
            pattern = re.compile(rf"(\b(?:{'|'.join(TARGET_COMMANDS)})\(\s*(?:TARGETS\s+)?)({re.escape(node)})\b")
            piece, count = pattern.subn(r"\g<1>${PROJECT_NAME}_\g<2>", piece)
            if count:
                changes.append(f"{node} -> ${{PROJECT_NAME}}_{node} ({count}x)")
        pieces[index] = piece
    merged = pieces[0] + "".join(block + piece for block, piece in zip(blocks, pieces[1:], strict=True))
    return merged, changes


def main(project: Path, answers_file: str) -> int:
    package = build_package(yaml.safe_load(files.text(project, answers_file, owned=True) or "{}"))
    if package.ros != 1 or not package.cpp_nodes:
        return 0
    cmake = f"{package.dir}/CMakeLists.txt"
    content = files.read(project, cmake, owned=True)
    if content is None or content.text is None:
        return 0
    text, changes = rename_targets(content.text, [node.name for node in package.cpp_nodes])
    if changes:
        files.write(project, cmake, text, like=content)
        print(f"rna-template 0.2.0: C++ targets are now named ${{PROJECT_NAME}}_<node>; renamed in your lines "
              f"of {package.dir}/CMakeLists.txt: {', '.join(changes)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), sys.argv[2]))
