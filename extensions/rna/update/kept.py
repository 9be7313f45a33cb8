"""Copier's own renders of the old and the new version, kept for the after-update step.

`copier update` renders the old version (old answers) and the new one (new answers) into
scratch folders and deletes them before the after-update step runs, and that step needs
the same two renders. Rendering them again was a third of an update, so the template's
glue copies each one out when Copier has finished rendering it (Copier then renders the
`when` of the template's task, in the scratch folder) into a folder of this process, and
the after-update step, given that folder, takes a render only if it was made from exactly
the answers (template source and commit included) the step would render it from.
Anything else (an older version's glue that kept nothing, `--skip-tasks`, `--exclude`,
answers that differ) and the step renders that version itself.

Layout of the folder: `<kind>/files/` (the render) and `<kind>/answers.yml` (the answers
file that render records, resolved as the template writes it), with `<kind>` `old` or
`new`, and `<kind>/from` the scratch folder it was copied from. The step finds the folder
named in POINTER, in the template clone it runs from (Copier's private clone, written
while Copier renders the step's command; the command line stays the plain one Copier shows).
"""

from __future__ import annotations

import shutil
from pathlib import Path

import yaml

# Copier's scratch folders in an update (copier/_main.py: TemporaryDirectory prefixes). Another
# name in another Copier version only means nothing is kept.
SCRATCH_PREFIXES = {"old": "copier._main.old_copy.", "new": "copier._main.new_copy."}


POINTER = ".rna-kept-renders"


def point(template: Path, folder: str) -> None:
    (template / POINTER).write_text(folder)  # not through rna/files.py: Copier's clone of the template


def pointed(template: Path) -> str | None:
    """The folder of kept renders named in `template`, if any."""
    try:
        return (template / POINTER).read_text().strip() or None  # not through rna/files.py: Copier's clone
    except OSError:
        return None


def kind_of(destination: Path) -> str | None:
    """`old` or `new` for one of Copier's update scratch folders, else None."""
    return next((kind for kind, prefix in SCRATCH_PREFIXES.items()
                 if any(part.startswith(prefix) for part in destination.parts)), None)


def keep(folder: Path, kind: str, destination: Path, answers_text: str) -> None:
    """Copy the render in `destination` to `folder`/`kind`, once per render (the hook runs more than once)."""
    target = folder / kind
    # not through rna/files.py: scratch
    if (target / "from").is_file() and (target / "from").read_text() == str(destination):
        return
    shutil.rmtree(target, ignore_errors=True)  # a render of an earlier update in this process
    # not through rna/files.py: a render of the template, copied as it is
    shutil.copytree(destination, target / "files", symlinks=True, ignore=shutil.ignore_patterns(".git"))
    (target / "answers.yml").write_text(answers_text)  # not through rna/files.py: scratch
    (target / "from").write_text(str(destination))  # not through rna/files.py: scratch


def kept(folder: str | None, kind: str, answers: dict) -> Path | None:
    """The kept render of `kind`, if it was rendered from exactly `answers` (an answers file's content)."""
    if not folder:
        return None
    target = Path(folder) / kind
    try:
        recorded = yaml.safe_load((target / "answers.yml").read_text())  # not through rna/files.py: scratch
    except (OSError, yaml.YAMLError):
        return None
    if not isinstance(recorded, dict) or recorded != answers or "_commit" not in answers:
        return None
    return target / "files" if (target / "files").is_dir() else None


def discard(folder: str | None) -> None:
    """Remove the kept renders once read: the next update in this process keeps its own."""
    for kind in SCRATCH_PREFIXES if folder else ():
        shutil.rmtree(Path(folder, kind), ignore_errors=True)
