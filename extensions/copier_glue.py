"""What Copier loads: Jinja filters and globals, and the hook that adds `package` to templates.

Copier imports this file by path (copier-template-extensions); `rna`, the package next to
it, is imported by its plain name. `copier update` renders the old and the new template
version in one process, so `rna` modules another checkout imported are dropped from
sys.modules first: each version's glue keeps the `rna` of its own checkout.
"""

from __future__ import annotations

import atexit
import functools
import getpass
import json
import os
import pickle
import re
import shutil
import subprocess
import sys
import tempfile
import textwrap
import types
from collections.abc import Mapping
from pathlib import Path

import yaml
from copier.errors import UserMessageError
from copier_template_extensions import ContextHook
from jinja2 import pass_context

_HERE = Path(__file__).resolve().parent


def _forget_other_rna() -> None:
    for name in [name for name in sys.modules if name in ("rna", "code_cache") or name.startswith("rna.")]:
        origin = getattr(sys.modules[name], "__file__", None) or ""
        if not Path(origin).resolve().is_relative_to(_HERE):
            del sys.modules[name]


_forget_other_rna()
sys.path.insert(0, str(_HERE))
try:
    import code_cache

    code_cache.import_from(_HERE)
    with code_cache.dataclass_methods_kept():
        import rna
        import rna.configs
        import rna.dialects
        import rna.distros
        import rna.dialects.lines
        import rna.dialects.python
        import rna.dialog
        import rna.graph
        import rna.replies
        import rna.lab
        import rna.model
        import rna.layout
        import rna.names
        import rna.update.kept
        import rna.update.refusals
        import rna.update.rename_answers
        import rna.update.resolve
        import rna.wording
        import rna.workspace
finally:
    sys.path.remove(str(_HERE))


def _answers(context) -> rna.Answers:
    return rna.Answers({key: context.get(key) for key in context.keys() if not key.startswith("_")})


@pass_context
def answer_error(context, question: str) -> str:
    """Copier validator: the broken rule for an answer typed at a prompt, else "".

    Answers given with --data, --data-file or --defaults are checked when rendering
    starts instead (RnaExtension.hook), where a broken rule ends the run with one line; a
    validator failing there would print a traceback.
    """
    conf = context.get("_copier_conf") or {}
    if conf.get("defaults") or question in (conf.get("data") or {}):
        return ""
    error = rna.question_error(question, context)
    if error is None and question == "node_name" and context.get("target") == "node":
        taken = _files_in_the_way(context, context.get("node_name"), rna.distros.languages(context.get("build_type")))
        error = f"{taken[0]} is already in the package: choose another name" if taken else None
    if error is None and (previous := _previous_answers(context)) is not None:
        refused = rna.update.refusals.switch_error(previous, context)
        error = refused.message if refused and refused.question == question else None
    return _under_the_prompt(question, error) if error else ""


def _under_the_prompt(question: str, error: str) -> str:
    """The error in lines an 80-column terminal shows whole, after the prefix Copier puts first."""
    prefix = f"Validation error for question '{question}': "
    wrapped = textwrap.fill(error, 79, initial_indent=" " * len(prefix), break_long_words=False,
                            break_on_hyphens=False)
    return wrapped[len(prefix):]


def _files_in_the_way(context, name: str, languages) -> list[str]:
    """Files a node added to an existing package would land on (none when it is an update)."""
    destination = (context.get("_copier_conf") or {}).get("dst_path")
    if destination is None or (Path(destination) / answers_file_name(context)).exists():
        return []
    ros = rna.distros.generation(context.get("ros_distro"))
    package = context.get("package_name")
    return [path for language in languages for path in rna.layout.node_files(package, name, ros, language)
            if (Path(destination) / path).exists()]


@pass_context
def default_description(context) -> str:
    """The default description: what the nodes answered so far do."""
    return _answers(context).default_description


@pass_context
def default_nodes(context) -> str:
    """The `nodes` default: the node the quick questions describe, or the demo."""
    return _answers(context).default_nodes


_dialogs: dict[str, list] = {}  # the dialog's result, per destination and starting nodes


def _interactive(context) -> bool:
    conf = context.get("_copier_conf") or {}
    return not conf.get("defaults") and sys.stdin.isatty() and sys.stdout.isatty()


