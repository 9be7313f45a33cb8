"""The shapes answers and the lab file come in: YAML text, lists, comma-separated prompt answers, known keys."""

from __future__ import annotations

import difflib
from collections.abc import Iterable, Mapping

import yaml


def load_yaml(value: object) -> object:
    """A YAML answer typed as text, or the value itself."""
    if not isinstance(value, str):
        return value
    try:
        return yaml.safe_load(value)
    except yaml.YAMLError as error:
        raise ValueError(f"not valid YAML ({str(error).splitlines()[0]})") from None


def split_list(text: object) -> list[str]:
    """Split a prompt answer on commas that are not inside brackets or quotes."""
    if text is None:
        return []
    if isinstance(text, list):
        return text
    items, depth, quote, current = [], 0, "", ""
    for char in str(text):
        if quote:
            quote = "" if char == quote else quote
        elif char in "'\"":
            quote = char
        elif char in "[{(":
            depth += 1
        elif char in "]})":
            depth -= 1
        elif char == "," and depth == 0:
            items.append(current)
            current = ""
            continue
        current += char
    items.append(current)
    return [item.strip() for item in items if item.strip()]


def as_list(value: object, what: str) -> list:
    """A list answer, or a comma-separated one typed at a prompt."""
    if value is None:
        return []
    if isinstance(value, str):
        return split_list(value)
    if not isinstance(value, list):
        raise ValueError(f"write {what} as a list")
    return value


def check_keys(item: Mapping, allowed: Iterable[str], what: str) -> None:
    """Every key of a mapping is one of `allowed`; a typo gets a suggestion."""
    allowed = list(allowed)
    for key in item:
        if key not in allowed:
            close = difflib.get_close_matches(str(key), allowed, n=1)
            fix = f"did you mean '{close[0]}'?" if close else f"use {', '.join(allowed)}:"
            raise ValueError(f"{what + ': ' if what else ''}{fix} unknown key '{key}'")
