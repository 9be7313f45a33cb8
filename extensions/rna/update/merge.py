"""A three-way line merge that also settles changes that only touch each other.

Copier merges the user's edits into the new version with git, which reports a conflict
whenever the two sides change neighbouring lines: a README line the user reworded just
before a paragraph the template adds, a library the user added to a list the template
grows. Where one side kept a run of lines as they were and only added lines before or
after it, while the other side changed that run, both changes fit: this merge takes
them both. Everything else stays a conflict, marked as Copier marks them.
"""

from __future__ import annotations

import difflib
import re
import subprocess
import tempfile
from pathlib import Path

from .project import Project, Render
from .summary import Report

OURS, BASE, THEIRS, END = "<<<<<<< before updating", "||||||| last update", "=======", ">>>>>>> after updating"


_METHOD = re.compile(r"^(\s+)def (\w+)\(")


def _methods(lines: list[str]) -> list[str] | None:
    """The names of the methods `lines` define, when they are whole methods of one class (at
    one indent) and nothing else; else None."""
    body = [line for line in lines if line.strip()]
    first = _METHOD.match(body[0]) if body else None
    if not first:
        return None
    names = []
    for line in body:
        method = _METHOD.match(line)
        if method and method.group(1) == first.group(1):
            names.append(method.group(2))
        elif not line.startswith(first.group(1) + " "):
            return None
    return names


def _settle(ours: list[str], base: list[str], theirs: list[str]) -> list[str] | None:
    """Both sides' changes of one conflicting region, when they fit together; else None."""
    if ours == base:
        return theirs
    if theirs == base or ours == theirs:
        return ours
    if not base:
        # Both added lines at one place: which order is right is the user's call, unless both
        # added whole Python methods of other names (the user's at the end of a class, where a
        # new starter method lands too): a class's methods have no order, so both are kept.
        mine, new = _methods(ours), _methods(theirs)
        return ours + theirs if mine and new and not set(mine) & set(new) else None
    for side, other in ((theirs, ours), (ours, theirs)):
        if side[:len(base)] == base:  # `side` kept the run and added lines after it
            return other + side[len(base):]
        if side[-len(base):] == base:  # `side` kept the run and added lines before it
            return side[:-len(base)] + other
    return None


def merge3(ours: str, base: str, theirs: str) -> tuple[str, bool]:
    """(the merged text, whether conflicts are left) of the user's text, the old render and the new one."""
    with tempfile.TemporaryDirectory(prefix="rna-merge-") as scratch:
        paths = []
        for name, text in (("ours", ours), ("base", base), ("theirs", theirs)):
            path = Path(scratch, name)
            path.write_bytes(text.encode("utf-8", "surrogateescape"))  # not through rna/files.py: the merge's scratch
            paths.append(str(path))
        result = subprocess.run(["git", "merge-file", "-p", "--diff3", "-L", OURS[8:], "-L", BASE[8:],
                                 "-L", END[8:], *paths], capture_output=True, encoding="utf-8",
                                errors="surrogateescape", check=False)
    if result.returncode < 0 or result.returncode > 127:
        raise RuntimeError(f"git merge-file failed: {result.stderr}")
    merged, conflicted, region, side = [], False, {}, None
    for line in result.stdout.split("\n"):
        if line == OURS:
            region, side = {"ours": [], "base": [], "theirs": []}, "ours"
        elif side and line == BASE:
            side = "base"
        elif side and line == THEIRS:
            side = "theirs"
        elif side and line == END:
            settled = _settle(region["ours"], region["base"], region["theirs"])
            if settled is None:
                conflicted = True
                settled = [OURS, *region["ours"], THEIRS, *region["theirs"], END]
            merged += settled
            side = None
        elif side:
            region[side].append(line)
        else:
            merged.append(line)
    return "\n".join(merged), conflicted


def sides(text: str) -> tuple[str, str]:
    """(the user's side, the template's side) of a text merge3 left conflicts in."""
    ours, theirs, side = [], [], None
    for line in text.split("\n"):
        if line == OURS:
            side = "ours"
        elif side == "ours" and line == THEIRS:
            side = "theirs"
        elif side and line == END:
            side = None
        else:
            (ours if side != "theirs" else []).append(line)
            (theirs if side != "ours" else []).append(line)
    return "\n".join(ours), "\n".join(theirs)


def rejected(path: str, text: str) -> tuple[str, str]:
    """A text with conflicts as `--conflict rej` leaves it: (the file with the user's side of each,
    its .rej file: the template's changes left out, as a diff against that file)."""
    ours, theirs = sides(text)
    diff = difflib.unified_diff(ours.split("\n"), theirs.split("\n"), f"a/{path}", f"b/{path}", lineterm="")
    return ours, "\n".join(diff) + "\n"


def write_conflicted(project: Project, path: str, text: str, like: str | None = None) -> bool:
    """A merged text written as the update's --conflict asks: its conflicts marked in it (inline),
    or the user's side in it and the template's in a .rej file beside it (rej); whether it was written."""
    if project.conflict != "rej" or OURS not in text:
        return project.write(path, text, like=like)
    ours, diff = rejected(path, text)
    return project.write(path, ours, like=like) and project.write(f"{path}.rej", diff)


def settle_conflicts(project: Project, old: Render, new: Render, report: Report, skip: re.Pattern,
                     handled: set[str] = frozenset()) -> None:
    """Files Copier left in conflict (markers or .rej) merged again here, kept when no conflict is left.

    `skip`: files merged otherwise; `handled`: files an earlier step merged already."""
    added, changed, _ = project.changed_files()
    for path in sorted(added | changed):
        target = path[:-4] if path.endswith(".rej") else path
        text = project.text(target)
        if skip.search(target) or target in handled or text is None or not (path.endswith(".rej") or OURS in text):
            continue
        ours, base, theirs = project.committed(target), old.text(target), new.text(target)
        if None in (ours, base, theirs):
            continue
        merged, conflicted = merge3(ours, base, theirs)
        if conflicted or not project.write(target, merged):
            continue
        if (project.root / f"{target}.rej").exists():
            (project.root / f"{target}.rej").unlink()
        project.resolve_in_index(target)
        report.merged.add(target)