def _dialog_wanted(context) -> bool:
    return context.get("node_setup") == "dialog" or context.get("edit_nodes") is True


def _dialog_start(context) -> tuple[str, list]:
    """The cache key and the nodes the dialog starts from: the answers updated, or the demo."""
    previous = _previous_answers(context) if context.get("edit_nodes") is True else None
    start = previous.get("nodes") if previous and isinstance(previous.get("nodes"), list) else None
    start = rna.update.resolve.resolved({**previous, "nodes": start})["nodes"] if start else rna.answers.DEMO_NODES
    destination = str((context.get("_copier_conf") or {}).get("dst_path"))
    return json.dumps([destination, start], sort_keys=True, default=str), start


@pass_context
def nodes_dialog(context) -> str:
    """The `nodes` default when they are edited step by step: the dialog's result, as YAML.

    It asks once per run (Copier renders a default more than once) and only at a terminal:
    with --defaults the nodes it starts from stand.
    """
    key, start = _dialog_start(context)
    if key not in _dialogs:
        if not _interactive(context):
            return yaml.safe_dump(start, sort_keys=False)
        answers = _answers(context)
        rules = rna.dialog.Rules(context.get("package_name") or "pkg", rna.update.resolve.build_type_of(context),
                                 answers.types)
        destination = (context.get("_copier_conf") or {}).get("dst_path")
        found = _found(str(destination)) if destination is not None else ()
        own = {}
        for (kind, name) in answers.types.own:
            own.setdefault(kind, []).append(name)
        existing = context.get("edit_nodes") is True and _previous_answers(context) is not None
        _dialogs[key] = rna.dialog.Dialog(start, rules, found=found, own=own, existing=existing).run()
    return yaml.safe_dump(_dialogs[key], sort_keys=False)


@pass_context
def nodes_dialog_pending(context) -> str:
    """A `nodes` validator: an error for the answer being updated when the dialog is to replace it.

    Copier drops a previous answer that its validator refuses and takes the question's
    default instead; with `ask: false` that default is the dialog's result (nodes_dialog).
    """
    if context.get("edit_nodes") is not True or not _interactive(context):
        return ""
    key, _ = _dialog_start(context)
    if key in _dialogs and context.get("nodes") == _dialogs[key]:
        return ""
    return "the nodes are edited step by step"


@pass_context
def found_interfaces(context, kind: str | None = None) -> str:
    """A help suffix: the interfaces already on disk around the destination, on lines of their own."""
    destination = (context.get("_copier_conf") or {}).get("dst_path")
    if destination is None:
        return ""
    found = [name for name in _found(str(destination)) if kind is None or f"/{kind}/" in name]
    return "".join("\n" + line for line in rna.wording.found_lines(found))


@functools.cache
def _found(destination: str) -> tuple[str, ...]:
    return tuple(rna.workspace.find_interfaces(Path(destination)))


@pass_context
def existing_package(context) -> dict | None:
    """The package already in the destination (its package.xml), if any: a node goes into it."""
    destination = (context.get("_copier_conf") or {}).get("dst_path")
    return rna.workspace.read_package(Path(destination)) if destination is not None else None


@pass_context
def answers_file_name(context) -> str:
    """`.copier-answers.yml`, or for a node added to a package `.copier-answers.rna-<node>.yml`."""
    if context.get("target") != "node":
        return ".copier-answers.yml"
    nodes = context.get("nodes") or [{}]
    first = nodes[0] if isinstance(nodes, list) and nodes else {}
    name = first.get("name") if isinstance(first, dict) else first
    return f".copier-answers.rna-{name or context.get('node_name') or 'node'}.yml"


@pass_context
def user_files(context, language: str, ros: int) -> str:
    """The glob of the files of one kind that users own, for `_skip_if_exists`."""
    return rna.layout.user_files_glob(context.get("package_name"), context.get("target"), ros, language)


@pass_context
def base_files(context, language: str, ros: int) -> str:
    return rna.layout.base_files_glob(context.get("package_name"), context.get("target"), ros, language)


@pass_context
def python_init_file(context, ros: int) -> str:
    return rna.layout.python_init_file(context.get("package_name"), context.get("target"), ros)


