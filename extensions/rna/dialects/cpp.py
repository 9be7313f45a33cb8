"""C++ as both ROS generations spell it: include blocks, literals and the starter code's samples."""

from __future__ import annotations

import math
from collections.abc import Iterable
from functools import cached_property

from .. import features, names
from .lines import LIMITS, NESTED_BREAK, NESTED_SPLIT, SPLIT, columns, splittable
from ..parameters import INT_RANGE, ParameterType

_SCALARS = {"bool": "bool", "int": "int64_t", "double": "double", "string": "std::string"}

# Starter code's values for a std_msgs `data` field, changing with a counter.
_SAMPLES = {
    "string": '"Hello World: " + std::to_string({count})',
    "int": "static_cast<decltype({field})>({count})",
    "float": "static_cast<decltype({field})>({count})",
    "bool": "{count} % 2 == 0",
}


def include(header: str) -> str:
    """One #include line; too long for 100 columns, continued the way uncrustify wants it."""
    line = f"#include {header}" if header.startswith("<") else f'#include "{header}"'
    return line if len(line) <= 100 else line.replace("#include ", "#include \\\n  ", 1)


def include_block(headers: Iterable[str]) -> str:
    """Headers ('<chrono>' or 'rclcpp/rclcpp.hpp') -> the #include block.

    Standard headers first, then the others in quotes, as in the ROS tutorials of
    both generations (cpplint counts <ros/ros.h> as a C system header).
    """
    standard = sorted({h for h in headers if h.startswith("<")})
    others = sorted({h for h in headers if not h.startswith("<")})
    blocks = []
    if standard:
        blocks.append("\n".join(include(h) for h in standard))
    if others:
        blocks.append("\n".join(include(h) for h in others))
    return "\n\n".join(blocks)


def number(value: int | float) -> str:
    """An integer or double literal; C++ has no literal for INT64_MIN (its magnitude overflows int64_t).

    Non-finite doubles have no literal either, and the answers refuse them (rna.parameters).
    """
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"no C++ literal for {value}: parameters take finite doubles")
        return repr(value)
    return "(-9223372036854775807 - 1)" if value == INT_RANGE[0] else str(value)


def literal(value: object, ptype: ParameterType, scalars: dict[str, str] = _SCALARS, split: bool = False) -> str:
    """A C++ expression of the parameter type's C++ type.

    `split`: a string may be cut (rna.dialects.lines) when its line is too long, a vector
    broken after its brace and its commas, and its strings cut.
    """
    if ptype.is_array:
        items = [literal(item, ParameterType(ptype.scalar), scalars, split) for item in value]
        if split:
            items = [NESTED_BREAK + item.replace(SPLIT, NESTED_SPLIT) for item in items]
        return f"std::vector<{scalars[ptype.scalar]}>{{{', '.join(items)}}}"
    if ptype.scalar == "bool":
        return "true" if value else "false"
    if ptype.scalar == "int":
        return number(int(value))
    if ptype.scalar == "double":
        return number(float(value))
    return string(value, split)


_CPP_ESCAPES = {"\\": "\\\\", '"': '\\"', "\n": "\\n", "\r": "\\r", "\t": "\\t"}


def string(text: str, split: bool = False) -> str:
    """A C++ string literal that reads back as `text` (UTF-8 source); `split`: cut at spaces if too long.

    Control characters become octal escapes (a hex escape would swallow the digits that
    follow), and '?' is escaped after another '?' so no trigraph forms (GCC warns).
    """
    spelled, previous = [], ""
    for char in text:
        if char in _CPP_ESCAPES:
            spelled.append((char, _CPP_ESCAPES[char]))
        elif ord(char) < 0x20 or ord(char) == 0x7F:
            spelled.append((char, f"\\{ord(char):03o}"))
        elif not char.isprintable():
            spelled.append((char, f"\\u{ord(char):04x}" if ord(char) < 0x10000 else f"\\U{ord(char):08x}"))
        elif char == "?" and previous == "?":  # also across a place the literal may be cut
            spelled.append((char, "\\?"))
        else:
            spelled.append((char, char))
        previous = char
    inside = splittable(spelled) if split else "".join(spelling for _, spelling in spelled)
    return '"' + inside + '"'


