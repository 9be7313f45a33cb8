"""Config files (`config/<node>.yaml`) merged by parameter, in the user's own text.

A tuned config file is the user's text: comments, order, blank lines. What the
template changes in it is per parameter: a default, a parameter added or dropped, a
description (the comment line above a parameter). So the merge starts from the user's
file and applies exactly those changes to it:

- a value the user never tuned takes the new default, in place (the user's comments on
  its lines stay, on the value's last line);
- a parameter the template adds goes after the one it follows in the template's order;
- a parameter the template drops goes, with its description, unless the user tuned it;
- the user's own parameters and comments stay as they are;
- a value the user tuned whose default changed too is a real conflict: the user's value
  stays and the conflict is marked (`<<<<<<< before updating` or a `.rej` file, as the
  update's --conflict asks), the rest is merged all the same.

The result is read back with PyYAML and must hold exactly the parameters intended, or
the merge gives up and leaves the conflict to the user. Every update runs it on each
config file that both the user and the template changed, so the outcome depends on the
three versions only, never on how Copier's line merge went.
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass, field

import yaml

from ..configs import yaml_entry, yaml_literal
from ..model import Package
from .project import Project, Render
from .summary import Report

CONFIG = re.compile(r"(^|/)config/(?P<node>[^/]+)\.yaml$")
KEY = re.compile(r"^(?P<indent>[ \t]*)(?P<key>[A-Za-z_][\w.\-/]*|'[^']*'|\"[^\"]*\"):(?P<rest>(?:[ \t].*)?)$")


def parameters(text: str) -> dict | None:
    """The parameters of a ROS 2 (`/**: ros__parameters:`) or ROS 1 (flat) config file."""
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError:
        return None
    if not isinstance(data, dict):
        return {} if data is None else None
    if len(data) == 1:
        (key, value), = data.items()
        if isinstance(value, dict) and "ros__parameters" in value:
            return value["ros__parameters"] or {}
    return data


@dataclass
class Entry:
    key: int  # the index of the parameter's line
    end: int  # the index after its last line (a value written over several lines)


@dataclass
class Layout:
    """Where the parameters are in a config file's lines."""

    indent: str
    entries: dict[str, Entry]
    start: int  # where the parameter mapping's lines begin


def layout(lines: list[str]) -> Layout:
    start, indent = 0, ""
    for index, line in enumerate(lines):
        match = re.match(r"^([ \t]*)ros__parameters:", line)
        if match:
            start = index + 1
            following = next((other for other in lines[start:] if other.strip() and not other.lstrip().startswith("#")),
                             "")
            depth = len(following) - len(following.lstrip())
            indent = following[:depth] if depth > len(match[1]) else match[1] + "  "
            break
    entries = {}
    index = start
    while index < len(lines):
        match = KEY.match(lines[index])
        if match and match["indent"] == indent:
            end = index + 1
            while end < len(lines) and lines[end].strip() and (
                    len(lines[end]) - len(lines[end].lstrip()) > len(indent) or lines[end].startswith(indent + "-")):
                end += 1
            entries[match["key"].strip("'\"")] = Entry(index, end)
            index = end
        else:
            index += 1
    return Layout(indent, entries, start)


def _comment_start(rest: str) -> int:
    """Where an inline comment starts in the text after `key:` (len(rest) if none)."""
    quote = None
    for index, char in enumerate(rest):
        if quote:
            quote = None if char == quote else quote
        elif char in "'\"":
            quote = char
        elif char == "#" and (index == 0 or rest[index - 1] in " \t"):
            return index
    return len(rest)


def _with_value(lines: list[str], value: object) -> list[str]:
    """A parameter's lines (its key's and those its value goes on over) with another value, the
    user's comments on them kept: on the last line of the value, as the user put them."""
    match = KEY.match(lines[0])
    comments = [rest[_comment_start(rest):] for rest in (match["rest"], *lines[1:])]
    written = yaml_entry(match["indent"], match["key"], value).split("\n")
    kept = " ".join(comment for comment in comments if comment)
    if kept:
        written[-1] += f"  {kept}"
    return written


@dataclass
class Merged:
    text: str
    conflicts: dict[str, tuple[object, object]] = field(default_factory=dict)  # name -> (yours, template's)


def intended(old: dict, mine: dict, new: dict) -> tuple[dict, dict]:
    """(the parameters the merged file holds, the real conflicts: name -> (yours, the new default))."""
    result, conflicts = {}, {}
    for name, value in mine.items():
        tuned = name not in old or value != old[name]
        if name in new:
            if tuned and name in old and new[name] != old[name] and value != new[name]:
                conflicts[name] = (value, new[name])
            result[name] = value if tuned else new[name]
        elif tuned:
            result[name] = value  # the user's own, or tuned before the template dropped it
    for name, value in new.items():
        if name not in old and name not in mine:
            result[name] = value  # new in the template (one the user deleted stays deleted)
    return result, conflicts


