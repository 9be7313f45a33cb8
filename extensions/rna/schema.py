"""A JSON Schema of the answers, made from the same rules the answers are checked with.

Editors that read `# yaml-language-server: $schema=<address>` complete and check an
answers file with it (docs/pages/how-to/system-from-a-file.md). The schema states what
a JSON Schema can: shapes, names, lengths, choices; rna.answers checks the rest (the
rules that look at several answers at once, the catalogue of standard types).
"""

from __future__ import annotations

from . import distros, layout, names, python_names
from . import qos as qos_rules
from .answers import QUICK_LISTS
from .definitions import SECTIONS
from .licenses import LICENSES
from .model import CALLBACK_GROUP_TYPES, EXECUTORS
from .parameters import SCALAR_TYPES, TYPE_ALIASES

_KEYWORDS = sorted({*python_names.KEYWORDS, *python_names.SOFT_KEYWORDS, *names.CPP_KEYWORDS})
# A part between '/' starts with a letter or '_'; ROS 2's {node} may stand in any part of it.
_ROS_TOKEN = r"(?:[A-Za-z_]|\{node\})(?:[A-Za-z0-9_]|\{node\})*"
_ROS_NAME = rf"^(~/|/)?{_ROS_TOKEN}(/{_ROS_TOKEN})*$"
_TYPE = r"^([a-z](?:[a-z0-9]|_(?=[a-z0-9]))*/((msg|srv|action)/)?)?[A-Z][A-Za-z0-9]*$"


def _anchored(pattern) -> str:
    return f"^{pattern.pattern}$"


def _text(description: str) -> dict:
    return {"type": "string", "minLength": 1, "pattern": r"^[^\n\r]*$", "description": description}


def _name(pattern: str, longest: int, description: str, shortest: int = 1) -> dict:
    return {"type": "string", "pattern": pattern, "minLength": shortest, "maxLength": longest,
            "not": {"$ref": "#/$defs/keyword"}, "description": description}


def _endpoint(kind: str, example: str) -> dict:
    """A topic, service or action, in the short form ('name:type') or the long one."""
    name_key = "topic" if kind == "msg" else "name"
    long_form = {
        "type": "object",
        "required": [name_key, "type"],
        "additionalProperties": False,
        "properties": {
            name_key: {"type": "string", "pattern": _ROS_NAME, "maxLength": names.ROS_NAME_MAX},
            "type": {"type": "string", "pattern": _TYPE},
            "id": _name(_anchored(names.SNAKE_CASE), names.IDENTIFIER_MAX,
                        "the code name, instead of one from the name"),
            **({"qos": _qos()} if kind == "msg" else {}),
        },
    }
    return {"type": "array", "items": {"oneOf": [
        {"type": "string", "pattern": r"^[^:\s]+:[^:\s]+(:[^:\s]+)?$", "description": f"short form, e.g. {example}"},
        long_form]}}


def _qos() -> dict:
    depth = {"type": "integer", "minimum": qos_rules.DEPTH_RANGE[0], "maximum": qos_rules.DEPTH_RANGE[1]}
    presets = {"enum": list(qos_rules.PRESETS)}
    policies = {key: {"enum": list(allowed)} for key, allowed in qos_rules.POLICIES.items()}
    return {"oneOf": [depth, presets, {"type": "object", "additionalProperties": False,
                                       "properties": {"preset": presets, "depth": depth, **policies}}]}


def _parameter() -> dict:
    types = [*SCALAR_TYPES, *(f"{t}[]" for t in SCALAR_TYPES), *TYPE_ALIASES]
    return {"type": "array", "items": {"oneOf": [
        {"type": "string", "pattern": r"^[a-z][a-z0-9_]*\s*(:\s*[^=\s]+)?\s*(=.*)?$",
         "description": "short form name:type=default, e.g. rate:double=10.0"},
        {"type": "object", "required": ["name"], "additionalProperties": False, "properties": {
            "name": _name(_anchored(names.SNAKE_CASE), names.IDENTIFIER_MAX, "the parameter's name"),
            "type": {"type": "string", "examples": types},
            "default": {"description": "a value of the type (int: 64-bit; ROS 1: 32-bit)"},
            "description": _text("what the parameter does"),
            "range": {"oneOf": [{"type": "array", "minItems": 2, "maxItems": 3, "items": {"type": "number"}},
                                {"type": "object", "additionalProperties": False,
                                 "properties": {key: {"type": "number"} for key in ("min", "max", "step")}}]},
            "read_only": {"type": "boolean"},
        }},
    ]}}


