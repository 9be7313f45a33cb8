"""Custom interfaces: messages, services and actions defined field by field in the answers.

A field is written as a line of a .msg file (`float64 x`, `string frame_id "map"`,
`geometry_msgs/Point[] path`, `int32 MAX_SPEED=10`), checked against the rosidl
rules of the ROS generation being generated, and written back normalised.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import yaml

from .names import is_camel_case, keyword_error, package_name_error

PRIMITIVES = {
    2: ("bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32",
        "uint32", "int64", "uint64", "string", "wstring"),
    1: ("bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32",
        "uint32", "int64", "uint64", "string", "time", "duration"),
}
# ROS 1 spellings ROS 2 writes as a message of another package: `Header header` is
# `std_msgs/Header header`, the time and duration primitives are builtin_interfaces' messages.
ROS1_SPELLINGS = {"Header": "std_msgs/Header", "time": "builtin_interfaces/Time",
                  "duration": "builtin_interfaces/Duration"}
_INTEGER_RANGES = {
    "int8": (-2**7, 2**7 - 1), "uint8": (0, 2**8 - 1), "int16": (-2**15, 2**15 - 1), "uint16": (0, 2**16 - 1),
    "int32": (-2**31, 2**31 - 1), "uint32": (0, 2**32 - 1), "int64": (-2**63, 2**63 - 1),
    "uint64": (0, 2**64 - 1), "byte": (0, 255), "char": (0, 255),
}
_FIELD_NAME = re.compile(r"[a-z](?:[a-z0-9]|_(?=[a-z0-9]))*")
_CONSTANT_NAME = re.compile(r"[A-Z](?:[A-Z0-9]|_(?=[A-Z0-9]))*")
_TYPE = re.compile(
    r"(?P<base>[A-Za-z][A-Za-z0-9_]*(?:/[A-Za-z][A-Za-z0-9_]*){0,2})"
    r"(?:<=(?P<string_bound>\d+))?"
    r"(?:\[(?P<array>(?:<=)?\d*)\])?"
)
SECTIONS = {"msg": ("fields",), "srv": ("request", "response"), "action": ("goal", "result", "feedback")}
SEPARATORS = {"msg": "", "srv": "---\n", "action": "---\n"}


@dataclass(frozen=True)
class Field:
    """One line of an interface definition."""

    type: str          # as written in the .msg file: float64[], geometry_msgs/Point, Target
    name: str
    value: str = ""    # a default (`float64 x 1.0`) or a constant's value (`int32 MAX=10`)
    constant: bool = False
    package: str = ""  # the package of a message type from another package

    @property
    def line(self) -> str:
        if self.constant:
            return f"{self.type} {self.name}={self.value}"
        return f"{self.type} {self.name}" + (f" {self.value}" if self.value else "")


@dataclass(frozen=True)
class Definition:
    """A message, service or action this package defines."""

    kind: str   # msg | srv | action
    name: str
    sections: tuple[tuple[Field, ...], ...]

    @property
    def file_name(self) -> str:
        return f"{self.kind}/{self.name}.{self.kind}"

    @property
    def text(self) -> str:
        """The file's content: sections separated by ---."""
        blocks = ["".join(field.line + "\n" for field in section) for section in self.sections]
        return "---\n".join(blocks)

    @property
    def packages(self) -> set[str]:
        """Other packages whose types the fields use."""
        return {field.package for section in self.sections for field in section if field.package}


def _parse_value(text: str, base: str, array: bool, what: str) -> str:
    """Check a default or constant value against its type; return it as written."""
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError:
        raise ValueError(f"{what}: cannot read the value {text}") from None
    values = value if array else [value]
    if array and not isinstance(value, list):
        raise ValueError(f"{what}: an array's value is a list like [1, 2]")
    for item in values:
        if base in ("string", "wstring"):
            ok = isinstance(item, str) and text.strip()[0] in "'\"[" or isinstance(item, str) and array
        elif base == "bool":
            ok = isinstance(item, bool)
        elif base in ("float32", "float64"):
            ok = isinstance(item, (int, float)) and not isinstance(item, bool)
        elif base in _INTEGER_RANGES:
            low, high = _INTEGER_RANGES[base]
            ok = isinstance(item, int) and not isinstance(item, bool) and low <= item <= high
        else:
            raise ValueError(f"{what}: only primitive types take a value")
        if not ok:
            raise ValueError(f"{what}: {text} is not a valid {base} value")
    return text.strip()


