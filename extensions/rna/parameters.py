"""Typed node parameters: the types users may name, and their defaults checked against them."""

from __future__ import annotations

import json
import math
import re
import sys
from dataclasses import dataclass

from .configs import flow_item

SCALAR_TYPES = ("bool", "int", "double", "string")
# ROS 2 parameters hold 64-bit integers (rcl_interfaces ParameterValue.integer_value); ROS 1's
# parameter server speaks XML-RPC, whose integers have 32 bits (rospy refuses larger ones).
INT_RANGES = {2: (-2**63, 2**63 - 1), 1: (-2**31, 2**31 - 1)}
INT_RANGE = INT_RANGES[2]
TYPE_ALIASES = {"integer": "int", "float": "double", "str": "string", "boolean": "bool"}


@dataclass(frozen=True)
class ParameterType:
    """A ROS parameter type: a scalar, or an array of one (`double[]`)."""

    scalar: str
    is_array: bool = False

    @property
    def name(self) -> str:
        return self.scalar + ("[]" if self.is_array else "")

    @property
    def is_numeric(self) -> bool:
        return self.scalar in ("int", "double") and not self.is_array

    def __str__(self) -> str:
        return self.name


def parse_type(text: object) -> ParameterType:
    """`double`, `int[]`, `string_array`, `float` ... -> ParameterType, or ValueError."""
    if not isinstance(text, str):
        raise ValueError(f"type '{text}' is not one of {', '.join(SCALAR_TYPES)} (or an array: double[])")
    name = text.strip().lower()
    is_array = name.endswith("[]") or name.endswith("_array")
    name = name.removesuffix("[]").removesuffix("_array")
    name = TYPE_ALIASES.get(name, name)
    if name not in SCALAR_TYPES:
        raise ValueError(f"type '{text}' is not one of {', '.join(SCALAR_TYPES)} (or an array: double[])")
    return ParameterType(name, is_array)


def spelled(value: object) -> str:
    """A value as the answers spell it (YAML: true, 'text', [1, 2]), for error messages."""
    return json.dumps(value, ensure_ascii=False) if isinstance(value, (bool, list, str)) else str(value)


def infer_type(value: object) -> ParameterType:
    """The parameter type of a YAML default value, when the user gave no type."""
    if isinstance(value, list):
        if not value:
            raise ValueError("an empty list does not say its type: add `type:` (e.g. double[])")
        element_types = {infer_type(item).scalar for item in value}
        if element_types == {"int", "double"}:
            return ParameterType("double", True)
        if len(element_types) != 1 or any(isinstance(item, list) for item in value):
            raise ValueError(f"the list {spelled(value)} mixes types; ROS arrays hold one type")
        return ParameterType(element_types.pop(), True)
    if isinstance(value, bool):
        return ParameterType("bool")
    if isinstance(value, int):
        return ParameterType("int")
    if isinstance(value, float):
        return ParameterType("double")
    if isinstance(value, str):
        return ParameterType("double" if exponent_float(value) is not None else "string")
    raise ValueError(f"cannot tell the type of the default {spelled(value)}: add `type:`")


# YAML 1.1, which PyYAML and Copier speak, reads a float with an exponent but no dot (1e-3)
# as a string; YAML 1.2, ROS 2's parameter files and Python read it as a number.
_EXPONENT_FLOAT = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)[eE][-+]?\d+")


def exponent_float(value: object) -> float | None:
    """A string such as '1e-3' as the float it means, else None."""
    return float(value) if isinstance(value, str) and _EXPONENT_FLOAT.fullmatch(value.strip()) else None


def coerce_scalar(value: object, scalar: str, ros: int = 2, what: str = "default") -> object:
    """One value of a scalar type (a default, an allowed value); ValueError starting with `what`."""
    if scalar == "bool":
        if isinstance(value, bool):
            return value
    elif scalar == "int":
        if isinstance(value, int) and not isinstance(value, bool):
            low, high = INT_RANGES[ros]
            if not low <= value <= high:
                where = " (ROS 1's parameter server)" if ros == 1 else ""
                raise ValueError(f"{what} {value} does not fit a {high.bit_length() + 1}-bit integer{where}")
            return value
    elif scalar == "double":
        value = value if exponent_float(value) is None else exponent_float(value)
        if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value):
            return float(value)
    elif scalar == "string":
        if isinstance(value, str):
            return value
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return str(value)
    raise ValueError(f"{what} {spelled(value)} is not {'an' if scalar == 'int' else 'a'} {scalar}")


def coerce_default(value: object, ptype: ParameterType, ros: int = 2) -> object:
    """Check a default against its type for a ROS generation; ints are accepted for doubles."""
    if value is None:
        return [] if ptype.is_array else {"bool": False, "int": 0, "double": 0.0, "string": ""}[ptype.scalar]
    if ptype.is_array:
        if not isinstance(value, list):
            raise ValueError(f"default {spelled(value)} is not a list, but the type is {ptype}")
        return [coerce_scalar(item, ptype.scalar, ros) for item in value]
    return coerce_scalar(value, ptype.scalar, ros)


def on_step(value: float, low: float, high: float, step: float, scalar: str) -> bool:
    """Whether ROS 2 takes `value` in a range with a step: a bound, or the minimum plus a whole number of steps.

    rclcpp and rclpy refuse any other value, the default included, so declare_parameter()
    would throw at start-up. Doubles count as equal within 100 ulp, as rclcpp compares them.
    """
    if not step:
        return True
    if scalar == "int":
        return value in (low, high) or (value - low) % step == 0

    def close(x: float, y: float) -> bool:
        return abs(x - y) <= sys.float_info.epsilon * abs(x + y) * 100

    steps = (value - low) / step
    return close(value, low) or close(value, high) or close(value, low + (round(steps) if math.isfinite(steps)
                                                                           else steps) * step)


