"""The nodes dialog: add, edit and remove nodes and their endpoints by short prompts.

Its result is the ordinary `nodes` answer (a list of mappings whose endpoints use the
short forms, `topic:type[:qos]`, `name:type`, `name:period`, `name:type=default`), so
the answers file reads as if it had been typed as YAML. Every check is the one the
`nodes` answer gets (answers/nodes.py): a node is read with `parse_node` before it is
kept, and its error, which starts with the node's name, is shown at the prompt.

`Dialog` asks through an `Asker` (questionary at a terminal, a script in the tests).
"""

from __future__ import annotations

import copy
import textwrap
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import yaml

from . import catalogue, distros, names
from .answers.nodes import Types, parameter_mapping, parse_node
from .interfaces import InterfaceType
from .parameters import SCALAR_TYPES, infer_type, parse_type
from .update.resolve import RENAMED_FROM

WIDTH = 79  # columns of a line, in an 80-column terminal
# questionary draws a choice after a 3-column pointer, and the one picked after the
# question: "🎤 <message> <choice>" (the emoji is 2 columns wide).


@dataclass(frozen=True)
class Kind:
    key: str  # the `nodes` key
    label: str  # one of them, in prompts
    interface: str | None = None  # msg, srv or action

    @property
    def plural(self) -> str:
        return self.label + "s"


KINDS = (
    Kind("publishers", "publisher", "msg"),
    Kind("subscribers", "subscriber", "msg"),
    Kind("service_servers", "service server", "srv"),
    Kind("service_clients", "service client", "srv"),
    Kind("action_servers", "action server", "action"),
    Kind("action_clients", "action client", "action"),
    Kind("timers", "timer"),
    Kind("parameters", "parameter"),
)
KIND_OF = {kind.key: kind for kind in KINDS}
NAME_PROMPTS = {"msg": "Topic name", "srv": "Service name", "action": "Action name"}
TYPE_PROMPTS = {"msg": "Message type[:qos]", "srv": "Service type",
                "action": "Action type"}
PARAMETER_TYPES = (*SCALAR_TYPES, *(f"{scalar}[]" for scalar in SCALAR_TYPES))
# Offered first in a type list: the packages most nodes use.
COMMON_PACKAGES = ("std_msgs", "geometry_msgs", "sensor_msgs", "nav_msgs", "std_srvs", "example_interfaces")

FLAGS = {"lifecycle": "Lifecycle node", "autostart": "Configured and activated by the launch file (autostart)",
         "component": "Component (rclcpp_components)",
         "diagnostics": "Diagnostics (diagnostic_updater, on /diagnostics)"}
BACK = "(empty: back)"  # a name left empty adds nothing
# A parameter's description and rules, edited one at a time: (key, label, which parameters have it).
PARAMETER_RULES = (
    ("description", "Description", "one line", lambda ptype, ros: True),
    ("range", "Range", "min, max or min, max, step", lambda ptype, ros: ptype.is_numeric),
    ("one_of", "Allowed values", "e.g. slow, fast", lambda ptype, ros: ptype.scalar != "bool"),
    ("length", "Number of values", "n, [min, max], {min: n} or {max: n}", lambda ptype, ros: ptype.is_array),
    ("not_empty", "Not empty", "", lambda ptype, ros: ptype.name == "string"),
    ("read_only", "Read-only", "", lambda ptype, ros: ros == 2),
)
FLAG_RULES = ("not_empty", "read_only")
ADD_NODE = "Add a node"
DONE = "Done"


def optional(check: Callable[[str], str | None]) -> Callable[[str], str | None]:
    """A name's check that lets an empty answer through (it goes back to the menu)."""
    return lambda answer: check(answer.strip()) if answer.strip() else None


def article(word: str) -> str:
    return ("an " if word[0] in "aeiou" else "a ") + word


def choice_width(message: str) -> int:
    """The widest choice that, once picked, still fits on its question's line."""
    return WIDTH - 4 - len(message)


def fit(text: str, width: int = WIDTH) -> str:
    """`text` on one line of at most `width` columns, cut with an ellipsis."""
    return text if len(text) <= width else text[:width - 1] + "…"


