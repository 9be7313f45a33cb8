"""The `nodes` answer: each node, in the long form (mappings) or the short forms typed at a prompt.

`cmd_vel:geometry_msgs/msg/Twist`, `rate:double=10.0` or `0.5` read the same as their
mappings; every rule broken raises ValueError with a sentence that starts with the node.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

import yaml

from .. import catalogue, distros, names, python_names
from .. import qos as qos_rules
from ..interfaces import InterfaceType, normalised_type, parse_interface
from ..model import (AUTOSTART_PARAMETER, BASE_MEMBERS, CALLBACK_GROUP_TYPES, DEFAULT_EXECUTOR, DIAGNOSTICS_TASK,
                     EXECUTORS, Action, CallbackGroup, Node, Service, Timer, Topic)
from ..qos import Qos
from ..parameters import INT_RANGE, Parameter, ParameterType, coerce_default, infer_type, on_step, parse_type
from ..shapes import as_list, check_keys, load_yaml



@dataclass(frozen=True)
class Types:
    """How endpoint types are read: the ROS generation, and this package's own interfaces."""

    ros: int = 2
    own: Mapping[tuple[str, str], InterfaceType] = field(default_factory=dict)
    distro: str | None = None  # checks the standard packages' types against its catalogue
    default_qos: object = None  # of an endpoint that names none (the lab's)

    def parse(self, text: object, kind: str) -> InterfaceType:
        """`pkg/kind/Name`, `pkg/Name`, or the bare `Name` of an interface defined here."""
        if isinstance(text, str) and (kind, text.strip()) in self.own:
            return self.own[(kind, text.strip())]
        interface = parse_interface(normalised_type(text, kind, self.ros), kind, self.ros)
        error = self.distro and catalogue.unknown_type_error(interface.package, kind, interface.name, self.distro)
        if error:
            raise ValueError(error)
        return interface


# The keys of a node whose entries name a type, and the kind of that type.
TYPED_KEYS = {"publishers": "msg", "subscribers": "msg", "service_servers": "srv", "service_clients": "srv",
              "action_servers": "action", "action_clients": "action"}


def normalised_entry(entry: object, kind: str, ros: int) -> object:
    """An endpoint (short form or mapping) with its type spelled as its ROS generation does
    (interfaces.normalised_type); everything else as given."""
    if isinstance(entry, str) and ":" in entry:
        name, _, rest = entry.partition(":")
        type_text, colon, qos = rest.partition(":") if kind == "msg" else (rest, "", "")
        written = normalised_type(type_text.strip(), kind, ros)
        return entry if written == type_text.strip() else f"{name}:{written}{colon}{qos}"
    if isinstance(entry, Mapping) and isinstance(entry.get("type"), str):
        written = normalised_type(entry["type"].strip(), kind, ros)
        return entry if written == entry["type"].strip() else {**entry, "type": written}
    return entry


def normalised_nodes(nodes: object, ros: int) -> object:
    """The `nodes` answer with every endpoint's type spelled for `ros` (a list of nodes; else as given)."""
    if not isinstance(nodes, list):
        return nodes
    return [{**node, **{key: [normalised_entry(entry, kind, ros) for entry in node[key]]
                        for key, kind in TYPED_KEYS.items() if isinstance(node.get(key), list)}}
            if isinstance(node, Mapping) else node for node in nodes]


def _split_short(text: str, fields: int) -> list[str]:
    """'topic:type:qos' -> parts; the type itself never contains ':'."""
    return [part.strip() for part in text.split(":", fields - 1)]


def _parse_qos(value: object, what: str, default: object = None) -> Qos:
    if value is None or value == "":
        return _parse_qos(default, what) if default not in (None, "") else qos_rules.PRESETS["default"]
    try:
        return qos_rules.parse(value)
    except ValueError as error:
        raise ValueError(f"{what}: {error}") from None


