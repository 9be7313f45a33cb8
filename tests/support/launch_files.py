"""A generated ROS 2 launch file in any format, read as one description, to compare the formats.

launch and launch_ros are not on the package registries, so no tier runs a launch file
(docs/pages/reference/testing.md). What they would do is read here statically: the XML
and YAML files through the entities and attributes launch's frontends parse (a frontend
refuses an attribute its action does not read), the Python file through launch_ros's
Python API, its calls evaluated from the source without importing it. Each is read for one
distro and may use only what every release of that distro's launch_ros has
(rna.launch_features, the one home of that table). Each reads back as the same
description: arguments, nodes (package, executable, name, namespace, parameter files and
values, remappings, ROS arguments, lifecycle autostart by launch_ros or by the node's own
parameter, condition) and containers with the nodes they load (namespace, parameters,
remappings, intra-process communication). Substitutions read as their XML spelling,
$(var name).
"""

from __future__ import annotations

import ast
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import yaml
from rna import launch_features

BOOLEAN_ATTRIBUTES = {"autostart"}
# Read with any type (launch_ros's <param value>): a YAML value keeps its own; XML's text is read as YAML.
TYPED_ATTRIBUTES = {"value"}
AUTOSTART = ("autostart", True)  # rna.model.AUTOSTART_PARAMETER, set to true


def _node(pkg, exec_, name, namespace, params, autostart, condition, remaps=(), ros_args=None) -> dict:
    """A node; `autostart` is "launch_ros", "parameter" (the node's own, set true) or None."""
    params = list(params)
    if AUTOSTART in params:
        assert autostart is None, f"{name}: started by launch_ros and by its parameter"
        params.remove(AUTOSTART)
        autostart = "parameter"
    return {"pkg": pkg, "exec": exec_, "name": name, "namespace": namespace, "params": tuple(params),
            "autostart": autostart, "condition": condition, "remaps": tuple(remaps), "ros_args": ros_args}


def _condition(attributes) -> tuple[str, str] | None:
    for key in ("if", "unless"):
        if attributes.get(key) is not None:
            return key, attributes[key]
    return None


def _description(args: dict, nodes: list[dict], containers: list[dict]) -> dict:
    return {"args": args, "nodes": nodes, "containers": containers}


# ----------------------------------------------------------------------------- XML and YAML

def _check_attributes(frontend: dict, tag: str, attributes) -> None:
    assert tag in frontend, f"<{tag}> is not an entity this template writes for the distro"
    unknown = set(attributes) - frontend[tag]
    assert not unknown, f"{tag}: launch does not read {sorted(unknown)}"


def _true(value) -> bool:
    return value is True or str(value).lower() == "true"


def _read_entities(entities, typed: bool, distro: str) -> dict:
    """(tag, attributes, children by tag) of each top-level action, in order, as one description;
    typed: the values are YAML's own (a YAML file), not text (an XML file)."""
    frontend = launch_features.frontend(distro)
    args, nodes, containers = {}, [], []
    for tag, attributes, children in entities:
        _check_attributes(frontend, tag, attributes)
        for child_tag, items in children.items():
            for child_attributes, _ in items:
                _check_attributes(frontend, child_tag, child_attributes)
        params = [_param(attrs, typed) for attrs, _ in children.get("param", [])]
        if tag == "arg":
            args[attributes["name"]] = attributes.get("default")
        elif tag in ("node", "lifecycle_node"):
            started = "launch_ros" if tag == "lifecycle_node" and _true(attributes.get("autostart")) else None
            nodes.append(_node(attributes["pkg"], attributes["exec"], attributes.get("name"),
                               attributes.get("namespace"), params, started, _condition(attributes),
                               _remaps(children), attributes.get("ros_args")))
        elif tag == "node_container":
            loaded = []
            for attrs, grandchildren in children.get("composable_node", []):
                for child_tag in ("param", "extra_arg", "remap"):
                    for child, _ in grandchildren.get(child_tag, []):
                        _check_attributes(frontend, child_tag, child)
                extra = [(a["name"], _extra_value(a["value"])) for a, _ in grandchildren.get("extra_arg", [])]
                loaded.append({"pkg": attrs["pkg"], "plugin": attrs["plugin"], "name": attrs.get("name"),
                               "namespace": attrs.get("namespace"),
                               "params": tuple(_param(p, typed) for p, _ in grandchildren.get("param", [])),
                               "remaps": _remaps(grandchildren), "extra": tuple(extra)})
            containers.append({"pkg": attributes["pkg"], "exec": attributes["exec"], "name": attributes["name"],
                               "namespace": attributes.get("namespace"), "condition": _condition(attributes),
                               "params": tuple(params), "ros_args": attributes.get("ros_args"), "nodes": loaded})
    return _description(args, nodes, containers)