def package_files() -> str:
    """The files of a whole package, one per line, as `_exclude` patterns of the destination's root."""
    return "\n".join("/" + path for path in rna.layout.PACKAGE_FILES)


@pass_context
def porting_from_ros1(context) -> bool:
    """Whether this update ports a ROS 1 package to ROS 2 (the build type then defaults to
    ament_cmake, which holds C++ and Python nodes alike, as catkin did)."""
    previous = _previous_answers(context)
    return (previous is not None and rna.distros.generation(previous.get("ros_distro")) == 1
            and rna.distros.generation(context.get("ros_distro")) == 2)


def lab() -> dict:
    """The lab's choices (extensions/lab.yml), for defaults in copier.yml; a broken file is one line."""
    try:
        return rna.lab.load()
    except rna.lab.LabError as error:
        raise UserMessageError(f"rna-template: {error}") from None


def git_config(key: str) -> str:
    """The user's git setting (user.name, user.email) as a default answer, or ""."""
    return _git_user_settings().get(key, "")


@functools.cache  # one git process for both answers' defaults (a glue load lasts one Copier worker)
def _git_user_settings() -> dict[str, str]:
    """The user's `user.*` git settings, the last value of each (as `git config --get` reads it)."""
    try:
        result = subprocess.run(["git", "config", "-z", "--get-regexp", r"^user\."], capture_output=True,
                                text=True, timeout=5, check=False)
    except (OSError, subprocess.SubprocessError):
        return {}
    settings = {}
    for entry in result.stdout.split("\0"):
        key, _, value = entry.partition("\n")
        if key:
            settings[key] = value.strip()
    return settings


def in_git_work_tree(path) -> bool:
    """Whether `path` is inside a git work tree (`copier update` needs one)."""
    try:
        result = subprocess.run(["git", "-C", str(path), "rev-parse", "--is-inside-work-tree"],
                                capture_output=True, text=True, timeout=5, check=False)
    except (OSError, subprocess.SubprocessError):
        return False
    return result.stdout.strip() == "true"


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


