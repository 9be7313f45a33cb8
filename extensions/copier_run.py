"""What the glue learns once in a Copier run and reuses at every render of it.

Copier renders about ten strings per file, each with a render context of its own that
the glue's context hook sees, so what the hook needs is found once: the answers file
that was in the destination before the run, whether it was edited by hand, the answers
given with --data checked, the package model of a set of answers; and what the questions'
defaults need once (the interfaces around the destination, the user's git settings).
Copier loads the glue
afresh for each of its workers (a copy has one, an update four), and the glue keeps one
`Run` per load; what outlives a worker (parsed answers files, the update's kept renders)
is process-wide.
"""

from __future__ import annotations

import atexit
import functools
import json
import os
import pickle
import re
import shutil
import sys
import tempfile
import types
from collections.abc import Mapping
from pathlib import Path

import yaml

import rna
import rna.files
import rna.git
import rna.answers
import rna.update.kept
import rna.update.refusals
import rna.update.resolve
import rna.workspace


def process_wide() -> types.ModuleType:
    """State shared by every load of the glue in one process, whatever the template version
    (an update runs the old version's glue for its old render; tests run hundreds of copies).
    Its attributes are a contract between template versions: only ever add to them."""
    return sys.modules.setdefault("rna_template_process_wide", types.ModuleType("rna_template_process_wide"))


class Run:
    """One Copier worker's findings (the glue is loaded afresh for each worker)."""

    def __init__(self):
        self.found_answers: dict[tuple[str, str], tuple[str, object] | None] = {}
        self.hand_edited: dict[tuple[str, str], bool] = {}
        self.languages_kept: dict[int, object] = {}
        self.given_checked: list[tuple[Mapping, set[str]]] = []  # Copier's `data` (one object per worker),
        # and the questions of it checked so far
        self.models: dict[bytes | str, object] = {}
        self.last_key: list = [(), None, None]  # the answer objects, where, and their key
        self.undecodable_names: dict[str, object] = {}

    def answers_found(self, conf: Mapping, name: str | None) -> tuple[str, object] | None:
        """The destination's answers file `name` as this worker first found it: (its text, what
        it reads as), or None when there was none.

        Copier writes the answers file halfway through its render; what the checks are about
        is the file that was there before: the answers being updated, or none for a new
        package (reading the new one would make a copy check its own answers at every file).
        """
        key = (str(conf.get("dst_path")), str(name))
        if key not in self.found_answers:
            found = _answers_file_in_destination(conf, name)
            self.found_answers[key] = answers_file(*found) if found is not None else None
        return self.found_answers[key]

    def previous_answers(self, context) -> dict | None:
        """The answers being updated: the answers file in the destination before Copier wrote, if any."""
        conf = context.get("_copier_conf") or {}
        read = self.answers_found(conf, conf.get("answers_file"))
        return read[1] if read is not None and isinstance(read[1], dict) else None

    def edited_by_hand(self, context) -> bool:
        """Whether the answers file an update starts from was edited by hand (the update would change nothing)."""
        conf = context.get("_copier_conf") or {}
        name = conf.get("answers_file") or ".copier-answers.yml"
        key = (str(conf.get("dst_path")), str(name))
        if key not in self.hand_edited:
            read = self.answers_found(conf, name)
            self.hand_edited[key] = read is not None and rna.update.resolve.edited_by_hand(*read) is True
        return self.hand_edited[key]

    def given_answers_checked(self, given: Mapping) -> set[str]:
        """The questions of a worker's given answers checked so far (the hook runs at every render;
        a choice that depends on other answers waits for them), to be added to."""
        found = next((checked for held, checked in self.given_checked if held is given), None)
        if found is None:
            found = set()
            self.given_checked.append((given, found))
        return found

    def given_answers_refusal(self, context) -> object | None:
        """Answers given with --data or --data-file, checked before Copier reads them: the first
        rule they break (its text is the one-line error), or None.

        Copier checks a choice, or parses a YAML answer, itself when it reaches the question,
        and a broken one ends in a traceback; this says the same in one line, first. A choice
        that depends on other answers (a build type for the distro) is checked as soon as they
        are known: given, in the answers file being updated, or answered before it.
        """
        conf = context.get("_copier_conf") or {}
        given = conf.get("data") or {}
        if not given:
            return None
        previous = self.previous_answers(context)
        if previous is not None:  # an update: before any other answer is read in the light of these
            refused = rna.update.refusals.switch_error(previous, given) if "ros_distro" in given else None
            if refused is None and "ros_distro" in given and conf.get("dst_path") is not None:
                package = rna.workspace.read_package(Path(conf["dst_path"]))
                refused = rna.update.refusals.port_error(previous, given, package)
            if (refused := refused or rna.update.refusals.first_copy_error(given)) is not None:
                return refused
        checked = self.given_answers_checked(given)
        if len(checked) == len(given) or _inside_a_validator():
            return None
        around = {key: context.get(key) for key in ("ros_distro", "build_type") if key in context.keys()}
        try:
            checked |= rna.answers.check_given(given, question_types(str(conf.get("src_path"))), around, skip=checked)
        except rna.AnswerError as error:
            return error
        return None

    def undecodable_name_refusal(self, destination: str) -> object | None:
        """A file of the project whose name is not UTF-8 makes Copier's update fail half-way, after
        it wrote the new version (copier._tools.normalize_git_path, 9.19): refused before it writes."""
        if destination not in self.undecodable_names:
            name = rna.update.refusals.undecodable_name(Path(destination))
            self.undecodable_names[destination] = rna.update.refusals.name_error(name) if name is not None else None
        return self.undecodable_names[destination]

    def keep_languages(self, nodes, previous: Mapping) -> None:
        """Nodes given without a language keep theirs: done in place, so once per list of nodes."""
        if self.languages_kept.get(id(nodes)) is not nodes:
            rna.update.resolve.keep_languages(nodes, previous)
            self.languages_kept[id(nodes)] = nodes

    def model(self, answers: dict, where: tuple, build):
        """The package model of `answers` (`build(answers)`, once per set of answers and `where`)."""
        key = self._key_of_this_render(answers, where)
        if key not in self.models:
            self.models[key] = build(answers)
        return self.models[key]

    def _key_of_this_render(self, answers: dict, where: tuple) -> bytes | str:
        """The same answer objects as the file before give the same key without making it again
        (a pickle of every node, for every file). Nothing changes answers in place once the
        render phase has started: the hook has given each node its language first."""
        values = tuple(answers.values())
        last_values, last_where, last_key = self.last_key
        if where == last_where and len(values) == len(last_values) and all(
                value is last for value, last in zip(values, last_values, strict=True)):
            return last_key
        key = _answers_key([answers, *where])
        self.last_key[:] = [values, where, key]
        return key


