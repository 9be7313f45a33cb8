"""The package model: Copier's answers, checked and turned into what the templates render.

`build_package(answers)` is the single entry point. It accepts the long form of
every answer (mappings) and the short forms people type at a prompt
(`cmd_vel:geometry_msgs/msg/Twist`, `rate:double=10.0`, `0.5`), checks them
against the ROS rules and raises AnswerError naming the question and the rule.
"""

from __future__ import annotations

import difflib
import re
import textwrap
from collections import Counter
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from functools import cached_property

import yaml

from . import names
from .definitions import Definition, parse_definitions
from .interfaces import InterfaceType, parse_interface
from .licenses import License, get_license
from .parameters import Parameter, ParameterType, coerce_default, infer_type, parse_type

ROS2_DISTROS = ("humble", "jazzy", "kilted", "rolling")
ROS1_DISTROS = ("noetic",)
BUILD_TYPES = {2: ("ament_cmake", "ament_python"), 1: ("catkin",)}
LANGUAGES = {"cpp": "cpp", "c++": "cpp", "python": "python", "py": "python"}
QOS_PROFILES = {"sensor_data": 5}
_EMAIL = re.compile(r"[^@\s]+@[^@\s]+\.[^@\s]+")

# Members the generated base classes declare besides the endpoints'.
BASE_MEMBERS = ("node_handle", "private_node_handle", "action_callback_group", "count")

# Names the generated Python files import or define besides interface types.
PYTHON_RESERVED = frozenset({
    "ActionClient", "ActionServer", "CancelResponse", "ExternalShutdownException",
    "FloatingPointRange", "GoalResponse", "GoalStatus", "IntegerRange", "MultiThreadedExecutor",
    "Node", "ParameterDescriptor", "ReentrantCallbackGroup", "State", "TransitionCallbackReturn",
})


class AnswerError(ValueError):
    """A broken rule in one answer: `str()` is the one line shown to the user."""

    def __init__(self, question: str, message: str) -> None:
        super().__init__(f"invalid answer to '{question}': {message}")
        self.question = question
        self.message = message


# --------------------------------------------------------------------------- endpoints


@dataclass(frozen=True)
class Qos:
    """A history depth, or a named profile of the ROS 2 client libraries."""

    depth: int = 10
    profile: str | None = None

    @property
    def cpp(self) -> str:
        return "rclcpp::SensorDataQoS()" if self.profile == "sensor_data" else str(self.depth)

    @property
    def python(self) -> str:
        return "qos_profile_sensor_data" if self.profile == "sensor_data" else str(self.depth)


@dataclass(frozen=True)
class Topic:
    """A publisher or a subscription."""

    role: str  # "publisher" | "subscriber"
    topic: str
    type: InterfaceType
    qos: Qos
    id: str

    @property
    def member(self) -> str:
        if self.role == "publisher":
            return names.with_suffix(self.id, "publisher")
        # The ROS 1 class is a Subscriber, the ROS 2 one a Subscription.
        return names.with_suffix(self.id, "subscriber" if self.type.ros == 1 else "subscription")

    @property
    def callback(self) -> str | None:
        return f"on_{self.id}" if self.role == "subscriber" else None

    @property
    def methods(self) -> tuple[str, ...]:
        """Methods the base class defines for this topic."""
        return (self.callback,) if self.callback else ()

    @property
    def label(self) -> str:
        return f"{self.role} '{self.topic}'"


@dataclass(frozen=True)
class Service:
    """A service server or client."""

    role: str  # "server" | "client"
    name: str
    type: InterfaceType
    id: str

    @property
    def member(self) -> str:
        return names.with_suffix(self.id, "service" if self.role == "server" else "client")

    @property
    def callback(self) -> str:
        return f"on_{self.id}_request" if self.role == "server" else f"on_{self.id}_response"

    @property
    def methods(self) -> tuple[str, ...]:
        """Methods the base class defines for this service."""
        return (self.callback,) if self.role == "server" else (f"call_{self.id}", self.callback)

    @property
    def label(self) -> str:
        return f"service {self.role} '{self.name}'"


