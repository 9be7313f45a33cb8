"""Typed node parameters: the types users may name, and their defaults checked against them."""

from __future__ import annotations

import json
import math
import re
import sys
from dataclasses import dataclass

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


def _coerce_scalar(value: object, scalar: str, ros: int) -> object:
    if scalar == "bool":
        if isinstance(value, bool):
            return value
    elif scalar == "int":
        if isinstance(value, int) and not isinstance(value, bool):
            low, high = INT_RANGES[ros]
            if not low <= value <= high:
                where = " (ROS 1's parameter server)" if ros == 1 else ""
                raise ValueError(f"default {value} does not fit a {high.bit_length() + 1}-bit integer{where}")
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
    raise ValueError(f"default {spelled(value)} is not {'an' if scalar == 'int' else 'a'} {scalar}")


def coerce_default(value: object, ptype: ParameterType, ros: int = 2) -> object:
    """Check a default against its type for a ROS generation; ints are accepted for doubles."""
    if value is None:
        return [] if ptype.is_array else {"bool": False, "int": 0, "double": 0.0, "string": ""}[ptype.scalar]
    if ptype.is_array:
        if not isinstance(value, list):
            raise ValueError(f"default {spelled(value)} is not a list, but the type is {ptype}")
        return [_coerce_scalar(item, ptype.scalar, ros) for item in value]
    return _coerce_scalar(value, ptype.scalar, ros)


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
    """A parameter a node declares, with its default and documentation."""

    name: str
    type: ParameterType
    default: object
    description: str = ""
    range: tuple[float, float, float] | None = None
    read_only: bool = False

    @property
    def has_descriptor(self) -> bool:
        return bool(self.description or self.range or self.read_only)

    @property
    def range_kind(self) -> str:
        """The ParameterDescriptor field for the range: integer_range or floating_point_range."""
        return "integer_range" if self.type.scalar == "int" else "floating_point_range"
