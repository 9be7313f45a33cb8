"""The nodes dialog: add, edit and remove nodes, their endpoints and parameters by short prompts.

Its result is the ordinary `nodes` answer (a list of mappings whose endpoints use the
short forms, `topic:type[:qos]`, `name:type`, `name:period`, `name:type=default`, or
mappings when they hold more than a short form can), so the answers file reads as if it
had been typed as YAML. Every check is the one the `nodes` answer gets (answers/nodes.py):
a node is read with `parse_node` before a change is kept, and its error is shown at the
prompt, whole.

What can be edited is described by tables, not by code: `ENTRY_FIELDS` (the keys of one
endpoint or parameter) and `NODE_SETTINGS` (a node's own keys). A new key of the `nodes`
answer is one row there: the menus, the prompts and the checks follow.

`Dialog` asks through an `Asker` (questionary at a terminal, a script in the tests).
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import yaml

from . import catalogue, distros, names, qos, terminal
from .answers.nodes import Types, normalised_entry, parameter_mapping, parse_node
from .interfaces import InterfaceType, normalised_type
from .model import CALLBACK_GROUP_TYPES, DEFAULT_EXECUTOR, EXECUTORS
from .parameters import SCALAR_TYPES
from .update.resolve import RENAMED_FROM

# questionary draws a choice after a pointer of 3 columns; the one picked is shown on
# the line under its question, after 2 (the question ends in a line break, as Copier's do).
POINTER = 3


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
PARAMETER_TYPES = (*SCALAR_TYPES, *(f"{scalar}[]" for scalar in SCALAR_TYPES))
# Offered first in a type list: the packages most nodes use.
COMMON_PACKAGES = ("std_msgs", "geometry_msgs", "sensor_msgs", "nav_msgs", "std_srvs", "example_interfaces")
NO_VALUE = "(none)"  # a choice that leaves an optional key out


@dataclass(frozen=True)
class Field:
    """One key of an endpoint or parameter, as the dialog asks it.

    `form`: "text" (kept as typed), "yaml" (a number, a list...: read as YAML), "list" (a YAML
    list, its brackets optional: `slow, fast`), "type" (an interface type, completed from the
    catalogue), "choice" (from `choices`) or "bool".
    `short`: the key is part of the entry's short form (`topic:type:qos`...); an entry with
    any other key is kept as a mapping. `asked`: asked when the entry is added.
    """

    key: str
    label: str
    prompt: str
    form: str = "text"
    choices: tuple[str, ...] = ()
    short: bool = True
    asked: bool = True
    optional: bool = False


_TOPIC = (Field("topic", "Topic", "Topic name"), Field("type", "Type", "Message type", "type"),
          Field("qos", "QoS", "QoS preset", "choice", tuple(qos.PRESETS), asked=False, optional=True))
_SERVICE = (Field("name", "Name", "Service name"), Field("type", "Type", "Service type", "type"))
_ACTION = (Field("name", "Name", "Action name"), Field("type", "Type", "Action type", "type"))
ENTRY_FIELDS: dict[str, tuple[Field, ...]] = {
    "publishers": _TOPIC,
    "subscribers": _TOPIC,
    "service_servers": _SERVICE,
    "service_clients": _SERVICE,
    "action_servers": _ACTION,
    "action_clients": _ACTION,
    "timers": (Field("name", "Name", "Timer name"), Field("period", "Period", "Period in seconds (e.g. 0.1)", "yaml")),
    "parameters": (
        Field("name", "Name", "Parameter name"),
        Field("type", "Type", "Parameter type", "choice", PARAMETER_TYPES),
        Field("default", "Default", "Default value (e.g. 1.5, true, text, [1, 2])", "yaml", optional=True),
        Field("description", "Description", "Description (one line)", short=False, asked=False, optional=True),
        Field("read_only", "Read-only", "Read-only (set at start-up only)", "bool", short=False, asked=False),
        Field("range", "Range", "Range as min, max or min, max, step (int and double)", "list", short=False,
              asked=False, optional=True),
        Field("one_of", "Allowed values", "Allowed values, e.g. slow, fast (an array's: of each value)", "list",
              short=False, asked=False, optional=True),
        Field("length", "Number of values", "Number of values (arrays): n, [min, max], {min: n} or {max: n}",
              "yaml", short=False, asked=False, optional=True),
        Field("not_empty", "Not empty", "Not empty (strings)", "bool", short=False, asked=False),
    ),
}


@dataclass(frozen=True)
class Setting:
    """One of a node's own keys, changed from the node's menu: a yes/no or a choice."""

    key: str
    label: str
    choices: tuple[str, ...] = ()  # empty: yes/no
    ros: tuple[int, ...] = (1, 2)
    # Offered only when this holds of the node (a mapping): e.g. autostart for lifecycle nodes.
    when: Callable[[Mapping], bool] = lambda node: True


NODE_SETTINGS = (
    Setting("lifecycle", "Lifecycle node", ros=(2,)),
    Setting("autostart", "Configured and activated by the launch file (autostart)", ros=(2,),
            when=lambda node: bool(node.get("lifecycle"))),
    Setting("component", "Component (rclcpp_components)", ros=(2,),
            when=lambda node: node.get("language") == "cpp" or bool(node.get("component"))),
    Setting("diagnostics", "Diagnostics (diagnostic_updater, on /diagnostics)"),
)
# Kept for the tests and the docs: the yes/no settings by key.
FLAGS = {setting.key: setting.label for setting in NODE_SETTINGS if not setting.choices}
BACK = "(empty: back)"  # a name left empty adds nothing
# Keys of a node besides its endpoints and flags, changed through menu entries of their own.
CALLBACK_KEYS = ("subscribers", "service_servers", "service_clients", "action_servers", "action_clients", "timers")
ADD_NODE = "Add a node"
BACK_TO_NODE = "Back"
DONE = "Done"
REMOVE = "Remove it"
KEEP = "Keep it"


def optional(check: Callable[[str], str | None]) -> Callable[[str], str | None]:
    """A name's check that lets an empty answer through (it goes back to the menu)."""
    return lambda answer: check(answer.strip()) if answer.strip() else None