@dataclass(frozen=True)
class Action:
    """An action server or client."""

    role: str  # "server" | "client"
    name: str
    type: InterfaceType
    id: str

    @property
    def member(self) -> str:
        return names.with_suffix(self.id, f"action_{self.role}")

    @property
    def callbacks(self) -> dict[str, str]:
        if self.role == "server":
            return {"goal": f"on_{self.id}_goal", "cancel": f"on_{self.id}_cancel",
                    "execute": f"execute_{self.id}"}
        return {"send": f"send_{self.id}_goal", "goal_response": f"on_{self.id}_goal_response",
                "feedback": f"on_{self.id}_feedback", "result": f"on_{self.id}_result",
                "done": f"_on_{self.id}_done"}

    @property
    def goal_active(self) -> str:
        """The client's flag: true from send_<id>_goal() until the goal ends."""
        return f"{self.id}_goal_active"

    @property
    def methods(self) -> tuple[str, ...]:
        """Methods (and, for a client, the goal flag) the base class defines for this action."""
        return tuple(self.callbacks.values()) + ((self.goal_active,) if self.role == "client" else ())

    @property
    def cpp_goal_handle(self) -> str:
        """The C++ alias the base class declares for this action's goal handle type."""
        return names.snake_to_camel(self.id) + ("GoalHandle" if self.role == "server" else "ClientGoalHandle")

    @property
    def label(self) -> str:
        return f"action {self.role} '{self.name}'"


@dataclass(frozen=True)
class Timer:
    """A periodic callback."""

    id: str
    period: float

    @property
    def member(self) -> str:
        return names.with_suffix(self.id, "timer")

    @property
    def callback(self) -> str:
        return f"on_{self.id}"

    @property
    def methods(self) -> tuple[str, ...]:
        return (self.callback,)

    @property
    def label(self) -> str:
        return f"timer '{self.id}'"

    @property
    def cpp_period(self) -> str:
        """The period as a std::chrono duration with an exact integer count."""
        for unit, scale in (("seconds", 1), ("milliseconds", 1e3), ("microseconds", 1e6)):
            count = self.period * scale
            if abs(count - round(count)) < 1e-9 * scale:
                return f"std::chrono::{unit}({round(count)})"
        return f"std::chrono::nanoseconds({round(self.period * 1e9)})"

    @property
    def hz_text(self) -> str:
        """'every 0.5 s' for docs and comments."""
        return f"every {self.period:g} s"


# --------------------------------------------------------------------------- nodes