def _remaps(children: dict) -> tuple[tuple[str, str], ...]:
    return tuple((attributes["from"], attributes["to"]) for attributes, _ in children.get("remap", []))


def _extra_value(value):
    """launch_ros reads an extra_arg's value as text (a YAML value must be a string), then as YAML."""
    assert isinstance(value, str), f"extra_arg value {value!r}: launch_ros reads it as a string"
    return yaml.safe_load(value)


def _param(attributes, typed: bool) -> str | tuple[str, object]:
    """A parameter file, or a (name, value) pair: launch_ros reads XML's text as YAML, while
    a YAML file's value keeps its type (a quoted "true" stays a string, refused by a bool)."""
    if "from" in attributes:
        return attributes["from"]
    value = attributes["value"]
    return attributes["name"], value if typed else yaml.safe_load(value)


def _xml_children(element) -> dict:
    children: dict[str, list] = {}
    for child in element:
        children.setdefault(child.tag, []).append((dict(child.attrib), _xml_children(child)))
    return children


def read_xml(text: str, distro: str) -> dict:
    root = ET.fromstring(text)
    assert root.tag == "launch"
    return _read_entities(((child.tag, dict(child.attrib), _xml_children(child)) for child in root), False, distro)


def _yaml_entity(tag: str, body) -> tuple[str, dict, dict]:
    """launch_yaml's reading: scalars are attributes, lists of mappings are child entities."""
    assert isinstance(body, dict), f"{tag}: an entity is a mapping"
    attributes = {key: value for key, value in body.items() if not isinstance(value, list)}
    children = {key: [_yaml_entity(key, item)[1:] for item in value]
                for key, value in body.items() if isinstance(value, list)}
    for key, value in attributes.items():
        # launch_yaml hands a true/false on to the attributes read as booleans only, text to the others.
        if key not in TYPED_ATTRIBUTES or tag == "extra_arg":
            assert isinstance(value, bool if key in BOOLEAN_ATTRIBUTES else str), f"{tag}: {key}: {value!r}"
    return tag, attributes, children


def read_yaml(text: str, distro: str) -> dict:
    document = yaml.safe_load(text)
    assert list(document) == ["launch"], "a YAML launch file is one `launch:` list"
    entities = []
    for item in document["launch"]:
        assert isinstance(item, dict) and len(item) == 1, f"each action is a mapping of one entity: {item!r}"
        ((tag, body),) = item.items()
        entities.append(_yaml_entity(tag, body))
    return _read_entities(entities, True, distro)


# ----------------------------------------------------------------------------- Python

