"""What copier.yml loads (`_jinja_extensions`): the template's Jinja filters and globals, and a
context hook that checks the answers and adds `package`, their model, to every render.

Copier loads this file by path (copier-template-extensions), afresh for each Jinja
environment (a copy makes one, an update four). The template's code is the package `rna`
beside it, imported by its plain name; an update runs the old and the new template version
in one process, so another checkout's modules are dropped from sys.modules first.
Everything the template changes in another library's behaviour (Copier's, Jinja's,
prompt_toolkit's, Python's) is a patch of patches/, switchable; copier_run.py keeps what
one run found (the answers file, the answers given with --data checked, the models).
"""

from __future__ import annotations

import functools
import getpass
import json
import sys
from collections.abc import Mapping
from pathlib import Path

import yaml
from copier.errors import UserMessageError
from copier_template_extensions import ContextHook
from jinja2 import pass_context

_HERE = Path(__file__).resolve().parent
_OWN_MODULES = ("rna", "patches", "copier_run")


def _forget_other_checkouts() -> None:
    for name in [name for name in sys.modules if name.split(".")[0] in _OWN_MODULES]:
        origin = getattr(sys.modules[name], "__file__", None) or ""
        if not Path(origin).resolve().is_relative_to(_HERE):
            del sys.modules[name]


_forget_other_checkouts()
sys.modules.pop("copier_run", None)  # its module state is one worker's: loaded afresh, as this glue is
sys.path.insert(0, str(_HERE))
try:
    import patches

    with patches.template_modules(_HERE):
        import copier_run
        import rna
        import rna.configs
        import rna.dialects
        import rna.dialects.lines
        import rna.dialects.python
        import rna.dialog
        import rna.distros
        import rna.git
        import rna.graph
        import rna.lab
        import rna.layout
        import rna.model
        import rna.names
        import rna.replies
        import rna.terminal
        import rna.update.kept
        import rna.update.refusals
        import rna.update.rename_answers
        import rna.update.resolve
        import rna.wording
        import rna.workspace
finally:
    sys.path.remove(str(_HERE))

_run = copier_run.Run()  # what this worker found: the answers file before it, the models made
absolute_source = copier_run.absolute_source  # a filter: the answers to record, the template's path absolute


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
        error = f"choose another name: {taken[0]} is already in the package" if taken else None
    if error is None and (previous := _run.previous_answers(context)) is not None:
        refused = rna.update.refusals.switch_error(previous, context)
        error = refused.message if refused and refused.question == question else None
    # Shown whole under the prompt, wrapped at the terminal's width (the patch whole_errors).
    return error or ""


def _files_in_the_way(context, name: str, languages) -> list[str]:
    """Files a node added to an existing package would land on (none when it is an update)."""
    destination = (context.get("_copier_conf") or {}).get("dst_path")
    if destination is None or (Path(destination) / answers_file_name(context)).exists():
        return []
    return rna.workspace.files_in_the_way(Path(destination), context.get("package_name"), name,
                                          rna.distros.generation(context.get("ros_distro")), languages)


@pass_context
def default_description(context) -> str:
    """The default description: what the nodes answered so far do; at a terminal, as much as the
    prompt shows on its line (after Copier's two columns), which would wrap a longer one mid-word."""
    return _answers(context).default_description(rna.terminal.width() - 2 if _interactive(context) else None)


@pass_context
def default_nodes(context) -> str:
    """The `nodes` default: the node the quick questions describe, or the demo."""
    return _answers(context).default_nodes


_dialogs: dict[str, list] = {}  # the dialog's result, per destination and starting nodes


def _interactive(context) -> bool:
    """Whether the dialog can ask at the terminal: not with --defaults, nor under copier-tui
    (copier_ui), which draws its own form on the terminal the dialog would draw over."""
    conf = context.get("_copier_conf") or {}
    return (not conf.get("defaults") and sys.stdin.isatty() and sys.stdout.isatty()
            and "copier_ui" not in sys.modules)