@dataclass(frozen=True)
class Node:
    """One node: its name, language and everything it talks to."""

    name: str
    language: str
    package: str
    ros: int = 2
    description: str = ""
    lifecycle: bool = False
    component: bool = False
    publishers: tuple[Topic, ...] = ()
    subscribers: tuple[Topic, ...] = ()
    service_servers: tuple[Service, ...] = ()
    service_clients: tuple[Service, ...] = ()
    action_servers: tuple[Action, ...] = ()
    action_clients: tuple[Action, ...] = ()
    timers: tuple[Timer, ...] = ()
    parameters: tuple[Parameter, ...] = ()

    @property
    def is_cpp(self) -> bool:
        return self.language == "cpp"

    @property
    def is_python(self) -> bool:
        return self.language == "python"

    @property
    def class_name(self) -> str:
        return names.snake_to_camel(self.name)

    @property
    def base_class_name(self) -> str:
        return self.class_name + "Base"

    @property
    def base_name(self) -> str:
        """File stem of the template-owned base: talker_base.py / talker_base.hpp."""
        return self.name + "_base"

    @property
    def header_guard(self) -> str:
        """ROS 2 style PKG__FILE_HPP_, ROS 1 style PKG_FILE_H."""
        if self.ros == 1:
            return f"{self.package}_{self.base_name}_H".upper()
        return f"{self.package}__{self.base_name}_HPP_".upper()

    @property
    def user_file(self) -> str:
        """The user-owned source file, relative to the package folder."""
        if self.is_cpp:
            return f"src/{self.name}.cpp"
        return f"scripts/{self.name}.py" if self.ros == 1 else f"{self.package}/{self.name}.py"

    @property
    def base_file(self) -> str:
        """The template-owned base class file, relative to the package folder."""
        if self.is_cpp:
            return f"include/{self.package}/{self.base_name}.{'h' if self.ros == 1 else 'hpp'}"
        return f"src/{self.package}/{self.base_name}.py" if self.ros == 1 else f"{self.package}/{self.base_name}.py"

    @property
    def executable(self) -> str:
        """What rosrun / ros2 run starts: ROS 1 Python scripts keep their .py."""
        return f"{self.name}.py" if self.ros == 1 and self.is_python else self.name

    @property
    def endpoints(self) -> tuple:
        return (self.publishers + self.subscribers + self.service_servers + self.service_clients
                + self.action_servers + self.action_clients + self.timers)

    @property
    def actions(self) -> tuple[Action, ...]:
        return self.action_servers + self.action_clients

    @property
    def interfaces(self) -> tuple[InterfaceType, ...]:
        """Every interface type the node uses, sorted by name, each once."""
        found = {endpoint.type for endpoint in self.endpoints if hasattr(endpoint, "type")}
        return tuple(sorted(found, key=lambda t: t.full_name))

    @cached_property
    def python_types(self) -> dict[InterfaceType, str]:
        """The name of each interface type in the node's Python files.

        A type whose name clashes with another type, the node's classes or an
        imported helper is imported under its package's name: NavMsgsOdometry.
        """
        taken = {self.class_name, self.base_class_name, *PYTHON_RESERVED}
        counts = Counter(t.name for t in self.interfaces)
        return {
            t: names.snake_to_camel(t.package) + t.name if counts[t.name] > 1 or t.name in taken else t.name
            for t in self.interfaces
        }

    @property
    def message_variables(self) -> dict[Topic, str]:
        """The starter code's variable for each publisher's message: msg, or <id>_msg for several."""
        if len(self.publishers) == 1:
            return {self.publishers[0]: "msg"}
        return {topic: f"{topic.id}_msg" for topic in self.publishers}

    @property
    def driver_timer(self) -> Timer | None:
        """The timer whose starter code publishes and calls: the first one, if it has work."""
        if self.timers and (self.publishers or self.service_clients or self.action_clients):
            return self.timers[0]
        return None

    @property
    def driver_docstring(self) -> str:
        """Docstring of the starter timer callback: what it does."""
        work = []
        if self.publishers:
            work.append("publish the next message" + ("s" if len(self.publishers) > 1 else ""))
        if self.service_clients:
            work.append("call the service" + ("s" if len(self.service_clients) > 1 else ""))
        if self.action_clients:
            work.append("send a goal" if len(self.action_clients) == 1 else "send goals")
        text = ", ".join(work[:-1]) + (" and " if len(work) > 1 else "") + work[-1]
        return text[0].upper() + text[1:] + "."

    @property
    def docstring_title(self) -> str:
        return f"The {self.name} node."

    @property
    def summary_lines(self) -> list[str]:
        """The summary wrapped for a docstring, after a blank line."""
        return ["", *textwrap.wrap(self.summary, 88)]

    @property
    def summary(self) -> str:
        """The description, or a sentence made from what the node does."""
        if self.description:
            return self.description if self.description.endswith(".") else self.description + "."
        parts = []
        listing = english_list

        if self.publishers:
            parts.append("publishes " + listing(t.topic for t in self.publishers))
        if self.subscribers:
            parts.append("subscribes to " + listing(t.topic for t in self.subscribers))
        if self.service_servers:
            parts.append("serves " + listing(s.name for s in self.service_servers))
        if self.service_clients:
            parts.append("calls " + listing(s.name for s in self.service_clients))
        if self.action_servers:
            parts.append("executes " + listing(a.name for a in self.action_servers) + " goals")
        if self.action_clients:
            parts.append("sends " + listing(a.name for a in self.action_clients) + " goals")
        if not parts:
            return f"The {self.name} node."
        text = english_list(parts)
        return text[0].upper() + text[1:] + "."

    @property
    def dependencies(self) -> tuple[str, ...]:
        """ROS packages the node's code uses, sorted."""
        deps = {t.package for t in self.interfaces}
        if self.ros == 2:
            if self.is_cpp:
                deps.add("rclcpp")
                if self.actions:
                    deps.add("rclcpp_action")
                if self.lifecycle:
                    deps.add("rclcpp_lifecycle")
                if self.component:
                    deps.add("rclcpp_components")
            else:
                deps.add("rclpy")
                if self.action_clients:
                    deps.add("action_msgs")  # GoalStatus, to report how a goal ended
            if any(parameter.has_descriptor for parameter in self.parameters):
                deps.add("rcl_interfaces")  # ParameterDescriptor
        else:
            deps.add("roscpp" if self.is_cpp else "rospy")
            if self.actions:
                deps.update({"actionlib", "actionlib_msgs"})
        return tuple(sorted(deps))


# --------------------------------------------------------------------------- package


@dataclass(frozen=True)
class Dependency:
    """A package.xml dependency: `depend` when C++ code builds against it."""

    name: str
    build: bool

    @property
    def tag(self) -> str:
        return "depend" if self.build else "exec_depend"