class _Reader:
    """Evaluates generate_launch_description()'s statements as launch_ros would build them."""

    def __init__(self, imports: dict[str, str], distro: str) -> None:
        self.imports = imports
        self.api = launch_features.python_api(distro)
        self.names: dict[str, object] = {}

    def value(self, node: ast.expr):
        if isinstance(node, ast.Constant):
            return node.value
        if isinstance(node, ast.Name):
            return self.names[node.id]
        if isinstance(node, ast.List):
            return [self.value(item) for item in node.elts]
        if isinstance(node, ast.Tuple):  # a remapping, (from, to)
            return tuple(self.value(item) for item in node.elts)
        if isinstance(node, ast.Dict):  # parameters by name, as launch_ros takes them
            return {self.value(key): self.value(value) for key, value in zip(node.keys, node.values, strict=True)}
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            return self.call(node.func.id, [self.value(arg) for arg in node.args],
                             {kw.arg: self.value(kw.value) for kw in node.keywords}, node)
        raise AssertionError(f"line {node.lineno}: {ast.unparse(node)} is more than the launch file needs")

    def call(self, name: str, args: list, kwargs: dict, node: ast.Call):
        assert name in self.api, f"line {node.lineno}: {name} is not part of launch or launch_ros's API used here"
        module, keywords = self.api[name]
        assert self.imports.get(name) == module, f"{name} is imported from {self.imports.get(name)}, not {module}"
        assert set(kwargs) <= keywords, f"line {node.lineno}: {name} takes no {sorted(set(kwargs) - keywords)}"
        if name == "FindPackageShare":
            return f"$(find-pkg-share {args[0]})"
        if name == "LaunchConfiguration":
            return f"$(var {args[0]})"
        if name == "PathJoinSubstitution":
            return "/".join(args[0])
        if name in ("IfCondition", "UnlessCondition"):
            return ("if" if name == "IfCondition" else "unless", args[0])
        return {"call": name, "args": args, **kwargs}


def read_python(text: str, distro: str) -> dict:
    tree = ast.parse(text)
    imports = {alias.asname or alias.name: statement.module for statement in tree.body
               if isinstance(statement, ast.ImportFrom) for alias in statement.names}
    (function,) = [s for s in tree.body if isinstance(s, ast.FunctionDef)]
    assert function.name == "generate_launch_description" and not function.args.args
    reader = _Reader(imports, distro)
    returned = None
    for statement in function.body:
        if isinstance(statement, ast.Expr) and isinstance(statement.value, ast.Constant):
            continue  # the docstring
        if isinstance(statement, ast.Assign):
            (target,) = statement.targets
            reader.names[target.id] = reader.value(statement.value)
        elif isinstance(statement, ast.Return):
            returned = reader.value(statement.value)
        else:
            raise AssertionError(f"line {statement.lineno}: unexpected statement")
    assert returned["call"] == "LaunchDescription"
    args, nodes, containers = {}, [], []
    for action in returned["args"][0]:
        call = action["call"]
        if call == "DeclareLaunchArgument":
            args[action["args"][0]] = action.get("default_value")
        elif call in ("Node", "LifecycleNode"):
            started = "launch_ros" if call == "LifecycleNode" and action.get("autostart") is True else None
            nodes.append(_node(action["package"], action["executable"], action.get("name"), action.get("namespace"),
                               _python_params(action), started, action.get("condition"),
                               action.get("remappings", ()), _ros_args(action)))
        elif call == "ComposableNodeContainer":
            loaded = [{"pkg": d["package"], "plugin": d["plugin"], "name": d.get("name"),
                       "namespace": d.get("namespace"), "params": _python_params(d),
                       "remaps": tuple(d.get("remappings", ())),
                       "extra": tuple(entry for e in d.get("extra_arguments", []) for entry in e.items())}
                      for d in action["composable_node_descriptions"]]
            containers.append({"pkg": action["package"], "exec": action["executable"], "name": action["name"],
                               "namespace": action.get("namespace"), "condition": action.get("condition"),
                               "params": _python_params(action), "ros_args": _ros_args(action), "nodes": loaded})
        else:
            raise AssertionError(f"{call} in the LaunchDescription")
    return _description(args, nodes, containers)