class RnaExtension(ContextHook):
    """Filters and globals for copier.yml and the templates, and `package`, the checked model
    of all answers, added to every render (one extension: Copier loads this file afresh for
    each extension copier.yml names)."""

    def __init__(self, environment):
        super().__init__(environment)
        _compile_each_string_once(environment)
        _compile_each_source_once_per_process(environment)
        _ask_git_for_the_file_mode_once_per_worker()
        _render_the_answers_file_name_once_per_render()
        environment.globals.update(
            answer_error=answer_error, answers_file_name=answers_file_name, base_files=base_files,
            builds_interfaces=rna.distros.BUILDS_INTERFACES, languages=rna.distros.languages,
            ubuntu=rna.distros.UBUNTU, autostart_parameter=rna.model.AUTOSTART_PARAMETER,
            default_description=default_description, default_nodes=default_nodes,
            nodes_dialog=nodes_dialog, nodes_dialog_pending=nodes_dialog_pending,
            existing_package=existing_package, found_interfaces=found_interfaces, git_config=git_config,
            porting_from_ros1=porting_from_ros1,
            in_git_work_tree=in_git_work_tree, lab=lab, docs_url=rna.lab.docs_url,
            login_name=getpass.getuser,
            package_files=package_files,
            python_init_file=python_init_file, user_files=user_files,
            # Line-breaking markers (rna/dialects/lines.py).
            br=rna.dialects.lines.BREAK, sbr=rna.dialects.lines.SPLIT, wrap=rna.dialects.lines.WRAP,
            opt=rna.dialects.lines.OPTIONAL, alt=rna.dialects.lines.ALTERNATIVE,
            endopt=rna.dialects.lines.OPTIONAL_END, yaml_entry=rna.configs.yaml_entry)
        environment.filters.update(
            absolute_source=absolute_source,
            answers_yaml=rna.update.resolve.answers_yaml,
            resolved_answers=rna.update.resolve.resolved,
            answers_checksum=rna.update.resolve.checksum,
            dialect=rna.dialects.dialect,
            driver_docstring=rna.wording.driver_docstring,
            fit_cpp=functools.partial(rna.dialects.lines.fit, language="cpp"),
            fit_python=functools.partial(rna.dialects.lines.fit, language="python"),
            graph=rna.graph.mermaid_lines, endpoint_rows=rna.graph.endpoint_rows,
            parameter_rows=rna.graph.parameter_rows, interface_rows=rna.graph.interface_rows,
            replies=lambda service, package: rna.replies.replies(service.type, package.definitions,
                                                                  package.interfaces_home),
            package_name_from_folder=rna.names.package_name_from_folder,
            period_text=rna.wording.period_text,
            md_cell=rna.wording.markdown_cell,
            python_literal=rna.dialects.python.literal,
            python_imports=rna.dialects.python.import_block,
            python_text=rna.dialects.python.text_literal,
            reflow=rna.dialects.lines.reflow,
            summary=rna.wording.node_summary,
            summary_lines=rna.wording.summary_lines,
            with_article=rna.wording.with_article,
            yaml_literal=rna.configs.yaml_literal,
        )

    def hook(self, context):
        """Check the answers, and add their model as `package` to the context of a render."""
        if (context.get("_copier_conf") or {}).get("answers_file") == "":
            # Copier renders the answers file's name with this value in the middle of a
            # render whose hook runs here too (every file, at its first look at the name):
            # that name needs no package and no checks.
            return
        _refuse_hand_edited_answers(context)
        if str(context.get("_copier_phase")) == "tasks":
            _keep_update_render(context)
        elif str(context.get("_copier_phase")) == "migrate" and str(context.get("_copier_operation")) == "update":
            _point_to_kept_renders(context)
        if str(context.get("_copier_phase")) != "render":
            _check_given_answers(context)
            return
        previous = _previous_answers(context)
        renamed = rna.update.rename_answers.rename_error(previous, context, update=_operation() != "copy")
        if renamed is not None:
            raise UserMessageError(f"rna-template: invalid answer to 'nodes': {renamed} (nothing was written)")
        if previous is not None:  # an update: answers were in the destination before this run
            _refuse_switch(previous, context)
            # nodes given without a language keep theirs: done in place, so once per list of nodes
            nodes = context.get("nodes")
            if _languages_kept.get(id(nodes)) is not nodes:
                rna.update.resolve.keep_languages(nodes, previous)
                _languages_kept[id(nodes)] = nodes
        answers = {key: context.get(key) for key in (*rna.answers.QUESTIONS, "copyright_year")}
        # Whether it is an update is part of the key: Copier renders some names before it
        # says which answers file it updates, and the update's checks must still run.
        where = (str((context.get('_copier_conf') or {}).get('dst_path')), previous is not None)
        key = _answers_key_of_this_render(answers, where)
        if key not in _models:
            try:
                _models[key] = rna.build_package(answers)
            except rna.AnswerError as error:
                raise UserMessageError(f"rna-template: {error}") from None
            _refuse_to_overwrite(_models[key], context)
            if previous is not None:
                _refuse_to_take_over(_models[key], previous, context)
        context["package"] = _models[key]


def _compile_each_string_once(environment) -> None:
    """Keep what `from_string` compiled: Copier compiles the same strings hundreds of times a
    run (the answers file name once per file, each question's `when`), Jinja caches only files.
    A kept template is preprocessed again all the same: Copier's yield tag resets its state
    there, and checks that state after rendering each file.

    Such a template's globals are the environment's (Jinja chains them behind an empty map
    of its own, which nothing here fills): each render copies them into its context, and a
    chain copies in Python, key by key (64 million instructions of a default copy's 2,100).
    """
    compile_string = environment.from_string
    compiled = {}

    def from_string(source, globals=None, template_class=None):
        if globals is not None or template_class is not None or not isinstance(source, str):
            return compile_string(source, globals, template_class)
        if source not in compiled:
            template = compile_string(source)
            template.globals = environment.globals
            compiled[source] = template
        else:
            environment.preprocess(source)
        return compiled[source]

    environment.from_string = from_string


