"""The `interfaces` answer: the messages, services and actions this package defines."""

from __future__ import annotations

from collections.abc import Mapping

from ..definitions import SECTIONS, Definition, parse_field
from ..names import is_camel_case
from .shapes import check_keys, load_yaml


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
    seen: set[str] = set()
    definitions = []
    for (kind, entry), name in zip(items, names, strict=True):
        if not isinstance(name, str) or not is_camel_case(name):
            raise ValueError(f"interface '{name}': names are CamelCase, starting with an upper-case letter")
        label = f"{'message' if kind == 'msg' else 'service' if kind == 'srv' else 'action'} '{name}'"
        if name in seen:
            raise ValueError(f"{label}: the name is used twice (messages, services and actions share names)")
        seen.add(name)
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
