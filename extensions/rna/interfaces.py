"""ROS interface types (messages, services, actions), named as ROS tools name them.

How each language spells a type (headers, C++ names, Python modules) is in rna.dialects.
"""

from __future__ import annotations

from dataclasses import dataclass

from .names import header_path_error, is_camel_case, package_name_error, type_name_error

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


def parse_interface(text: object, kind: str, ros: int = 2) -> InterfaceType:
    """Parse `pkg/kind/Name` (or the short `pkg/Name`) for a use that needs `kind`.

    Raises ValueError with a sentence naming the rule that was broken.
    """
    wanted = KIND_NAMES[kind]
    example = {"msg": "std_msgs/msg/String", "srv": "std_srvs/srv/Trigger",
               "action": "test_msgs/action/Fibonacci"}[kind]
    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"a {wanted} type is required, e.g. {example}")
    parts = text.strip().split("/")
    if len(parts) == 2:
        package, name = parts
        given_kind = kind
    elif len(parts) == 3:
        package, given_kind, name = parts
    else:
        raise ValueError(f"'{text}' is not an interface type: write it as {example}")
    if given_kind not in KINDS:
        raise ValueError(f"'{text}': the middle part must be msg, srv or action")
    if given_kind != kind:
        given = KIND_NAMES[given_kind]
        raise ValueError(f"'{text}' is {'an' if given == 'action' else 'a'} {given} type, but "
                         f"{'an' if wanted == 'action' else 'a'} {wanted} type is needed here")
    if package_name_error(package):
        raise ValueError(f"'{text}': '{package}' is not a valid package name (REP 144)")
    if not is_camel_case(name):
        raise ValueError(f"'{text}': type names are CamelCase, starting with an upper-case letter")
    if type_name_error(name):
        raise ValueError(f"'{text}': {type_name_error(name)}")
    if header_path_error(package, kind, name):
        raise ValueError(f"'{text}': {header_path_error(package, kind, name)}")
    return InterfaceType(package, kind, name, ros)
