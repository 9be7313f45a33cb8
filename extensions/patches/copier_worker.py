"""The patches of Copier's Worker: `git_file_mode` and `answers_file_name`.

Copier's Worker asks git for a setting after writing each file, and renders the answers
file's name anew for each file it renders: work whose result cannot change within a
worker's render. These wrap the Worker's method and property (on Copier's class, once per
process, marked so that another load of this package, or another template version's,
leaves them be) so that the work is done once per worker, and Copier's own code still runs
whenever the result could differ.
"""

from __future__ import annotations

import functools
import subprocess

from . import guards


def _worker_differs(member: str, parameters: list[str] | None, uses: tuple[str, ...]) -> str | None:
    """Whether Copier's Worker differs from the one the wrapper of `member` was written for: the
    method (or, `parameters` None, property) itself, and the members the wrapper reads (`uses`)."""
    try:
        from copier._main import Worker
    except ImportError:
        return "Copier has no copier._main.Worker"
    reason = guards.method_differs(Worker, member, parameters) or guards.members_missing(Worker, uses)
    return f"Copier's {reason}" if reason else guards.copier_differs()


def _git_file_mode_differs() -> str | None:
    return _worker_differs("_sync_git_index_executable_bit", ["self", "dst_relpath", "src_mode"],
                           ("jinja_env", "subproject"))


def _answers_file_name_differs() -> str | None:
    try:
        from copier._types import Phase
    except ImportError:
        return "Copier has no copier._types.Phase"
    if not hasattr(Phase, "RENDER") or not hasattr(Phase, "current"):
        return "Copier's Phase has no RENDER or current()"
    return _worker_differs("answers_relpath", None, ("jinja_env", "answers", "answers_file", "template"))


GUARDS = {"git_file_mode": _git_file_mode_differs, "answers_file_name": _answers_file_name_differs}
NEEDS: dict[str, str] = {}


def install(environment, on) -> None:
    """Both change Copier's Worker class, once per process."""
    for name, patch in (("git_file_mode", _ask_git_for_the_file_mode_once_per_worker),
                        ("answers_file_name", _render_the_answers_file_name_once_per_render)):
        if on(name):
            patch()


# ─── git_file_mode ────────────────────────────────────────────────────────────


def _ask_git_for_the_file_mode_once_per_worker() -> None:
    """Copier asks git for `core.fileMode` after writing each file, a git process per file
    (Worker._sync_git_index_executable_bit changes git's index only when that setting is
    false). The answer is the same for every file one worker writes: it is asked once per
    worker (its Jinja environment holds it), and Copier's method runs when it is false.
    """
    from copier._main import Worker

    sync = Worker._sync_git_index_executable_bit
    if getattr(sync, "rna_once_per_worker", False):  # another load, or another template version, did it
        return

    @functools.wraps(sync)
    def once_per_worker(self, dst_relpath, src_mode):
        settings = self.jinja_env.__dict__.setdefault("rna_git_file_mode", {})
        root = str(self.subproject.local_abspath)
        if root not in settings:
            settings[root] = _git_file_mode(root)
        if settings[root] != "false":
            return None
        return sync(self, dst_relpath, src_mode)

    once_per_worker.rna_once_per_worker = True
    Worker._sync_git_index_executable_bit = once_per_worker


def _git_file_mode(root: str) -> str | None:
    """`git config --type=bool --get core.fileMode` in `root`, or None (no repository, unset, no git)."""
    try:
        result = subprocess.run(["git", "config", "--type=bool", "--get", "core.fileMode"], cwd=root,
                                capture_output=True, text=True, check=False)
    except OSError:
        return None
    return result.stdout.strip() if result.returncode == 0 else None


# ─── answers_file_name ────────────────────────────────────────────────────────


def _render_the_answers_file_name_once_per_render() -> None:
    """Copier renders the answers file's name (`_answers_file`, templated here) anew for each
    file it renders, and each time a context hook reads `_copier_conf.answers_file`.

    While a worker renders its files (Copier's render phase), its answers are final, so the
    name is too: it is rendered once per render phase of a worker (its Jinja environment
    holds it) and asked anew in every other phase. A kept name is preprocessed all the
    same, as compiling it would: Copier's yield tag resets its state there, and Copier
    checks that state after rendering each file.
    """
    from copier._main import Worker
    from copier._types import Phase

    answers_relpath = Worker.answers_relpath
    if getattr(answers_relpath.fget, "rna_once_per_render", False):
        return
    render_name = answers_relpath.fget

    @functools.wraps(render_name)
    def once_per_render(self):
        if Phase.current() is not Phase.RENDER:
            return render_name(self)
        held = self.jinja_env.__dict__.get("rna_answers_relpath")
        if held is None or held[0] is not self.answers:  # the answers object is the worker's render's
            held = self.jinja_env.__dict__["rna_answers_relpath"] = (self.answers, render_name(self))
        else:
            self.jinja_env.preprocess(str(self.answers_file or self.template.answers_relpath))
        return held[1]

    once_per_render.rna_once_per_render = True
    Worker.answers_relpath = property(once_per_render, doc=answers_relpath.__doc__)
