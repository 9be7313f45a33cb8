"""Reading a generated package as ROS tools do: package.xml through catkin_pkg, launch files, the model,
the README's tables as a Markdown renderer splits them."""

from __future__ import annotations

import re
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

from catkin_pkg.package import parse_package

from .generation import ROOT, answers_of

sys.path.insert(0, str(ROOT / "extensions"))
import rna  # noqa: E402 - the template's own package


def model_of(destination: Path) -> rna.Package:
    """The package model of a generated destination, from its answers file."""
    return rna.build_package(answers_of(destination))


def package_dir(destination: Path) -> Path:
    return destination / answers_of(destination)["package_name"]


def dependencies(package_xml: Path) -> dict[str, set[str]]:
    """`depend` and `exec_depend` names of a package.xml that catkin_pkg parses and validates."""
    package = parse_package(str(package_xml))
    package.validate()
    assert package.package_format == 3
    return {
        "depend": {d.name for d in package.build_depends} & {d.name for d in package.exec_depends}
        & {d.name for d in package.build_export_depends},
        "exec_depend": {d.name for d in package.exec_depends} - {d.name for d in package.build_depends},
    }


def dependency_names(package_xml: Path) -> set[str]:
    """The package names a package.xml depends on (build, exec or export)."""
    package = parse_package(str(package_xml))
    package.validate()
    return {d.name for d in package.build_depends + package.exec_depends + package.build_export_depends}


def launched_nodes(launch_file: Path) -> dict[str, str]:
    """executable -> the params file each <node> (or <lifecycle_node>) of the launch file loads (ROS 2 or ROS 1)."""
    root = ET.parse(launch_file).getroot()
    nodes = {}
    for node in [*root.iter("node"), *root.iter("lifecycle_node")]:
        if node.get("exec"):
            nodes[node.get("exec")] = node.find("param").get("from")
        else:
            loaded = node.find("rosparam")
            assert loaded.get("command") == "load"
            nodes[node.get("type")] = loaded.get("file")
    return nodes


TABLE_PIPE = re.compile(r"(?<!\\)\|")  # GFM splits a row at every pipe not escaped, in code spans too


def table_rows_of_wrong_width(markdown: str) -> list[str]:
    """Rows of the Markdown tables whose cell count differs from their header's."""
    wrong, columns = [], None
    for line in markdown.splitlines():
        if not line.startswith("|"):
            columns = None
            continue
        count = len(TABLE_PIPE.findall(line))
        columns = columns or count
        if count != columns:
            wrong.append(line)
    return wrong