def _parse_id(given: object, ros_name: str, what: str) -> str:
    if given is not None:
        error = names.identifier_error(given, f"{what}: id")
        if error:
            raise ValueError(error)
        return str(given)
    derived = names.identifier_from_name(ros_name)
    if not derived[:1].isalpha():  # '/_1/x' gives '1_x', and members like 1_x_publisher do not compile
        raise ValueError(f"{what}: give the endpoint an `id`: the code name derived from it, {names.quoted(derived)}, "
                         "does not start with a letter")
    if names.too_long(derived, names.IDENTIFIER_MAX):
        raise ValueError(f"{what}: give the endpoint a shorter `id`: the code name derived from it, "
                         f"{names.quoted(derived)}, is {len(derived)} characters long (at most {names.IDENTIFIER_MAX})")
    return derived


def _parse_topic(item: object, role: str, types: Types) -> Topic:
    if isinstance(item, str):
        parts = _split_short(item, 3)
        if len(parts) < 2:
            raise ValueError(f"{role} '{item}': write it as topic:type, e.g. chatter:std_msgs/msg/String")
        item = dict(zip(("topic", "type", "qos"), parts, strict=False))
    if not isinstance(item, Mapping):
        raise ValueError(f"write a {role} as 'topic:type' or a mapping with topic and type")
    check_keys(item, ("topic", "type", "qos", "id"), role)
    topic = item.get("topic")
    what = f"{role} '{topic}'"
    error = names.topic_name_error(topic, "topic", types.ros)
    if error:
        raise ValueError(f"{role}: {error}")
    interface = types.parse(item.get("type"), "msg")
    qos = _parse_qos(item.get("qos"), what, types.default_qos)
    return Topic(role, topic, interface, qos, _parse_id(item.get("id"), topic, what))


def _parse_service_or_action(item: object, cls: type, kind: str, role: str, types: Types):
    what = f"{'service' if kind == 'srv' else 'action'} {role}"
    example = "reset:std_srvs/srv/Trigger" if kind == "srv" else "fibonacci:test_msgs/action/Fibonacci"
    if isinstance(item, str):
        parts = _split_short(item, 2)
        if len(parts) < 2:
            raise ValueError(f"{what} '{item}': write it as name:type, e.g. {example}")
        item = dict(zip(("name", "type"), parts, strict=True))
    if not isinstance(item, Mapping):
        raise ValueError(f"write a {what} as 'name:type' or a mapping with name and type")
    check_keys(item, ("name", "type", "id"), what)
    name = item.get("name")
    error = names.topic_name_error(name, "service" if kind == "srv" else "action", types.ros)
    if error:
        raise ValueError(f"{what}: {error}")
    interface = types.parse(item.get("type"), kind)
    return cls(role, name, interface, _parse_id(item.get("id"), name, f"{what} '{name}'"))


def _parse_timer(item: object) -> Timer:
    if isinstance(item, (int, float)) and not isinstance(item, bool):
        item = {"period": item}
    elif isinstance(item, str):
        parts = _split_short(item, 2)
        item = {"period": parts[0]} if len(parts) == 1 else {"name": parts[0], "period": parts[1]}
    if not isinstance(item, Mapping):
        raise ValueError("write a timer as a period in seconds, 'name:period' or a mapping")
    check_keys(item, ("name", "period"), "timer")
    name = item.get("name", "timer")
    error = names.identifier_error(name, "timer")
    if error:
        raise ValueError(error)
    period = item.get("period")
    try:
        period = float(period)
    except (TypeError, ValueError):
        raise ValueError(f"timer '{name}': give the period in seconds, e.g. 0.1: '{period}' is not a number") from None
    if not 0 < period <= 86400:
        raise ValueError(f"timer '{name}': give a period of more than 0 s and at most a day, not {period:g} s")
    if period < 1e-9:  # the generated code counts nanoseconds: a shorter period is a timer that never waits
        raise ValueError(f"timer '{name}': give a period of at least a nanosecond, what ROS timers count in: "
                         f"{period} s is shorter")
    return Timer(name, period)


_SHORT_PARAMETER = re.compile(r"(?P<name>[^:=\s]+)\s*(?::\s*(?P<type>[^=\s]+))?\s*(?:=(?P<default>.*))?", re.S)


