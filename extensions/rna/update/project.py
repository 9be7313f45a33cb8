"""The project being updated, seen three ways: committed, rendered by the old version, by the new one.

`copier update` requires a clean git project, so the last commit holds exactly what the
user had before the update. The old and new renders are fresh copies of the template
(old version with the old answers, new version with the new ones) in scratch folders:
together they tell, for every file, whether the user edited it and whether the template
changed it. Every file is read and written through rna/files.py: binary files, other
encodings, CRLF line ends, symbolic links and large files come through as they were.
"""

from __future__ import annotations

import os
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

from .. import files
from ..files import Content


def git(project: Path, *args: str, check: bool = True, stdin: str | None = None) -> subprocess.CompletedProcess:
    """git's output as text; paths that are not UTF-8 come through as Python's file system names."""
    return subprocess.run(["git", *args], cwd=project, capture_output=True, encoding="utf-8",
                          errors="surrogateescape", check=check, input=stdin)


def render(template: str, commit: str, answers: dict, destination: Path) -> Path:
    """A fresh copy of `template` at `commit` with `answers`, without tasks or migrations."""
    import copier

    data = {key: value for key, value in answers.items() if not key.startswith("_")}
    copier.run_copy(template, destination, data=data, vcs_ref=commit, defaults=True,
                    unsafe=True, quiet=True, skip_tasks=True)
    return destination


def files_under(root: Path) -> set[str]:
    """Every file below `root` (relative paths), `.git` left out; links are not followed."""
    found = set()
    for folder, folders, names in os.walk(root):
        folders[:] = [name for name in folders if name != ".git"]
        found.update(str(Path(folder, name).relative_to(root)) for name in names)
        # a link to a folder is listed by os.walk among the folders, and is a file here
        found.update(str(Path(folder, name).relative_to(root)) for name in folders if Path(folder, name).is_symlink())
    return found


@dataclass
class Render:
    """A fresh copy of one template version, in a scratch folder."""

    root: Path
    files: set[str] = field(init=False)

    def __post_init__(self) -> None:
        self.files = files_under(self.root)

    def content(self, path: str) -> Content | None:
        return files.read(self.root, path, owned=True) if path in self.files else None

    def text(self, path: str) -> str | None:
        content = self.content(path)
        return content.text if content is not None else None


@dataclass(frozen=True)
class Entry:
    """A file of the last commit, from `git ls-tree`."""

    mode: str
    object: str
    size: int

    @property
    def is_link(self) -> bool:
        return self.mode == "120000"


