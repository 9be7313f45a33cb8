"""A node's config file: how YAML spells parameter values (merging one: rna/update/config_merge.py)."""

from __future__ import annotations

import yaml


def yaml_literal(value: object) -> str:
    """One YAML scalar or flow list that ROS's parameter parsers read back with the same type."""
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, list):
        return "[" + ", ".join(yaml_literal(item) for item in value) + "]"
    return yaml.safe_dump(value, default_flow_style=True, width=10**6).strip().removesuffix("...").strip()