@dataclass(frozen=True)
class Parameter:
    """A parameter a node declares, with its default, documentation and the rules its values keep."""

    name: str
    type: ParameterType
    default: object
    description: str = ""
    range: tuple[float, float, float] | None = None
    read_only: bool = False
    one_of: tuple = ()  # the values allowed (of each element, for an array)
    length: tuple[int, int | None] | None = None  # an array's (least, most) elements; most None: no limit
    not_empty: bool = False  # a string that may not be ''

    @property
    def has_checks(self) -> bool:
        """Rules the base class checks itself (rclcpp and rclpy check ranges and read-only)."""
        return bool(self.one_of or self.length or self.not_empty)

    @property
    def has_descriptor(self) -> bool:
        return bool(self.description or self.range or self.read_only or self.has_checks)

    @property
    def range_kind(self) -> str:
        """The ParameterDescriptor field for the range: integer_range or floating_point_range."""
        return "integer_range" if self.type.scalar == "int" else "floating_point_range"


def value_text(value: object) -> str:
    """A value as the config file spells it in a list, on one line: 0.5, slow, 'yes', '', 'a, b'."""
    return flow_item(value)


def count_text(number: int) -> str:
    """3 -> '3 values', 1 -> '1 value'."""
    return f"{number} value" + ("" if number == 1 else "s")


def length_text(length: tuple[int, int | None]) -> str:
    """(1, 6) -> '1 to 6 values'; (3, 3) -> 'exactly 3 values'; (1, None) -> 'at least 1 value'."""
    least, most = length
    if most is None:
        return f"at least {count_text(least)}"
    if least == most:
        return f"exactly {count_text(most)}"
    return f"at most {count_text(most)}" if least == 0 else f"{least} to {count_text(most)}"


def range_text(parameter: Parameter, ros: int) -> str:
    """'0.1 to 100.0', with its step in ROS 2 (ROS 1 checks the bounds only): '0 to 100 in steps of 5'."""
    low, high, step = parameter.range
    text = f"{value_text(low)} to {value_text(high)}"
    return text + (f" in steps of {value_text(step)}" if step and ros == 2 else "")


def one_of_text(parameter: Parameter) -> str:
    return ", ".join(value_text(value) for value in parameter.one_of)


def rules(parameter: Parameter, ros: int) -> tuple[str, ...]:
    """The rules a parameter's values keep, in words: its config comment, the README, the descriptor."""
    found = []
    if parameter.range:
        found.append(range_text(parameter, ros))
    if parameter.one_of:
        found.append(("each one of: " if parameter.type.is_array else "one of: ") + one_of_text(parameter))
    if parameter.length:
        found.append(length_text(parameter.length))
    if parameter.not_empty:
        found.append("not empty")
    if parameter.read_only and ros == 2:
        found.append("read-only")
    return tuple(found)


def constraints(parameter: Parameter) -> str:
    """A ROS 2 ParameterDescriptor's additional_constraints: the rules it has no field for."""
    return "; ".join(rules(Parameter(parameter.name, parameter.type, parameter.default, one_of=parameter.one_of,
                                     length=parameter.length, not_empty=parameter.not_empty), 2))


def comment(parameter: Parameter, ros: int) -> str:
    """The config file's comment line above a parameter: its description, then its rules."""
    said = "; ".join(rules(parameter, ros))
    if not parameter.description:
        return said[:1].upper() + said[1:]
    return f"{parameter.description} ({said})" if said else parameter.description


def checks(parameter: Parameter, ros: int) -> tuple[tuple[str, str], ...]:
    """(rule, the reason a value breaking it is refused) for each rule the node's own code checks.

    ROS 2's client libraries check ranges and read-only themselves, with reasons of their own;
    ROS 1 has neither, so its nodes check ranges too (the bounds only) as they start.
    `rule` is `range`, `one_of`, `each_one_of`, `length` or `not_empty`.
    """
    name = parameter.name
    found = []
    if parameter.range and ros == 1:
        found.append(("range", f"{name} must be from {range_text(parameter, ros)}"))
    if parameter.one_of and parameter.type.is_array:
        found.append(("each_one_of", f"each value of {name} must be one of: {one_of_text(parameter)}"))
    elif parameter.one_of:
        found.append(("one_of", f"{name} must be one of: {one_of_text(parameter)}"))
    if parameter.length:
        found.append(("length", f"{name} must have {length_text(parameter.length)}"))
    if parameter.not_empty:
        found.append(("not_empty", f"{name} must not be empty"))
    return tuple(found)


def refusal(parameter: Parameter, value: object, ros: int) -> str | None:
    """Why a node refuses `value` for `parameter` as it starts (the reasons of `checks`; ROS 2's
    range as rclcpp and rclpy check it, steps included), or None. For a value read from a config file."""
    if parameter.range and ros == 2:
        low, high, step = parameter.range
        number = isinstance(value, (int, float)) and not isinstance(value, bool)
        if not number or not low <= value <= high or not on_step(value, low, high, step, parameter.type.scalar):
            return f"{parameter.name} must be from {range_text(parameter, ros)}"
    items = value if isinstance(value, list) else None
    broken = {
        "range": lambda: not isinstance(value, (int, float)) or not parameter.range[0] <= value <= parameter.range[1],
        "one_of": lambda: value not in parameter.one_of,
        "each_one_of": lambda: items is None or any(item not in parameter.one_of for item in items),
        "length": lambda: items is None or len(items) < parameter.length[0] or (
            parameter.length[1] is not None and len(items) > parameter.length[1]),
        "not_empty": lambda: value == "",
    }
    return next((reason for rule, reason in checks(parameter, ros) if broken[rule]()), None)