def _dialog_start(context) -> tuple[str, list]:
    """The cache key and the nodes the dialog starts from: the answers updated, or none (a new
    package's nodes are the user's from the first; without a terminal the demo stands in)."""
    previous = _run.previous_answers(context) if context.get("edit_nodes") is True else None
    start = previous.get("nodes") if previous and isinstance(previous.get("nodes"), list) else None
    start = (rna.update.resolve.resolved({**previous, "nodes": start})["nodes"] if start
             else [] if _interactive(context) else rna.answers.DEMO_NODES)
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
        found = copier_run.interfaces_found(str(destination)) if destination is not None else ()
        own = {}
        for (kind, name) in answers.types.own:
            own.setdefault(kind, []).append(name)
        existing = context.get("edit_nodes") is True and _run.previous_answers(context) is not None
        _dialogs[key] = rna.dialog.Dialog(start, rules, found=found, own=own, existing=existing).run()
    return yaml.safe_dump(_dialogs[key], sort_keys=False)


@pass_context
def updating(context) -> bool:
    """Whether this run updates a package (its answers file was in the destination before)."""
    return _run.previous_answers(context) is not None


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
    found = [name for name in copier_run.interfaces_found(str(destination)) if kind is None or f"/{kind}/" in name]
    return "".join("\n" + line for line in rna.wording.found_lines(found))


@pass_context
def existing_package(context) -> dict | None:
    """The package already in the destination (its package.xml), if any: a node goes into it."""
    destination = (context.get("_copier_conf") or {}).get("dst_path")
    return rna.workspace.read_package(Path(destination)) if destination is not None else None


@pass_context
def answers_file_name(context) -> str:
    """copier.yml's `_answers_file`: one per package, or per node added to a package (rna/layout.py)."""
    return rna.layout.answers_file_name(context.get("target"), context.get("nodes"), context.get("node_name"))


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


def package_files(ros_distro: str | None = None) -> str:
    """The files of a whole package, as `_exclude` patterns, for a node added to a package."""
    return rna.layout.package_files_excluded(rna.distros.generation(ros_distro))


@pass_context
def porting_from_ros1(context) -> bool:
    """Whether this update ports a ROS 1 package to ROS 2 (the build type then defaults to
    ament_cmake, which holds C++ and Python nodes alike, as catkin did)."""
    previous = _run.previous_answers(context)
    return previous is not None and rna.distros.ports(previous.get("ros_distro"), context.get("ros_distro"))


def lab() -> dict:
    """The lab's choices (extensions/lab.yml), for defaults in copier.yml; a broken file is one line."""
    try:
        return rna.lab.load()
    except rna.lab.LabError as error:
        raise UserMessageError(f"rna-template: {error}") from None


def git_config(key: str) -> str:
    """The user's git setting (user.name, user.email) as a default answer, or ""."""
    return copier_run.git_user_settings().get(key, "")