def parse_field(text: object, *, package: str, local_names: set[str], ros: int) -> Field:
    """Parse one field line; raises ValueError naming the rule broken."""
    if not isinstance(text, str) or not text.strip():
        raise ValueError("a field is a line like 'float64 x'")
    line = text.strip()
    constant = re.fullmatch(r"(\S+)\s+([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(.+)", line)
    parts = [constant[1], constant[2], constant[3]] if constant else line.split(None, 2)
    if len(parts) < 2:
        raise ValueError(f"field '{line}': write the type then the name, e.g. 'float64 x'")
    type_text, name = parts[0], parts[1]
    value = parts[2] if len(parts) > 2 else ""
    what = f"field '{line}'"
    match = _TYPE.fullmatch(type_text)
    if not match:
        raise ValueError(f"{what}: '{type_text}' is not a type (e.g. float64, float64[], geometry_msgs/Point)")
    base, array = match["base"], match["array"]
    if ros == 1 and (match["string_bound"] or (array or "").startswith("<=")):
        raise ValueError(f"{what}: bounded strings and arrays are ROS 2 features")
    if match["string_bound"] and base not in ("string", "wstring"):
        raise ValueError(f"{what}: only strings take a bound like string<=10")
    other_package = ""
    if "/" in base:
        pieces = base.split("/")
        other_package, type_name = pieces[0], pieces[-1]
        if len(pieces) == 3 and pieces[1] != "msg":
            raise ValueError(f"{what}: a field's type is a message, not a {pieces[1]}")
        if package_name_error(other_package) or not is_camel_case(type_name):
            raise ValueError(f"{what}: '{base}' is not a message type (package/Type)")
        base = f"{other_package}/{type_name}"  # .msg files name other packages' types without /msg/
        if other_package == package:
            other_package, base = "", type_name
    elif base not in PRIMITIVES[ros]:
        if base == "Header" and ros == 1:
            other_package, base = "std_msgs", "Header"
        elif base in ROS1_SPELLINGS and ros == 2:  # ROS 1's names, kept by a package ported to ROS 2
            other_package, base = ROS1_SPELLINGS[base].split("/")[0], ROS1_SPELLINGS[base]
        elif not is_camel_case(base):
            raise ValueError(f"{what}: '{base}' is not a ROS {ros} primitive type or a CamelCase message")
        elif base not in local_names:
            raise ValueError(f"{what}: unknown type '{base}': define it in interfaces.messages or write "
                             "package/Type")
    if constant:
        if not _CONSTANT_NAME.fullmatch(name):
            raise ValueError(f"{what}: constant names are UPPER_CASE")
        if array is not None or base not in PRIMITIVES[ros] or base in ("time", "duration"):
            raise ValueError(f"{what}: constants have a primitive, non-array type")
        value = _parse_value(value, base, False, what)
    else:
        if not _FIELD_NAME.fullmatch(name):
            raise ValueError(f"{what}: field names are lower_snake_case, starting with a letter")
        if keyword_error(name):
            raise ValueError(f"{what}: {keyword_error(name)}")
        if value:
            if ros == 1:
                raise ValueError(f"{what}: default values are a ROS 2 feature")
            value = _parse_value(value, base, array is not None, what)
    type_out = base + (f"<={match['string_bound']}" if match["string_bound"] else "")
    type_out += f"[{array}]" if array is not None else ""
    return Field(type_out, name, value, bool(constant), other_package)