def _python_params(action: dict) -> tuple:
    """Parameter files and (name, value) pairs, as the frontends list them."""
    return tuple(entry for p in action.get("parameters", []) for entry in (p.items() if isinstance(p, dict) else [p]))


def _ros_args(action: dict) -> str | None:
    """ros_arguments as the frontends' ros_args attribute spells them: one command line."""
    return " ".join(action["ros_arguments"]) if "ros_arguments" in action else None


READERS = {".xml": read_xml, ".yaml": read_yaml, ".py": read_python}


def description(path: Path, distro: str) -> dict:
    """The launch file, whatever its format, as one description (asserting it uses only what every
    release of the distro's launch and launch_ros reads)."""
    return READERS[path.suffix](path.read_text(encoding="utf-8"), distro)


# What every node gets from the launch arguments (rna.model.LAUNCH_ARGUMENTS).
SIM_TIME = ("use_sim_time", "$(var use_sim_time)")
NAMESPACE = "$(var namespace)"
LOG_LEVEL = "--log-level $(var log_level)"


def expected_description(package) -> dict:
    """What the package model says its launch file starts."""
    components = [node for node in package.nodes if node.component]
    container_condition = ("if", "$(var container)") if components else None
    args = {argument.name: argument.default for argument in package.launch_arguments}
    if components:
        args |= {"container": "false", "container_executable": package.container_executable}
    config = f"$(find-pkg-share {package.name})/config"
    nodes = [_node(package.name, node.name, node.name, NAMESPACE, [f"{config}/{node.name}.yaml", SIM_TIME],
                   package.autostart_form if node.autostart else None,
                   ("unless", "$(var container)") if node.component else None, node.remappings, LOG_LEVEL)
             for node in package.nodes]
    containers = [{"pkg": "rclcpp_components", "exec": "$(var container_executable)",
                   "name": f"{package.name}_container", "namespace": NAMESPACE, "condition": container_condition,
                   "params": (SIM_TIME,), "ros_args": LOG_LEVEL,
                   "nodes": [{"pkg": package.name, "plugin": f"{package.name}::{node.class_name}", "name": node.name,
                              "namespace": NAMESPACE,
                              "params": (f"{config}/{node.name}.yaml", SIM_TIME,
                                         *([AUTOSTART] if node.autostart else [])),
                              "remaps": node.remappings,
                              "extra": (("use_intra_process_comms", True),) if package.intra_process(node) else ()}
                             for node in components]}]
    return _description(args, nodes, containers if components else [])


# ----------------------------------------------------------------------------- running it

def substituted(text: str, values: dict, share) -> str:
    """`text` with $(var NAME) given by `values` and $(find-pkg-share PACKAGE) by share(PACKAGE)."""
    text = re.sub(r"\$\(find-pkg-share ([^)]+)\)", lambda match: str(share(match[1])), text)
    return re.sub(r"\$\(var ([^)]+)\)", lambda match: str(values[match[1]]), text)


def ros_arguments(node: dict, values: dict, share) -> list[str]:
    """What launch_ros gives a node of the description on its command line (after --ros-args),
    with the launch arguments `values`: its name and namespace, its parameter files, then its
    parameters, remappings and ROS arguments."""
    arguments = ["-r", f"__node:={node['name']}"]
    namespace = substituted(node["namespace"] or "", values, share).strip("/")
    if namespace:
        arguments += ["-r", f"__ns:=/{namespace}"]
    for param in node["params"]:
        if isinstance(param, str):
            arguments += ["--params-file", substituted(param, values, share)]
        else:
            name, value = param
            value = substituted(value, values, share) if isinstance(value, str) else value
            arguments += ["-p", f"{name}:={str(value).lower() if isinstance(value, bool) else value}"]
    for source, target in node["remaps"]:
        arguments += ["-r", f"{substituted(source, values, share)}:={substituted(target, values, share)}"]
    if node["ros_args"]:
        arguments += substituted(node["ros_args"], values, share).split()
    return arguments