def _parse_parameter(item: object, ros: int) -> Parameter:
    if isinstance(item, str):
        match = _SHORT_PARAMETER.fullmatch(item.strip())
        if not match:
            raise ValueError(f"parameter '{item}': write it as name:type=default, e.g. rate:double=10.0")
        item = {"name": match["name"]}
        if match["type"]:
            item["type"] = match["type"]
        if match["default"] is not None:
            try:
                item["default"] = yaml.safe_load(match["default"])
            except yaml.YAMLError:
                raise ValueError(f"parameter '{match['name']}': write the default as YAML (e.g. 1.5, true, [1, 2]): "
                                 f"'{match['default']}' does not read as YAML") from None
    if not isinstance(item, Mapping):
        raise ValueError("write a parameter as 'name:type=default' or a mapping with name, type and default")
    check_keys(item, ("name", "type", "default", "description", "range", "read_only"), "parameter")
    name = item.get("name")
    error = names.parameter_name_error(name, ros)
    if error:
        raise ValueError(error)
    what = f"parameter '{name}'"
    try:
        if item.get("type") is not None:
            ptype = parse_type(item["type"])
        elif item.get("default") is not None:
            ptype = infer_type(item["default"])
        else:
            raise ValueError("give a type or a default")
        default = coerce_default(item.get("default"), ptype, ros)
    except ValueError as error:
        raise ValueError(f"{what}: {error}") from None
    if ptype.is_array and not default:
        raise ValueError(f"{what}: give it a default that is not empty: array parameters need one")
    description = item.get("description") or ""
    if description and names.one_line_error(description):
        raise ValueError(f"{what}: description: {names.one_line_error(description)}")
    read_only = item.get("read_only", False)
    if not isinstance(read_only, bool):
        raise ValueError(f"{what}: set read_only to true or false")
    value_range = _parse_range(item.get("range"), ptype, default, what, ros)
    return Parameter(name, ptype, default, description.strip(), value_range, read_only)


def _parse_range(value: object, ptype: ParameterType, default: object, what: str, ros: int):
    if value is None:
        return None
    if not ptype.is_numeric:
        raise ValueError(f"{what}: only int and double parameters take a range")
    if isinstance(value, Mapping):
        check_keys(value, ("min", "max", "step"), f"{what} range")
        value = [value.get("min"), value.get("max"), value.get("step", 0)]
    if not isinstance(value, list) or len(value) not in (2, 3):
        raise ValueError(f"{what}: range must be [min, max] or [min, max, step]")
    low, high, *rest = value
    step = rest[0] if rest else 0
    for bound in (low, high, step):
        if isinstance(bound, bool) or not isinstance(bound, (int, float)):
            raise ValueError(f"{what}: range bounds must be numbers")
        if ptype.scalar == "int" and not isinstance(bound, int):
            raise ValueError(f"{what}: an int parameter needs whole-number range bounds")
        if ptype.scalar == "int" and not INT_RANGE[0] <= bound <= INT_RANGE[1]:
            raise ValueError(f"{what}: range bound {bound} does not fit a 64-bit integer")
        if ptype.scalar == "double" and not math.isfinite(bound):
            raise ValueError(f"{what}: range bounds must be finite")
    if low > high:
        raise ValueError(f"{what}: range minimum {low} is above its maximum {high}")
    if step < 0:
        raise ValueError(f"{what}: range step must not be negative")
    if not low <= default <= high:
        raise ValueError(f"{what}: default {default} is outside the range [{low}, {high}]")
    if ros == 2 and not on_step(default, low, high, step, ptype.scalar):  # ROS 1 ranges are comments
        raise ValueError(f"{what}: default {default} is not the minimum {low} plus a whole number of steps of "
                         f"{step}, which ROS 2 refuses at start-up")
    cast = int if ptype.scalar == "int" else float
    return (cast(low), cast(high), cast(step))


def _check_unique(items: Iterable[tuple[str, str]]) -> None:
    """items: (name, label) pairs; a name used twice is an error naming both uses."""
    seen: dict[str, str] = {}
    for name, label in items:
        if name in seen:
            raise ValueError(f"give each a name of its own: {seen[name]} and {label} both use the name '{name}'")
        seen[name] = label


_NODE_KEYS = ("name", "language", "description", "lifecycle", "autostart", "component", "diagnostics", "publishers",
              "subscribers", "service_servers", "service_clients", "action_servers", "action_clients", "timers",
              "parameters", "executor", "threads", "callback_groups", "remappings", "renamed_from")


