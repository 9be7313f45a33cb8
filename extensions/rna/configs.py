"""A node's config file: how YAML spells parameter values (merging one: rna/update/config_merge.py)."""

from __future__ import annotations

import math

import yaml


def yaml_float(value: float) -> str:
    """A float as YAML 1.1 reads it back as a float, in PyYAML and rosparam (ROS 1) as in rcl (ROS 2).

    YAML 1.1 takes a number with an exponent for a float only with a '.' before the exponent
    (`1e+308` is a string, `1.0e+308` a float), and spells infinity and NaN `.inf` and `.nan`.
    """
    if math.isnan(value):
        return ".nan"
    if math.isinf(value):
        return ".inf" if value > 0 else "-.inf"
    mantissa, e, exponent = repr(value).partition("e")  # repr signs the exponent: 1e+308, 5e-324
    return mantissa + ("" if "." in mantissa else ".0") + e + exponent


def yaml_literal(value: object) -> str:
    """One YAML scalar or flow list that ROS's parameter parsers read back with the same type."""
    if isinstance(value, float):
        return yaml_float(value)
    if isinstance(value, list):
        return "[" + ", ".join(flow_item(item) for item in value) + "]"
    return yaml.safe_dump(value, default_flow_style=True, width=10**6).strip().removesuffix("...").strip()


def flow_item(value: object) -> str:
    """An element of a flow list: a string plain on its own may not be in a list (`a, b`, `??/`)."""
    if not isinstance(value, str):
        return yaml_literal(value)
    return yaml.safe_dump([value], default_flow_style=True, width=10**6).strip()[1:-1]


def yaml_entry(indent: str, key: str, value: object, width: int = 99) -> str:
    """`key: value` at `indent`, as the config file writes it (the template and the update's merge).

    A list too long for `width` columns breaks after its bracket and its commas, its elements
    on lines 2 columns deeper than the key (YAML reads a flow list across lines); an element
    longer than a line stays whole.
    """
    line = f"{indent}{key}: {yaml_literal(value)}"
    if not isinstance(value, list) or len(line) <= width:
        return line
    items = [flow_item(item) for item in value]
    pad = indent + "  "
    lines, current = [f"{indent}{key}: ["], pad
    for index, item in enumerate(items):
        piece = item + ("," if index < len(items) - 1 else "]")
        if current != pad and len(current) + 1 + len(piece) > width:
            lines.append(current)
            current = pad
        current += piece if current == pad else " " + piece
    lines.append(current)
    return "\n".join(lines)
