"""The project being updated, seen three ways: committed, rendered by the old version, by the new one.

`copier update` requires a clean git project, so the last commit holds exactly what the
user had before the update. The old and new renders are fresh copies of the template
(old version with the old answers, new version with the new ones) in scratch folders:
together they tell, for every file, whether the user edited it and whether the template
changed it.
"""

from __future__ import annotations

import contextlib
import subprocess
from dataclasses import dataclass, field
from pathlib import Path


def git(project: Path, *args: str, check: bool = True, stdin: str | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(["git", *args], cwd=project, capture_output=True, text=True, check=check, input=stdin)


def render(template: str, commit: str, answers: dict, destination: Path) -> Path:
    """A fresh copy of `template` at `commit` with `answers`, without tasks or migrations."""
    import copier

    data = {key: value for key, value in answers.items() if not key.startswith("_")}
    copier.run_copy(template, destination, data=data, vcs_ref=commit, defaults=True,
                    unsafe=True, quiet=True, skip_tasks=True)
    return destination


def files_under(root: Path) -> set[str]:
    """Every file below `root` (relative paths), `.git` left out."""
    return {str(path.relative_to(root)) for path in root.rglob("*")
            if path.is_file() and ".git" not in path.relative_to(root).parts}


def read(root: Path, path: str) -> str | None:
    file = root / path
    if not file.is_file():
        return None
    try:
        return file.read_text()
    except UnicodeDecodeError:
        return file.read_bytes().decode("latin-1")  # compared, never parsed


@dataclass
class Render:
    """A fresh copy of one template version, in a scratch folder."""

    root: Path
    files: set[str] = field(init=False)

    def __post_init__(self) -> None:
        self.files = files_under(self.root)

    def text(self, path: str) -> str | None:
        return read(self.root, path) if path in self.files else None


@dataclass
class Project:
    """The destination folder of the update, and its last commit (what the user had)."""

    root: Path
    answers_file: str
    conflict: str | None = None  # how the update was told to leave conflicts: inline or rej
    _committed: dict[str, str | None] = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        self.prefix = git(self.root, "rev-parse", "--show-prefix").stdout.strip()
        # --full-name: from a package inside a larger repository git lists paths from
        # this folder otherwise, and the prefix is taken off below.
        listed = git(self.root, "ls-tree", "-r", "-z", "--full-name", "--name-only", "HEAD", "--", ".").stdout
        self.committed_files = {name[len(self.prefix):] for name in listed.split("\0") if name}

    def committed(self, path: str) -> str | None:
        """The file as the user committed it, or None."""
        if not self._committed:
            self._committed.update(self._all_committed())
        if path not in self._committed:
            shown = git(self.root, "show", f"HEAD:{self.prefix}{path}", check=False) \
                if path in self.committed_files else None
            self._committed[path] = shown.stdout if shown is not None and shown.returncode == 0 else None
        return self._committed[path]

    def _all_committed(self) -> dict[str, str]:
        """Every committed file that reads as UTF-8, from one git process (the update reads them all)."""
        paths = sorted(path for path in self.committed_files if "\n" not in path)
        listed = "".join(f"HEAD:{self.prefix}{path}\n" for path in paths).encode()
        output = subprocess.run(["git", "cat-file", "--batch"], cwd=self.root, input=listed, capture_output=True,
                                check=False).stdout
        found, start = {}, 0
        for path in paths:
            end = output.find(b"\n", start)
            if end < 0:  # git stopped short: the rest is read alone when asked
                break
            header = output[start:end].split()
            start = end + 1
            if len(header) != 3 or not header[2].isdigit():  # "<name> missing": no content follows
                continue
            size = int(header[2])
            if header[1] == b"blob":
                with contextlib.suppress(UnicodeDecodeError):  # read alone, as before, when asked
                    # as `git show` read in text mode gives it: universal newlines
                    found[path] = output[start:start + size].decode().replace("\r\n", "\n").replace("\r", "\n")
            start += size + 1
        return found

    def text(self, path: str) -> str | None:
        """The file as it is now."""
        return read(self.root, path)

    def write(self, path: str, text: str) -> None:
        target = self.root / path
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(text)

    def restore(self, path: str, to: str | None = None) -> None:
        """Put the committed file back, at its place or at `to`, with its mode."""
        target = self.root / (to or path)
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(self.committed(path) or "")
        mode = git(self.root, "ls-tree", "HEAD", "--", f"{self.root / path}").stdout.split(" ", 1)[0]
        if mode == "100755":
            target.chmod(0o755)

    def remove(self, path: str) -> None:
        target = self.root / path
        if target.is_file():
            target.unlink()
        for parent in target.relative_to(self.root).parents:
            folder = self.root / parent
            if not folder.is_dir():
                continue  # gone already (Copier removed what it emptied)
            if folder == self.root or any(folder.iterdir()):
                break
            folder.rmdir()

    def current_files(self) -> set[str]:
        """Files in the project now that git does not ignore."""
        listed = git(self.root, "ls-files", "-z", "--full-name", "--cached", "--others", "--exclude-standard",
                     "--", ".").stdout
        names = {name[len(self.prefix):] for name in listed.split("\0") if name}
        return {name for name in names if (self.root / name).is_file()}

    def resolve_in_index(self, path: str) -> None:
        """Clear a conflict Copier recorded in the index for a file settled here."""
        git(self.root, "reset", "-q", "--", path, check=False)
