"""What Copier loads: Jinja filters and globals, and the hook that adds `package` to templates.

Copier imports this file by path (copier-template-extensions). The `rna` package
next to it is imported under a name unique to this checkout, because
`copier update` renders the old and the new template version in one process and
a plain `import rna` would hand the new version the old version's modules.
"""

from __future__ import annotations

import functools
import getpass
import hashlib
import importlib.util
import json
import subprocess
import sys
from pathlib import Path

from copier.errors import UserMessageError
from copier_template_extensions import ContextHook
from jinja2 import pass_context
from jinja2.ext import Extension


def _load_rna():
    package_dir = Path(__file__).resolve().parent / "rna"
    name = "rna_" + hashlib.sha256(str(package_dir).encode()).hexdigest()[:12]
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(
            name, package_dir / "__init__.py", submodule_search_locations=[str(package_dir)]
        )
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]


rna = _load_rna()


@pass_context
def answer_error(context, question: str) -> str:
    """Copier validator: the broken rule for an answer typed at a prompt, else "".

    Answers given with --data, --data-file or --defaults are checked when
    rendering starts instead (PackageContext), where a broken rule ends the run
    with one line; a validator failing there would print a traceback.
    """
    conf = context.get("_copier_conf") or {}
    if conf.get("defaults") or question in (conf.get("data") or {}):
        return ""
    return rna.question_error(question, context) or ""


@pass_context
def describe_nodes(context) -> str:
    """The default description: what the nodes answered so far do."""
    return rna.model.describe_nodes(context)


@pass_context
def found_interfaces(context, kind: str | None = None) -> str:
    """A help suffix listing the interfaces already on disk around the destination."""
    destination = (context.get("_copier_conf") or {}).get("dst_path")
    if destination is None:
        return ""
    found = [name for name in _found(str(destination)) if kind is None or f"/{kind}/" in name]
    if not found:
        return ""
    shown = ", ".join(found[:12]) + (f" and {len(found) - 12} more" if len(found) > 12 else "")
    return f" (found in your workspace: {shown})"


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


def git_config(key: str) -> str:
    """The user's git setting (user.name, user.email) as a default answer, or ""."""
    try:
        result = subprocess.run(["git", "config", "--get", key], capture_output=True,
                                text=True, timeout=5, check=False)
    except (OSError, subprocess.SubprocessError):
        return ""
    return result.stdout.strip()


class RnaExtension(Extension):
    """Filters and globals for copier.yml and the templates."""

    def __init__(self, environment):
        super().__init__(environment)
        environment.globals.update(answer_error=answer_error, answers_file_name=answers_file_name,
                                   describe_nodes=describe_nodes, existing_package=existing_package,
                                   found_interfaces=found_interfaces, git_config=git_config,
                                   login_name=getpass.getuser)
        code = rna.code
        environment.filters.update(
            package_name_from_folder=rna.names.package_name_from_folder,
            split_list=rna.split_list,
            python_literal=rna.parameters.python_literal,
            python_text=code.python_text,
            with_article=code.with_article,
            python_base_imports=code.python_base_imports,
            python_node_imports=code.python_node_imports,
            python_descriptor=code.python_descriptor,
            python_sample=code.python_sample,
            python_format=code.python_format,
            cpp_base_includes=code.cpp_base_includes,
            cpp_node_includes=code.cpp_node_includes,
            cpp_parameter_descriptor=code.cpp_parameter_descriptor,
            cpp_sample=code.cpp_sample,
            cpp_format=code.cpp_format,
            cpp_format_arg=code.cpp_format_arg,
            cmake_targets=code.cmake_targets,
            ros1_python_base_imports=code.ros1_python_base_imports,
            ros1_python_node_imports=code.ros1_python_node_imports,
            ros1_cpp_base_includes=code.ros1_cpp_base_includes,
            ros1_cpp_node_includes=code.ros1_cpp_node_includes,
        )


_models: dict[str, object] = {}


class PackageContext(ContextHook):
    """Adds `package`, the checked model of all answers, to every template render."""

    def hook(self, context):
        if str(context.get("_copier_phase")) != "render":
            return
        answers = {key: context.get(key) for key in (*rna.model.QUESTIONS, "copyright_year")}
        key = json.dumps([answers, str((context.get('_copier_conf') or {}).get('dst_path'))],
                         sort_keys=True, default=str)
        if key not in _models:
            try:
                _models[key] = rna.build_package(answers)
            except rna.AnswerError as error:
                raise UserMessageError(f"rna-template: {error}") from None
            _refuse_to_overwrite(_models[key], context)
        context["package"] = _models[key]


def _refuse_to_overwrite(package, context) -> None:
    """A node added to an existing package must not land on files already there."""
    destination = (context.get("_copier_conf") or {}).get("dst_path")
    if package.target != "node" or destination is None:
        return
    destination = Path(destination)
    if (destination / answers_file_name(context)).exists():
        return  # an update of the node
    node = package.nodes[0]
    for path in (node.user_file, node.base_file, f"config/{node.name}.yaml"):
        if (destination / path).exists():
            raise UserMessageError(f"rna-template: invalid answer to 'nodes': {path} already exists in "
                                   f"{package.name}; choose another node name (nothing was written)")