def _process_wide() -> types.ModuleType:
    """State shared by every load of this glue in one process.

    Copier loads the glue afresh for each Jinja environment it makes (one per render:
    `copier update` makes three, the old version's glue for the old render; tests make
    hundreds in one process), so module globals last one render; this lasts the process.
    Its attributes are a contract between template versions: only ever add to them.
    """
    return sys.modules.setdefault("rna_template_process_wide", types.ModuleType("rna_template_process_wide"))


def _compile_each_source_once_per_process(environment) -> None:
    """Share Jinja's compiled code between environments and runs (code_cache.py).

    Jinja compiles a template to a code object that takes its environment when it runs
    (what its bytecode cache stores), so environments that compile alike share it: the
    key is the source, its name and everything of the environment that the compiler
    reads (syntax, options, extensions, the names of filters and tests, Jinja's version).
    A hit is preprocessed all the same (Copier's yield tag resets its state there).

    A line of plain text (a choice's label or value, a question's type, a path's part:
    about a hundred a copy, a sixth of a millisecond each to compile) is not kept: some of
    it names the destination. Jinja compiles every such line to the same code but for the
    text and the columns it takes, so its code is a kept stand-in's of the same width,
    with the text put in place.
    """
    compile_source = environment.compile
    codes = None

    def compile(source, name=None, filename=None, raw=False, defer_init=False):  # noqa: A001 - Jinja's name
        nonlocal codes
        if raw or not isinstance(source, str):
            return compile_source(source, name, filename, raw, defer_init)
        if codes is None:  # the settings are complete once Copier compiles
            codes = code_cache.store("jinja", _compiler_signature(environment))
        plain = not _has_jinja_syntax(environment, source)
        if plain and not _is_one_plain_line(source, name, filename, defer_init):
            return compile_source(source, name, filename, raw, defer_init)
        compiled = _stand_in(source) if plain else source
        key = (compiled, name, defer_init)
        code = codes.get(key)
        if code is None:
            code = compile_source(compiled, name, filename, raw, defer_init)
            codes.put(key, code)
            if not plain:
                return code
        if plain:
            code = _with_constant(code, compiled, source)
            if code is None:  # another Jinja, whose code does not hold the line as one constant
                return compile_source(source, name, filename, raw, defer_init)
        environment.preprocess(source, name, filename)
        return code

    environment.compile = compile


def _stand_in(line: str) -> str:
    """A line that names nothing, as wide as `line` in Python's source (Jinja's code yields
    it as a literal, and Python's code records the columns, in UTF-8 bytes, of each expression)."""
    return "x" * (len(repr(line).encode()) - 2)


def _is_one_plain_line(source: str, name, filename, defer_init) -> bool:
    """Whether Jinja's code for this plain text is the stand-in line's with the text in its
    place: one line (Jinja rewrites line breaks), not empty, compiled by `from_string`."""
    return bool(source) and "\n" not in source and "\r" not in source and name is None and filename is None \
        and not defer_init


def _with_constant(code: types.CodeType, old: str, new: str) -> types.CodeType | None:
    """`code`, with the string constant `old` replaced by `new` in it and its nested code;
    None when `old` is in none of them."""
    found = False

    def replaced(constant):
        nonlocal found
        if isinstance(constant, types.CodeType):
            nested = _with_constant(constant, old, new)
            found = found or nested is not None
            return constant if nested is None else nested
        if type(constant) is str and constant == old:
            found = True
            return new
        return constant

    constants = tuple(replaced(constant) for constant in code.co_consts)
    return code.replace(co_consts=constants) if found else None


def _has_jinja_syntax(environment, source: str) -> bool:
    starts = (environment.block_start_string, environment.variable_start_string, environment.comment_start_string,
              environment.line_statement_prefix, environment.line_comment_prefix)
    return any(start and start in source for start in starts)


def _ask_git_for_the_file_mode_once_per_worker() -> None:
    """Copier asks git for `core.fileMode` after writing each file, a git process per file.

    (Worker._sync_git_index_executable_bit: it changes git's index only when that setting
    is false.) The answer is the same for every file one Copier worker writes, so it is
    asked once per worker (its Jinja environment holds it), and the method runs as Copier
    wrote it when the setting is false. With another Copier, where the method is not
    there, nothing is changed.
    """
    try:
        from copier._main import Worker
    except ImportError:
        return
    sync = getattr(Worker, "_sync_git_index_executable_bit", None)
    if sync is None or getattr(sync, "rna_once_per_worker", False):
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