@dataclass
class Project:
    """The destination folder of the update, and its last commit (what the user had)."""

    root: Path
    answers_file: str
    conflict: str | None = None  # how the update was told to leave conflicts: inline or rej
    owned: set[str] = field(default_factory=set)  # what the template makes: read whatever its size
    unwritable: list[tuple[str, str]] = field(default_factory=list)  # (path, why) a step could not write
    _committed: dict[str, Content | None] = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        self.prefix = git(self.root, "rev-parse", "--show-prefix").stdout.strip()
        # --full-name: from a package inside a larger repository git lists paths from
        # this folder otherwise, and the prefix is taken off below. -l: each blob's size.
        listed = git(self.root, "ls-tree", "-r", "-z", "-l", "--full-name", "HEAD", "--", ".").stdout
        self.entries: dict[str, Entry] = {}
        for line in filter(None, listed.split("\0")):
            meta, _, name = line.partition("\t")
            mode, kind, obj, size = meta.split()
            if kind == "blob":  # a submodule is a commit: not a file of this project
                self.entries[name[len(self.prefix):]] = Entry(mode, obj, int(size))
        self.committed_files = set(self.entries)

    # --- the last commit

    def committed_content(self, path: str) -> Content | None:
        """The file as the user committed it, or None."""
        if not self._committed:
            self._committed.update(self._all_committed())
        if path not in self._committed:
            entry = self.entries.get(path)
            self._committed[path] = None if entry is None else self._read_committed(path, entry)
        return self._committed[path]

    def committed(self, path: str) -> str | None:
        """The text of the file as the user committed it, or None (no such file, not text)."""
        content = self.committed_content(path)
        return content.text if content is not None else None

    def _read_committed(self, path: str, entry: Entry) -> Content:
        if entry.size > files.LARGE and not entry.is_link and path not in self.owned:
            return Content("large", size=entry.size)
        data = files.blob(self.root, entry.object)
        return files.link(data) if entry.is_link else files.of_bytes(data)

    def _all_committed(self) -> dict[str, Content]:
        """Every committed file the update reads (not the large ones), from one git process."""
        wanted = {path: entry for path, entry in self.entries.items() if entry.size <= files.LARGE or entry.is_link}
        found = files.blobs(self.root, sorted({entry.object for entry in wanted.values()}))
        return {path: files.link(found[entry.object]) if entry.is_link else files.of_bytes(found[entry.object])
                for path, entry in wanted.items() if entry.object in found}

    def committed_mode(self, path: str) -> str | None:
        entry = self.entries.get(path)
        return entry.mode if entry is not None else None

    # --- the project now

    def content(self, path: str) -> Content | None:
        """The file as it is now."""
        return files.read(self.root, path, owned=path in self.owned)

    def text(self, path: str) -> str | None:
        """The text of the file as it is now, or None (no such file, not text)."""
        content = self.content(path)
        return content.text if content is not None else None

    def write(self, path: str, text: str, like: str | None = None) -> bool:
        """Write `text` to `path` as the user's file holds text: in its encoding and line ends
        (the file as committed at `like`, or at `path`, or as it is now). Whether it was written:
        a file that cannot be (a link, a folder leading out of the project, text its encoding
        cannot hold) is left as it is and listed for the user."""
        committed = self.committed_content(like or path)
        try:
            files.write(self.root, path, text, committed if committed is not None and committed.kind == "text"
                        else None)
        except files.NotWritable as error:
            self.unwritable.append((path, str(error)))
            return False
        return True

    def restore(self, path: str, to: str | None = None) -> None:
        """Put the committed file back, at its place or at `to`: its bytes (or link), with its mode."""
        content = self.committed_content(path)
        if content is None:
            return
        executable = self.committed_mode(path) == "100755"
        try:
            if content.kind == "large":  # not held in memory: git writes it
                files.put_blob(self.root, to or path, self.entries[path].object, executable)
            else:
                files.put(self.root, to or path, content, executable)
        except files.NotWritable as error:
            self.unwritable.append((to or path, str(error)))

    def remove(self, path: str) -> None:
        target = self.root / path
        if target.is_file() or target.is_symlink():
            target.unlink()
        for parent in target.relative_to(self.root).parents:
            folder = self.root / parent
            if folder.is_symlink() or not folder.is_dir():
                continue  # gone already (Copier removed what it emptied)
            if folder == self.root or any(folder.iterdir()):
                break
            folder.rmdir()

    def current_files(self) -> set[str]:
        """Files (and links) in the project now that git does not ignore."""
        listed = git(self.root, "ls-files", "-z", "--full-name", "--cached", "--others", "--exclude-standard",
                     "--", ".").stdout
        names = {name[len(self.prefix):] for name in listed.split("\0") if name}
        return {name for name in names if (self.root / name).is_symlink() or (self.root / name).is_file()}

    def changed_files(self) -> tuple[set[str], set[str], set[str]]:
        """(added, changed, removed) since the last commit, as git sees them (its index's file
        times spare it reading the files nobody touched, large ones included)."""
        listed = git(self.root, "status", "--porcelain=v1", "-z", "--untracked-files=all", "--no-renames",
                     "--", ".").stdout
        added, changed, removed = set(), set(), set()
        for item in filter(None, listed.split("\0")):
            status, name = item[:2], item[3:][len(self.prefix):]
            exists = (self.root / name).is_symlink() or (self.root / name).is_file()
            if name not in self.committed_files:
                if exists:
                    added.add(name)
            elif not exists:
                removed.add(name)
            elif status != "  ":
                changed.add(name)
        return added, changed, removed

    def line_ends_as_checked_out(self) -> None:
        """Give the files the update wrote the line ends git checks them out with (CRLF in a
        checkout made so by .gitattributes or core.autocrlf; Copier writes LF)."""
        added, changed, _ = self.changed_files()
        files.as_checked_out(self.root, sorted(added | changed))

    def resolve_in_index(self, path: str) -> None:
        """Clear a conflict Copier recorded in the index for a file settled here."""
        git(self.root, "reset", "-q", "--", path, check=False)