def entry_text(key: str, entry: object) -> str:
    """An endpoint as one short line: its short form, or the short form of its mapping."""
    if not isinstance(entry, Mapping):
        return str(entry)
    if key == "timers":
        return f"{entry.get('name', 'timer')}:{entry.get('period')}"
    if key == "parameters":
        text = str(entry.get("name"))
        if entry.get("type") is not None:
            text += f":{entry['type']}"
        return text + (f"={entry['default']}" if entry.get("default") is not None else "")
    first = entry.get("topic", entry.get("name"))
    qos = f":{entry['qos']}" if entry.get("qos") not in (None, "") else ""
    return f"{first}:{entry.get('type')}{qos}"


def short_parameter(mapping: Mapping) -> str | dict:
    """A parameter's mapping as its short form `name:type=default` when it has nothing else."""
    default = rule_text(mapping["default"]) if "default" in mapping else ""
    if set(mapping) - {"name", "type", "default"} or "\n" in default:
        return dict(mapping)
    return entry_text("parameters", {**mapping, "default": default} if "default" in mapping else mapping)


def rule_text(value: object) -> str:
    """A rule's value as it is typed: [0.0, 10.0], [slow, fast], {min: 1}."""
    return yaml.safe_dump(value, default_flow_style=True, width=10**6).strip().removesuffix("...").strip()


def read_rule(key: str, answer: str) -> object:
    """What is typed for a rule, as the answers hold it; '' removes it. A list may be typed without brackets."""
    answer = answer.strip()
    if not answer or key == "description":
        return answer
    try:
        value = yaml.safe_load(answer)
        if key in ("range", "one_of") and not isinstance(value, list):
            value = yaml.safe_load(f"[{answer}]")
    except yaml.YAMLError:
        return answer  # the node's check says what is wrong with it
    return value


def parameter_type(mapping: Mapping):
    """A parameter's type as its answer gives it, or None."""
    try:
        return parse_type(mapping["type"]) if mapping.get("type") is not None else infer_type(mapping.get("default"))
    except ValueError:
        return None


def timer_name(entry: object) -> str:
    """A timer's name: given as `name:period` or in a mapping, else `timer` (answers/nodes.py)."""
    text = entry_text("timers", entry)
    return text.split(":", 1)[0] if ":" in text else "timer"


def node_line(node: Mapping) -> str:
    """`talker (Python): 1 publisher, 1 timer`."""
    counts = []
    for kind in KINDS:
        count = len(node.get(kind.key) or [])
        if count:
            counts.append(f"{count} {kind.label if count == 1 else kind.plural}")
    language = distros.LANGUAGE_NAMES.get(str(node.get("language")), "")
    text = f"{node.get('name')}" + (f" ({language})" if language else "")
    return text + (": " + ", ".join(counts) if counts else ": nothing yet")


def short_endpoint(name: str, value: str) -> str:
    """The short form of one endpoint from its two answers (name, then type, period or type=default)."""
    return f"{name.strip()}:{value.strip()}"


def type_choices(interface: str, ros: int, distro: str | None, found: Sequence[str] = (),
                 own: Sequence[str] = ()) -> list[str]:
    """Types of one kind to complete from: the package's own, the workspace's, then the catalogue's.

    The common packages come first; any other type may still be typed.
    """
    listed = list(own)
    for name in found:  # pkg/kind/Name, as ROS 1 spells it without the kind
        package, kind, type_name = name.split("/")
        if kind == interface:
            listed.append(InterfaceType(package, kind, type_name, ros).full_name)
    loaded = catalogue.load(distro) if distro else None
    if loaded:
        common = {package: index for index, package in enumerate(COMMON_PACKAGES)}
        packages = sorted(loaded["packages"], key=lambda package: (common.get(package, len(common)), package))
        for package in packages:
            for name in loaded["packages"][package].get(interface, ()):
                listed.append(InterfaceType(package, interface, name, ros).full_name)
    return list(dict.fromkeys(listed))


@dataclass
class Rules:
    """What the package's other answers decide about its nodes."""

    package: str
    build_type: str
    types: Types

    @property
    def languages(self) -> tuple[str, ...]:
        return distros.languages(self.build_type)

    def node_error(self, node: Mapping) -> str | None:
        """The `nodes` rule a node breaks, as parse_node words it (starting with the node), or None."""
        try:
            parse_node(dict(node), package=self.package, build_type=self.build_type, types=self.types)
        except ValueError as error:
            return str(error)
        return None

    def name_error(self, name: str, others: Sequence[str]) -> str | None:
        error = names.node_name_error(name)
        if error:
            return error
        if name in others:
            return f"there is a node '{name}' already"
        return None