def _inside_a_validator() -> bool:
    """Whether Copier is rendering a question's validator, which turns any error into a
    traceback ("Validation error for question ..."): a given answer is checked at the next
    render instead (the question's own `when` comes before its answer is validated)."""
    frame = sys._getframe(1)
    while frame is not None:
        if frame.f_code.co_name == "validate_answer":
            return True
        frame = frame.f_back
    return False


def _answers_key(values: list) -> bytes | str:
    """A key that differs whenever the answers do (1, 1.0 and True too): a pickle, several times
    faster to make than JSON; values that do not pickle are written as JSON instead."""
    try:
        return pickle.dumps(values, protocol=5)
    except (pickle.PicklingError, TypeError, AttributeError):
        return json.dumps(values, sort_keys=True, default=str)


def _answers_file_in_destination(conf: Mapping, name: str | None) -> tuple[str, int, int] | None:
    """The destination's answers file `name` as (path, mtime, size), what its cached reads are
    keyed by; None when there is none, or when it is Copier's own in a scratch render."""
    if conf.get("dst_path") is None or name is None or copiers_scratch(str(conf["dst_path"])):
        return None
    path = Path(conf["dst_path"], name)
    try:
        stat = path.stat()
    except OSError:
        return None
    return str(path), stat.st_mtime_ns, stat.st_size


@functools.lru_cache(maxsize=8)
def copiers_scratch(destination: str) -> bool:
    """Whether Copier renders the old or the new version into a scratch folder of its update
    (whose answers file is that render's own, not answers being updated)."""
    return rna.update.kept.kind_of(Path(destination)) is not None


def answers_file(path: str, mtime_ns: int, size: int) -> tuple[str, object] | None:
    """An answers file's text and what it reads as (None when it does not read as YAML), read
    once per version of the file in a process: both template versions of an update need it,
    parsed as Copier parses it (PyYAML's Python parser: 10 to 15 ms for 20 nodes).
    Process-wide (`answers_files`): {(path, mtime_ns, size): that pair or None}, 8 at most."""
    read = process_wide().__dict__.setdefault("answers_files", {})
    key = (path, mtime_ns, size)
    if key not in read:
        if len(read) >= 8:
            del read[next(iter(read))]
        read[key] = _read_answers_file(path)
    return read[key]