@dataclass(frozen=True)
class Package:
    """Everything the templates render, derived from the answers."""

    name: str
    description: str
    maintainer: str
    maintainer_email: str
    license: License
    copyright_holder: str
    copyright_year: int
    ros_distro: str
    build_type: str
    nodes: tuple[Node, ...] = field(default_factory=tuple)
    definitions: tuple[Definition, ...] = ()
    interfaces_location: str = "separate"  # or "package": this package builds them
    target: str = "package"  # or "node": one node added to a package the template did not make

    @property
    def dir(self) -> str:
        """The package folder within the destination: the destination itself for a node."""
        return "." if self.target == "node" else self.name

    # --- interfaces this package defines

    @property
    def interfaces_home(self) -> str:
        """The package folder the .msg/.srv/.action files go to, or "" without any."""
        if not self.definitions:
            return ""
        return self.name if self.interfaces_location == "package" else f"{self.name}_interfaces"

    @property
    def interfaces_package(self) -> str:
        """The separate interfaces package to generate beside this one, or ""."""
        return self.interfaces_home if self.interfaces_home != self.name else ""

    @property
    def builds_interfaces(self) -> bool:
        """This package itself runs the interface generators."""
        return bool(self.definitions) and self.interfaces_home == self.name

    def definitions_of(self, kind: str) -> tuple[Definition, ...]:
        return tuple(d for d in self.definitions if d.kind == kind)

    @property
    def interface_dependencies(self) -> tuple[str, ...]:
        """Packages the generated interfaces need, sorted."""
        deps = {package for definition in self.definitions for package in definition.packages}
        if self.definitions_of("action"):
            deps |= {"actionlib_msgs", "std_msgs"} if self.ros == 1 else {"action_msgs"}
        return tuple(sorted(deps))

    @property
    def ros(self) -> int:
        return 1 if self.ros_distro in ROS1_DISTROS else 2

    @property
    def launch_file(self) -> str:
        return f"launch/{self.name}.launch" + ("" if self.ros == 1 else ".xml")

    @property
    def user_files(self) -> tuple[str, ...]:
        """Files the user owns, relative to the destination: created once, never rewritten."""
        prefix = "" if self.target == "node" else f"{self.name}/"
        return tuple(prefix + node.user_file for node in self.nodes)

    @property
    def cpp_nodes(self) -> tuple[Node, ...]:
        return tuple(node for node in self.nodes if node.is_cpp)

    @property
    def python_nodes(self) -> tuple[Node, ...]:
        return tuple(node for node in self.nodes if node.is_python)

    @property
    def python_dir(self) -> str:
        """The Python package folder, or "" when the package has no Python code."""
        if self.build_type == "ament_python" or self.python_nodes:
            return self.name
        return ""

    @cached_property
    def dependencies(self) -> tuple[Dependency, ...]:
        """The nodes' dependencies, each once, sorted: what package.xml lists."""
        cpp = {dep for node in self.cpp_nodes for dep in node.dependencies}
        everything = {dep for node in self.nodes for dep in node.dependencies}
        if self.builds_interfaces:
            cpp |= set(self.interface_dependencies)
            everything |= set(self.interface_dependencies)
            if self.ros == 1:
                # One list serves find_package() and catkin_package(): both tools are <depend>s.
                everything |= {"message_generation", "message_runtime"}
        everything.discard(self.name)  # its own interfaces
        # catkin finds every dependency at build time (find_package COMPONENTS).
        return tuple(Dependency(dep, dep in cpp or self.ros == 1) for dep in sorted(everything))

    @property
    def cpp_dependencies(self) -> tuple[str, ...]:
        return tuple(dep.name for dep in self.dependencies if dep.build)

    @property
    def copyright_line(self) -> str:
        return f"Copyright {self.copyright_year} {self.copyright_holder}"

    def header(self, comment: str) -> str:
        """The copyright and license comment block that starts each source file."""
        return self.license.header(self.copyright_line, comment)

    @property
    def license_text(self) -> str:
        return self.license.text(self.copyright_line)


# --------------------------------------------------------------------------- parsing


@dataclass(frozen=True)
class Types:
    """How endpoint types are read: the ROS generation, and this package's own interfaces."""

    ros: int = 2
    own: Mapping[tuple[str, str], InterfaceType] = field(default_factory=dict)

    def parse(self, text: object, kind: str) -> InterfaceType:
        """`pkg/kind/Name`, `pkg/Name`, or the bare `Name` of an interface defined here."""
        if isinstance(text, str) and (kind, text.strip()) in self.own:
            return self.own[(kind, text.strip())]
        return parse_interface(text, kind, self.ros)


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