class RnaExtension(ContextHook):
    """Filters and globals for copier.yml and the templates, and `package`, the checked model
    of all answers, added to every render (one extension: Copier loads this file afresh for
    each extension copier.yml names)."""

    def __init__(self, environment):
        super().__init__(environment)
        patches.install(environment)
        environment.globals.update(
            answer_error=answer_error, answers_file_name=answers_file_name, base_files=base_files,
            builds_interfaces=rna.distros.BUILDS_INTERFACES, languages=rna.distros.languages,
            ubuntu=rna.distros.UBUNTU, autostart_parameter=rna.model.AUTOSTART_PARAMETER,
            default_description=default_description, default_nodes=default_nodes,
            nodes_dialog=nodes_dialog, nodes_dialog_pending=nodes_dialog_pending,
            existing_package=existing_package, found_interfaces=found_interfaces, git_config=git_config,
            porting_from_ros1=porting_from_ros1, in_git_work_tree=rna.git.in_work_tree, lab=lab,
            docs_url=rna.lab.docs_url, copier_command=rna.terminal.copier_command, updating=updating,
            login_name=getpass.getuser, package_files=package_files,
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
            spinning=rna.wording.spinning_text,
            summary=rna.wording.node_summary,
            summary_lines=rna.wording.summary_lines,
            with_article=rna.wording.with_article,
            yaml_literal=rna.configs.yaml_literal,
        )

    def hook(self, context):
        """Check the answers, and add their model as `package` to the context of a render."""
        conf = context.get("_copier_conf") or {}
        if conf.get("answers_file") == "":
            # Copier renders the answers file's name with this value in the middle of a
            # render whose hook runs here too: that name needs no package and no checks.
            return
        phase, operation = str(context.get("_copier_phase")), str(context.get("_copier_operation"))
        if operation == "update" and _run.edited_by_hand(context):
            raise UserMessageError(f"rna-template: {rna.update.refusals.hand_edit_error(conf.get('answers_file'))}")
        _refuse_to_copy_over_a_package(context)
        if phase == "tasks":
            copier_run.keep_update_render(context, absolute_source(context.get("_copier_answers") or {}))
        elif phase == "migrate" and operation == "update":
            copier_run.point_to_kept_renders(context)
        if phase != "render":
            _stop(_run.given_answers_refusal(context))
            return
        previous = _run.previous_answers(context)
        # Outside a package's own answers (a copy, or the scratch renders of an update), renames are
        # refused only in a copy: the scratch renders follow the answers as given.
        in_scratch = conf.get("dst_path") is not None and copier_run.copiers_scratch(str(conf["dst_path"]))
        renamed = rna.update.rename_answers.rename_error(previous, context, update=in_scratch)
        if renamed is not None:
            raise UserMessageError(f"rna-template: invalid answer to 'nodes': {renamed} (nothing was written)")
        if previous is not None:  # an update: answers were in the destination before this run
            _stop(rna.update.refusals.switch_error(previous, context))
            _stop(_run.undecodable_name_refusal(str(conf.get("dst_path"))))
            _run.keep_languages(context.get("nodes"), previous)
        answers = {key: context.get(key) for key in (*rna.answers.QUESTIONS, "copyright_year")}
        # Whether it is an update is part of the key: Copier renders some names before it
        # says which answers file it updates, and the update's checks must still run.
        where = (str(conf.get("dst_path")), previous is not None)
        context["package"] = _run.model(answers, where, functools.partial(_checked_package, context, previous))


def _checked_package(context, previous: Mapping | None, answers: dict):
    """The model of the answers, refused in one line when the answers or the destination break a rule:
    a node added to a package must not land on its files, nor a node an update adds take over one of
    the user's files of its name."""
    try:
        package = rna.build_package(answers)
    except rna.AnswerError as error:
        raise UserMessageError(f"rna-template: {error}") from None
    destination = (context.get("_copier_conf") or {}).get("dst_path")
    taken = _files_in_the_way(context, package.nodes[0].name, (package.nodes[0].language,)) \
        if package.target == "node" else []
    if taken:
        raise UserMessageError(f"rna-template: invalid answer to 'nodes': choose another node name: {taken[0]} "
                               f"already exists in {package.name} (nothing was written)")
    if previous is not None and destination is not None:
        _stop(rna.update.refusals.take_over_error(package, previous, Path(destination)))
    return package


def _refuse_to_copy_over_a_package(context) -> None:
    """`copier recopy` (a copy, to Copier) or `copier copy` into a package this template made
    would replace the user's lines in every file they share with the template: stop first."""
    if str(context.get("_copier_operation")) != "copy" or _run.previous_answers(context) is None:
        return
    name = (context.get("_copier_conf") or {}).get("answers_file")
    raise UserMessageError(f"rna-template: {rna.update.refusals.copy_over_error(name)}")


def _stop(refused) -> None:
    """A refusal of the update's rules (rna/update/refusals.py), if any, as Copier's one-line error."""
    if refused is not None:
        raise UserMessageError(f"rna-template: {refused}")