def _render_the_answers_file_name_once_per_render() -> None:
    """Copier renders the answers file's name (`_answers_file`, templated here) anew for each
    file it renders, and again each time a render's context hook reads `_copier_conf.answers_file`:
    about ten renders per file, each with a render context of its own.

    While a worker renders its files (Copier's render phase, after the questions), its answers
    are final, so the name is too: it is rendered once per render phase of a worker (its Jinja
    environment holds it) and asked anew in every other phase. A kept name is preprocessed all
    the same, as compiling it would: Copier's yield tag resets its state there, and Copier
    checks that state after rendering each file. With another Copier, where the property or
    the phases are not there, nothing is changed.
    """
    try:
        from copier._main import Worker
        from copier._types import Phase
    except ImportError:
        return
    answers_relpath = getattr(Worker, "answers_relpath", None)
    if not isinstance(answers_relpath, property) or getattr(answers_relpath.fget, "rna_once_per_render", False):
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


def _git_file_mode(root: str) -> str | None:
    """`git config --type=bool --get core.fileMode` in `root`, or None (no repository, unset, no git)."""
    try:
        result = subprocess.run(["git", "config", "--type=bool", "--get", "core.fileMode"], cwd=root,
                                capture_output=True, text=True, check=False)
    except OSError:
        return None
    return result.stdout.strip() if result.returncode == 0 else None


def _compiler_signature(environment) -> str:
    import jinja2

    finalize = environment.finalize
    return repr((
        jinja2.__version__, type(environment).__module__, type(environment).__qualname__,
        sorted(environment.extensions), environment.block_start_string, environment.block_end_string,
        environment.variable_start_string, environment.variable_end_string, environment.comment_start_string,
        environment.comment_end_string, environment.line_statement_prefix, environment.line_comment_prefix,
        environment.trim_blocks, environment.lstrip_blocks, environment.newline_sequence,
        environment.keep_trailing_newline, environment.optimized, environment.is_async,
        environment.autoescape if isinstance(environment.autoescape, bool) else id(environment.autoescape),
        None if finalize is None else (getattr(finalize, "__module__", None),
                                       getattr(finalize, "__qualname__", id(finalize)),
                                       getattr(finalize, "jinja_pass_arg", None)),
        sorted(environment.filters), sorted(environment.tests), sorted(environment.policies.items(), key=repr)))


_models: dict[bytes | str, object] = {}
_last_key: list = [(), None, None]  # the answer objects, where, and their key (a Copier worker's)


def _answers_key_of_this_render(answers: dict, where: tuple) -> bytes | str:
    """The model's key for the answers of a file's render: the same answer objects as the
    file before give the same key without making it again (it takes a pickle of every node,
    for every file). Nothing changes answers in place once the render phase has started:
    the hook has given each node its language before the first key is made.
    """
    values = tuple(answers.values())
    last_values, last_where, last_key = _last_key
    if where == last_where and len(values) == len(last_values) and all(
            value is last for value, last in zip(values, last_values, strict=True)):
        return last_key
    key = _answers_key([answers, *where])
    _last_key[:] = [values, where, key]
    return key


def _answers_key(values: list) -> bytes | str:
    """A key that differs whenever the answers do (1, 1.0 and True too), made for every rendered file.

    A pickle is several times faster to make than JSON, and a package with many nodes
    renders many files; values that do not pickle are written as JSON instead.
    """
    try:
        return pickle.dumps(values, protocol=5)
    except (pickle.PicklingError, TypeError, AttributeError):
        return json.dumps(values, sort_keys=True, default=str)


def _operation() -> str | None:
    """"copy" or "update": what Copier runs. Its templates see `_copier_operation` in tasks and
    exclusions only; the scratch renders of an update run as part of it."""
    try:
        from copier._main import _operation as operation
    except ImportError:  # another Copier: renames are checked in the project only
        return None
    return operation.get(None)