def _parse_executor(item: Mapping, ros: int, language: str, distro: str | None) -> tuple[str, int]:
    """(executor, threads): what the node spins on, and a multi-threaded one's thread count (0: one per core)."""
    executor = item.get("executor")
    executor = DEFAULT_EXECUTOR if executor in (None, "") else executor
    if executor not in EXECUTORS:
        raise ValueError(f"executor '{executor}' is not one of {', '.join(EXECUTORS)}")
    error = distros.executor_error(executor, ros, language, distro)
    if error:
        raise ValueError(error)
    threads = item.get("threads")
    if threads is None:
        return executor, 0
    if executor != "multi_threaded":
        raise ValueError("threads is for a multi_threaded executor: set executor: multi_threaded as well")
    if isinstance(threads, bool) or not isinstance(threads, int) or not 1 <= threads <= distros.THREADS_MAX:
        raise ValueError(f"threads must be a whole number from 1 to {distros.THREADS_MAX} (leave it out for one "
                         "per core)")
    return executor, threads


def _endpoint_names(endpoint) -> set[str]:
    """What a callback group's members may call an endpoint: its name as given, or its code name."""
    if isinstance(endpoint, Topic):
        return {endpoint.topic, endpoint.id}
    return {getattr(endpoint, "name", endpoint.id), endpoint.id}


def _parse_callback_groups(value: object, node: Node) -> tuple[CallbackGroup, ...]:
    groups, grouped = [], {}
    for item in as_list(value, "callback_groups"):
        if not isinstance(item, Mapping):
            raise ValueError("a callback group must be a mapping with a name and its members")
        check_keys(item, ("name", "type", "members"), "callback group")
        name = item.get("name")
        error = names.identifier_error(name, "callback group")
        if error:
            raise ValueError(error)
        kind = item.get("type") or "mutually_exclusive"
        if kind not in CALLBACK_GROUP_TYPES:
            raise ValueError(f"callback group '{name}': type '{kind}' is not one of {', '.join(CALLBACK_GROUP_TYPES)}")
        wanted = item.get("members")
        wanted = [part.strip() for part in wanted.split(",")] if isinstance(wanted, str) else wanted
        if not isinstance(wanted, list) or not wanted:
            raise ValueError(f"callback group '{name}': list its members, the names of endpoints or timers "
                             "of the node (e.g. members: [reset, control_loop])")
        members = []
        for member in wanted:
            found = [e for e in node.callback_endpoints if str(member) in _endpoint_names(e)]
            if not found:
                publisher = any(str(member) in _endpoint_names(t) for t in node.publishers)
                raise ValueError(f"callback group '{name}': {names.quoted(member)} "
                                 + ("is a publisher, which has no callback to run" if publisher else
                                    "is none of the node's subscribers, services, actions or timers"))
            if len(found) > 1:
                raise ValueError(f"callback group '{name}': {names.quoted(member)} names "
                                 f"{' and '.join(e.label for e in found)}: give one an `id` to tell them apart")
            (endpoint,) = found
            if endpoint in grouped:
                raise ValueError(f"the {endpoint.label} is in callback groups '{grouped[endpoint]}' and '{name}': a "
                                 "callback is in one group")
            grouped[endpoint] = name
            members.append(endpoint)
        groups.append(CallbackGroup(name, kind, tuple(members)))
    _check_unique((group.name, group.label) for group in groups)
    return tuple(groups)


def _parse_remappings(value: object) -> tuple[tuple[str, str], ...]:
    """`{from: to}`: a name the node uses, and the one the launch file gives it instead.

    Sorted: the answers file writes a mapping's keys in order, and no two rules name one
    name, so which comes first changes nothing.
    """
    if value in (None, {}):
        return ()
    if not isinstance(value, Mapping):
        raise ValueError("remappings must be a mapping of names, from: to (e.g. {cmd_vel: /robot/cmd_vel})")
    pairs, seen = [], {}
    for source, target in value.items():
        for name in (source, target):
            error = names.topic_name_error(name, "remapped")
            if error:
                raise ValueError(f"remappings: {error}")
        resolved = names.fully_qualified(source, "node")
        if resolved == names.fully_qualified(target, "node"):
            raise ValueError(f"remappings: '{source}' is remapped to itself")
        if resolved in seen:
            raise ValueError(f"remappings: '{seen[resolved]}' and '{source}' are one name to the node: keep one")
        seen[resolved] = source
        pairs.append((source, target))
    return tuple(sorted(pairs))