def merge(old_text: str, mine_text: str, new_text: str, descriptions: tuple[dict, dict] = ({}, {})) -> Merged | None:
    """The user's file with the template's changes from `old_text` to `new_text`, or None.

    `descriptions`: parameter -> its description, in the old and the new answers (the
    comment line the template writes above a parameter).
    """
    old, mine, new = parameters(old_text), parameters(mine_text), parameters(new_text)
    if old is None or mine is None or new is None:
        return None
    wanted, conflicts = intended(old, mine, new)
    lines = mine_text.split("\n")
    places = layout(lines)
    new_lines = new_text.split("\n")
    new_places = layout(new_lines)
    indent = places.indent
    old_descriptions, new_descriptions = descriptions

    def description_above(entry: Entry) -> int | None:
        return entry.key - 1 if entry.key > places.start and lines[entry.key - 1].lstrip().startswith("#") else None

    edits: list[tuple[int, int, list[str]]] = []  # (from, to, replacement) on the user's lines
    for name, entry in places.entries.items():
        if name not in wanted:  # dropped by the template, untuned
            first = entry.key
            above = description_above(entry)
            if above is not None and lines[above].strip() == f"# {old_descriptions.get(name)}":
                first = above
            last = entry.end
            if first > 0 and not lines[first - 1].strip() and last < len(lines) and not lines[last].strip():
                last += 1
            edits.append((first, last, []))
            continue
        if wanted[name] != mine[name]:
            edits.append((entry.key, entry.end, _with_value(lines[entry.key:entry.end], wanted[name])))
        above = description_above(entry)
        before, after = old_descriptions.get(name), new_descriptions.get(name)
        if before != after and above is not None and lines[above].strip() == f"# {before}":
            edits.append((above, above + 1, [f"{indent}# {after}"] if after else []))
        elif before != after and after and not before and above is None:
            edits.append((entry.key, entry.key, [f"{indent}# {after}"]))
    order = list(new_places.entries)
    for position, name in enumerate(order):
        if name in places.entries or name not in wanted:
            continue
        block = ([f"{indent}# {new_descriptions[name]}"] if new_descriptions.get(name) else [])
        block.append(yaml_entry(indent, name, wanted[name]))
        previous = next((places.entries[other] for other in reversed(order[:position])
                         if other in places.entries), None)
        if previous is not None:
            at = previous.end
            if at < len(lines) and not lines[at].strip():
                edits.append((at + 1, at + 1, [*block, ""]))
            else:
                edits.append((at, at, block))
        elif places.entries:
            first = min(places.entries.values(), key=lambda e: e.key)
            above = description_above(first)
            at = above if above is not None and lines[above].strip() != "" else first.key
            edits.append((at, at, [*block, ""]))
        else:
            at = len(lines)
            while at > places.start and not lines[at - 1].strip():
                at -= 1
            edits.append((at, at, block))
    for start, end, replacement in sorted(edits, key=lambda edit: (edit[0], edit[1]), reverse=True):
        lines[start:end] = replacement
    text = "\n".join(lines)
    if not places.entries and wanted:
        text = re.sub(r"ros__parameters:\s*\{\}", "ros__parameters:", text).replace("\n{}\n", "\n")
    if parameters(text) != wanted:
        return None
    return Merged(text, conflicts)


def marked(text: str, conflicts: dict[str, tuple[object, object]]) -> str:
    """The merged text with each conflicting parameter's line between Copier's conflict markers."""
    lines = text.split("\n")
    places = layout(lines)
    for name, (_, theirs) in sorted(conflicts.items(), key=lambda item: -places.entries[item[0]].key):
        entry = places.entries[name]
        yours = lines[entry.key:entry.end]
        lines[entry.key:entry.end] = ["<<<<<<< before updating", *yours, "=======",
                                      *_with_value(yours, theirs), ">>>>>>> after updating"]
    return "\n".join(lines)


def _rejected(path: str, text: str, conflicts: dict[str, tuple[object, object]]) -> str:
    """A .rej file: the template's changes the merge left out, as a diff against the merged file."""
    lines = text.split("\n")
    places = layout(lines)
    theirs = list(lines)
    for name, (_, value) in sorted(conflicts.items(), key=lambda item: -places.entries[item[0]].key):
        entry = places.entries[name]
        theirs[entry.key:entry.end] = _with_value(lines[entry.key:entry.end], value)
    return "\n".join(difflib.unified_diff(lines, theirs, f"a/{path}", f"b/{path}", lineterm="")) + "\n"


def write_merged(project: Project, path: str, merged: Merged) -> bool:
    """The merged file, its conflicts marked in it or in a .rej file beside it, as the
    update's --conflict asked (what Copier did with the file, when it was not told); whether
    it could be written."""
    rejected = project.root / f"{path}.rej"
    in_a_rej_file = project.conflict == "rej" if project.conflict else rejected.exists()
    if merged.conflicts and in_a_rej_file:
        return project.write(path, merged.text) and project.write(f"{path}.rej", _rejected(path, merged.text,
                                                                                            merged.conflicts))
    if not project.write(path, marked(merged.text, merged.conflicts) if merged.conflicts else merged.text):
        return False
    if rejected.exists():
        rejected.unlink()
    return True


def descriptions_of(package: Package | None, path: str) -> dict:
    match = CONFIG.search(path)
    if package is None or match is None:
        return {}
    node = next((node for node in package.nodes if node.name == match["node"]), None)
    return {p.name: p.description for p in node.parameters if p.description} if node else {}


def merge_config_files(project: Project, old: Render, new: Render, packages: tuple[Package | None, Package | None],
                       report: Report, skip: set[str] = frozenset()) -> None:
    """Each config file both the user and the template changed, merged by parameter in the user's text
    (`skip`: merged by an earlier step)."""
    for path in sorted(p for p in new.files if CONFIG.search(p) and p not in skip):
        before, generated = project.committed(path), old.text(path)
        if before is None or generated is None or before == generated or new.text(path) == generated:
            continue
        merged = merge(generated, before, new.text(path), (descriptions_of(packages[0], path),
                                                           descriptions_of(packages[1], path)))
        if merged is None or not write_merged(project, path, merged):
            continue  # not YAML the merge can read: Copier's line merge stands, conflicts and all
        if not merged.conflicts:
            project.resolve_in_index(path)
        report.merged.add(path)
        for name, (yours, theirs) in merged.conflicts.items():
            report.notes.append(f"{path}: you tuned {name} to {yaml_literal(yours)} and its default is now "
                                f"{yaml_literal(theirs)}: keep one.")