def _as_list(value: object, what: str) -> list:
    if value is None:
        return []
    if isinstance(value, str):
        return split_list(value)
    if not isinstance(value, list):
        raise ValueError(f"{what} must be a list")
    return value


def _check_keys(item: Mapping, allowed: Iterable[str], what: str) -> None:
    allowed = list(allowed)
    for key in item:
        if key not in allowed:
            close = difflib.get_close_matches(str(key), allowed, n=1)
            hint = f" (did you mean '{close[0]}'?)" if close else f" (known: {', '.join(allowed)})"
            raise ValueError(f"{what}: unknown key '{key}'{hint}")


def _split_short(text: str, fields: int) -> list[str]:
    """'topic:type:qos' -> parts; the type itself never contains ':'."""
    return [part.strip() for part in text.split(":", fields - 1)]


def _parse_qos(value: object, what: str) -> Qos:
    if value is None or value == "":
        return Qos()
    if isinstance(value, bool):
        raise ValueError(f"{what}: qos must be a history depth (e.g. 10) or 'sensor_data'")
    if isinstance(value, int) or (isinstance(value, str) and value.isdigit()):
        depth = int(value)
        if not 1 <= depth <= 10000:
            raise ValueError(f"{what}: qos depth {depth} must be between 1 and 10000")
        return Qos(depth)
    if value in QOS_PROFILES:
        return Qos(QOS_PROFILES[value], value)
    raise ValueError(f"{what}: qos must be a history depth (e.g. 10) or 'sensor_data', not '{value}'")


def _parse_id(given: object, ros_name: str, what: str) -> str:
    if given is not None:
        error = names.identifier_error(given, f"{what}: id")
        if error:
            raise ValueError(error)
        return str(given)
    return names.identifier_from_name(ros_name)


def _parse_topic(item: object, role: str, types: Types) -> Topic:
    if isinstance(item, str):
        parts = _split_short(item, 3)
        if len(parts) < 2:
            raise ValueError(f"{role} '{item}': write it as topic:type, e.g. chatter:std_msgs/msg/String")
        item = dict(zip(("topic", "type", "qos"), parts, strict=False))
    if not isinstance(item, Mapping):
        raise ValueError(f"a {role} must be 'topic:type' or a mapping with topic and type")
    _check_keys(item, ("topic", "type", "qos", "id"), role)
    topic = item.get("topic")
    what = f"{role} '{topic}'"
    error = names.topic_name_error(topic, "topic")
    if error:
        raise ValueError(f"{role}: {error}")
    interface = types.parse(item.get("type"), "msg")
    return Topic(role, topic, interface, _parse_qos(item.get("qos"), what), _parse_id(item.get("id"), topic, what))


def _parse_service_or_action(item: object, cls: type, kind: str, role: str, types: Types):
    what = f"{'service' if kind == 'srv' else 'action'} {role}"
    example = "reset:std_srvs/srv/Trigger" if kind == "srv" else "fibonacci:test_msgs/action/Fibonacci"
    if isinstance(item, str):
        parts = _split_short(item, 2)
        if len(parts) < 2:
            raise ValueError(f"{what} '{item}': write it as name:type, e.g. {example}")
        item = dict(zip(("name", "type"), parts, strict=True))
    if not isinstance(item, Mapping):
        raise ValueError(f"a {what} must be 'name:type' or a mapping with name and type")
    _check_keys(item, ("name", "type", "id"), what)
    name = item.get("name")
    error = names.topic_name_error(name, "service" if kind == "srv" else "action")
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
        raise ValueError("a timer must be a period in seconds, 'name:period' or a mapping")
    _check_keys(item, ("name", "period"), "timer")
    name = item.get("name", "timer")
    error = names.identifier_error(name, "timer")
    if error:
        raise ValueError(error)
    period = item.get("period")
    try:
        period = float(period)
    except (TypeError, ValueError):
        raise ValueError(f"timer '{name}': period '{period}' is not a number of seconds") from None
    if not 0 < period <= 86400:
        raise ValueError(f"timer '{name}': period must be more than 0 s and at most a day")
    return Timer(name, period)


_SHORT_PARAMETER = re.compile(r"(?P<name>[^:=\s]+)\s*(?::\s*(?P<type>[^=\s]+))?\s*(?:=(?P<default>.*))?", re.S)