class Asker:
    """The prompts the dialog uses; each returns the answer (questionary at a terminal)."""

    def select(self, message: str, choices: Sequence[str], default: str | None = None) -> str:
        import questionary

        # Typing filters the choices: a long menu is reached by a few letters.
        return questionary.select(message, choices=list(choices), default=default, qmark="🎤",
                                  use_search_filter=True, use_jk_keys=False).unsafe_ask()

    def say(self, line: str) -> None:
        print(line, flush=True)

    def text(self, message: str, default: str = "", validate: Callable[[str], str | None] | None = None,
             complete: Sequence[str] = ()) -> str:
        import questionary

        def check(answer: str):
            error = validate(answer) if validate else None
            # Shown under the prompt: wrapped at the terminal's width rather than by it.
            return textwrap.fill(error, WIDTH - 1) if error else True

        # Checked on Enter: a half-typed answer is not an error yet.
        if complete:
            return questionary.autocomplete(message, choices=list(complete), default=default, validate=check,
                                            match_middle=True, qmark="🎤", validate_while_typing=False).unsafe_ask()
        return questionary.text(message, default=default, validate=check, qmark="🎤",
                                validate_while_typing=False).unsafe_ask()


class Dialog:
    """The nodes, changed one prompt at a time, starting from `nodes`."""

    def __init__(self, nodes: object, rules: Rules, asker: Asker | None = None,
                 found: Sequence[str] = (), own: Mapping[str, Sequence[str]] | None = None,
                 existing: bool = False) -> None:
        """`existing`: the nodes are the package's (an update): a node renamed says its old name."""
        self.nodes = [dict(node) if isinstance(node, Mapping) else {"name": str(node)}
                      for node in (copy.deepcopy(nodes) if isinstance(nodes, list) else [])]
        self.existing = {node["name"] for node in self.nodes} if existing else set()
        self.rules = rules
        for node in self.nodes:  # written out, as the answers file records it
            node.setdefault("language", distros.default_language(rules.build_type))
        self.ask = asker or Asker()
        self.found = list(found)
        self.own = dict(own or {})

    # --- the package's nodes

    def run(self) -> list[dict]:
        while True:
            message = f"Nodes ({len(self.nodes)}): what next?"
            choices = [ADD_NODE]
            for node in self.nodes:
                choices.append(fit(f"Edit {node_line(node)}", choice_width(message)))
            choices.extend(f"Remove {node['name']}" for node in self.nodes)
            choices.append(DONE)
            count = len(self.nodes)
            picked = self.ask.select(message, choices, default=DONE if self.nodes else ADD_NODE)
            if picked not in choices:  # a filter that matched nothing
                continue
            if picked == DONE:
                if self.nodes:
                    return self.nodes
                self.ask.say("A package needs a node: add one.")
                continue
            if picked == ADD_NODE:
                self.add_node()
                continue
            index = choices.index(picked) - 1
            if index < count:
                self.edit_node(self.nodes[index])
            else:
                del self.nodes[index - count]

    def add_node(self) -> None:
        others = [node["name"] for node in self.nodes]
        # The language first: some rules on the name depend on it.
        language = (self._language(self.rules.languages[0]) if len(self.rules.languages) > 1
                    else self.rules.languages[0])
        name = self.ask.text(f"Node name, lower_snake_case {BACK}",
                             validate=optional(lambda answer: self._name_error({"language": language}, answer,
                                                                               others))).strip()
        if not name:
            return
        node = {"name": name, "language": language}
        self.nodes.append(node)
        self.edit_node(node)

    def _language(self, current: str) -> str:
        titles = {distros.LANGUAGE_NAMES[language]: language for language in self.rules.languages}
        picked = self.ask.select("Language of the node", list(titles),
                                 default=distros.LANGUAGE_NAMES.get(current))
        return titles.get(picked, current)

    # --- one node

    def edit_node(self, node: dict) -> None:
        while True:
            choices, actions = [], []
            for kind in KINDS:
                choices.append(f"Add {article(kind.label)}")
                actions.append(("add", kind))
            message = "What next?"
            for index, entry in enumerate(node.get("parameters") or []):
                choices.append(fit(f"Edit parameter {entry_text('parameters', entry)}", choice_width(message)))
                actions.append(("parameter", index))
            for kind in KINDS:
                for index, entry in enumerate(node.get(kind.key) or []):
                    choices.append(fit(f"Remove {kind.label} {entry_text(kind.key, entry)}", choice_width(message)))
                    actions.append(("remove", (kind, index)))
            choices.append(f"Rename {node['name']}")
            actions.append(("rename", None))
            if len(self.rules.languages) > 1:
                choices.append(f"Language: {distros.LANGUAGE_NAMES.get(str(node.get('language')), '?')}")
                actions.append(("language", None))
            for flag in self.flags(node):
                choices.append(f"{FLAGS[flag]}: {'yes' if node.get(flag) else 'no'}")
                actions.append(("flag", flag))
            choices.append(f"Done with {node['name']}")
            actions.append(("done", None))
            self.ask.say(fit(f"Node {node_line(node)}"))
            picked = self.ask.select(message, choices, default=choices[-1])
            if picked not in choices:
                continue
            action, what = actions[choices.index(picked)]
            if action == "done":
                return
            if action == "add":
                self.add_endpoint(node, what)
            elif action == "parameter":
                self.edit_parameter(node, what)
            elif action == "remove":
                kind, index = what
                del node[kind.key][index]
                if not node[kind.key]:
                    del node[kind.key]
            elif action == "rename":
                self._renamed(node, self._rename(node))
            elif action == "language":
                self._change(node, "language", self._language(str(node.get("language"))))
            elif action == "flag":
                self._change(node, what, not node.get(what))

    def edit_parameter(self, node: dict, index: int) -> None:
        """A parameter's description and rules, one at a time, each checked as the node's answer."""
        while True:
            mapping = parameter_mapping(node["parameters"][index])
            ptype = parameter_type(mapping)
            if ptype is None:
                return
            choices, keys = [], []
            for key, label, _, applies in PARAMETER_RULES:
                if not applies(ptype, self.rules.types.ros) and key not in mapping:
                    continue
                if key in FLAG_RULES:
                    shown = "yes" if mapping.get(key) else "no"
                else:
                    shown = (mapping[key] if key == "description" else rule_text(mapping[key])) if key in mapping \
                        else "(none)"
                choices.append(fit(f"{label}: {shown}", choice_width("What next?")))
                keys.append(key)
            done = f"Done with {mapping['name']}"
            choices.append(done)
            self.ask.say(fit(f"Parameter {entry_text('parameters', mapping)}"))
            picked = self.ask.select("What next?", choices, default=done)
            if picked == done:
                return
            if picked not in choices:
                continue
            key = keys[choices.index(picked)]
            if key in FLAG_RULES:
                self._set_rule(node, index, mapping, key, not mapping.get(key))
                continue
            label, hint = next((label, hint) for name, label, hint, _ in PARAMETER_RULES if name == key)
            current = "" if key not in mapping else mapping[key] if key == "description" else rule_text(mapping[key])
            answer = self.ask.text(f"{label}, {hint} (empty: none)", default=current,
                                   validate=lambda typed, key=key, mapping=mapping: self._rule_error(
                                       node, index, mapping, key, typed))
            self._set_rule(node, index, mapping, key, read_rule(key, answer))

    def _with_rule(self, node: dict, index: int, mapping: dict, key: str, value: object) -> dict:
        """The node with one rule of a parameter set (a value of '' or False removes it)."""
        changed = {name: item for name, item in mapping.items() if name != key}
        if value not in ("", False, None):
            changed[key] = value
        entries = list(node["parameters"])
        entries[index] = short_parameter(changed)
        return {**node, "parameters": entries}

    def _rule_error(self, node: dict, index: int, mapping: dict, key: str, typed: str) -> str | None:
        return self.rules.node_error(self._with_rule(node, index, mapping, key, read_rule(key, typed)))

    def _set_rule(self, node: dict, index: int, mapping: dict, key: str, value: object) -> None:
        changed = self._with_rule(node, index, mapping, key, value)
        error = self.rules.node_error(changed)
        if error:
            self.ask.say(error)
            return
        node["parameters"] = changed["parameters"]

    def flags(self, node: Mapping) -> list[str]:
        """The yes/no keys a node may change here: diagnostics; in ROS 2 lifecycle, autostart for lifecycle nodes,
        components in C++."""
        if self.rules.types.ros != 2:
            return ["diagnostics"]
        flags = ["lifecycle", "autostart"] if node.get("lifecycle") else ["lifecycle"]
        if node.get("language") == "cpp" or node.get("component"):
            flags.append("component")
        return flags + ["diagnostics"]

    def _change(self, node: dict, key: str, value: object) -> None:
        """Set one key, unless the node would then break a rule: then say which, and keep it."""
        changed = {**node, key: value}
        if key == "lifecycle" and value is False:
            changed.pop("autostart", None)  # only a lifecycle node is started that way
        error = self.rules.node_error(changed)
        if error:
            self.ask.say(error)
            return
        node.clear()
        node.update((name, item) for name, item in changed.items() if item is not False)

    def _rename(self, node: dict) -> str:
        others = [other["name"] for other in self.nodes if other is not node]
        return self.ask.text("New name", default=node["name"],
                             validate=lambda answer: self._name_error(node, answer.strip(), others)).strip()

    def _renamed(self, node: dict, name: str) -> None:
        """The package's own node renamed keeps its old name in `renamed_from`: the update carries its files."""
        was = node.get(RENAMED_FROM) or (node["name"] if node["name"] in self.existing else None)
        node["name"] = name
        if was and was != name:
            node[RENAMED_FROM] = was
        else:
            node.pop(RENAMED_FROM, None)

    def _name_error(self, node: Mapping, name: str, others: Sequence[str]) -> str | None:
        """The name's own rules, then those of the node it names (a name that shadows a module...)."""
        return self.rules.name_error(name, others) or self.rules.node_error({**node, "name": name})

    def _with(self, node: dict, kind: Kind, entry: str) -> dict:
        return {**node, kind.key: [*(node.get(kind.key) or []), entry]}

    def _entry_error(self, node: dict, kind: Kind, entry: str) -> str | None:
        return self.rules.node_error(self._with(node, kind, entry))

    def add_endpoint(self, node: dict, kind: Kind) -> None:
        """Two prompts: the name, then the type (a period for a timer, type=default for a parameter)."""
        if kind.interface:
            what = {"msg": "topic", "srv": "service", "action": "action"}[kind.interface]
            name = self.ask.text(f"{NAME_PROMPTS[kind.interface]} {BACK}",
                                 validate=optional(lambda answer: names.topic_name_error(answer, what))).strip()
            if not name:
                return
            choices = type_choices(kind.interface, self.rules.types.ros, self.rules.types.distro, self.found,
                                   self.own.get(kind.interface, ()))
            value = self.ask.text(TYPE_PROMPTS[kind.interface], complete=choices,
                                  validate=lambda answer: self._entry_error(node, kind, short_endpoint(
                                      name, answer))).strip()
        elif kind.key == "timers":
            taken = {timer_name(entry) for entry in node.get("timers") or []}
            suggested = next(name for name in ("timer", *(f"timer{n}" for n in range(2, 100))) if name not in taken)
            name = self.ask.text(f"Timer name {BACK}", default=suggested,
                                 validate=optional(lambda answer: names.identifier_error(answer, "timer"))).strip()
            if not name:
                return
            value = self.ask.text("Period in seconds (e.g. 0.1)",
                                  validate=lambda answer: self._entry_error(node, kind, short_endpoint(
                                      name, answer))).strip()
        else:
            ros = self.rules.types.ros
            name = self.ask.text(f"Parameter name {BACK}",
                                 validate=optional(lambda answer: names.parameter_name_error(answer, ros))).strip()
            if not name:
                return
            ptype = self.ask.select("Parameter type", PARAMETER_TYPES, default="double") or "double"

            def typed(answer: str) -> str:
                return f"{ptype}={answer.strip()}" if answer.strip() else ptype

            default = self.ask.text("Default value (e.g. 1.5, true, text, [1, 2])",
                                    validate=lambda answer: self._entry_error(node, kind, short_endpoint(
                                        name, typed(answer))))
            value = typed(default)
        node[kind.key] = [*(node.get(kind.key) or []), short_endpoint(name, value)]
