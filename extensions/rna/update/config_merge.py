"""Config files (`config/<node>.yaml`) merged by parameter where the line merge conflicts.

`copier update` merges a config file line by line. Where that conflicts (a tuned value
next to a changed default, or a file laid out by an older version), the parameters
themselves say what to keep: the user's value for every parameter the user tuned, the
new default for every other one, and every parameter the user added. Only a parameter
the user tuned whose default also changed is a real conflict.
"""

from __future__ import annotations

import re

import yaml

from ..configs import yaml_literal
from .project import Project, Render
from .summary import Report

MARKERS = ("<<<<<<< before updating", ">>>>>>> after updating")


def parameters(text: str) -> dict | None:
    """The parameters of a ROS 2 (`/**: ros__parameters:`) or ROS 1 (flat) config file."""
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError:
        return None
    if not isinstance(data, dict):
        return {} if data is None else None
    if len(data) == 1:
        (key, value), = data.items()
        if isinstance(value, dict) and "ros__parameters" in value:
            return value["ros__parameters"] or {}
    return data


def merge(old_text: str, mine_text: str, new_text: str) -> str | None:
    """The new file with the user's tuned and added parameters, or None on a real conflict."""
    old, mine, new = parameters(old_text), parameters(mine_text), parameters(new_text)
    if old is None or mine is None or new is None:
        return None
    values, extra = {}, {}
    for name, value in mine.items():
        tuned = name not in old or value != old[name]
        if name in new:
            if tuned and name in old and new[name] != old[name] and value != new[name]:
                return None  # tuned here, and its default changed too
            values[name] = value if tuned else new[name]
        elif tuned:
            extra[name] = value  # the user's own, or tuned before the template dropped it
    text = new_text
    for name, value in values.items():
        line = f"{name}: {yaml_literal(value)}"
        text = re.sub(rf"^(\s*){re.escape(name)}:[^\n]*$", lambda m, line=line: m[1] + line, text, count=1, flags=re.M)
    if extra:
        ros2 = "ros__parameters" in new_text
        text = text.replace("ros__parameters: {}", "ros__parameters:").rstrip("\n") + "\n"
        indent = "    " if ros2 else ""
        text += "".join(f"{indent}{name}: {yaml_literal(value)}\n" for name, value in extra.items())
    return text


def merge_config_files(project: Project, old: Render, new: Render, report: Report) -> None:
    """Settle line conflicts in config/<node>.yaml by parameter."""
    for path in sorted(p for p in new.files if re.search(r"(^|/)config/[^/]+\.yaml$", p)):
        current, before = project.text(path), project.committed(path)
        if before is None or current is None or not any(m in current for m in MARKERS):
            continue
        merged = merge(old.text(path) or "", before, new.text(path))
        if merged is not None:
            project.write(path, merged)
            project.resolve_in_index(path)
            report.merged.add(path)