def _refuse_switch(previous: Mapping, answers: Mapping, destination: object = None) -> None:
    refused = rna.update.refusals.switch_error(previous, answers)
    if refused is None and destination is not None:
        refused = rna.update.refusals.port_error(previous, answers, rna.workspace.read_package(Path(destination)))
    if refused is not None:
        raise UserMessageError(f"rna-template: {refused}")


def _refuse_hand_edited_answers(context) -> None:
    """An update of an answers file edited by hand would change nothing: stop first."""
    if str(context.get("_copier_operation")) != "update":
        return
    conf = context.get("_copier_conf") or {}
    name = conf.get("answers_file") or ".copier-answers.yml"
    key = (str(conf.get("dst_path")), str(name))
    if key not in _hand_edited:
        read = _answers_found(conf, name)
        _hand_edited[key] = read is not None and rna.update.resolve.edited_by_hand(*read) is True
    if _hand_edited[key]:
        raise UserMessageError(f"rna-template: {rna.update.refusals.hand_edit_error(conf.get('answers_file'))}")


# Copier loads this glue afresh for each of its workers (a copy has one, an update four),
# so these last one worker's run.
_found_answers: dict[tuple[str, str], tuple[str, object] | None] = {}
_hand_edited: dict[tuple[str, str], bool] = {}
_languages_kept: dict[int, object] = {}


def _answers_found(conf: Mapping, name: str | None) -> tuple[str, object] | None:
    """The destination's answers file `name` as this Copier worker first found it: (its text,
    what it reads as), or None when there was none.

    Copier writes the answers file halfway through its render (a copy's first one, an
    update's new answers); what the checks are about is the file that was there before:
    the answers being updated, or none for a new package. Reading the one just written
    (at every file after it) only made a second model of the same answers, and made a copy
    of n nodes check each node's language n times per file.
    """
    key = (str(conf.get("dst_path")), str(name))
    if key not in _found_answers:
        found = _answers_file_in_destination(conf, name)
        _found_answers[key] = _answers_file(*found) if found is not None else None
    return _found_answers[key]


def _previous_answers(context) -> dict | None:
    """The answers being updated: the answers file in the destination before Copier wrote, if any."""
    conf = context.get("_copier_conf") or {}
    read = _answers_found(conf, conf.get("answers_file"))
    return read[1] if read is not None and isinstance(read[1], dict) else None


def _answers_file_in_destination(conf: Mapping, name: str | None) -> tuple[str, int, int] | None:
    """The destination's answers file `name` as (path, mtime, size), what its cached reads are
    keyed by; None when there is none, or when it is Copier's own in a scratch render."""
    if conf.get("dst_path") is None or name is None or _copiers_scratch(str(conf["dst_path"])):
        return None
    path = Path(conf["dst_path"], name)
    try:
        stat = path.stat()
    except OSError:
        return None
    return str(path), stat.st_mtime_ns, stat.st_size


@functools.lru_cache(maxsize=8)
def _copiers_scratch(destination: str) -> bool:
    """Whether Copier renders the old or the new version into a scratch folder of its update.

    The answers file that appears there halfway through the render is that render's own,
    not answers being updated nor edited by hand: reading it (with PyYAML's Python parser,
    at every file after it) only made a second model of the same answers.
    """
    return rna.update.kept.kind_of(Path(destination)) is not None


def _answers_file(path: str, mtime_ns: int, size: int) -> tuple[str, object] | None:
    """An answers file's text and what it reads as (None when it does not read as YAML), read
    once per version of the file in a process: the hook runs for every file, both the answers
    being updated and the hand-edit check need it, and an update runs the glue of both
    template versions (PyYAML's Python parser, as Copier reads it: 10 to 15 ms for 20 nodes).
    Process-wide (`answers_files`): {(path, mtime_ns, size): that pair or None}, 8 at most."""
    read = _process_wide().__dict__.setdefault("answers_files", {})
    key = (path, mtime_ns, size)
    if key not in read:
        if len(read) >= 8:
            del read[next(iter(read))]
        read[key] = _read_answers_file(path)
    return read[key]


def _read_answers_file(path: str) -> tuple[str, object] | None:
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return None
    try:
        return text, yaml.safe_load(text)
    except yaml.YAMLError:
        return text, None


_checked: list[Mapping] = []  # the given answers checked: a worker's are one object, Copier's `data`


