"""What the answers say about renamed nodes (`renamed_from`), apart from carrying them out.

The glue checks them at every render (`rename_error`); the after-update step reads which
nodes were renamed and writes the answers file without the keys once they are consumed.
Kept apart from renames.py, which carries the renames out, so that a copy, which only
checks, does not load the update's merging.
"""

from __future__ import annotations

from collections.abc import Mapping

import yaml

from . import resolve

KEY = resolve.RENAMED_FROM


def renames(answers: Mapping) -> dict[str, str]:
    """new node name -> the name it was renamed from, as the node answers say."""
    found = {}
    for node in answers.get("nodes") or []:
        if isinstance(node, Mapping) and node.get(KEY) and node.get("name"):
            found[str(node["name"])] = str(node[KEY])
    return found


def rename_error(previous: Mapping | None, answers: Mapping, update: bool = True) -> str | None:
    """Why the `renamed_from` keys of the answers cannot be followed, or None.

    `previous`: the answers being updated (None outside the project: a copy, or one of the
    scratch renders of an update, which follow the answers as given).
    """
    wanted = renames(answers)
    if not wanted or (previous is None and update):
        return None
    if previous is None:
        return (f"node '{next(iter(wanted))}': {KEY} is for `copier update` (it names a node of the package "
                "being updated); a new package has no node to rename")
    before = {str(node.get("name") if isinstance(node, Mapping) else node) for node in previous.get("nodes") or []}
    now = {str(node.get("name") if isinstance(node, Mapping) else node) for node in answers.get("nodes") or []}
    written = renames(previous)  # Copier writes the new answers file before it renders the rest
    seen: dict[str, str] = {}
    for new, old in wanted.items():
        if old == new or written.get(new) == old:
            continue
        if old not in before:
            return f"node '{new}': {KEY} '{old}' is no node of the package ({', '.join(sorted(before))})"
        if old in now:
            return f"node '{new}': {KEY} '{old}', but '{old}' is still in the nodes: remove it, or rename another"
        if old in seen:
            return f"nodes '{seen[old]}' and '{new}' are both renamed from '{old}'"
        seen[old] = new
    return None


def without_keys(answers: Mapping) -> dict:
    """The answers with the `renamed_from` keys left out (what a fresh copy of the new answers is made of)."""
    nodes = answers.get("nodes")
    if not isinstance(nodes, list):
        return dict(answers)
    return {**answers, "nodes": [{key: value for key, value in node.items() if key != KEY}
                                 if isinstance(node, Mapping) else node for node in nodes]}


def without_renames(answers_text: str) -> str | None:
    """The answers file with the consumed `renamed_from` keys left out (and its checksum again), or None."""
    answers = yaml.safe_load(answers_text)
    if not isinstance(answers, dict) or not renames(answers):
        return None
    answers = without_keys(answers)
    header = [line for line in answers_text.splitlines() if line.startswith("#")]
    header = [f"{resolve.CHECKSUM_LINE}{resolve.checksum(answers)}" if line.startswith(resolve.CHECKSUM_LINE)
              else line for line in header]
    return "\n".join(header) + "\n" + resolve.answers_yaml(answers)
