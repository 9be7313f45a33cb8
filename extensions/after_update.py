"""Run by `copier update` once it has finished (an unversioned "after" migration).

Copier merges the template's changes into the project line by line; this script, given
the answers file (the project is the current folder) and the renders of the old and the
new version Copier made in this update (rna/update/kept.py; rendered again when they were
not kept), finishes the job so that nothing the user wrote is lost (rna/update/ says how,
one module per job), then prints what the update did and what the user must do. It exits
1 when the user must act: a conflict, an edited file the answers no longer make, code
that no longer matches its base class.
"""

from __future__ import annotations

import sys
import tempfile
import traceback
from pathlib import Path

import yaml

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import patches  # noqa: E402 - next to this file

with patches.template_modules(HERE):
    from rna import Package, build_package  # the template's own package, next to this file
    from rna.update import blocks, config_merge, drift, kept, merge, port, protect, rename_answers, renames
    from rna.update.project import Project, Render, git, render
    from rna.update.summary import Report, changes, summary

MARKERS = ("<<<<<<< before updating", ">>>>>>> after updating")


def package_of(answers: dict, report: Report) -> Package | None:
    """The model of the answers, or None when this version cannot read them."""
    try:
        return build_package(answers)
    except ValueError as error:  # answers an older version accepted and this one does not
        report.problems.append(f"Your node files were not checked (the old answers do not read: {error}): "
                               "compare them with `git diff HEAD` before committing.")
        return None


def conflicts(project: Project, touched: set[str]) -> list[str]:
    """Files the merge left conflict markers in, and .rej files, among the files the update touched."""
    found = []
    for path in sorted(touched):
        if path.endswith(".rej"):
            found.append(path)
        elif any(marker in (project.text(path) or "") for marker in MARKERS):
            found.append(path)
    return found


def render_of(kind: str, answers: dict, renders: str | None, template: Path, scratch: str) -> Render:
    """The render of one version: the one Copier made in this update if it was kept, else a new one."""
    folder = kept.kept(renders, kind, answers)
    if folder is None:
        folder = render(str(template), answers["_commit"], answers, Path(scratch, kind))
    return Render(folder)


def main(answers_file: str, project_root: Path | None = None, template: Path = HERE.parent,
         renders: str | None = None, conflict: str | None = None) -> int:
    """Finish the update; 0 when it is done, 1 when the user has items to do or it failed."""
    root = project_root or Path.cwd()
    try:
        return finish(answers_file, root, template, renders, conflict)
    except Exception as error:  # noqa: BLE001 - whatever broke, the user's package must come back whole
        print(rolled_back(root, error), file=sys.stderr)
        return 1


def finish(answers_file: str, root: Path, template: Path, renders: str | None, conflict: str | None) -> int:
    project = Project(root, answers_file, conflict)
    old_answers = yaml.safe_load(project.committed(answers_file) or "{}") or {}
    new_answers = yaml.safe_load(project.text(answers_file) or "{}") or {}
    renamed = rename_answers.renames(new_answers)  # new name -> old name, said by the answers once
    if renamed and (consumed := rename_answers.without_renames(project.text(answers_file))) is not None:
        project.write(answers_file, consumed)
    report = Report()
    renders = renders or kept.pointed(template)
    with tempfile.TemporaryDirectory(prefix="rna-update-") as scratch:
        old = render_of("old", old_answers, renders, template, scratch)
        new_answers = rename_answers.without_keys(new_answers)  # the renames are this update's, not answers
        new = render_of("new", new_answers, renders, template, scratch)
        project.owned |= old.files | new.files
        packages = (package_of(old_answers, report), package_of(new_answers, report))
        handled = set()
        ported = port.porting(packages)  # ROS 1 -> ROS 2: the port carries every file of the user's
        if None not in packages and not ported:
            handled |= renames.carry_renamed_package(project, old, new, packages, report)
            handled |= renames.carry_renamed_nodes(project, old, new, packages, renamed, report)
        if ported:
            handled |= port.port_package(project, old, new, packages, report, renamed)
        protect.keep_edited_files(project, old, new, packages, report, skip=handled)
        if None not in packages:
            user_files = set(packages[0].user_files) | set(packages[1].user_files)
            protect.refresh_untouched_starters(project, old, new, user_files, report)
            if not ported:
                drift.port_edited_user_files(project, old, new, packages, report, renamed)
        merge.settle_conflicts(project, old, new, report, skip=config_merge.CONFIG, handled=handled)
        config_merge.merge_config_files(project, old, new, packages, report, skip=handled)
        blocks.leave_out_user_declarations(project, new, report)
        blocks.dropped_but_used(project, old, report)
        blocks.unreadable_package_xml(project, report)
        project.line_ends_as_checked_out()
        added, changed, removed = project.changed_files()
        report.conflicts = conflicts(project, added | changed)
        report.unwritable = list(project.unwritable)
        edited = {path for path in changed if protect.edited(project, old, path)}
    kept.discard(renders)
    versions = f"{old_answers.get('_commit')} -> {new_answers.get('_commit')}"
    moved = {path for pair in report.renamed for path in pair}
    print(summary(report, changes(added, changed, removed, edited, {answers_file} | moved), versions))
    return 1 if report.failed else 0


def rolled_back(root: Path, error: Exception) -> str:
    """Put the project back as the user committed it (Copier updates a clean project only, so
    whatever is not committed is the update's), and say so in one line."""
    for command in (("reset", "-q", "--", "."), ("checkout", "-q", "HEAD", "--", "."), ("clean", "-fdq", "--", ".")):
        git(root, *command, check=False)
    where = traceback.extract_tb(error.__traceback__)[-1]
    return (f"rna-template: the update failed while finishing ({type(error).__name__}: {error}, at "
            f"{Path(where.filename).name}:{where.lineno}), so it was undone: the package is as you committed it. "
            "Please report this, with the command you ran.")


if __name__ == "__main__":
    # argv: the answers file, then Copier's --conflict (inline or rej).
    sys.exit(main(sys.argv[1], conflict=sys.argv[2] if len(sys.argv) > 2 else None))