def _read_answers_file(path: str) -> tuple[str, object] | None:
    text = rna.files.text(Path(path).parent, Path(path).name, owned=True)
    if text is None:
        return None
    try:
        return text, yaml.safe_load(text)
    except yaml.YAMLError:
        return text, None


# A template source that is not a local path: a URL, Copier's gh:/gl: shortcuts, git's user@host:path.
_REMOTE_SOURCE = re.compile(r"^([A-Za-z][\w+.-]*://|gh:|gl:|[^/:\s]+@[^/:\s]+:)")


def absolute_source(answers: Mapping, cwd: str | None = None) -> dict:
    """The answers to record, with a template given by a relative local path made absolute.

    Copier records `_src_path` as typed, and `copier update` resolves it from wherever it
    runs: `copier copy . ~/demo` would record `.`, which later names the project itself.
    Copier renders in the directory it was started from (it does not chdir), so that is
    where a relative path is resolved. URLs, shortcuts and absolute or `~` paths stay.
    """
    recorded = dict(answers)
    source = recorded.get("_src_path")
    if not isinstance(source, str) or _REMOTE_SOURCE.match(source) or source.startswith("~"):
        return recorded
    path = Path(cwd or os.getcwd(), source)
    if not Path(source).is_absolute() and path.exists():
        recorded["_src_path"] = os.path.normpath(path)
    return recorded


@functools.cache
def copier_yml(template: str) -> dict:
    """The template's copier.yml as written (libyaml's parser when PyYAML has it: it is read once a run)."""
    try:
        # not through rna/files.py: the template's
        loaded = yaml.load(Path(template, "copier.yml").read_text(encoding="utf-8"),
                           Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
    except (OSError, yaml.YAMLError):
        return {}
    return loaded if isinstance(loaded, dict) else {}


def question_types(template: str) -> dict[str, str]:
    """Each question's `type:` in the template's copier.yml (Copier casts given answers to it)."""
    return {name: spec.get("type", "str") for name, spec in copier_yml(template).items()
            if not name.startswith("_") and isinstance(spec, dict)}


@functools.cache
def interfaces_found(destination: str) -> tuple[str, ...]:
    """The interfaces on disk around the destination (rna/workspace.py), looked for once a worker."""
    return tuple(rna.workspace.find_interfaces(Path(destination)))


git_user_settings = functools.cache(rna.git.user_settings)  # one git process a worker, for both defaults


# ─── The update's renders, kept for the after-update step (rna/update/kept.py) ───


def kept_renders_folder(create: bool = False) -> str:
    """This process's folder of kept update renders, or "" (process-wide: the old version's
    glue keeps the old render)."""
    holder = process_wide()
    if create and not getattr(holder, "kept_renders", ""):
        holder.kept_renders = tempfile.mkdtemp(prefix="rna-update-renders-")
        atexit.register(shutil.rmtree, holder.kept_renders, True)
    return getattr(holder, "kept_renders", "")


def point_to_kept_renders(context) -> None:
    """Tell the after-update step, which runs from the template Copier renders its command
    from, where this process keeps the renders (a file in that private clone)."""
    folder = kept_renders_folder()
    source = (context.get("_copier_conf") or {}).get("src_path")
    if folder and source is not None and Path(source).is_dir():
        rna.update.kept.point(Path(source), folder)


def keep_update_render(context, recorded: Mapping) -> None:
    """Keep Copier's render of the old or the new version in an update, now that it is complete
    (the `when` of the template's task is rendered then, before the task runs), with the
    answers it records. A render excluding more than the template itself does (`--exclude`,
    or the new version's exclusions in the old render) is not the after-update step's: not kept.
    """
    conf = context.get("_copier_conf") or {}
    if str(context.get("_copier_operation")) != "update" or conf.get("dst_path") is None:
        return
    destination = Path(conf["dst_path"])
    kind = rna.update.kept.kind_of(destination)
    if kind is None or not destination.is_dir():
        return
    own = copier_yml(str(conf.get("src_path"))).get("_exclude") or []
    if not set(conf.get("exclude") or ()) <= set(own):
        return
    rna.update.kept.keep(Path(kept_renders_folder(create=True)), kind, destination,
                         rna.update.resolve.answers_yaml(rna.update.resolve.resolved(recorded)))
