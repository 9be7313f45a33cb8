"""mkdocs hook: the site's address, the generated parts of the answers reference, and node graphs.

The address comes from extensions/rna/lab.py (a fork's extensions/lab.yml can change it),
the one place prompts and generated READMEs read it from. The tables of every question
and of every key of a node come from copier.yml and from the JSON Schema that rna.schema
makes from the template's own rules, so the reference says what the validators check. `<!-- rna: graph of <example> -->` in a
page becomes the Mermaid graph of docs/examples/<example>.yml, as the package's generated
README draws it (rna.graph).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "extensions"))

from rna import build_package, graph, lab, schema  # noqa: E402 - the template's own package
from rna.port import rules as port_rules  # noqa: E402

_JINJA = re.compile(r"\{\{.*?\}\}|\{%.*?%\}", re.S)
# A help's link to a page of this site, shown as its address.
_DOCS_URL = re.compile(r"\{\{\s*docs_url\('([^']*)'\)\s*\}\}")


def on_config(config):
    config["site_url"] = lab.docs_url()
    return config


def _not(rule: dict) -> str:
    """What a `not` rule excludes, in words."""
    parts = []
    for excluded in rule.get("anyOf", [rule]):
        if excluded.get("$ref", "").endswith("/keyword"):
            parts.append("a Python or C++ keyword")
        elif "const" in excluded:
            parts.append(f"`{excluded['const']}`")
        elif "pattern" in excluded:
            parts.append(f"a name matching `{excluded['pattern']}`")
    return "not " + " nor ".join(parts)


def _words(rule: dict) -> str:
    """A schema property in words: its choices, its shape, its limits."""
    parts = []
    if "enum" in rule:
        parts.append("one of " + ", ".join(f"`{value}`" for value in rule["enum"]))
    if rule.get("pattern") == r"^[^\n\r]*$":
        parts.append("one line of text")
    elif rule.get("type") == "string" and "pattern" in rule:
        parts.append(f"matches `{rule['pattern']}`")
    if "minLength" in rule and rule["minLength"] > 1:
        parts.append(f"at least {rule['minLength']} characters")
    if "maxLength" in rule:
        parts.append(f"at most {rule['maxLength']} characters")
    if "minimum" in rule and "maximum" in rule:
        parts.append(f"from {rule['minimum']} to {rule['maximum']}")
    if "not" in rule:
        parts.append(_not(rule["not"]))
    if rule.get("type") == "array":
        forms = rule.get("items", {}).get("oneOf", [])
        shapes = [form.get("description") or ("a mapping of " + ", ".join(f"`{key}`" for key in form["properties"]))
                  if form.get("type") == "object" else form.get("description", form.get("type", ""))
                  for form in forms]
        parts.append("a list" + (" of: " + "; or ".join(filter(None, shapes)) if shapes else ""))
    if rule.get("type") == "object" and "properties" in rule:
        parts.append("a mapping of " + ", ".join(f"`{key}`" for key in rule["properties"]))
    if rule.get("type") == "boolean":
        parts.append("`true` or `false`")
    return "; ".join(parts) or rule.get("description", "")


def _cell(text: object) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def questions_table() -> str:
    questions = yaml.safe_load((ROOT / "copier.yml").read_text())
    rules = schema.answers_schema()["properties"]
    rows = ["| Question | Type | Checked by the validators | Help |", "| --- | --- | --- | --- |"]
    for name, question in questions.items():
        if name.startswith("_") or not isinstance(question, dict):
            continue
        help_text = _DOCS_URL.sub(lambda match: f"<{lab.docs_url(match[1])}>", question.get("help", ""))
        help_text = _cell(_JINJA.sub("…", help_text))
        rule = _cell(_words(rules[name])) if name in rules else ""
        rows.append(f"| `{name}` | {question.get('type', 'str')} | {rule} | {help_text} |")
    return "\n".join(rows)


def node_keys_table() -> str:
    node = schema.answers_schema()["properties"]["nodes"]["items"]["oneOf"][1]["properties"]
    rows = ["| Key | Checked by the validators |", "| --- | --- |"]
    rows += [f"| `{key}` | {_cell(_words(rule))} |" for key, rule in node.items()]
    return "\n".join(rows)


def port_rules_table() -> str:
    """The port's rule table (rna.port.rules, the one the rewriters name), one table per language."""
    parts = []
    for language in dict.fromkeys(rule.language for rule in port_rules.RULES):
        rows = [f"### {language}", "", "| ROS 1 | ROS 2 | Note | Rule |", "| --- | --- | --- | --- |"]
        for rule in (rule for rule in port_rules.RULES if rule.language == language):
            ros2 = f"TODO(port): {_cell(rule.ros2)}" if rule.todo else f"`{_cell(rule.ros2)}`"
            rows.append(f"| `{_cell(rule.ros1)}` | {ros2} | {_cell(rule.note)} | `{rule.key}` |")
        parts.append("\n".join(rows))
    return "\n\n".join(parts)


# The answers an example leaves to the person copying it.
_EXAMPLE_DEFAULTS = {"package_name": "example", "description": "An example", "maintainer": "Ada Lovelace",
                     "maintainer_email": "ada@example.com", "license": "Apache-2.0",
                     "copyright_holder": "Ada Lovelace", "copyright_year": 2026, "ros_distro": "jazzy",
                     # The graph does not depend on these.
                     "build_type": "ament_python", "launch_format": "xml", "target": "package",
                     "interfaces": {}, "interfaces_location": "separate"}
_GRAPH = re.compile(r"<!-- rna: graph of ([a-z0-9_]+) -->")


def example_graph(name: str) -> str:
    """The Mermaid block a package made from docs/examples/<name>.yml has in its README."""
    answers = yaml.safe_load((ROOT / "docs" / "examples" / f"{name}.yml").read_text())
    package = build_package({**_EXAMPLE_DEFAULTS, **answers})
    return "```mermaid\n" + "\n".join(graph.mermaid_lines(package.nodes)) + "\n```"


def on_page_markdown(markdown, page, config, files):
    markdown = _GRAPH.sub(lambda match: example_graph(match[1]), markdown)
    return (markdown.replace("<!-- rna: questions -->", questions_table())
            .replace("<!-- rna: node keys -->", node_keys_table())
            .replace("<!-- rna: port rules -->", port_rules_table()))