def _check_given_answers(context) -> None:
    """Answers given with --data or --data-file, checked before Copier reads them.

    Copier checks a choice, or parses a YAML answer, itself when it reaches the question,
    and a broken one ends in a traceback; this says the same in one line, first.
    """
    conf = context.get("_copier_conf") or {}
    given = conf.get("data") or {}
    previous = _previous_answers(context) if "ros_distro" in given else None
    if previous is not None:  # before any other answer is read in the light of the new distro
        _refuse_switch(previous, given, conf.get("dst_path"))
    if not given or any(given is checked for checked in _checked):
        return
    _checked.append(given)
    try:
        rna.answers.check_given(given, _question_types(str(conf.get("src_path"))))
    except rna.AnswerError as error:
        raise UserMessageError(f"rna-template: {error}") from None


@functools.cache
def _copier_yml(template: str) -> dict:
    """The template's copier.yml as written (libyaml's parser when PyYAML has it: it is read once a run)."""
    try:
        loaded = yaml.load(Path(template, "copier.yml").read_text(encoding="utf-8"),
                           Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
    except (OSError, yaml.YAMLError):
        return {}
    return loaded if isinstance(loaded, dict) else {}


def _question_types(template: str) -> dict[str, str]:
    """Each question's `type:` in the template's copier.yml (Copier casts given answers to it)."""
    return {name: spec.get("type", "str") for name, spec in _copier_yml(template).items()
            if not name.startswith("_") and isinstance(spec, dict)}


def _kept_renders_folder(create: bool = False) -> str:
    """This process's folder of kept update renders (rna/update/kept.py), or "".

    Held process-wide (_process_wide): the old version's glue keeps the old render.
    """
    holder = _process_wide()
    if create and not getattr(holder, "kept_renders", ""):
        holder.kept_renders = tempfile.mkdtemp(prefix="rna-update-renders-")
        atexit.register(shutil.rmtree, holder.kept_renders, True)
    return getattr(holder, "kept_renders", "")


def _point_to_kept_renders(context) -> None:
    """Tell the after-update step, which runs from the template Copier renders its command
    from, where this process keeps the renders (a file in that private clone)."""
    folder = _kept_renders_folder()
    source = (context.get("_copier_conf") or {}).get("src_path")
    if folder and source is not None and Path(source).is_dir():
        rna.update.kept.point(Path(source), folder)


def _keep_update_render(context) -> None:
    """Keep Copier's render of the old or the new version in an update, now that it is complete.

    The `when` of the template's task is rendered once a render is complete, before the
    task runs. A render excluding more than the template itself does (`--exclude`, or the
    new version's exclusions in the old render) is not what the after-update step would
    render: it is not kept.
    """
    conf = context.get("_copier_conf") or {}
    if str(context.get("_copier_operation")) != "update" or conf.get("dst_path") is None:
        return
    destination = Path(conf["dst_path"])
    kind = rna.update.kept.kind_of(destination)
    if kind is None or not destination.is_dir():
        return
    own = _copier_yml(str(conf.get("src_path"))).get("_exclude") or []
    if not set(conf.get("exclude") or ()) <= set(own):
        return
    recorded = rna.update.resolve.resolved(absolute_source(context.get("_copier_answers") or {}))
    rna.update.kept.keep(Path(_kept_renders_folder(create=True)), kind, destination,
                         rna.update.resolve.answers_yaml(recorded))


def _refuse_to_take_over(package, previous: Mapping, context) -> None:
    """A node an update adds must not take over a source file of the user's own that has its name."""
    destination = (context.get("_copier_conf") or {}).get("dst_path")
    if destination is None:
        return
    refused = rna.update.refusals.take_over_error(package, previous, Path(destination))
    if refused is not None:
        raise UserMessageError(f"rna-template: {refused}")


def _refuse_to_overwrite(package, context) -> None:
    """A node added to an existing package must not land on files already there."""
    if package.target != "node":
        return
    node = package.nodes[0]
    taken = _files_in_the_way(context, node.name, (node.language,))
    if taken:
        raise UserMessageError(f"rna-template: invalid answer to 'nodes': {taken[0]} already exists in "
                               f"{package.name}; choose another node name (nothing was written)")
