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
3. merges a config file the line merge left in conflict by parameter instead
   (rna/configs.py);
4. reports conflict markers and .rej files left by the merge and exits 1 if any.

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
from rna import build_package, configs  # noqa: E402 - the template's own package, next to this file

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


def user_files(answers: dict) -> set[str] | None:
    """The files the answers make the user's (relative to the project folder), or None."""
    try:
        return set(build_package(answers).user_files)
    except ValueError as error:  # answers an older version accepted and this one does not
        print(f"rna-template: cannot tell your files from these answers ({error})", file=sys.stderr)
        return None


def protect_user_files(project: Path, old: Path, new: Path, paths: set[str]) -> None:
    """Keep an edited file of a removed node; refresh a file the user never edited."""
    for path in sorted(paths):
        before = committed(project, path)  # the user's version, if the file existed
        generated = (old / path).read_text() if (old / path).is_file() else None
        edited = before is not None and before != generated
        current = project / path
        if (new / path).is_file():
            unchanged = current.is_file() and current.read_text() == before
            if before is not None and not edited and unchanged and (new / path).read_text() != before:
                shutil.copy(new / path, current)
                print(f"rna-template: {path} was never edited, so it now holds the current starter code")
        elif edited and not current.exists():
            git(project, "checkout", "HEAD", "--", path)
            print(f"rna-template: KEPT {path}: its node is gone from the answers, but you had edited it. "
                  "Delete it once you no longer need it.")


def merge_config_files(project: Path, old: Path, new: Path) -> None:
    """Settle line conflicts in config/<node>.yaml by parameter (rna/configs.py)."""
    for rendered in sorted(new.rglob("config/*.yaml")):
        path = str(rendered.relative_to(new))
        current, before = project / path, committed(project, path)
        if before is None or not current.is_file() or not any(m in current.read_text() for m in MARKERS):
            continue
        old_text = (old / path).read_text() if (old / path).is_file() else ""
        merged = configs.merge(old_text, before, rendered.read_text())
        if merged is not None:
            current.write_text(merged)
            git(project, "add", "--", path)  # clears the conflict Copier recorded in the index
            print(f"rna-template: {path} merged by parameter: your tuned values kept, new defaults taken")


def conflicts(project: Path) -> list[str]:
    """Files the merge left conflict markers in, and .rej files."""
    found = []
    for path in sorted(p for p in project.rglob("*") if p.is_file() and ".git" not in p.parts):
        if path.suffix == ".rej":
            found.append(str(path.relative_to(project)))
            continue
        try:
            text = path.read_text()
        except (UnicodeDecodeError, OSError):
            continue
        if any(marker in text for marker in MARKERS):
            found.append(str(path.relative_to(project)))
    return found


def main(project: Path, template: str, answers_file: str) -> int:
    old_answers = yaml.safe_load(committed(project, answers_file) or "{}") or {}
    new_answers = yaml.safe_load((project / answers_file).read_text())
    paths = [user_files(old_answers), user_files(new_answers)]
    with tempfile.TemporaryDirectory(prefix="rna-update-") as scratch:
        old = render(template, old_answers["_commit"], old_answers, Path(scratch, "old"))
        new = render(template, new_answers["_commit"], new_answers, Path(scratch, "new"))
        if None not in paths:
            protect_user_files(project, old, new, paths[0] | paths[1])
        merge_config_files(project, old, new)
    failed = conflicts(project)
    if failed:
        print("\nrna-template: copier update could not merge your edits in these files:", file=sys.stderr)
        for path in failed:
            print(f"  {path}", file=sys.stderr)
        print("Resolve the '<<<<<<< before updating' blocks (or .rej files), then commit.\n", file=sys.stderr)
    if None in paths:
        print("rna-template: your node files were not checked: compare them with `git diff HEAD` before "
              "committing (a removed node's file may be gone).", file=sys.stderr)
    return 1 if failed or None in paths else 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), sys.argv[2], sys.argv[3]))
