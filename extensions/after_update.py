"""Run by `copier update` once it has finished (an unversioned "after" migration).

Copier's update gets two things wrong for a project where users own some files:

* A file of the user's (a node's `<node>.py` / `<node>.cpp`, `_skip_if_exists`) is
  deleted when its node leaves the answers, edited or not.
* It leaves conflict markers in files and still exits 0.

This script, given the project folder, renders the previous template version with
the previous answers and the current version with the current answers (Copier's own
API, into temporary folders), then:

1. puts back every user file of a removed node that the user had edited (it stays
   where it was, and is reported);
2. refreshes every user file the user never edited to what a fresh copy would hold
   now (new callbacks of a grown node, a newer starter), so an untouched package
   stays equal to a fresh one;
3. reports conflict markers and .rej files left by the merge and exits 1 if any.

Nothing here changes a file the user edited.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rna import build_package  # noqa: E402 - the template's own package, next to this file

MARKERS = ("<<<<<<< before updating", ">>>>>>> after updating")


def git(project: Path, *args: str, check: bool = True) -> subprocess.CompletedProcess:
    return subprocess.run(["git", *args], cwd=project, capture_output=True, text=True, check=check)


def committed(project: Path, path: str) -> str | None:
    """The file's content in the last commit, which copier update requires to be clean."""
    prefix = git(project, "rev-parse", "--show-prefix").stdout.strip()
    shown = git(project, "show", f"HEAD:{prefix}{path}", check=False)
    return shown.stdout if shown.returncode == 0 else None


def render(template: str, commit: str, answers: dict, destination: Path) -> Path:
    """A fresh copy of `template` at `commit` with `answers`, without tasks or migrations."""
    import copier

    data = {key: value for key, value in answers.items() if not key.startswith("_")}
    copier.run_copy(template, destination, data=data, vcs_ref=commit, defaults=True,
                    unsafe=True, quiet=True, skip_tasks=True)
    return destination


def user_files(answers: dict) -> set[str]:
    """The files the answers make the user's (relative to the project folder)."""
    try:
        return set(build_package(answers).user_files)
    except ValueError as error:  # answers an older version accepted and this one does not
        print(f"rna-template: cannot tell your files from these answers ({error})", file=sys.stderr)
        return set()


def main(project: Path, template: str, answers_file: str) -> int:
    old_answers = yaml.safe_load(committed(project, answers_file) or "{}") or {}
    new_answers = yaml.safe_load((project / answers_file).read_text())
    kept, refreshed = [], []
    with tempfile.TemporaryDirectory(prefix="rna-update-") as scratch:
        old = render(template, old_answers["_commit"], old_answers, Path(scratch, "old"))
        new = render(template, new_answers["_commit"], new_answers, Path(scratch, "new"))
        for path in sorted(user_files(old_answers) | user_files(new_answers)):
            before = committed(project, path)  # the user's version, if the file existed
            generated = (old / path).read_text() if (old / path).is_file() else None
            edited = before is not None and before != generated
            current = project / path
            if (new / path).is_file():
                unchanged = current.is_file() and current.read_text() == before
                if before is not None and not edited and unchanged:
                    if (new / path).read_text() != before:
                        shutil.copy(new / path, current)
                        refreshed.append(path)
            elif edited and not current.exists():
                git(project, "checkout", "HEAD", "--", path)
                kept.append(path)

    for path in refreshed:
        print(f"rna-template: {path} was never edited, so it now holds the current starter code")
    for path in kept:
        print(f"rna-template: KEPT {path}: its node is gone from the answers, but you had edited "
              "it. Delete it once you no longer need it.")

    conflicts = []
    for path in sorted(p for p in project.rglob("*") if p.is_file() and ".git" not in p.parts):
        if path.suffix == ".rej":
            conflicts.append(str(path.relative_to(project)))
            continue
        try:
            text = path.read_text()
        except (UnicodeDecodeError, OSError):
            continue
        if any(marker in text for marker in MARKERS):
            conflicts.append(str(path.relative_to(project)))
    if conflicts:
        print("\nrna-template: copier update could not merge your edits in these files:", file=sys.stderr)
        for path in conflicts:
            print(f"  {path}", file=sys.stderr)
        print("Resolve the '<<<<<<< before updating' blocks (or .rej files), then commit.\n",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), sys.argv[2], sys.argv[3]))