def _node() -> dict:
    timer = {"oneOf": [{"type": "number", "minimum": 1e-9, "maximum": 86400}, {"type": "string"},
                       {"type": "object", "required": ["period"], "additionalProperties": False, "properties": {
                           "name": _name(_anchored(names.SNAKE_CASE), names.IDENTIFIER_MAX, "the timer's name"),
                           "period": {"type": "number", "minimum": 1e-9, "maximum": 86400}}}]}
    node = {
        "type": "object",
        "required": ["name"],
        "additionalProperties": False,
        "properties": {
            "name": {**_name(_anchored(names.SNAKE_CASE), names.NODE_NAME_MAX, "the node's name"),
                     "not": {"anyOf": [{"$ref": "#/$defs/keyword"}, {"pattern": "_base$"}]}},
            "language": {"enum": sorted(distros.LANGUAGES)},
            "description": _text("what the node does"),
            "lifecycle": {"type": "boolean"},
            "autostart": {"type": "boolean"},
            "component": {"type": "boolean"},
            "diagnostics": {"type": "boolean"},
            "renamed_from": {**_name(_anchored(names.SNAKE_CASE), names.NODE_NAME_MAX,
                                     "the node's name before this update renames it")},
            "publishers": _endpoint("msg", "cmd_vel:geometry_msgs/msg/Twist"),
            "subscribers": _endpoint("msg", "odom:nav_msgs/msg/Odometry"),
            "service_servers": _endpoint("srv", "reset:std_srvs/srv/Trigger"),
            "service_clients": _endpoint("srv", "enable:std_srvs/srv/SetBool"),
            "action_servers": _endpoint("action", "fibonacci:test_msgs/action/Fibonacci"),
            "action_clients": _endpoint("action", "fibonacci:test_msgs/action/Fibonacci"),
            "timers": {"type": "array", "items": timer},
            "parameters": _parameter(),
            "executor": {"enum": list(EXECUTORS),
                         "description": "what the node spins on (static and events: C++, where the distro has them)"},
            "threads": {"type": "integer", "minimum": 1, "maximum": distros.THREADS_MAX,
                        "description": "a multi_threaded executor's threads (none: one per core)"},
            "callback_groups": {"type": "array", "items": {
                "type": "object", "required": ["name", "members"], "additionalProperties": False, "properties": {
                    "name": _name(_anchored(names.SNAKE_CASE), names.IDENTIFIER_MAX, "the group's name"),
                    "type": {"enum": list(CALLBACK_GROUP_TYPES)},
                    "members": {"oneOf": [{"type": "array", "minItems": 1, "items": {"type": "string"}},
                                          {"type": "string", "description": "comma-separated"}],
                                "description": "the node's subscribers, services, actions and timers in the "
                                               "group, by name"}}}},
            "remappings": {"type": "object", "description": "from: to, names the launch file remaps",
                           "propertyNames": {"pattern": _ROS_NAME, "maxLength": names.ROS_NAME_MAX},
                           "additionalProperties": {"type": "string", "pattern": _ROS_NAME,
                                                    "maxLength": names.ROS_NAME_MAX}},
        },
        # The launch file configures and activates lifecycle nodes only.
        "allOf": [
            {"if": {"required": ["autostart"], "properties": {"autostart": {"const": True}}},
             "then": {"required": ["lifecycle"], "properties": {"lifecycle": {"const": True}}}},
            # A thread count is a multi-threaded executor's.
            {"if": {"required": ["threads"]},
             "then": {"required": ["executor"], "properties": {"executor": {"const": "multi_threaded"}}}},
        ],
    }
    return {"type": "array", "minItems": 1, "items": {"oneOf": [
        {"type": "string", "pattern": _anchored(names.SNAKE_CASE)}, node]}}


def _interfaces() -> dict:
    def definitions(kind: str) -> dict:
        fields = {"type": "array", "items": {"type": "string"}}
        return {"type": "array", "items": {"type": "object", "required": ["name"], "additionalProperties": False,
                                           "properties": {
                                               "name": {"type": "string", "pattern": _anchored(names.CAMEL_CASE),
                                                        "maxLength": names.TYPE_NAME_MAX},
                                               **{section: fields for section in SECTIONS[kind]}}}}
    return {"type": "object", "additionalProperties": False,
            "properties": {"messages": definitions("msg"), "services": definitions("srv"),
                           "actions": definitions("action")}}


def answers_schema(docs_url: str = "") -> dict:
    """The schema of an answers file (.copier-answers.yml, or a --data-file)."""
    properties = {
        "package_name": {**_name(_anchored(names.PACKAGE_NAME), names.PACKAGE_NAME_MAX, "REP 144 package name",
                                 shortest=2),
                         "not": {"anyOf": [{"$ref": "#/$defs/keyword"}, {"const": "test"}]}},
        "description": _text("one sentence that says what the package does"),
        "maintainer": _text("the maintainer's full name"),
        "maintainer_email": {"type": "string", "pattern": names.EMAIL.pattern},
        "license": {"enum": list(LICENSES)},
        "copyright_holder": _text("the copyright holder in each source file's header"),
        "copyright_year": {"type": "integer", "minimum": 1970, "maximum": 9999},
        "ros_distro": {"enum": list(distros.DISTROS)},
        "build_type": {"enum": list(distros.BUILD_TYPES)},
        "launch_format": {"enum": list(layout.LAUNCH_FORMATS[2]),
                          "description": "the launch file's format (ROS 2; ROS 1 launch files are XML)"},
        "target": {"enum": ["package", "node"]},
        "interfaces": _interfaces(),
        "interfaces_location": {"enum": ["separate", "package"]},
        "nodes": _node(),
        "node_setup": {"enum": ["demo", "one", "dialog", "list"]},
        "edit_nodes": {"type": "boolean",
                       "description": "not recorded: whether an update edits the nodes step by step"},
        "node_name": {"type": "string", "pattern": _anchored(names.SNAKE_CASE), "maxLength": names.NODE_NAME_MAX},
        "node_language": {"enum": ["cpp", "python"]},
        **{question: {"type": "string", "description": f"comma-separated short forms of {key}"}
           for question, key in QUICK_LISTS.items()},
    }
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "$id": f"{docs_url.rstrip('/')}/schema/answers.json" if docs_url else "answers.json",
        "title": "rna-template answers",
        "$defs": {"keyword": {"enum": _KEYWORDS, "description": "a Python or C++ keyword"}},
        "type": "object",
        "properties": properties,
        # Copier's own keys (_commit, _src_path) are kept in answers files.
        "patternProperties": {"^_": {}},
        "additionalProperties": False,
    }
