"""Files the user edited stay; files the user never touched follow the template.

Copier deletes every file the old version made and the new one does not, edited or
not, and never refreshes a user file (`_skip_if_exists`) once it exists. Here:

- a file the user had edited (its committed text differs from the old render) that the
  new answers no longer make is put back and reported: the update fails until the user
  decides (`kept`);
- a node's user file the user never edited gets the new starter code, so an untouched
  package stays equal to a fresh copy.
"""

from __future__ import annotations

from .project import Project, Render
from .summary import Report


def edited(project: Project, old: Render, path: str) -> bool:
    """The user changed this file (or made it): its committed text is not what the old version made."""
    before = project.committed(path)
    return before is not None and before != old.text(path)


def refresh_untouched_starters(project: Project, old: Render, new: Render, user_files: set[str],
                               report: Report) -> None:
    """A user file never edited holds what a fresh copy would hold now."""
    for path in sorted(user_files & new.files):
        before = project.committed(path)
        if before is None or edited(project, old, path) or project.text(path) != before:
            continue
        if new.text(path) != before:
            project.write(path, new.text(path))
            report.notes.append(f"{path} was never edited, so it now holds the current starter code.")


def keep_edited_files(project: Project, old: Render, new: Render, why: dict[str, str], report: Report) -> None:
    """Put back each edited file the new answers no longer make (Copier deleted it)."""
    for path in sorted(old.files - new.files):
        if not edited(project, old, path) or (project.root / path).exists():
            continue
        project.restore(path)
        report.notes.append(f"KEPT {path}: its node is gone from the answers, but you had edited it. "
                            "Delete it once you no longer need it.")
