"""ROS naming rules, and the code identifiers derived from the names users give.

Every check returns an error sentence (naming the rule) or None, so the same
rule serves Copier's interactive validators and the one-line errors of a
non-interactive run.
"""

from __future__ import annotations

import re
import unicodedata
from collections import Counter

from . import python_names

CPP_KEYWORDS = frozenset(
    """
    alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t
    char16_t char32_t class compl concept const consteval constexpr constinit const_cast
    continue co_await co_return co_yield decltype default delete do double dynamic_cast
    else enum explicit export extern false final float for friend goto if import inline
    int long module mutable namespace new noexcept not not_eq nullptr operator or or_eq
    override private protected public register reinterpret_cast requires return short
    signed sizeof static static_assert static_cast struct switch template this
    thread_local throw true try typedef typeid typename union unsigned using virtual void
    volatile wchar_t while xor xor_eq
    """.split()
)

# REP 144: lowercase letters, digits and single underscores, starting with a letter.
PACKAGE_NAME = re.compile(r"[a-z](?:[a-z0-9]|_(?=[a-z0-9]))*")
SNAKE_CASE = re.compile(r"[a-z](?:[a-z0-9]|_(?=[a-z0-9]))*")
CAMEL_CASE = re.compile(r"[A-Z][A-Za-z0-9]*")
NAME_TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")

# Longest names, so that every line the template writes fits the 100 columns ROS's
# linters allow: `from <package>.<node>_base import (` needs package + node <= 79 characters;
# a ROS 2 C++ node's `std::make_shared<package::NodeClass>();` and its header guard
# <PACKAGE>__<NODE>_BASE_HPP_ after `#endif  // ` need package + node <= 73.
PACKAGE_NAME_MAX = 39
NODE_NAME_MAX = 39
CPP_PACKAGE_AND_NODE_MAX = 73
ROS_NAME_MAX = 80  # topics, services, actions: a string literal on a continuation line
IDENTIFIER_MAX = 50  # the code name of an endpoint, in members and callbacks
TYPE_NAME_MAX = 50
# uncrustify moves a longer #include "<package>/<kind>/<type>.hpp" onto a continuation line,
# where cpplint counts its length.
HEADER_PATH_MAX = 96

# catkin_pkg's own check of a maintainer's e-mail address (catkin_make fails on others).
EMAIL = re.compile(r"^[-a-zA-Z0-9_%+]+(\.[-a-zA-Z0-9_%+]+)*@[-a-zA-Z0-9%]+(\.[-a-zA-Z0-9%]+)*\.[a-zA-Z]{2,}$")

# Parameters the ROS 2 client libraries declare on every node themselves.
ROS2_DECLARED_PARAMETERS = frozenset({"use_sim_time", "start_type_description_service"})

# Names a type cannot take: Python's keywords and built-in names (generated modules and
# the nodes import types by name) and the C macros every C++ file sees.
_C_MACROS = frozenset({"NULL", "EOF", "TRUE", "FALSE", "NAN", "INFINITY"})
RESERVED_TYPE_NAMES = frozenset(python_names.CAPITALIZED_BUILTINS | {"None", "True", "False"} | _C_MACROS)

# Names pycodestyle refuses as ambiguous, as they look like 1 and 0 (E741-E743).
AMBIGUOUS_NAMES = frozenset({"l", "O", "I"})

# Callbacks of rclcpp_lifecycle / rclpy.lifecycle that a generated callback must not shadow.
LIFECYCLE_CALLBACKS = frozenset(
    {"on_configure", "on_activate", "on_deactivate", "on_cleanup", "on_shutdown", "on_error"}
)


def quoted(name: object, longest: int = 40) -> str:
    """A name as an error message quotes it: whole, or its start and '...' when long."""
    text = str(name)
    return f"'{text}'" if len(text) <= longest else f"'{text[:longest - 10]}...'"


def too_long(name: str, limit: int, what: str = "") -> str | None:
    """The length rule every generated name follows, so that generated lines fit 100 columns."""
    if len(name) <= limit:
        return None
    return (f"shorten it to at most {limit} characters: {what}{quoted(name)} is {len(name)} long "
            "(so that generated lines fit 100 columns)")


def keyword_error(name: str) -> str | None:
    """Names that become modules, namespaces or fields cannot be language keywords."""
    if name in python_names.KEYWORDS or name in python_names.SOFT_KEYWORDS:
        return f"choose another name: '{name}' is a Python keyword"
    if name in CPP_KEYWORDS:
        return f"choose another name: '{name}' is a C++ keyword"
    return None


