"""Answers stored resolved: what a default made of one answer is written out, so it never moves.

A node's language defaults from the build type (C++ in ament_cmake and catkin, Python in
ament_python). Were only the answer given recorded, changing the build type or the
distro later would re-read every node written without a language as the new default:
Python nodes turned C++. So:

- the answers file records every node with its language (`resolved()`);
- during an update, a node given without a language keeps the one it had in the answers
  being updated, so the answers files of versions that did not record it (0.1.0, 0.2.0)
  and `--data nodes=...` written as the docs show mean what they meant
  (`keep_languages()`); a new node gets the build type's default.

The one-node questions of a first copy (rna.answers.FIRST_COPY) are not recorded: `nodes`
holds what they made (and `node_setup` how they were made), and an update
changes the nodes there (refusals.first_copy_error), so the file never says one thing in
`node_publishers` and another in `nodes`.

The answers file also records a checksum of its answers (`checksum()`): Copier renders
the old version from that file, so answers edited there by hand would be taken for the
package's old answers and the update would change nothing; `edited_by_hand()` tells.
"""

from __future__ import annotations

import hashlib
import json
import re
from collections.abc import Mapping

import yaml

from .. import distros
from ..answers import FIRST_COPY
from ..answers.nodes import normalised_nodes

RENAMED_FROM = "renamed_from"  # a node's old name, during the update that renames it (rename_answers.py)
CHECKSUM_LINE = "# rna-template checksum of the answers below: "
_CHECKSUM = re.compile(r"^" + re.escape(CHECKSUM_LINE) + r"([0-9a-f]+)\s*$", re.MULTILINE)


def build_type_of(answers: Mapping) -> str:
    """The build type the answers give (ROS 1 packages are catkin and do not record it)."""
    if distros.generation(answers.get("ros_distro")) == 1:
        return "catkin"
    return answers.get("build_type") or "ament_python"


def _name(node: object) -> object:
    return node.get("name") if isinstance(node, Mapping) else node


def languages(answers: Mapping) -> dict[str, str]:
    """Each node's language: the one written, or its build type's default."""
    nodes = answers.get("nodes")
    if not isinstance(nodes, list):
        return {}
    default = distros.default_language(build_type_of(answers))
    found = {}
    for node in nodes:
        language = node.get("language") if isinstance(node, Mapping) else None
        found[str(_name(node))] = distros.LANGUAGES.get(str(language or default).lower(), str(language))
    return found


def resolved(answers: Mapping) -> dict:
    """The answers to record: every node a mapping with its language written out, its
    endpoints' types spelled as the package's ROS generation spells them, and not the first
    copy's ways to the nodes."""
    recorded = {key: value for key, value in answers.items() if key not in FIRST_COPY}
    nodes = recorded.get("nodes")
    if isinstance(nodes, list):
        nodes = recorded["nodes"] = normalised_nodes(nodes, distros.generation(recorded.get("ros_distro")))
        written = languages(recorded)
        recorded["nodes"] = [
            {**node, "language": node.get("language") or written[str(node.get("name"))]}
            if isinstance(node, Mapping) else {"name": node, "language": written[str(node)]} if isinstance(node, str)
            else node
            for node in nodes]
    return recorded


def keep_languages(nodes: object, previous: Mapping) -> list[str]:
    """Give each node listed without a language the one it had in `previous`, in place.

    Returns the names of the nodes that kept a language their new build type would not
    have given them by default.
    """
    if not isinstance(nodes, list):
        return []
    before = languages(previous)
    kept = []
    for index, node in enumerate(nodes):
        name = _name(node)
        was = (node.get(RENAMED_FROM) if isinstance(node, Mapping) else None) or name
        if not isinstance(name, str) or was not in before:
            continue
        if isinstance(node, str):
            nodes[index] = {"name": node, "language": before[was]}
        elif isinstance(node, dict) and not node.get("language"):
            node["language"] = before[was]
        else:
            continue
        kept.append(name)
    return kept


def checksum(answers: Mapping) -> str:
    """A checksum of the answers (Copier's own `_` keys left out: `_src_path` may move)."""
    recorded = {key: value for key, value in answers.items() if not str(key).startswith("_")}
    text = json.dumps(recorded, sort_keys=True, ensure_ascii=True, default=str)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def edited_by_hand(text: str, answers: object = None) -> bool | None:
    """Whether an answers file's answers differ from those its checksum was made of.

    None when it cannot tell: no checksum (written by 0.2.0 or older) or no YAML mapping.
    Layout and comments do not count; only the answers they read as (`answers`, when the
    caller has read `text` already).
    """
    found = _CHECKSUM.search(text)
    if found is None:
        return None
    if answers is None:
        try:
            answers = yaml.safe_load(text)
        except yaml.YAMLError:
            return None
    if not isinstance(answers, dict):
        return None
    return checksum(answers) != found.group(1)


def answers_yaml(answers: Mapping) -> str:
    """The answers file's YAML, as Copier's to_nice_yaml writes it, but always read back the same.

    PyYAML writes some characters raw that it then reads as something else (NEL, U+0085, in a
    quoted string reads back as a space), and a string parameter default may hold any
    character: such answers are written with escapes instead.
    """
    text = yaml.dump(answers, indent=4, allow_unicode=True, default_flow_style=False)
    # Written all in ASCII, every other character was escaped already: the escaped spelling
    # below would be the same text, so there is nothing to read back (PyYAML's Python parser
    # takes about 1 ms per node of the answers).
    if not text.isascii() and yaml.safe_load(text) != answers:
        text = yaml.dump(answers, indent=4, allow_unicode=False, default_flow_style=False)
    return text