def article(word: str) -> str:
    return ("an " if word[0] in "aeiou" else "a ") + word


def fitting(forms: Sequence[str], width: int) -> str:
    """The first of `forms` (most detailed first) that fits `width` columns; the last one, which
    says the least, shortened in its middle only when even it does not fit (a terminal too narrow
    for a name)."""
    for form in forms:
        if len(form) <= width:
            return form
    last = forms[-1]
    keep = max(width - 1, 2)
    return last[:keep - keep // 2] + "…" + last[len(last) - keep // 2:]


def choice_width() -> int:
    """The widest choice a menu can show whole at this terminal (after the pointer)."""
    return terminal.width() - POINTER


def entry_mapping(key: str, entry: object) -> dict:
    """An endpoint or parameter as a mapping of its keys, from its short form or its mapping."""
    if isinstance(entry, Mapping):
        return dict(entry)
    if key == "timers":
        if isinstance(entry, str) and ":" in entry:
            name, _, period = entry.partition(":")
            return {"name": name.strip(), "period": yaml.safe_load(period) if period.strip() else None}
        return {"period": entry}
    text = str(entry)
    if key == "parameters":
        return parameter_mapping(text) or {"name": text}
    fields = [field.key for field in ENTRY_FIELDS[key] if field.short]
    parts = [part.strip() for part in text.split(":", len(fields) - 1)]
    return {field: part for field, part in zip(fields, parts, strict=False) if part != ""}


def _yaml_text(value: object) -> str:
    """A value as its short form writes it (1.5, true, [1, 2], text)."""
    if isinstance(value, str):
        return value
    return yaml.safe_dump(value, default_flow_style=True).strip().removesuffix("...").strip()


def entry_value(key: str, mapping: Mapping) -> object:
    """An endpoint or parameter in its short form when that holds all its keys, else its mapping."""
    allowed = {field.key for field in ENTRY_FIELDS[key] if field.short}
    present = {name: value for name, value in mapping.items() if value not in (None, "")}
    if set(present) - allowed:
        return present
    if key == "timers":
        period = present.get("period")
        return f"{present['name']}:{_yaml_text(period)}" if "name" in present else period
    if key == "parameters":
        text = str(present.get("name"))
        if present.get("type") is not None:
            text += f":{present['type']}"
        return text + (f"={_yaml_text(present['default'])}" if "default" in present else "")
    fields = [field.key for field in ENTRY_FIELDS[key] if field.short]
    parts = [str(present.get(field, "")) for field in fields]
    while len(parts) > 2 and not parts[-1]:
        parts.pop()
    return ":".join(parts)


def entry_text(key: str, entry: object) -> str:
    """An endpoint as one short line: its short form, or the short form of its mapping."""
    mapping = entry_mapping(key, entry)
    if key == "timers":
        return f"{mapping.get('name', 'timer')}:{_yaml_text(mapping.get('period'))}"
    if key == "parameters":
        text = str(mapping.get("name"))
        if mapping.get("type") is not None:
            text += f":{mapping['type']}"
        return text + (f"={_yaml_text(mapping['default'])}" if mapping.get("default") is not None else "")
    first = mapping.get("topic", mapping.get("name"))
    qos_text = f":{mapping['qos']}" if mapping.get("qos") not in (None, "") else ""
    return f"{first}:{mapping.get('type')}{qos_text}"


def entry_forms(kind: Kind, entry: object) -> list[str]:
    """The ways to show an entry in a menu, most detailed first."""
    mapping = entry_mapping(kind.key, entry)
    name = str(mapping.get("topic", mapping.get("name", "timer")))
    kept = entry_text(kind.key, entry)
    forms = [f"{kind.label} {kept}"]
    if "type" in mapping:
        forms.append(f"{kind.label} {name} ({str(mapping['type']).rsplit('/', 1)[-1]})")
    forms.append(f"{kind.label} {name}")
    return forms


def timer_name(entry: object) -> str:
    """A timer's name: given as `name:period` or in a mapping, else `timer` (answers/nodes.py)."""
    return str(entry_mapping("timers", entry).get("name") or "timer")


def node_forms(node: Mapping) -> list[str]:
    """`talker (Python): 1 publisher, 1 timer` and shorter ways to say it, for a menu's width."""
    counts = []
    for kind in KINDS:
        count = len(node.get(kind.key) or [])
        if count:
            counts.append(f"{count} {kind.label if count == 1 else kind.plural}")
    total = sum(len(node.get(kind.key) or []) for kind in KINDS)
    language = distros.LANGUAGE_NAMES.get(str(node.get("language")), "")
    name = f"{node.get('name')}"
    titled = name + (f" ({language})" if language else "")
    if not counts:
        return [f"{titled}: nothing yet", f"{name}: nothing yet", name]
    plural = "s" if total > 1 else ""
    summed = f"{total} endpoint{plural}" + (f" and parameter{plural}" if node.get("parameters") else "")
    return [f"{titled}: " + ", ".join(counts), f"{name}: " + ", ".join(counts), f"{titled}: {summed}",
            f"{name}: {summed}", name]


def callback_names(node: Mapping) -> list[str]:
    """The names a callback group's members may be given: the node's endpoints with callbacks, as written."""
    found = []
    for key in CALLBACK_KEYS:
        for entry in node.get(key) or []:
            text = entry_text(key, entry)
            found.append(timer_name(entry) if key == "timers" else text.split(":", 1)[0])
    return found


def group_text(group: object) -> str:
    """A callback group in one line: `requests (reentrant): reset, dock`."""
    if not isinstance(group, Mapping):
        return str(group)
    members = group.get("members")
    members = ", ".join(map(str, members)) if isinstance(members, list) else str(members)
    return f"{group.get('name')} ({group.get('type') or 'mutually_exclusive'}): {members}"


def node_line(node: Mapping) -> str:
    """`talker (Python): 1 publisher, 1 timer`."""
    return node_forms(node)[0]


def type_choices(interface: str, ros: int, distro: str | None, found: Sequence[str] = (),
                 own: Sequence[str] = (), first: Sequence[str] = ()) -> list[str]:
    """Types of one kind to complete from: `first`, the package's own, the workspace's, then the catalogue's.

    The common packages come first; any other type may still be typed.
    """
    listed = [*first, *own]
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
            return f"choose another name: there is a node '{name}' already"
        return None


class Asker:
    """The prompts the dialog uses; each returns the answer (questionary at a terminal).

    A question ends in a line break, as Copier's do: the answer is shown under it, where a
    long one has the whole line.

    An answer's error is shown whole under the prompt by the patch `whole_errors`
    (extensions/patches/prompts.py), as Copier's are.
    """

    def select(self, message: str, choices: Sequence[str], default: str | None = None) -> str:
        import questionary

        # Typing filters the choices: a long menu is reached by a few letters.
        return questionary.select(self.fitted(message) + "\n ", choices=list(choices), default=default, qmark="🎤",
                                  use_search_filter=True, use_jk_keys=False).unsafe_ask()

    @staticmethod
    def fitted(message: str) -> str:
        """The question wrapped at the terminal's width, after the question mark's 3 columns."""
        return terminal.fitted_lines("   " + message, terminal.width())[3:]

    def confirm(self, message: str, default: bool = False) -> bool:
        import questionary

        return questionary.confirm(self.fitted(message) + "\n ", default=default, qmark="🎤").unsafe_ask()

    def say(self, line: str) -> None:
        print("\n".join(terminal.wrap(line, terminal.width())), flush=True)

    def text(self, message: str, default: str = "", validate: Callable[[str], str | None] | None = None,
             complete: Sequence[str] = ()) -> str:
        import questionary

        def check(answer: str):
            error = validate(answer) if validate else None
            return error or True  # shown whole, wrapped, under the prompt (rna/terminal.py)

        # Checked on Enter: a half-typed answer is not an error yet.
        if complete:
            return questionary.autocomplete(self.fitted(message) + "\n ", choices=list(complete), default=default,
                                            validate=check, match_middle=True, qmark="🎤",
                                            validate_while_typing=False).unsafe_ask()
        return questionary.text(self.fitted(message) + "\n ", default=default, validate=check, qmark="🎤",
                                validate_while_typing=False).unsafe_ask()


class Dialog:
    """The nodes, changed one prompt at a time, starting from `nodes`."""

    def __init__(self, nodes: object, rules: Rules, asker: Asker | None = None,
                 found: Sequence[str] = (), own: Mapping[str, Sequence[str]] | None = None,
                 existing: bool = False) -> None:
        """`existing`: the nodes are the package's (an update): a node renamed says its old name,
        and removing one says that its files go."""
        self.nodes = [dict(node) if isinstance(node, Mapping) else {"name": str(node)}
                      for node in (copy.deepcopy(nodes) if isinstance(nodes, list) else [])]
        self.existing = {node["name"] for node in self.nodes} if existing else set()
        self.rules = rules
        for node in self.nodes:  # written out, as the answers file records it
            node.setdefault("language", distros.default_language(rules.build_type))
            for kind in KINDS:
                if kind.interface and isinstance(node.get(kind.key), list):
                    node[kind.key] = [normalised_entry(entry, kind.interface, rules.types.ros)
                                      for entry in node[kind.key]]
        self.ask = asker or Asker()
        self.found = list(found)
        self.own = dict(own or {})
        self.removed: list[tuple[int, dict]] = []  # (where it was, the node): undone last first

    # --- the package's nodes

    def run(self) -> list[dict]:
        while True:
            message = f"Nodes ({len(self.nodes)}): what next?"
            choices = [ADD_NODE]
            width = choice_width()
            for node in self.nodes:
                choices.append(fitting([f"Edit {form}" for form in node_forms(node)], width))
            choices.extend(fitting([f"Remove {node['name']}"], width) for node in self.nodes)
            undo = fitting([f"Undo removing {self.removed[-1][1]['name']}", "Undo the removal"], width) \
                if self.removed else None
            choices.extend([undo] if undo else [])
            choices.append(DONE)
            count = len(self.nodes)
            picked = self.ask.select(message, choices, default=DONE if self.nodes else ADD_NODE)
            if picked not in choices:  # a filter that matched nothing
                continue
            if picked == DONE:
                if self.nodes:
                    return self.nodes
                self.ask.say("Add a node first: a package needs one.")
                continue
            if picked == ADD_NODE:
                self.add_node()
                continue
            if picked == undo:
                index, node = self.removed.pop()
                self.nodes.insert(min(index, len(self.nodes)), node)
                continue
            index = choices.index(picked) - 1
            if index < count:
                self.edit_node(self.nodes[index])
            else:
                self.remove_node(self.nodes[index - count])

    def remove_node(self, node: dict) -> None:
        """Asked first: on an update, its files go too (git keeps what was committed)."""
        name = node["name"]
        was = node.get(RENAMED_FROM) or (name if name in self.existing else None)
        question = (f"Remove {name}? The update deletes its files, your edits too (git keeps them)" if was
                    else f"Remove {name}?")
        if self.ask.confirm(question, default=False):
            self.removed.append((self.nodes.index(node), node))
            self.nodes.remove(node)

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

    def settings(self, node: Mapping) -> list[Setting]:
        """The node's own keys it may change here, in this ROS generation and with its other keys."""
        return [setting for setting in NODE_SETTINGS
                if self.rules.types.ros in setting.ros and setting.when(node)]

    def flags(self, node: Mapping) -> list[str]:
        """The yes/no keys a node may change here (the settings without choices)."""
        return [setting.key for setting in self.settings(node) if not setting.choices]

    def edit_node(self, node: dict) -> None:
        while True:
            width = choice_width()
            choices, actions = [], []
            for kind in KINDS:
                choices.append(f"Add {article(kind.label)}")
                actions.append(("add", kind))
            for kind in KINDS:
                for index, entry in enumerate(node.get(kind.key) or []):
                    choices.append(fitting([f"Edit {form}" for form in entry_forms(kind, entry)], width))
                    actions.append(("entry", (kind, index)))
            choices.append(fitting([f"Rename {node['name']}", "Rename"], width))
            actions.append(("rename", None))
            if len(self.rules.languages) > 1:
                choices.append(f"Language: {distros.LANGUAGE_NAMES.get(str(node.get('language')), '?')}")
                actions.append(("language", None))
            for setting in self.settings(node):
                value = node.get(setting.key)
                shown = (value or NO_VALUE) if setting.choices else ("yes" if value else "no")
                choices.append(fitting([f"{setting.label}: {shown}"], width))
                actions.append(("setting", setting))
            choices.append(fitting(self.running_forms(node), width))
            actions.append(("running", None))
            choices.append(fitting([f"Done with {node['name']}", "Done with this node"], width))
            actions.append(("done", None))
            self.ask.say(f"Node {node_line(node)}")
            picked = self.ask.select("What next?", choices, default=choices[-1])
            if picked not in choices:
                continue
            action, what = actions[choices.index(picked)]
            if action == "done":
                return
            if action == "add":
                self.add_entry(node, what)
            elif action == "entry":
                self.edit_entry(node, *what)
            elif action == "rename":
                self._renamed(node, self._rename(node))
            elif action == "language":
                self._change(node, "language", self._language(str(node.get("language"))))
            elif action == "setting":
                self._setting(node, what)
            elif action == "running":
                self.edit_running(node)

    def running_forms(self, node: Mapping) -> list[str]:
        """The node menu's one entry for how the node runs: `Executor, callback groups, remappings: ...`."""
        executor = node.get("executor") or DEFAULT_EXECUTOR
        groups, remaps = len(node.get("callback_groups") or []), len(node.get("remappings") or {})
        said = [executor + (f" ({node['threads']} threads)" if node.get("threads") else "")]
        if groups:
            said.append(f"{groups} group{'s' if groups > 1 else ''}")
        if remaps:
            said.append(f"{remaps} remap{'s' if remaps > 1 else ''}")
        ros2 = self.rules.types.ros == 2
        head, short = (("Executor, callback groups, remappings", "Executor, groups, remaps") if ros2
                       else ("Executor, remappings", "Executor, remaps"))
        return [f"{head}: {', '.join(said)}", f"{short}: {', '.join(said)}", f"{head}: {executor}",
                f"{short}: {executor}", head]

    def edit_running(self, node: dict) -> None:
        """Its own menu: the executor, callback groups (ROS 2) and the launch file's remappings."""
        while True:
            width = choice_width()
            entries = self.threading_entries(node, width)
            choices = [label for label, _ in entries] + [BACK_TO_NODE]
            picked = self.ask.select("Executor, callback groups and remappings", choices, default=BACK_TO_NODE)
            if picked not in choices[:-1]:
                return
            action, what = entries[choices.index(picked)][1]
            if action == "executor":
                self.change_executor(node)
            elif action == "add_group":
                self.add_callback_group(node)
            elif action == "add_remapping":
                self.add_remapping(node)
            else:
                self._remove(node, "callback_groups" if action == "remove_group" else "remappings", what)

    def threading_entries(self, node: Mapping, width: int) -> list[tuple[str, tuple]]:
        """Menu entries for the executor, callback groups (ROS 2) and remappings: (label, action)."""
        executor = node.get("executor") or DEFAULT_EXECUTOR
        threads = f", {node['threads']} threads" if node.get("threads") else ""
        entries = [(f"Executor: {executor}{threads}", ("executor", None))]
        if self.rules.types.ros == 2:
            entries.append(("Add a callback group", ("add_group", None)))
            entries += [(fitting([f"Remove callback group {group_text(group)}", "Remove callback group"
                                  + (f" {group.get('name')}" if isinstance(group, Mapping) else "")], width),
                         ("remove_group", index)) for index, group in enumerate(node.get("callback_groups") or [])]
        entries.append(("Add a remapping (launch file)", ("add_remapping", None)))
        entries += [(fitting([f"Remove remapping {source} -> {target}", f"Remove remapping {source}"], width),
                     ("remove_remapping", source))
                    for source, target in (node.get("remappings") or {}).items()]
        return entries

    def change_executor(self, node: dict) -> None:
        """Pick the executor among those the node's language and distro have; a multi-threaded one's threads."""
        offered = [executor for executor in EXECUTORS
                   if not self.rules.node_error({**node, "executor": executor, "threads": None})]
        executor = self.ask.select("Executor the node spins on", offered,
                                   default=node.get("executor") or DEFAULT_EXECUTOR)
        if executor not in offered:
            return
        threads = None
        if executor == "multi_threaded":
            answer = self.ask.text("Threads (empty: one per core)", default=str(node.get("threads") or ""),
                                   validate=optional(lambda text: None if text.isdigit() and self.rules.node_error(
                                       {**node, "executor": executor, "threads": int(text)}) is None
                                       else "a whole number of threads, 1 or more")).strip()
            threads = int(answer) if answer else None
        changed = {key: value for key, value in node.items() if key not in ("executor", "threads")}
        if executor != DEFAULT_EXECUTOR:
            changed["executor"] = executor
        if threads:
            changed["threads"] = threads
        self._replace(node, changed)

    def add_callback_group(self, node: dict) -> None:
        """A name, a type, then the members: the node's endpoints with callbacks, comma-separated."""
        taken = {group.get("name") for group in node.get("callback_groups") or [] if isinstance(group, Mapping)}
        name = self.ask.text(f"Callback group name {BACK}", validate=optional(
            lambda answer: names.identifier_error(answer, "callback group")
            or (f"there is a callback group '{answer}' already" if answer in taken else None))).strip()
        if not name:
            return
        kind = self.ask.select("Its callbacks run", ["mutually_exclusive (one at a time)",
                                                     "reentrant (side by side)"]).split(" ", 1)[0]
        if kind not in CALLBACK_GROUP_TYPES:
            return

        def with_group(answer: str) -> dict:
            members = [part.strip() for part in answer.split(",") if part.strip()]
            group = {"name": name, "members": members}
            if kind != "mutually_exclusive":
                group["type"] = kind
            return {**node, "callback_groups": [*(node.get("callback_groups") or []), group]}

        answer = self.ask.text("Its members, comma-separated (e.g. " + ", ".join(callback_names(node)[:2] or ["reset"])
                               + ")", complete=callback_names(node),
                               validate=lambda text: self.rules.node_error(with_group(text)))
        node["callback_groups"] = with_group(answer)["callback_groups"]

    def add_remapping(self, node: dict) -> None:
        """A name the node uses, then the name the launch file gives it instead."""
        source = self.ask.text(f"Name to remap {BACK}", complete=[*callback_names(node), *(
            entry_text("publishers", entry).split(":", 1)[0] for entry in node.get("publishers") or [])],
            validate=optional(lambda answer: names.topic_name_error(answer, "remapped"))).strip()
        if not source:
            return
        target = self.ask.text(f"Remap {source} to", validate=lambda answer: self.rules.node_error(
            {**node, "remappings": {**(node.get("remappings") or {}), source: answer.strip()}})).strip()
        node["remappings"] = {**(node.get("remappings") or {}), source: target}

    @staticmethod
    def _remove(node: dict, key: str, which: object) -> None:
        if key == "callback_groups":
            del node[key][which]
        else:
            node[key] = {source: target for source, target in node[key].items() if source != which}
        if not node[key]:
            del node[key]

    def _setting(self, node: dict, setting: Setting) -> None:
        if not setting.choices:
            self._change(node, setting.key, not node.get(setting.key))
            return
        picked = self.ask.select(setting.label, [*setting.choices, NO_VALUE],
                                 default=node.get(setting.key) or NO_VALUE)
        self._change(node, setting.key, None if picked == NO_VALUE else picked)

    def _change(self, node: dict, key: str, value: object) -> None:
        """Set one key, unless the node would then break a rule: then say which, and keep it."""
        changed = {**node, key: value}
        if key == "lifecycle" and value is False:
            changed.pop("autostart", None)  # only a lifecycle node is started that way
        self._replace(node, {name: item for name, item in changed.items() if item is not False and item is not None})

    def _replace(self, node: dict, changed: dict) -> None:
        """The node becomes `changed`, unless that breaks a rule: then say which, and keep it."""
        error = self.rules.node_error(changed)
        if error:
            self.ask.say(error)
            return
        node.clear()
        node.update(changed)

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

    # --- one endpoint or parameter

    def _with_entry(self, node: Mapping, kind: Kind, index: int, entry: object) -> dict:
        """The node with its entry `index` of `kind` replaced (or added, at the end)."""
        entries = list(node.get(kind.key) or [])
        entries[index:index + 1] = [entry]
        return {**node, kind.key: entries}

    def _entry_error(self, node: Mapping, kind: Kind, index: int, mapping: Mapping) -> str | None:
        return self.rules.node_error(self._with_entry(node, kind, index, entry_value(kind.key, mapping)))

    def _graph_type(self, kind: Kind, name: str, node: str) -> str | None:
        """The type the package's nodes already use for a topic, service or action of this name
        (of node `node`: its {node} is its own name)."""
        met = names.graph_name(name, node)
        if met is None or not kind.interface:
            return None
        for other in self.nodes:
            for other_kind in KINDS:
                if other_kind.interface != kind.interface:
                    continue
                for entry in other.get(other_kind.key) or []:
                    mapping = entry_mapping(other_kind.key, entry)
                    if names.graph_name(str(mapping.get("topic", mapping.get("name", ""))),
                                        str(other.get("name"))) == met:
                        return str(mapping.get("type"))
        return None

    def _ask_field(self, node: dict, kind: Kind, index: int, mapping: dict, field: Field,
                   first: bool = False) -> bool:
        """Ask one key of the entry, checked as the node with it; False when a first name is left empty."""
        current = mapping.get(field.key)
        if field.form == "bool":
            mapping[field.key] = not current
            return True
        if field.form == "choice":
            choices = [*field.choices, *([NO_VALUE] if field.optional else [])]
            default = str(current) if current is not None else ("double" if field.key == "type" else choices[0])
            picked = self.ask.select(field.prompt, choices, default=default if default in choices else None)
            mapping[field.key] = None if picked == NO_VALUE else picked
            return True

        def candidate(answer: str) -> dict:
            value = answer.strip()
            if field.form in ("yaml", "list") and value:
                try:
                    value = yaml.safe_load(value)
                    if field.form == "list" and not isinstance(value, list):
                        value = yaml.safe_load(f"[{answer.strip()}]")
                except yaml.YAMLError:
                    pass  # kept as text: the node's check says what is wrong with it
            elif field.form == "type" and kind.interface and value:
                value = normalised_type(value, kind.interface, self.rules.types.ros)
            return {**mapping, field.key: value if value != "" else None}

        def check(answer: str) -> str | None:
            if first:  # the entry's name alone: the rest is not given yet
                what = {"msg": "topic", "srv": "service", "action": "action"}.get(kind.interface or "")
                if what:
                    return names.topic_name_error(answer.strip(), what, self.rules.types.ros)
                if kind.key == "timers":
                    return names.identifier_error(answer.strip(), "timer")
                return names.parameter_name_error(answer.strip(), self.rules.types.ros)
            if not answer.strip() and field.optional:
                return self._entry_error(node, kind, index, candidate(""))
            return self._entry_error(node, kind, index, candidate(answer))

        default = "" if current is None else _yaml_text(current) if field.form in ("yaml", "list") else str(current)
        complete: list[str] = []
        if field.form == "type" and kind.interface:
            used = self._graph_type(kind, str(mapping.get("topic", mapping.get("name", ""))), str(node.get("name")))
            default = default or used or ""
            complete = type_choices(kind.interface, self.rules.types.ros, self.rules.types.distro, self.found,
                                    self.own.get(kind.interface, ()), first=[used] if used else [])
        prompt = f"{field.prompt} {BACK}" if first else field.prompt
        answer = self.ask.text(prompt, default=default, validate=optional(check) if first else check,
                               complete=complete)
        if first and not answer.strip():
            return False
        mapping.update(candidate(answer))
        return True

    def add_entry(self, node: dict, kind: Kind) -> None:
        """The keys asked of a new entry, one prompt each: its name first (empty: back)."""
        fields = [field for field in ENTRY_FIELDS[kind.key] if field.asked]
        index = len(node.get(kind.key) or [])
        mapping: dict = {}
        if kind.key == "timers":
            taken = {timer_name(entry) for entry in node.get("timers") or []}
            mapping["name"] = next(name for name in ("timer", *(f"timer{n}" for n in range(2, 100)))
                                   if name not in taken)
        for position, field in enumerate(fields):
            if not self._ask_field(node, kind, index, mapping, field, first=position == 0):
                return
        node[kind.key] = [*(node.get(kind.key) or []), entry_value(kind.key, mapping)]

    def edit_entry(self, node: dict, kind: Kind, index: int) -> None:
        """An entry's menu: each of its keys with its value, changed in place; or remove it."""
        while True:
            entries = node.get(kind.key) or []
            if index >= len(entries):
                return
            mapping = entry_mapping(kind.key, entries[index])
            width = choice_width()
            choices, fields = [], []
            for field in ENTRY_FIELDS[kind.key]:
                value = mapping.get(field.key)
                if field.form == "bool":
                    shown = "yes" if value else "no"
                else:
                    shown = NO_VALUE if value in (None, "") else _yaml_text(value)
                choices.append(fitting([f"{field.label}: {shown}", f"{field.label}"], width))
                fields.append(field)
            choices.extend([f"Remove this {kind.label}", "Done"])
            picked = self.ask.select(fitting([f"The {kind.label} {entry_text(kind.key, entries[index])}:",
                                              f"The {kind.label}:"], terminal.width() - 3), choices,
                                     default="Done")
            if picked == "Done" or picked not in choices:
                return
            if picked == f"Remove this {kind.label}":
                del node[kind.key][index]
                if not node[kind.key]:
                    del node[kind.key]
                return
            field = fields[choices.index(picked)]
            changed = dict(mapping)
            self._ask_field(node, kind, index, changed, field)
            error = self._entry_error(node, kind, index, changed)
            if error:  # a yes/no or a choice breaks a rule: said, and the entry stays
                self.ask.say(error)
                continue
            node[kind.key][index] = entry_value(kind.key, changed)
