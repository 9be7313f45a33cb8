"""ROS interface types (messages, services, actions), named as ROS tools name them.

How each language spells a type (headers, C++ names, Python modules) is in rna.dialects.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .names import header_path_error, is_camel_case, package_name_error, snake_case_of, type_name_error

KINDS = ("msg", "srv", "action")
KIND_NAMES = {"msg": "message", "srv": "service", "action": "action"}

# std_msgs types whose single `data` field a starter node can fill and print.
_DATA_FIELDS = {
    "String": "string",
    "Bool": "bool",
    **{name: "int" for name in ("Int8", "Int16", "Int32", "Int64", "UInt8", "UInt16", "UInt32", "UInt64")},
    **{name: "float" for name in ("Float32", "Float64")},
}


@dataclass(frozen=True)
class InterfaceType:
    """One interface type, spelled for the ROS generation (1 or 2) being generated."""

    package: str
    kind: str
    name: str
    ros: int = 2

    @property
    def full_name(self) -> str:
        """The name ROS tools print: pkg/msg/Name on ROS 2, pkg/Name on ROS 1."""
        if self.ros == 1:
            return f"{self.package}/{self.name}"
        return f"{self.package}/{self.kind}/{self.name}"

    @property
    def data_field(self) -> str | None:
        """'string', 'int', 'float' or 'bool' for std_msgs types with a single data field."""
        if self.package == "std_msgs" and self.kind == "msg":
            return _DATA_FIELDS.get(self.name)
        return None

    def __str__(self) -> str:
        return self.full_name


def normalised_type(text: object, kind: str, ros: int) -> object:
    """A type as its package's ROS generation spells it: on ROS 2 `geometry_msgs/Twist` (ROS 1's
    spelling) is `geometry_msgs/msg/Twist`, on ROS 1 `geometry_msgs/msg/Twist` is `geometry_msgs/Twist`.

    The one place the spelling is decided: the nodes dialog, the `nodes` answer and the
    answers file all go through it. A bare name (the package's own interface), a type of
    another kind and anything that is not a type stay as given, for the checks to name.
    """
    if not isinstance(text, str):
        return text
    parts = [part.strip() for part in text.strip().split("/")]
    if not all(parts):
        return text
    if ros == 2 and len(parts) == 2:
        return f"{parts[0]}/{kind}/{parts[1]}"
    if ros == 1 and len(parts) == 3 and parts[1] == kind:
        return f"{parts[0]}/{parts[2]}"
    return "/".join(parts) if len(parts) in (2, 3) else text


def _camel_case_of(name: str) -> str:
    """'twist' -> 'Twist', 'laser_scan' -> 'LaserScan': a type name an error can suggest."""
    return "".join(part[:1].upper() + part[1:] for part in re.split(r"[^A-Za-z0-9]+", name) if part)


def parse_interface(text: object, kind: str, ros: int = 2) -> InterfaceType:
    """Parse `pkg/kind/Name` (or the short `pkg/Name`) for a use that needs `kind`.

    Raises ValueError with a sentence that leads with the fix, then names the rule broken.
    """
    wanted = KIND_NAMES[kind]
    example = {"msg": "std_msgs/msg/String", "srv": "std_srvs/srv/Trigger",
               "action": "test_msgs/action/Fibonacci"}[kind]
    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"give {'an' if wanted == 'action' else 'a'} {wanted} type, e.g. {example}")
    parts = text.strip().split("/")
    if len(parts) == 2:
        package, name = parts
        given_kind = kind
    elif len(parts) == 3:
        package, given_kind, name = parts
    else:
        raise ValueError(f"write it as package/{kind}/Type, e.g. {example}: '{text}' is not an interface type")
    if given_kind not in KINDS:
        raise ValueError(f"use {InterfaceType(package, kind, name, ros).full_name}: '{text}' has '{given_kind}' "
                         "where msg, srv or action goes")
    if given_kind != kind:
        given = KIND_NAMES[given_kind]
        raise ValueError(f"give {'an' if wanted == 'action' else 'a'} {wanted} type here: '{text}' is "
                         f"{'an' if given == 'action' else 'a'} {given} type")
    if package_name_error(package):
        suggestion = snake_case_of(package)
        fix = (f"use {InterfaceType(suggestion, kind, name, ros).full_name}: "
               if suggestion and not package_name_error(suggestion) else "")
        raise ValueError(f"{fix}'{text}': '{package}' is not a valid package name (REP 144)")
    if not is_camel_case(name):
        suggestion = _camel_case_of(name)
        fix = (f"use {InterfaceType(package, kind, suggestion, ros).full_name}: " if is_camel_case(suggestion)
               else "")
        raise ValueError(f"{fix}'{text}': type names are CamelCase, starting with an upper-case letter")
    if type_name_error(name):
        raise ValueError(f"'{text}': {type_name_error(name)}")
    if header_path_error(package, kind, name):
        raise ValueError(f"'{text}': {header_path_error(package, kind, name)}")
    return InterfaceType(package, kind, name, ros)