def package_name_error(name: object) -> str | None:
    """REP 144 package names, which also become a C++ namespace and a Python package."""
    if not isinstance(name, str) or not name:
        return "give a package name"
    if not PACKAGE_NAME.fullmatch(name):
        return _use(_passing(snake_case_of(name), package_name_error),
                    f"'{name}' breaks REP 144 (lowercase letters, digits and single underscores, starting with "
                    "a letter)")
    if len(name) < 2:
        return f"give it at least two characters: '{name}' breaks REP 144"
    return keyword_error(name)


def generated_package_name_error(name: object) -> str | None:
    """A package this template generates: REP 144, and a Python package that imports right."""
    error = package_name_error(name)
    if error:
        return error
    if too_long(name, PACKAGE_NAME_MAX):
        return too_long(name, PACKAGE_NAME_MAX)
    if name == "test":
        return ("choose another name: 'test' is left out of Python packages by setup.py's "
                "find_packages(exclude=['test'])")
    if name in python_names.STDLIB_MODULES:
        return (f"choose another name: '{name}' is a module of Python's standard library, which the package's "
                "own module would shadow")
    return None


def node_name_error(name: object) -> str | None:
    """ROS node names that also name a source file, a Python module and a class."""
    if not isinstance(name, str) or not name:
        return "give a node name"
    if not SNAKE_CASE.fullmatch(name):
        return _use(_passing(snake_case_of(name), node_name_error),
                    f"'{name}' is not a valid node name (lower_snake_case: letters, digits and single underscores, "
                    "starting with a letter)")
    if too_long(name, NODE_NAME_MAX):
        return too_long(name, NODE_NAME_MAX)
    if name.endswith("_base"):
        return _use(_passing(name.removesuffix("_base"), node_name_error),
                    f"'{name}' ends in '_base', which is kept for the generated base classes")
    if snake_to_camel(name) in AMBIGUOUS_NAMES:
        return (f"give it a longer name: '{name}' would name its class {snake_to_camel(name)}, which flake8 "
                "refuses as ambiguous (E742)")
    return keyword_error(name)


# A substitution in a ROS 2 name (rcl_expand_topic_name): {node} is the node's name.
SUBSTITUTION = re.compile(r"\{([^{}/]*)\}")
NAMESPACE_SUBSTITUTIONS = ("ns", "namespace")


def substitution_error(name: str, what: str, ros: int) -> str | None:
    """Why the substitutions of a name are not ones its node resolves, or None.

    ROS 2 resolves {node} in any part of a name. {ns} and {namespace} stand for the node's
    namespace, which is '/' for a node started in none (as the launch file starts them):
    ROS then refuses the name they make ('//chatter'), and a relative name resolves in
    the node's namespace all the same. ROS 1 names have no substitutions.
    """
    if ros == 1:
        return f"{what} '{name}': substitutions like {{node}} are ROS 2's; a ROS 1 name has none (use '~/...')"
    for match in SUBSTITUTION.finditer(name):
        if match[1] in NAMESPACE_SUBSTITUTIONS:
            relative = SUBSTITUTION.sub(lambda m: m[0] if m[1] == "node" else "", name).lstrip("/") or "x"
            return (f"{what} '{name}': {{{match[1]}}} is the node's namespace, '/' for a node started in none (as "
                    f"the launch file starts it), and ROS refuses the name it then makes; '{relative}' is resolved "
                    "in the node's namespace all the same")
        if match[1] != "node":
            return (f"{what} '{name}': {{{match[1]}}} is no substitution ROS 2 resolves here; {{node}}, the node's "
                    "name, is")
    if "{" in SUBSTITUTION.sub("", name) or "}" in SUBSTITUTION.sub("", name):
        return f"{what} '{name}': a '{{' or '}}' that does not enclose a substitution such as {{node}}"
    return None


