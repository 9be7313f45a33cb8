"""What an update did, file by file, and what the user must do next: the last thing it prints.

Each step of the after-update work records what it did in a `Report`; `summary()` adds
what git shows (files added, updated, merged, removed) and writes a short text for an
80-column terminal. The step exits 1 when the report holds anything the user must act
on (a conflict, an edited file the answers no longer make, code to port, a change it
could not write), and its last line says the update is done all the same: Copier then
prints that its task "returned non-zero exit status 1" and exits 1.
"""

from __future__ import annotations

import textwrap
from dataclasses import dataclass, field

WIDTH = 80


@dataclass(frozen=True)
class Ported:
    """A file of the user's ported to ROS 2: where it is (and was), each rewrite, the TODO(port) lines left."""

    path: str
    was: str | None
    rewrites: tuple[str, ...]  # `line N: before -> after`, N a line of the ROS 1 file
    todos: int


@dataclass
class Report:
    renamed: list[tuple[str, str]] = field(default_factory=list)  # (old path, new path)
    kept: list[tuple[str, str]] = field(default_factory=list)  # (path, why)
    to_port: list[tuple[str, str]] = field(default_factory=list)  # (path, what changed and where the starter is)
    conflicts: list[str] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)  # other things the user must do, one line each
    notes: list[str] = field(default_factory=list)  # said, nothing to do
    merged: set[str] = field(default_factory=set)  # files this step merged itself
    unwritable: list[tuple[str, str]] = field(default_factory=list)  # (path, why) a change could not be written
    ported: list[Ported] = field(default_factory=list)  # files a port to ROS 2 rewrote (rna/update/port.py)
    review: str = "git diff HEAD"  # how to see what the update did (a port moves files: git diff -M)

    @property
    def todos(self) -> int:
        return sum(item.todos for item in self.ported)

    @property
    def items(self) -> int:
        """How many things the user must do before committing."""
        return (len(self.kept) + len(self.to_port) + len(self.conflicts) + len(self.problems) + len(self.unwritable)
                + self.todos)

    @property
    def failed(self) -> bool:
        """Whether the user has items to do (the step then exits 1)."""
        return self.items > 0


@dataclass(frozen=True)
class Changes:
    """How the project changed, from git's point of view: relative paths."""

    added: list[str]
    updated: list[str]  # the template's changes to files the user had not edited
    merged: list[str]  # the template's changes merged with the user's edits
    removed: list[str]


def changes(added: set[str], changed: set[str], removed: set[str], edited: set[str], ignore: set[str]) -> Changes:
    """What git sees changed since the last commit; `edited`: the files the user had edited
    (their changes are merged with the template's, the others' only updated)."""
    changed = changed - ignore
    return Changes(sorted(added - ignore), sorted(changed - edited), sorted(changed & edited), sorted(removed - ignore))


def _files_line(label: str, paths: list[str]) -> list[str]:
    if not paths:
        return []
    text = f"  {label + ':':<10}" + ", ".join(paths)
    return textwrap.wrap(text, WIDTH, subsequent_indent=" " * 12, break_on_hyphens=False, break_long_words=False)


def _item_lines(path: str, why: str) -> list[str]:
    return textwrap.wrap(f"    {path}: {why}", WIDTH, subsequent_indent=" " * 6, break_on_hyphens=False,
                         break_long_words=False)


def _ported_lines(ported: list[Ported]) -> list[str]:
    """The files a port to ROS 2 rewrote: each rewrite, and the TODO(port) lines left in each."""
    rewrites, todos = sum(len(item.rewrites) for item in ported), sum(item.todos for item in ported)
    lines = [f"  ported to ROS 2 ({rewrites} rewrite{'s' * (rewrites != 1)}, {todos} line{'s' * (todos != 1)} "
             f"left marked TODO(port)):"]
    for item in ported:
        where = f"{item.path} (was {item.was})" if item.was and item.was != item.path else item.path
        counted = [f"{len(item.rewrites)} rewrite{'s' * (len(item.rewrites) != 1)}" if item.rewrites
                   else "your lines carried as written"]
        if item.todos:
            counted.append(f"{item.todos} TODO(port)")
        lines += _item_lines(where, ", ".join(counted))
        for rewrite in item.rewrites:
            lines += textwrap.wrap(rewrite, WIDTH, initial_indent=" " * 6, subsequent_indent=" " * 8,
                                   break_on_hyphens=False, break_long_words=False)
    if todos:
        lines += textwrap.wrap("    each TODO(port) is an item for you: a line of yours no rule ports, left as it was "
                               "under a comment naming its ROS 2 counterpart (git grep -n 'TODO(port)' lists them).",
                               WIDTH, subsequent_indent=" " * 6)
    return lines


def summary(report: Report, change: Changes, versions: str) -> str:
    """The text printed at the end of every update."""
    lines = [f"rna-template: what this update changed ({versions})"]
    renamed = [f"{old} -> {new}" for old, new in report.renamed]
    for label, paths in (("added", change.added), ("updated", change.updated),
                         ("merged", sorted(set(change.merged) | report.merged)), ("removed", change.removed),
                         ("renamed", renamed)):
        lines += _files_line(label, paths)
    if len(lines) == 1:
        lines.append("  nothing: the package already matches these answers")
    for note in report.notes:
        lines += textwrap.wrap(f"  {note}", WIDTH, subsequent_indent="    ")
    if report.kept:
        lines.append("  kept (you had edited them; the answers no longer make them):")
        for path, why in report.kept:
            lines += _item_lines(path, why)
    if report.to_port:
        lines.append("  to port (the template changed what your code builds on):")
        for path, why in report.to_port:
            lines += _item_lines(path, why)
    if report.ported:
        lines += _ported_lines(report.ported)
    if report.conflicts:
        lines.append("  conflicts (resolve the '<<<<<<< before updating' blocks or .rej files):")
        lines += [f"    {path}" for path in report.conflicts]
    if report.unwritable:
        lines.append("  not written (the template changed them; do it by hand):")
        for path, why in report.unwritable:
            lines += _item_lines(path, why)
    for problem in report.problems:
        lines += textwrap.wrap(f"  {problem}", WIDTH, subsequent_indent="    ")
    lines += textwrap.wrap(outcome(report.items, report.review), WIDTH)
    return "\n".join(lines)


def outcome(items: int, review: str = "git diff HEAD") -> str:
    """The summary's last words: done, or done with items for the user (what exit 1 means here)."""
    if not items:
        return f"Done. Review with `{review}`, then commit."
    which = "it is" if items == 1 else "they are"
    return (f"Done, with {items} item{'s' if items > 1 else ''} for you (above): review with `{review}`, and "
            f"commit once {which} done. copier exits with status 1 to say so; its line \"Task ... returned "
            "non-zero exit status 1\" below means that, not a failure.")
