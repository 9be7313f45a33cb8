"""ROS naming rules, and the code identifiers derived from the names users give.

Every check returns an error sentence (naming the rule) or None, so the same
rule serves Copier's interactive validators and the one-line errors of a
non-interactive run.
"""

from __future__ import annotations

import keyword
import re

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
_PACKAGE_NAME = re.compile(r"[a-z](?:[a-z0-9]|_(?=[a-z0-9]))*")
_SNAKE_CASE = re.compile(r"[a-z](?:[a-z0-9]|_(?=[a-z0-9]))*")
_CAMEL_CASE = re.compile(r"[A-Z][A-Za-z0-9]*")
_NAME_TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")

# Callbacks of rclcpp_lifecycle / rclpy.lifecycle that a generated callback must not shadow.
LIFECYCLE_CALLBACKS = frozenset(
    {"on_configure", "on_activate", "on_deactivate", "on_cleanup", "on_shutdown", "on_error"}
)


def keyword_error(name: str) -> str | None:
    """Names that become modules, namespaces or fields cannot be language keywords."""
    if keyword.iskeyword(name) or keyword.issoftkeyword(name):
        return f"'{name}' is a Python keyword"
    if name in CPP_KEYWORDS:
        return f"'{name}' is a C++ keyword"
    return None


def package_name_error(name: object) -> str | None:
    """REP 144 package names, which also become a C++ namespace and a Python package."""
    if not isinstance(name, str) or not name:
        return "a package name is required"
    if not _PACKAGE_NAME.fullmatch(name):
        return (
            f"'{name}' breaks REP 144: use lowercase letters, digits and single "
            "underscores, starting with a letter"
        )
    if len(name) < 2:
        return f"'{name}' breaks REP 144: a package name has at least two characters"
    return keyword_error(name)


def node_name_error(name: object) -> str | None:
    """ROS node names that also name a source file, a Python module and a class."""
    if not isinstance(name, str) or not name:
        return "a node name is required"
    if not _SNAKE_CASE.fullmatch(name):
        return (
            f"'{name}' is not a valid node name: use lower_snake_case (letters, digits and "
            "single underscores, starting with a letter)"
        )
    if len(name) > 255:
        return f"'{name[:20]}...' is too long for a ROS node name (255 characters at most)"
    if name.endswith("_base"):
        return f"'{name}' ends in '_base', which is kept for the generated base classes"
    return keyword_error(name)


def topic_name_error(name: object, what: str = "topic") -> str | None:
    """ROS 2 topic and service name rules (which ROS 1 names also satisfy).

    Substitutions such as {node} are refused because generated identifiers are
    derived from the name.
    """
    if not isinstance(name, str) or not name:
        return f"a {what} name is required"
    if "{" in name or "}" in name:
        return f"{what} '{name}': substitutions like {{node}} are not supported here"
    rest = name
    if rest.startswith("~"):
        rest = rest[1:]
        if rest and not rest.startswith("/"):
            return f"{what} '{name}': '~' must be followed by '/'"
        rest = rest[1:]
    elif rest.startswith("/"):
        rest = rest[1:]
    if not rest:
        return f"{what} '{name}' has no name after its prefix"
    if rest.endswith("/"):
        return f"{what} '{name}' must not end with '/'"
    for token in rest.split("/"):
        if not token:
            return f"{what} '{name}' must not contain '//'"
        if not _NAME_TOKEN.fullmatch(token):
            return (
                f"{what} '{name}': each part between '/' uses letters, digits and '_' "
                "and does not start with a digit"
            )
    return None


def parameter_name_error(name: object) -> str | None:
    """Parameter names: snake_case, valid as a ROS 1 and a ROS 2 parameter name."""
    if not isinstance(name, str) or not name:
        return "a parameter name is required"
    if not _SNAKE_CASE.fullmatch(name):
        return (
            f"'{name}' is not a valid parameter name: use lower_snake_case (letters, digits "
            "and single underscores, starting with a letter)"
        )
    return None


def identifier_error(name: object, what: str) -> str | None:
    """An explicit code name for an endpoint or a timer."""
    if not isinstance(name, str) or not _SNAKE_CASE.fullmatch(name):
        return f"{what} '{name}' must be lower_snake_case"
    return keyword_error(name)


def is_camel_case(name: str) -> bool:
    return bool(_CAMEL_CASE.fullmatch(name))


def camel_to_snake(name: str) -> str:
    """rosidl's rule for turning a type name into a file name (PointCloud2 -> point_cloud2)."""
    name = re.sub(r"(.)([A-Z][a-z]+)", r"\1_\2", name)
    name = re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", name)
    return name.lower()


def snake_to_camel(name: str) -> str:
    """Class name for a node (target_detection -> TargetDetection)."""
    return "".join(part[:1].upper() + part[1:] for part in name.split("_"))


def identifier_from_name(name: str) -> str:
    """The code name derived from a topic, service or action name.

    '/camera/depth/points' -> 'camera_depth_points', '~/cmdVel' -> 'cmd_vel'.
    """
    tokens = [token for token in name.lstrip("~").split("/") if token]
    return "_".join(camel_to_snake(token) for token in tokens).strip("_")


def with_suffix(identifier: str, suffix: str) -> str:
    """'chatter' + 'publisher' -> 'chatter_publisher'; 'timer' + 'timer' -> 'timer'."""
    if identifier == suffix or identifier.endswith("_" + suffix):
        return identifier
    return f"{identifier}_{suffix}"


def package_name_from_folder(folder: str) -> str:
    """A REP 144 default for the package name from the destination folder's name."""
    name = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", folder).lower()
    name = re.sub(r"[^a-z0-9]+", "_", name).strip("_")
    name = re.sub(r"^[0-9_]+", "", name)
    return name if package_name_error(name) is None else "my_package"