def parse_node(item: object, *, package: str, build_type: str, types: Types) -> Node:
    """One entry of `nodes`; raises ValueError with a message that starts with the node."""
    if isinstance(item, str):
        item = {"name": item}
    if not isinstance(item, Mapping):
        raise ValueError("write each node as a mapping with at least a name")
    name = item.get("name")
    error = names.node_name_error(name)
    if error:
        raise ValueError(error)
    label = f"node '{name}'"
    ros = types.ros
    try:
        check_keys(item, _NODE_KEYS, "node")
        if "renamed_from" in item and names.node_name_error(item["renamed_from"]):
            raise ValueError(f"renamed_from: {names.node_name_error(item['renamed_from'])}")
        language = distros.LANGUAGES.get(str(item.get("language") or distros.default_language(build_type)).lower())
        if language is None:
            raise ValueError(f"use cpp or python: language '{item.get('language')}' is neither")
        error = distros.language_error(build_type, language)
        if error:
            raise ValueError(error)
        flags = {}
        for flag in ("lifecycle", "autostart", "component", "diagnostics"):
            flags[flag] = item.get(flag, False)
            if not isinstance(flags[flag], bool):
                raise ValueError(f"set {flag} to true or false")
        if ros == 1 and (flags["lifecycle"] or flags["component"]):
            raise ValueError("leave out lifecycle and component: they are ROS 2 features")
        if flags["component"] and language != "cpp":
            raise ValueError("make it a C++ node to make it a component: components are C++ nodes "
                             "(rclcpp_components)")
        if flags["autostart"] and not flags["lifecycle"]:
            raise ValueError("autostart is for lifecycle nodes: set lifecycle: true as well")
        description = item.get("description") or ""
        if description and names.one_line_error(description):
            raise ValueError(f"description: {names.one_line_error(description)}")
        node = Node(
            name=name,
            language=language,
            package=package,
            ros=ros,
            description=description.strip(),
            lifecycle=flags["lifecycle"],
            autostart=flags["autostart"],
            component=flags["component"],
            diagnostics=flags["diagnostics"],
            publishers=tuple(_parse_topic(x, "publisher", types)
                             for x in as_list(item.get("publishers"), "publishers")),
            subscribers=tuple(_parse_topic(x, "subscriber", types)
                              for x in as_list(item.get("subscribers"), "subscribers")),
            service_servers=tuple(_parse_service_or_action(x, Service, "srv", "server", types)
                                  for x in as_list(item.get("service_servers"), "service_servers")),
            service_clients=tuple(_parse_service_or_action(x, Service, "srv", "client", types)
                                  for x in as_list(item.get("service_clients"), "service_clients")),
            action_servers=tuple(_parse_service_or_action(x, Action, "action", "server", types)
                                 for x in as_list(item.get("action_servers"), "action_servers")),
            action_clients=tuple(_parse_service_or_action(x, Action, "action", "client", types)
                                 for x in as_list(item.get("action_clients"), "action_clients")),
            timers=tuple(_parse_timer(x) for x in as_list(item.get("timers"), "timers")),
            parameters=tuple(_parse_parameter(x, ros) for x in as_list(item.get("parameters"), "parameters")),
        )
        executor, threads = _parse_executor(item, ros, language, types.distro)
        if item.get("callback_groups") and ros == 1:
            raise ValueError("callback groups are a ROS 2 feature (roscpp's MultiThreadedSpinner runs each "
                             "subscription's callbacks one at a time, different ones side by side)")
        node = dataclasses.replace(node, executor=executor, threads=threads,
                                   callback_groups=_parse_callback_groups(item.get("callback_groups"), node),
                                   remappings=_parse_remappings(item.get("remappings")))
        _check_node_names(node)
        _check_script_name(node)
        _check_cpp_names(node)
    except ValueError as error:
        raise ValueError(f"{label}: {error}") from None
    return node