def _parse_parameter(item: object) -> Parameter:
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
                raise ValueError(f"parameter '{match['name']}': cannot read the default '{match['default']}'") from None
    if not isinstance(item, Mapping):
        raise ValueError("a parameter must be 'name:type=default' or a mapping with name, type and default")
    _check_keys(item, ("name", "type", "default", "description", "range", "read_only"), "parameter")
    name = item.get("name")
    error = names.parameter_name_error(name)
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
        default = coerce_default(item.get("default"), ptype)
    except ValueError as error:
        raise ValueError(f"{what}: {error}") from None
    if ptype.is_array and not default:
        raise ValueError(f"{what}: array parameters need a non-empty default")
    description = item.get("description") or ""
    if not isinstance(description, str) or "\n" in description:
        raise ValueError(f"{what}: description must be one line of text")
    read_only = item.get("read_only", False)
    if not isinstance(read_only, bool):
        raise ValueError(f"{what}: read_only must be true or false")
    value_range = _parse_range(item.get("range"), ptype, default, what)
    return Parameter(name, ptype, default, description.strip(), value_range, read_only)


def _parse_range(value: object, ptype: ParameterType, default: object, what: str):
    if value is None:
        return None
    if not ptype.is_numeric:
        raise ValueError(f"{what}: only int and double parameters take a range")
    if isinstance(value, Mapping):
        _check_keys(value, ("min", "max", "step"), f"{what} range")
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
    if low > high:
        raise ValueError(f"{what}: range minimum {low} is above its maximum {high}")
    if step < 0:
        raise ValueError(f"{what}: range step must not be negative")
    if not low <= default <= high:
        raise ValueError(f"{what}: default {default} is outside the range [{low}, {high}]")
    cast = int if ptype.scalar == "int" else float
    return (cast(low), cast(high), cast(step))


def _check_unique(node_label: str, items: Iterable[tuple[str, str]]) -> None:
    """items: (name, label) pairs; a name used twice is an error naming both uses."""
    seen: dict[str, str] = {}
    for name, label in items:
        if name in seen:
            raise ValueError(f"{node_label}: {seen[name]} and {label} both use the name '{name}'")
        seen[name] = label


_NODE_KEYS = ("name", "language", "description", "lifecycle", "component", "publishers", "subscribers",
              "service_servers", "service_clients", "action_servers", "action_clients", "timers",
              "parameters")


def parse_node(item: object, *, package: str, build_type: str, types: Types) -> Node:
    """One entry of `nodes`; raises ValueError with a message that starts with the node."""
    if isinstance(item, str):
        item = {"name": item}
    if not isinstance(item, Mapping):
        raise ValueError("each node must be a mapping with at least a name")
    name = item.get("name")
    error = names.node_name_error(name)
    if error:
        raise ValueError(error)
    label = f"node '{name}'"
    ros = types.ros
    try:
        _check_keys(item, _NODE_KEYS, "node")
        default_language = "python" if build_type == "ament_python" else "cpp"
        language = LANGUAGES.get(str(item.get("language") or default_language).lower())
        if language is None:
            raise ValueError(f"language '{item.get('language')}' is not cpp or python")
        if build_type == "ament_python" and language == "cpp":
            raise ValueError("an ament_python package holds Python nodes only; choose build_type ament_cmake for C++")
        flags = {}
        for flag in ("lifecycle", "component"):
            flags[flag] = item.get(flag, False)
            if not isinstance(flags[flag], bool):
                raise ValueError(f"{flag} must be true or false")
        if ros == 1 and (flags["lifecycle"] or flags["component"]):
            raise ValueError("lifecycle and component nodes are ROS 2 features")
        if flags["component"] and language != "cpp":
            raise ValueError("components are C++ nodes (rclcpp_components)")
        description = item.get("description") or ""
        if not isinstance(description, str) or "\n" in description.strip():
            raise ValueError("description must be one line of text")
        node = Node(
            name=name,
            language=language,
            package=package,
            ros=ros,
            description=description.strip(),
            lifecycle=flags["lifecycle"],
            component=flags["component"],
            publishers=tuple(_parse_topic(x, "publisher", types)
                             for x in _as_list(item.get("publishers"), "publishers")),
            subscribers=tuple(_parse_topic(x, "subscriber", types)
                              for x in _as_list(item.get("subscribers"), "subscribers")),
            service_servers=tuple(_parse_service_or_action(x, Service, "srv", "server", types)
                                  for x in _as_list(item.get("service_servers"), "service_servers")),
            service_clients=tuple(_parse_service_or_action(x, Service, "srv", "client", types)
                                  for x in _as_list(item.get("service_clients"), "service_clients")),
            action_servers=tuple(_parse_service_or_action(x, Action, "action", "server", types)
                                 for x in _as_list(item.get("action_servers"), "action_servers")),
            action_clients=tuple(_parse_service_or_action(x, Action, "action", "client", types)
                                 for x in _as_list(item.get("action_clients"), "action_clients")),
            timers=tuple(_parse_timer(x) for x in _as_list(item.get("timers"), "timers")),
            parameters=tuple(_parse_parameter(x) for x in _as_list(item.get("parameters"), "parameters")),
        )
        _check_node_names(node, label)
    except ValueError as error:
        raise ValueError(f"{label}: {error}") from None
    return node