class CppDialect:
    """What ROS 1 and ROS 2 C++ code share.

    The base class names every interface type by an alias it declares, as ros2/examples
    does (`using Twist = geometry_msgs::msg::Twist;`), which keeps lines short; the user's
    class inherits the aliases. A type whose name clashes with another one or with a
    name the code uses is aliased with its package's name in front: NavMsgsOdometry.
    """

    SCALARS = _SCALARS
    string = staticmethod(string)

    @staticmethod
    def overriding(declaration: str, indent: str = "  ") -> str:
        """The last line of a method's declaration with its `override`, which uncrustify (ROS's
        configuration) moves to a line of its own, at the method's indent, past 100 columns."""
        line = f"{declaration} override"
        return line if columns(line, "cpp") <= LIMITS["cpp"][0] else f"{declaration}\n{indent}override"

    @staticmethod
    def value(value: bool | str) -> str:
        """A C++ literal for a field the starter code sets: a bool or a text."""
        return ("true" if value else "false") if isinstance(value, bool) else string(value)
    # Names the generated C++ uses unqualified in the node's classes.
    RESERVED = frozenset({"CallbackReturn", "Node", "LifecycleNode"})

    def __init__(self, node) -> None:
        self.node = node

    def _names(self, interfaces) -> dict:
        """interface -> the name its alias (or aliases' stem) takes in the node's classes."""
        node = self.node
        return names.type_aliases(interfaces, {node.class_name, node.base_class_name, *self.RESERVED})

    @cached_property
    def alias_names(self) -> dict:
        return self._names(self.node.interfaces)

    def type(self, interface) -> str:
        """The name of an interface type in the node's classes (its alias)."""
        return self.alias_names[interface]

    def parameter_type(self, parameter) -> str:
        scalar = self.SCALARS[parameter.type.scalar]
        return f"std::vector<{scalar}>" if parameter.type.is_array else scalar

    def parameter_default(self, parameter) -> str:
        """The default as a literal that breaks when its line is too long."""
        return literal(parameter.default, parameter.type, self.SCALARS, split=True)

    def _needs(self, which: str) -> list[str]:
        return [item for need in features.needs(self.node) for item in getattr(need, which)]

    def _starter_headers(self) -> list[str]:
        """What the starter code of the user's file uses besides the node's own needs."""
        node = self.node
        headers = [self.header(t) for t in node.starter_interfaces]
        if node.starter_publishes:
            headers.append("<cstddef>")  # the message counter's std::size_t
        if any(t.type.data_field in ("string", "int", "float") for t in node.starter_built_messages):
            headers.append("<string>")  # std::to_string
        if any(t.type.data_field in ("int", "float") for t in node.subscribers):
            headers.append("<string>")
        return headers

    @property
    def base_includes(self) -> str:
        """Includes of the generated base class header."""
        return include_block([*self._needs("base"), *(self.header(t) for t in self.node.interfaces)])

    @property
    def node_includes(self) -> str:
        """Includes of the user's src/<node>.cpp: what its starter code uses."""
        own = f"{self.node.package}/{self.node.base_name}.{self.HEADER_EXTENSION}"
        return include_block([own, *self._needs("user"), *self._starter_headers()])

    @staticmethod
    def sample(data_field: str, count: str, field: str = "msg.data") -> str:
        """A C++ expression giving a std_msgs `data` field (`field`, as the code reaches it) a value
        that changes with `count`."""
        return _SAMPLES[data_field].format(count=count, field=field)

    @staticmethod
    def format(data_field: str) -> str:
        """The printf conversion that prints a `data` field (quoted for text)."""
        return '\\"%s\\"' if data_field == "string" else "%s"

    @staticmethod
    def format_arg(data_field: str, expression: str) -> str:
        """The printf argument for format()."""
        if data_field == "string":
            return f"{expression}.c_str()"
        if data_field == "bool":
            return f'{expression} ? "true" : "false"'
        return f"std::to_string({expression}).c_str()"
