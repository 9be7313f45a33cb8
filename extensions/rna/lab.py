"""A lab's own choices (extensions/lab.yml): defaults, dependencies, header, files, docs address.

The file is the one a fork of the template edits; upstream ships it with comments only.
`load()` reads and checks it once; an error names the file, the key and the rule.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from pathlib import Path

import yaml

from . import distros, names
from .shapes import check_keys
from .licenses import LICENSES

FILE = Path(__file__).resolve().parent.parent / "lab.yml"
# Where the template's own documentation lives (docs/mkdocs.yml's site_url says the same).
DOCS_URL = "https://lab.github.io/rna-template/"
DEPENDENCY_TAGS = ("depend", "build_depend", "exec_depend", "test_depend")
KEYS = ("maintainer", "maintainer_email", "copyright_holder", "license", "ros_distro", "build_type", "qos",
        "dependencies", "header", "files", "docs_url")


class LabError(ValueError):
    """A broken rule in extensions/lab.yml: `str()` is the one line shown."""


def _check(lab: Mapping) -> None:
    check_keys(lab, KEYS, "")
    for key in ("maintainer", "copyright_holder"):
        if key in lab and names.one_line_error(lab[key]):
            raise ValueError(f"{key}: {names.one_line_error(lab[key])}")
    if "maintainer_email" in lab and names.email_error(lab["maintainer_email"]):
        raise ValueError(f"maintainer_email: {names.email_error(lab['maintainer_email'])}")
    if "license" in lab and lab["license"] not in LICENSES:
        raise ValueError(f"license: '{lab['license']}' is not one of {', '.join(LICENSES)}")
    if "ros_distro" in lab and lab["ros_distro"] not in distros.DISTROS:
        raise ValueError(f"ros_distro: '{lab['ros_distro']}' is not one of {', '.join(distros.DISTROS)}")
    if "build_type" in lab and lab["build_type"] not in distros.BUILD_TYPES_OF[2]:
        raise ValueError(f"build_type: '{lab['build_type']}' is not one of {', '.join(distros.BUILD_TYPES_OF[2])}")
    dependencies = lab.get("dependencies", {})
    if not isinstance(dependencies, Mapping):
        raise ValueError("dependencies: give a mapping of tag to package names, e.g. exec_depend: [lab_bringup]")
    check_keys(dependencies, DEPENDENCY_TAGS, "dependencies")
    for tag, packages in dependencies.items():
        for package in packages if isinstance(packages, list) else [packages]:
            if names.package_name_error(package):
                raise ValueError(f"dependencies: {tag}: {names.package_name_error(package)}")
    if "header" in lab and not isinstance(lab["header"], str):
        raise ValueError("header: give the lines as text")
    files = lab.get("files", {})
    if not isinstance(files, Mapping) or not all(isinstance(text, str) for text in files.values()):
        raise ValueError("files: give a mapping of a path in the package to its text")
    for path in files:
        if not isinstance(path, str) or Path(path).is_absolute() or ".." in Path(path).parts:
            raise ValueError(f"files: '{path}' is not a path within the package")


@functools.cache
def load(path: Path = FILE) -> dict:
    """The lab's choices, checked; {} when the file holds comments only (upstream's)."""
    try:
        lab = yaml.safe_load(path.read_text()) if path.is_file() else None  # not through rna/files.py: the template's
    except yaml.YAMLError as error:
        raise LabError(f"{path.name}: not valid YAML ({str(error).splitlines()[0]})") from None
    lab = lab or {}
    if not isinstance(lab, Mapping):
        raise LabError(f"{path.name}: give a mapping of the keys it documents")
    try:
        _check(lab)
    except ValueError as error:
        raise LabError(f"{path.name}: {error}") from None
    return dict(lab)


def docs_url(page: str = "") -> str:
    """The full address of a page of the documentation (the lab's site, or the template's)."""
    return load().get("docs_url", DOCS_URL).rstrip("/") + "/" + page.lstrip("/")


def dependencies(lab: Mapping) -> list[tuple[str, str]]:
    """(tag, package) of every dependency the lab adds to each package, in file order."""
    found = []
    for tag, packages in lab.get("dependencies", {}).items():
        found += [(tag, package) for package in (packages if isinstance(packages, list) else [packages])]
    return found


def files(lab: Mapping) -> list[dict]:
    """{path, text} of every file the lab adds to each package."""
    return [{"path": path, "text": text if text.endswith("\n") else text + "\n"}
            for path, text in lab.get("files", {}).items()]