def topic_name_error(name: object, what: str = "topic", ros: int = 2) -> str | None:
    """ROS topic, service and action name rules: ROS 2's, which ROS 1 names also satisfy but
    for the substitution {node}, ROS 2's alone."""
    if not isinstance(name, str) or not name:
        return f"give a {what} name"
    if too_long(name, ROS_NAME_MAX):
        return too_long(name, ROS_NAME_MAX, f"{what} ")
    if "{" in name or "}" in name:
        error = substitution_error(name, what, ros)
        if error:
            return error
    rest = SUBSTITUTION.sub("x", name)  # a part that starts with {node} starts with a letter
    if rest.startswith("~"):
        rest = rest[1:]
        if rest and not rest.startswith("/"):
            return f"{what} '{name}': use ~/{rest}: '~' must be followed by '/'"
        rest = rest[1:]
    elif rest.startswith("/"):
        rest = rest[1:]
    if not rest:
        return f"{what} '{name}': give a name after its prefix"
    if rest.endswith("/"):
        return f"{what} '{name}': " + _use(_passing(name.rstrip("/"), topic_name_error), "it must not end with '/'")
    for token in rest.split("/"):
        if not token:
            return f"{what} '{name}': " + _use(_passing(re.sub("/+", "/", name), topic_name_error),
                                                "it must not contain '//'")
        if not NAME_TOKEN.fullmatch(token):
            return f"{what} '{name}': " + _use(_passing(ros_name_of(name), topic_name_error),
                                                "each part between '/' uses letters, digits and '_' and does not "
                                                "start with a digit")
    return None


def parameter_name_error(name: object, ros: int = 2) -> str | None:
    """Parameter names: snake_case, valid as a ROS 1 and a ROS 2 parameter name and as a member."""
    if not isinstance(name, str) or not name:
        return "give a parameter name"
    if not SNAKE_CASE.fullmatch(name):
        return _use(_passing(snake_case_of(name), lambda n: parameter_name_error(n, ros)),
                    f"'{name}' is not a valid parameter name (lower_snake_case: letters, "
                    "digits and single underscores, starting with a letter)")
    if too_long(name, IDENTIFIER_MAX):
        return too_long(name, IDENTIFIER_MAX, "parameter ")
    if ros == 2 and name in ROS2_DECLARED_PARAMETERS:
        return f"choose another name: parameter '{name}' is declared by ROS 2 itself on every node"
    # ROS 1 nodes keep each parameter in a member named after it (self.<name>, <name>_).
    if ros == 1 and name in AMBIGUOUS_NAMES:
        return (f"give parameter '{name}' a longer name: a ROS 1 node keeps it in a member named after it, "
                f"self.{name} in Python, which flake8 refuses as ambiguous (E741)")
    return keyword_error(name)


def identifier_error(name: object, what: str) -> str | None:
    """A code name for an endpoint or a timer, given or derived from a ROS name."""
    if not isinstance(name, str) or not SNAKE_CASE.fullmatch(name):
        return f"{what} '{name}': " + _use(_passing(snake_case_of(name), keyword_error), "it must be lower_snake_case")
    if too_long(name, IDENTIFIER_MAX):
        return too_long(name, IDENTIFIER_MAX, f"{what} ")
    return keyword_error(name)


def type_name_error(name: str) -> str | None:
    """A message, service or action name beyond CamelCase: one every generated language can use."""
    if name in RESERVED_TYPE_NAMES:
        return f"choose another name: '{name}' is a Python keyword, a Python built-in or a C macro"
    if too_long(name, TYPE_NAME_MAX):
        return too_long(name, TYPE_NAME_MAX)
    return None


def header_path_error(package: str, kind: str, name: str) -> str | None:
    """A type's C++ header path (rosidl's <package>/<kind>/<type_in_snake_case>.hpp) must fit a line."""
    path = f"{package}/{kind}/{camel_to_snake(name)}.hpp"
    if len(path) > HEADER_PATH_MAX:
        return (f"give it a shorter type or package name: its C++ header {quoted(path, 60)} is {len(path)} "
                f"characters long, at most {HEADER_PATH_MAX}")
    return None


def email_error(address: object) -> str | None:
    if not isinstance(address, str) or not EMAIL.fullmatch(address.strip()):
        return f"write it as name@host.domain: '{address}' is not an e-mail address catkin_pkg accepts"
    return None


def one_line_error(text: object) -> str | None:
    """Free text that lands in code, XML and YAML: one non-empty line of printable characters."""
    if not isinstance(text, str) or not text.strip():
        return "give one line of text"
    if any(unicodedata.category(char) in ("Cc", "Co", "Cs", "Cn", "Zl", "Zp") for char in text.strip()):
        return "give one line of printable text (no newline, carriage return, tab or other control character)"
    return None


def is_camel_case(name: str) -> bool:
    return bool(CAMEL_CASE.fullmatch(name))


def camel_to_snake(name: str) -> str:
    """rosidl's rule for turning a type name into a file name (PointCloud2 -> point_cloud2)."""
    name = re.sub(r"(.)([A-Z][a-z]+)", r"\1_\2", name)
    name = re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", name)
    return name.lower()


