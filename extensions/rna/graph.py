"""The package's nodes as a graph, for its README: a Mermaid flowchart and per-node tables.

GitHub, GitLab and MkDocs render a ```mermaid block as a diagram; elsewhere it stays
readable text. Node ids in the chart are made up (n0, t0...) because ROS names hold
characters Mermaid reads as syntax; the labels carry the names.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from dataclasses import dataclass

from . import names
from .configs import yaml_literal
from .interfaces import InterfaceType
from .qos import describe as qos_words
from .qos import parse as parse_qos
from .wording import markdown_cell, period_text


@dataclass(frozen=True)
class Vertex:
    """A topic, service or action in the chart: one per name and type."""

    kind: str  # topic | service | action
    name: str
    type: str

    @property
    def shape(self) -> tuple[str, str]:
        # Topics as boxes, services as hexagons, actions as subroutines (double-sided boxes).
        return {"topic": ("[", "]"), "service": ("{{", "}}"), "action": ("[[", "]]")}[self.kind]


# Publishing and subscribing are data flows (solid); calls and goals are requests (dotted, thick).
_ARROWS = {"topic": "-->", "service": "-.->", "action": "==>"}


def _label(*lines: str) -> str:
    return '"' + "<br/>".join(line.replace('"', "#quot;") for line in lines) + '"'


def mermaid_lines(nodes: Iterable) -> list[str]:
    """A `flowchart LR` of the nodes and what connects them: writers point to readers.

    A publisher points to its topic and the topic to each subscriber; a client points to
    the service or action, and that to its server. Endpoints whose other side is outside
    the package still show, with one side.
    """
    nodes = list(nodes)
    vertices: dict[Vertex, str] = {}
    edges: list[tuple[str, str, str]] = []

    labels: dict[tuple[str, str], Vertex] = {}

    def vertex(kind: str, name: str, type_) -> str:
        # One vertex per name the nodes meet on (`odom` and `/odom` alike), labelled as first written.
        met = names.graph_name(name, node.name) or f"{node.name}/{name}"
        key = labels.setdefault((kind, met), Vertex(kind, names.with_node(name, node.name), type_.full_name))
        return vertices.setdefault(key, f"{kind[0]}{len(vertices)}")

    for index, node in enumerate(nodes):
        me = f"n{index}"
        for topic in node.publishers:
            edges.append((me, vertex("topic", topic.topic, topic.type), _ARROWS["topic"]))
        for topic in node.subscribers:
            edges.append((vertex("topic", topic.topic, topic.type), me, _ARROWS["topic"]))
        for kind, clients, servers in (("service", node.service_clients, node.service_servers),
                                       ("action", node.action_clients, node.action_servers)):
            for endpoint in clients:
                edges.append((me, vertex(kind, endpoint.name, endpoint.type), _ARROWS[kind]))
            for endpoint in servers:
                edges.append((vertex(kind, endpoint.name, endpoint.type), me, _ARROWS[kind]))
    lines = ["flowchart LR"]
    lines.extend(f"  n{index}([{_label(node.name)}])" for index, node in enumerate(nodes))
    for key, ident in vertices.items():
        opening, closing = key.shape
        lines.append(f"  {ident}{opening}{_label(key.name, key.type)}{closing}")
    lines.extend(f"  {source} {arrow} {target}" for source, target, arrow in dict.fromkeys(edges))
    return lines


def markdown_code(text: str) -> str:
    """Text as a Markdown code span that survives a table cell: backticks and pipes included."""
    fence = "`" * (max((len(run) for run in re.findall("`+", text)), default=0) + 1)
    padded = f" {text} " if text.startswith("`") or text.endswith("`") else text
    return f"{fence}{padded}{fence}".replace("|", "\\|")


def endpoint_rows(node) -> list[tuple[str, str, str, str]]:
    """(what, name, type or period, QoS) for each thing the node talks through, as README table cells."""
    rows = []
    for label, topics in (("publishes", node.publishers), ("subscribes to", node.subscribers)):
        rows.extend((label, markdown_code(t.topic), markdown_code(t.type.full_name),
                     qos_words(t.qos, node.ros, t.role == "publisher")) for t in topics)
    for label, endpoints in (("serves", node.service_servers), ("calls", node.service_clients),
                             ("executes goals of", node.action_servers), ("sends goals to", node.action_clients)):
        rows.extend((label, markdown_code(e.name), markdown_code(e.type.full_name), "") for e in endpoints)
    rows.extend(("timer", markdown_code(t.id), period_text(t.period), "") for t in node.timers)
    if node.diagnostics:  # diagnostic_updater's own publisher, with a depth (ROS 1: a queue) of 1
        array = InterfaceType("diagnostic_msgs", "msg", "DiagnosticArray", node.ros)
        rows.append(("publishes its status on", markdown_code("/diagnostics"), markdown_code(array.full_name),
                     qos_words(parse_qos(1), node.ros, publisher=True)))
    return rows


def _default_text(value: object) -> str:
    """A default as the config file writes it; on one line, since a table row is one line."""
    text = yaml_literal(value)
    return json.dumps(value, ensure_ascii=False) if "\n" in text or "\r" in text else text


def parameter_rows(node) -> list[tuple[str, str, str, str]]:
    """(name, type, default, description) for each parameter, as README table cells."""
    return [(markdown_code(p.name), markdown_code(str(p.type)), markdown_code(_default_text(p.default)),
             markdown_cell(" ".join(p.description.split()))) for p in node.parameters]


def interface_rows(package) -> list[tuple[str, str]]:
    """(type, fields) for each interface the package defines; a service's or action's parts split by ---."""
    rows = []
    for definition in package.definitions:
        full_name = InterfaceType(package.interfaces_home, definition.kind, definition.name, package.ros).full_name
        parts = ["; ".join(field.line for field in section) for section in definition.sections]
        rows.append((markdown_code(full_name), " --- ".join(markdown_code(part) if part else "(empty)"
                                                            for part in parts)))
    return rows
