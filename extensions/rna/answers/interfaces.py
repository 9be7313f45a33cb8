"""The `interfaces` answer: the messages, services and actions this package defines."""

from __future__ import annotations

from collections.abc import Mapping

from ..definitions import SECTIONS, Definition, parse_field
from ..interfaces import KIND_NAMES
from ..names import camel_to_snake, header_path_error, is_camel_case, type_name_error
from ..shapes import check_keys, load_yaml


def parse_definitions(value: object, *, package: str, ros: int) -> tuple[Definition, ...]:
    """The `interfaces` answer: {messages: [...], services: [...], actions: [...]}."""
    if value in (None, "", {}):
        return ()
    value = load_yaml(value)
    if not isinstance(value, Mapping):
        raise ValueError("give a mapping with messages, services and/or actions")
    kinds = {"messages": "msg", "services": "srv", "actions": "action"}
    check_keys(value, tuple(kinds), "interfaces")
    items = []
    for key, kind in kinds.items():
        entries = value.get(key) or []
        if not isinstance(entries, list):
            raise ValueError(f"{key} must be a list")
        for entry in entries:
            if not isinstance(entry, Mapping):
                raise ValueError(f"each of {key} is a mapping with a name and its fields")
            items.append((kind, entry))
    names = [entry.get("name") for _, entry in items]
    local_names = {name for (kind, _), name in zip(items, names, strict=True)
                   if kind == "msg" and isinstance(name, str)}
    derived = _derived_names(items, ros)
    seen: set[str] = set()
    files: dict[str, str] = {}
    definitions = []
    for (kind, entry), name in zip(items, names, strict=True):
        if not isinstance(name, str) or not is_camel_case(name):
            raise ValueError(f"interface '{name}': names are CamelCase, starting with an upper-case letter")
        label = f"{'message' if kind == 'msg' else 'service' if kind == 'srv' else 'action'} '{name}'"
        if name in seen:
            raise ValueError(f"{label}: the name is used twice (messages, services and actions share names)")
        seen.add(name)
        if type_name_error(name):
            raise ValueError(f"{label}: {type_name_error(name)}")
        if header_path_error(package, kind, name):
            raise ValueError(f"{label}: {header_path_error(package, kind, name)}")
        if name in derived:
            raise ValueError(f"{label}: message generation already makes a type of that name for {derived[name]}")
        stem = camel_to_snake(name)
        if stem in files:
            raise ValueError(f"{label}: its generated files would be named like those of '{files[stem]}' ({stem})")
        files[stem] = name
        check_keys(entry, ("name", *SECTIONS[kind]), label)
        sections = []
        for section in SECTIONS[kind]:
            lines = entry.get(section) or []
            if isinstance(lines, str):
                lines = [line for line in lines.splitlines() if line.strip()]
            if not isinstance(lines, list):
                raise ValueError(f"{label}: {section} is a list of lines like 'float64 x'")
            try:
                fields = tuple(parse_field(line, package=package, local_names=local_names, ros=ros)
                               for line in lines)
            except ValueError as error:
                raise ValueError(f"{label}: {error}") from None
            field_names = [field.name for field in fields]
            duplicates = {n for n in field_names if field_names.count(n) > 1}
            if duplicates:
                raise ValueError(f"{label}: {section} has '{sorted(duplicates)[0]}' twice")
            sections.append(fields)
        if kind == "msg" and name in {f.type.split("[")[0] for f in sections[0]}:
            raise ValueError(f"{label}: a message cannot contain itself")
        definitions.append(Definition(kind, name, tuple(sections)))
    return tuple(definitions)


# The types ROS 1 message generation makes for each service and action, beside the
# definition's own (ROS 2's all contain an underscore, which no CamelCase name has).
_ROS1_DERIVED = {"srv": ("Request", "Response"),
                 "action": ("Action", "ActionGoal", "ActionResult", "ActionFeedback", "Goal", "Result", "Feedback")}


def _derived_names(items, ros: int) -> dict[str, str]:
    """Names message generation derives from the definitions -> what derives them."""
    if ros != 1:
        return {}
    return {entry.get("name") + suffix: f"the {KIND_NAMES[kind]} '{entry.get('name')}'"
            for kind, entry in items if isinstance(entry.get("name"), str)
            for suffix in _ROS1_DERIVED.get(kind, ())}