def _check_script_name(node: Node) -> None:
    """A ROS 1 Python node runs as scripts/<node>.py, whose folder Python searches first."""
    if node.ros != 1 or not node.is_python:
        return
    imported = {node.package, *node.dependencies}
    if node.name in imported or node.name in python_names.STDLIB_MODULES:
        raise ValueError(f"choose another name: its script {node.executable} would shadow the Python module "
                         f"'{node.name}' it needs")


def _check_cpp_names(node: Node) -> None:
    """A ROS 2 C++ node's lines that hold both its package's name and its own fit 100 columns."""
    together = len(node.package) + len(node.name)
    if node.ros == 2 and node.is_cpp and together > names.CPP_PACKAGE_AND_NODE_MAX:
        raise ValueError(f"give it a shorter name: its name and the package's have {together} characters together: "
                         "a C++ node's have at "
                         f"most {names.CPP_PACKAGE_AND_NODE_MAX}, so generated lines fit 100 columns")


def _check_node_names(node: Node) -> None:
    """Every ROS name and every generated member and callback is used once per node."""
    _check_unique((t.topic, t.label) for t in node.publishers)
    _check_unique((t.topic, t.label) for t in node.subscribers)
    _check_unique((s.name, s.label) for s in node.service_servers + node.service_clients)
    _check_unique((a.name, a.label) for a in node.actions)
    reserved = ([(AUTOSTART_PARAMETER, "the parameter a lifecycle node starts itself by")]
                if node.starts_itself else [])
    _check_unique([*reserved, *((p.name, f"parameter '{p.name}'") for p in node.parameters)])
    _check_unique((e.member, e.label) for e in node.endpoints)
    methods = [(method, endpoint.label) for endpoint in node.endpoints for method in endpoint.methods]
    methods.extend((name, "a lifecycle callback") for name in names.LIFECYCLE_CALLBACKS)
    if node.diagnostics:
        methods.append((DIAGNOSTICS_TASK, "the diagnostics updater"))
    _check_unique(methods)
    # ROS 1 nodes keep parameters in members named after them; ROS 2 nodes ask for them by name.
    _check_unique([*((e.member, e.label) for e in node.endpoints), *methods,
                   *((group.member, group.label) for group in node.callback_groups),
                   *((name, "a member of the base class") for name in BASE_MEMBERS),
                   *((name, "the diagnostics updater") for name in node.diagnostics_members),
                   *((p.name, f"parameter '{p.name}'") for p in node.parameters if node.ros == 1)])


def parse_nodes(value: object, *, package: str, build_type: str, types: Types) -> tuple[Node, ...]:
    value = load_yaml(value)
    if not isinstance(value, list) or not value:
        raise ValueError("give a list with at least one node")
    nodes = tuple(parse_node(item, package=package, build_type=build_type, types=types) for item in value)
    _check_unique((node.name, f"node '{node.name}'") for node in nodes)
    _check_connections(nodes)
    return nodes


def _check_connections(nodes: tuple[Node, ...]) -> None:
    """The package's own nodes that share a topic, service or action agree on its type and, for topics, QoS."""
    ends: dict[tuple[str, str], list[tuple[str, object]]] = {}
    for node in nodes:
        for endpoint in node.endpoints:
            if isinstance(endpoint, Timer):
                continue
            name = names.graph_name(endpoint.topic if isinstance(endpoint, Topic) else endpoint.name, node.name)
            if name is not None:
                ends.setdefault((type(endpoint).__name__, name), []).append((node.name, endpoint))
    for (kind, name), found in ends.items():
        what = {"Topic": "topic", "Service": "service", "Action": "action"}[kind]
        (first, one), *others = found
        for other, endpoint in others:
            if endpoint.type != one.type:
                raise ValueError(f"{what} '{name}': give its nodes one type: node '{first}' uses "
                                 f"{one.type.full_name} and node '{other}' {endpoint.type.full_name}")
        if kind == "Topic" and nodes[0].ros == 2:
            publishers = [(who, t.qos) for who, t in found if t.role == "publisher"]
            subscribers = [(who, t.qos) for who, t in found if t.role == "subscriber"]
            for writer, reader, why in qos_rules.incompatible_pairs(publishers, subscribers):
                raise ValueError(f"topic '{name}': give both the same qos preset: node '{reader}' never hears node "
                                 f"'{writer}': {why}")