def _check_node_names(node: Node, label: str) -> None:
    """Every ROS name and every generated member and callback is used once per node."""
    _check_unique(label, ((t.topic, t.label) for t in node.publishers))
    _check_unique(label, ((t.topic, t.label) for t in node.subscribers))
    _check_unique(label, ((s.name, s.label) for s in node.service_servers + node.service_clients))
    _check_unique(label, ((a.name, a.label) for a in node.actions))
    _check_unique(label, ((p.name, f"parameter '{p.name}'") for p in node.parameters))
    _check_unique(label, ((e.member, e.label) for e in node.endpoints))
    methods = [(method, endpoint.label) for endpoint in node.endpoints for method in endpoint.methods]
    methods.extend((name, "a lifecycle callback") for name in names.LIFECYCLE_CALLBACKS)
    _check_unique(label, methods)
    # ROS 1 nodes keep parameters in members named after them.
    _check_unique(label, [*((e.member, e.label) for e in node.endpoints), *methods,
                          *((name, "a member of the base class") for name in BASE_MEMBERS),
                          *((p.name, f"parameter '{p.name}'") for p in node.parameters)])


def parse_nodes(value: object, *, package: str, build_type: str, types: Types) -> tuple[Node, ...]:
    if isinstance(value, str):
        try:
            value = yaml.safe_load(value)
        except yaml.YAMLError as error:
            raise ValueError(f"not valid YAML ({str(error).splitlines()[0]})") from None
    if not isinstance(value, list) or not value:
        raise ValueError("give a list with at least one node")
    nodes = tuple(parse_node(item, package=package, build_type=build_type, types=types) for item in value)
    _check_unique("nodes", ((node.name, f"node '{node.name}'") for node in nodes))
    return nodes


# --------------------------------------------------------------------------- answers


def ros_generation(distro: object) -> int:
    return 1 if distro in ROS1_DISTROS else 2


def question_error(question: str, answers: Mapping) -> str | None:
    """The error for one question given the answers so far, or None: for Copier validators."""
    try:
        _check_question(question, answers)
    except ValueError as error:
        return str(error)
    return None


def interfaces_package_name(answers: Mapping) -> str:
    """Where the package's own interfaces live: <package>_interfaces, or the package itself."""
    package = answers.get("package_name") or "pkg"
    return package if answers.get("interfaces_location") == "package" else f"{package}_interfaces"


def parse_types(answers: Mapping) -> tuple[tuple[Definition, ...], Types]:
    """The interfaces the answers define, and how node answers read types with them."""
    ros = ros_generation(answers.get("ros_distro"))
    home = interfaces_package_name(answers)
    definitions = parse_definitions(answers.get("interfaces"), package=home, ros=ros)
    own = {(d.kind, d.name): InterfaceType(home, d.kind, d.name, ros) for d in definitions}
    return definitions, Types(ros, own)


