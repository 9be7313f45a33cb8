"""English for comments, docstrings, logs, the README and the prompts: what a node does, in a sentence."""

from __future__ import annotations

import html
import textwrap
from collections.abc import Iterable


def english_list(items: Iterable[str]) -> str:
    """['a', 'b', 'c'] -> 'a, b and c'."""
    items = list(items)
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def found_lines(names: list[str], width: int = 72, shown: int = 12) -> list[str]:
    """'Found in your workspace: a, b ... and 3 more', wrapped at `width` for a prompt's help.

    Names are never split (they hold no spaces); later lines are indented by two.
    """
    if not names:
        return []
    text = ", ".join(names[:shown]) + (f" and {len(names) - shown} more" if len(names) > shown else "")
    return textwrap.wrap("Found in your workspace: " + text, width, subsequent_indent="  ",
                         break_long_words=False, break_on_hyphens=False)


def with_article(word: str) -> str:
    """'approach' -> 'an approach', 'reset' -> 'a reset' (for log messages and docs)."""
    return ("an " if word.lstrip("/~")[:1].lower() in "aeiou" else "a ") + word


def capitalised(text: str) -> str:
    return text[:1].upper() + text[1:]


def markdown_cell(text: str) -> str:
    """Text for a cell of a Markdown table: HTML special characters and pipes escaped."""
    return html.escape(text, quote=False).replace("|", "\\|")


def period_text(period: float) -> str:
    """'every 0.5 s' for docs and comments."""
    return f"every {period:g} s"


def node_summary(node) -> str:
    """The node's description, or a sentence made from what it does."""
    if node.description:
        return node.description if node.description.endswith(".") else node.description + "."
    parts = summary_parts(node)
    if not parts:
        return f"The {node.name} node."
    return capitalised(english_list(parts)) + "."


def summary_parts(node) -> list[str]:
    """What a node does, one clause per kind of endpoint: 'publishes cmd_vel', 'subscribes to odom'..."""
    parts = []
    if node.publishers:
        parts.append("publishes " + english_list(t.topic for t in node.publishers))
    if node.subscribers:
        parts.append("subscribes to " + english_list(t.topic for t in node.subscribers))
    if node.service_servers:
        parts.append("serves " + english_list(s.name for s in node.service_servers))
    if node.service_clients:
        parts.append("calls " + english_list(s.name for s in node.service_clients))
    if node.action_servers:
        parts.append("executes " + english_list(a.name for a in node.action_servers) + " goals")
    if node.action_clients:
        parts.append("sends " + english_list(a.name for a in node.action_clients) + " goals")
    if node.diagnostics:
        parts.append("reports its status on /diagnostics")
    return parts


def summary_lines(node, width: int = 88, escape=None) -> list[str]:
    """The summary wrapped for a docstring or comment, after a blank line; `escape` spells the
    text for where it lands first (a Python docstring's three double quotes).

    No line ends with a backslash, which would continue a C++ `//` comment onto the next.
    """
    text = node_summary(node)
    lines = textwrap.wrap(escape(text) if escape else text, width)
    for index in range(len(lines) - 1):
        while lines[index].endswith("\\") or lines[index].endswith("??/"):
            head, _, word = lines[index].rpartition(" ")
            if not head:
                break
            lines[index], lines[index + 1] = head, f"{word} {lines[index + 1]}"
    return ["", *lines]


def driver_docstring(node) -> str:
    """What the starter timer callback does."""
    work = []
    if node.publishers:
        work.append("publish the next message" + ("s" if len(node.publishers) > 1 else ""))
    if node.service_clients:
        work.append("call the service" + ("s" if len(node.service_clients) > 1 else ""))
    if node.action_clients:
        work.append("send a goal" if len(node.action_clients) == 1 else "send goals")
    return capitalised(english_list(work)) + "."


def describe_nodes(nodes, width: int | None = None) -> str:
    """A package description from its nodes: what each does, or their names; with `width`, the
    most it can say in that many columns (a prompt shows it as its default, on one line)."""
    forms = []
    if len(nodes) <= 3:
        if any(node.description for node in nodes):
            forms.append(" ".join(node_summary(node) for node in nodes))
        else:
            forms.append(capitalised("; ".join(f"the {node.name} node {node_summary(node)[0].lower()}"
                                               f"{node_summary(node)[1:-1]}" for node in nodes)))
    if len(nodes) == 1 and not nodes[0].description:  # fewer of what it does
        parts = summary_parts(nodes[0])
        forms.extend(f"The {nodes[0].name} node {english_list(parts[:count])}"
                     for count in range(len(parts) - 1, 0, -1))
    forms.append("Nodes " + english_list(node.name for node in nodes) if len(nodes) > 1
                 else f"The {nodes[0].name} node")
    forms.append(f"{len(nodes)} ROS nodes" if len(nodes) > 1 else "A ROS node")
    return next((form for form in forms if width is None or len(form) <= width), forms[-1])


def threads_text(node) -> str:
    """A multi-threaded executor's threads, in words."""
    return f"{node.threads} threads" if node.threads else "as many threads as the machine has cores"


_EXECUTORS = {"single_threaded": "a single-threaded executor", "multi_threaded": "a multi-threaded executor",
              "static": "a static single-threaded executor", "events": "an events executor"}


def spinning_text(node) -> str:
    """How a node runs its callbacks and what its launch file changes, for its README: '' when
    it spins as every node does by default (one thread, no groups, no remappings)."""
    sentences = []
    if node.executor != "single_threaded" or node.callback_groups:
        executor = _EXECUTORS[node.executor]
        if node.multi_threaded:
            executor += f" of {node.threads} threads" if node.threads else " of one thread per core"
        if node.ros == 1 and node.multi_threaded:
            executor = "a ros::MultiThreadedSpinner" + executor.removeprefix("a multi-threaded executor")
        what = "Its executable spins it on" if node.component else "Spins on"
        sentences.append(f"{what} {executor}.")
        groups = [f"`{group.name}` ({group.type.replace('_', ' ')}: "
                  + ", ".join(f"`{getattr(e, 'topic', None) or getattr(e, 'name', e.id)}`" for e in group.members)
                  + ")" for group in node.callback_groups]
        if groups:
            sentences.append(f"Callback group{'s' if len(groups) > 1 else ''} apart from the node's default one: "
                             f"{english_list(groups)}.")
    if node.remappings:
        remapped = [f"`{source}` to `{target}`" for source, target in node.remappings]
        sentences.append(f"The launch file remaps {english_list(remapped)}.")
    return " ".join(sentences)