def snake_to_camel(name: str) -> str:
    """Class name for a node (target_detection -> TargetDetection)."""
    return "".join(part[:1].upper() + part[1:] for part in name.split("_"))


def type_aliases(interfaces, taken) -> dict:
    """interface type -> the name generated code calls it by: its own name (Odometry), or, when
    another type or a name in `taken` has it, prefixed with its package's (NavMsgsOdometry), and
    with its kind too when its package has it as two kinds (NavMsgsSrvGetMap, NavMsgsActionGetMap)."""
    names = Counter(t.name for t in interfaces)
    qualified = Counter((t.package, t.name) for t in interfaces)

    def alias(t) -> str:
        if names[t.name] == 1 and t.name not in taken:
            return t.name
        kind = t.kind.capitalize() if qualified[(t.package, t.name)] > 1 else ""
        return snake_to_camel(t.package) + kind + t.name

    return {t: alias(t) for t in interfaces}


def identifier_from_name(name: str) -> str:
    """The code name derived from a topic, service or action name.

    '/camera/depth/points' -> 'camera_depth_points', '~/cmdVel' -> 'cmd_vel', '{node}/state' -> 'node_state'.
    """
    tokens = [SUBSTITUTION.sub(r"\1", token) for token in name.lstrip("~").split("/") if token]
    return "_".join(camel_to_snake(token) for token in tokens).strip("_")


def with_suffix(identifier: str, suffix: str) -> str:
    """'chatter' + 'publisher' -> 'chatter_publisher'; 'timer' + 'timer' -> 'timer'."""
    if identifier == suffix or identifier.endswith("_" + suffix):
        return identifier
    return f"{identifier}_{suffix}"


def snake_case_of(text: object) -> str | None:
    """The lower_snake_case name closest to `text`, for an error to suggest: 'Motor-Driver',
    'motor driver' and 'MotorDriver' -> 'motor_driver'; None when no letter is left."""
    if not isinstance(text, str):
        return None
    name = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", text.strip()).lower()
    name = re.sub(r"[^a-z0-9]+", "_", name).strip("_")
    name = re.sub(r"^[0-9_]+", "", name)
    return name if SNAKE_CASE.fullmatch(name) else None


def ros_name_of(text: str) -> str | None:
    """The topic, service or action name closest to `text`: each part between '/' made a valid
    token ('cmd vel' -> 'cmd_vel', 'camera/2d-image' -> 'camera/d_image'); None when one has nothing left."""
    prefix = "~/" if text.startswith("~/") else "/" if text.startswith("/") else ""
    tokens = []
    for token in text[len(prefix):].split("/"):
        token = re.sub(r"^[0-9_]+", "", re.sub(r"[^A-Za-z0-9_]+", "_", token.strip()).strip("_"))
        if not token:
            return None
        tokens.append(token)
    return prefix + "/".join(tokens)


def _passing(suggestion: str | None, check) -> str | None:
    """The suggestion, if the rules it is suggested for take it."""
    return suggestion if suggestion is not None and check(suggestion) is None else None


def _use(suggestion: str | None, problem: str) -> str:
    """An error that leads with its fix: 'use motor_driver: <problem>', or the problem alone."""
    return f"use {suggestion}: {problem}" if suggestion else problem


def package_name_from_folder(folder: str) -> str:
    """A REP 144 default for the package name from the destination folder's name."""
    name = snake_case_of(folder) or ""
    return name if package_name_error(name) is None else "my_package"


def with_node(name: str, node: str) -> str:
    """The name with ROS 2's {node} substitution resolved: '{node}/state' -> 'driver/state'."""
    return name.replace("{node}", node)


def graph_name(name: str, node: str) -> str | None:
    """The name endpoints meet on when every node runs in one namespace (a launch file's),
    leading slash or not; None for a private (~) name, which meets no other node's."""
    return None if name.startswith("~") else with_node(name, node).lstrip("/")


def fully_qualified(name: str, node: str, namespace: str = "/") -> str:
    """The name ROS resolves a topic, service or action name to for a node in `namespace`,
    as graph queries list it: 'chatter' -> '/chatter', '~/state' -> '/<node>/state',
    '{node}/state' -> '/<node>/state'."""
    name = with_node(name, node)
    base = namespace.rstrip("/")
    if name.startswith("~"):
        return f"{base}/{node}{name[1:]}"
    return name if name.startswith("/") else f"{base}/{name}"