def _check_question(question: str, answers: Mapping) -> None:
    value = answers.get(question)
    ros = ros_generation(answers.get("ros_distro"))
    if question == "package_name":
        error = names.package_name_error(value)
        if error:
            raise ValueError(error)
    elif question in ("description", "maintainer", "copyright_holder"):
        if not isinstance(value, str) or not value.strip() or "\n" in value.strip():
            raise ValueError("give one line of text")
    elif question == "maintainer_email":
        if not isinstance(value, str) or not _EMAIL.fullmatch(value.strip()):
            raise ValueError(f"'{value}' is not an e-mail address")
    elif question == "license":
        get_license(value)
    elif question == "ros_distro":
        if value not in ROS2_DISTROS + ROS1_DISTROS:
            raise ValueError(f"'{value}' is not one of {', '.join(ROS2_DISTROS + ROS1_DISTROS)}")
    elif question == "build_type":
        if value not in BUILD_TYPES[ros]:
            raise ValueError(f"'{value}' is not one of {', '.join(BUILD_TYPES[ros])} for ROS {ros}")
    elif question == "interfaces":
        parse_types(answers)
    elif question == "interfaces_location":
        if value not in (None, "separate", "package"):
            raise ValueError(f"'{value}' is not separate or package")
        if value == "package" and answers.get("build_type") == "ament_python":
            raise ValueError("an ament_python package cannot build interfaces: keep them separate")
    elif question == "nodes":
        nodes = parse_nodes(value, package=answers.get("package_name") or "pkg",
                            build_type=answers.get("build_type"), types=parse_types(answers)[1])
        if answers.get("target") == "node" and len(nodes) != 1:
            raise ValueError("a node added to an existing package is one node: give exactly one")
    elif question == "target":
        if value not in (None, "package", "node"):
            raise ValueError(f"'{value}' is not package or node")
        if value == "node" and answers.get("interfaces"):
            raise ValueError("a node added to an existing package cannot define interfaces: name "
                             "existing ones, or generate a package")
    elif question == "node_name":
        error = names.node_name_error(value)
        if error:
            raise ValueError(error)
    elif question in QUICK_LISTS:
        # The one-node quick questions take comma-separated short forms.
        key = QUICK_LISTS[question]
        language = "python" if answers.get("build_type") == "ament_python" else answers.get("node_language")
        parse_node({"name": "node", "language": language, key: value},
                   package="pkg", build_type=answers.get("build_type"), types=Types(ros))


# Quick one-node questions and the `nodes` key each one fills.
QUICK_LISTS = {
    "node_publishers": "publishers",
    "node_subscribers": "subscribers",
    "node_service_servers": "service_servers",
    "node_service_clients": "service_clients",
    "node_action_servers": "action_servers",
    "node_action_clients": "action_clients",
    "node_timers": "timers",
    "node_parameters": "parameters",
}

def english_list(items: Iterable[str]) -> str:
    """['a', 'b', 'c'] -> 'a, b and c'."""
    items = list(items)
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def describe_nodes(answers: Mapping) -> str:
    """A default package description from the nodes: what each does, or their names."""
    try:
        nodes = parse_nodes(answers.get("nodes"), package=answers.get("package_name") or "pkg",
                            build_type=answers.get("build_type"), types=parse_types(answers)[1])
    except ValueError:
        return "ROS nodes"
    if len(nodes) > 3:
        return "Nodes " + english_list(node.name for node in nodes)
    if any(node.description for node in nodes):
        return " ".join(node.summary for node in nodes)
    text = "; ".join(f"the {node.name} node {node.summary[0].lower()}{node.summary[1:-1]}" for node in nodes)
    return text[0].upper() + text[1:]


QUESTIONS = ("package_name", "description", "maintainer", "maintainer_email", "license",
             "copyright_holder", "ros_distro", "build_type", "target", "interfaces", "interfaces_location",
             "nodes")


def build_package(answers: Mapping) -> Package:
    """Check every answer and build the model; raises AnswerError on the first broken rule."""
    answers = dict(answers)
    if ros_generation(answers.get("ros_distro")) == 1 and not answers.get("build_type"):
        answers["build_type"] = "catkin"  # not asked, so not in the answers file either
    for question in QUESTIONS:
        try:
            _check_question(question, answers)
        except ValueError as error:
            raise AnswerError(question, str(error)) from None
    definitions, types = parse_types(answers)
    year = answers.get("copyright_year")
    if isinstance(year, bool) or not isinstance(year, int) or not 1970 <= year <= 9999:
        raise AnswerError("copyright_year", f"'{year}' is not a year")
    return Package(
        name=answers["package_name"],
        description=answers["description"].strip(),
        maintainer=answers["maintainer"].strip(),
        maintainer_email=answers["maintainer_email"].strip(),
        license=get_license(answers["license"]),
        copyright_holder=answers["copyright_holder"].strip(),
        copyright_year=year,
        ros_distro=answers["ros_distro"],
        build_type=answers["build_type"],
        nodes=parse_nodes(answers["nodes"], package=answers["package_name"],
                          build_type=answers["build_type"], types=types),
        definitions=definitions,
        interfaces_location=answers.get("interfaces_location") or "separate",
        target=answers.get("target") or "package",
    )
