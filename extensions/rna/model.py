"""The package model: the package, its nodes and their endpoints, in ROS terms.

What the templates render and the after-update step reads: names as ROS knows them,
the identifiers derived from them, the files of each node (rna.layout) and the packages
each uses (rna.features). It knows nothing of Copier's questions (rna.answers builds
it) nor of how a language spells code (rna.dialects).
"""

from __future__ import annotations

import itertools
import posixpath

from dataclasses import dataclass, field
from functools import cached_property

from . import distros, features, launch_features, layout, names
from .definitions import Definition
from .interfaces import InterfaceType
from .licenses import License
from . import parameters as parameter_rules
from .parameters import Parameter
from .qos import Qos, intra_process_error

# Members the generated base classes declare besides the endpoints'.
BASE_MEMBERS = ("node_handle", "private_node_handle", "start_goal_thread", "goal_threads", "goal_threads_mutex",
                "autostart_timer")
# The parameter a lifecycle component declares to configure and activate itself once loaded.
AUTOSTART_PARAMETER = "autostart"
# The method of a node with diagnostics that fills in its status (the updater's task).
DIAGNOSTICS_TASK = "on_diagnostics"
# The method of a ROS 2 node with parameters that the base class calls after an accepted change.
PARAMETERS_HOOK = "on_parameters_changed"


@dataclass(frozen=True)
class LaunchArgument:
    """An argument of the package's launch file, applied to every node it starts."""

    name: str
    default: str
    description: str


# ROS 2 launch files (launch_ros's Node, LifecycleNode, ComposableNode take each); ROS 1's take the
# first two (roslaunch has no per-node log level).
LAUNCH_ARGUMENTS = (
    LaunchArgument("namespace", "", "The namespace of every node, e.g. robot1 (none by default)"),
    LaunchArgument("use_sim_time", "false", "true: every node follows the simulated clock on /clock (Gazebo)"),
    LaunchArgument("log_level", "info", "The nodes' log level: debug, info, warn, error or fatal"),
)
# roslaunch refuses an empty `ns`: the root namespace is '/'.
ROS1_LAUNCH_ARGUMENTS = (
    LaunchArgument("namespace", "/", "The namespace of every node, e.g. robot1 (the root one, /, by default)"),
    LAUNCH_ARGUMENTS[1],
)


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

    @property
    def starter_log_throttle(self) -> float | None:
        """Seconds between the starter callback's logs of a subscription to a sensor stream
        (sensor_data QoS: a camera, a lidar, tens of messages a second), else None: one log a
        message."""
        return 1.0 if self.role == "subscriber" and self.qos.preset == "sensor_data" else None


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
    def call(self) -> str | None:
        return f"call_{self.id}" if self.role == "client" else None

    @property
    def methods(self) -> tuple[str, ...]:
        """Methods the base class defines for this service."""
        return (self.callback,) if self.role == "server" else (self.call, self.callback)

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
                    "execute": f"execute_{self.id}", "run": f"run_{self.id}_goal"}
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


# The executors a node may spin on (rna.distros.executor_error says where each exists).
EXECUTORS = ("single_threaded", "multi_threaded", "static", "events")
DEFAULT_EXECUTOR = "single_threaded"
CALLBACK_GROUP_TYPES = ("mutually_exclusive", "reentrant")


@dataclass(frozen=True)
class CallbackGroup:
    """Endpoints whose callbacks a multi-threaded executor runs one at a time (mutually
    exclusive) or side by side (reentrant), apart from the node's default group."""

    name: str
    type: str  # one of CALLBACK_GROUP_TYPES
    members: tuple = ()  # the node's subscriptions, servers, clients and timers in it

    @property
    def member(self) -> str:
        return names.with_suffix(self.name, "callback_group")

    @property
    def label(self) -> str:
        return f"callback group '{self.name}'"


@dataclass(frozen=True)
class Node:
    """One node: its name, language and everything it talks to."""

    name: str
    language: str
    package: str
    ros: int = 2
    description: str = ""
    lifecycle: bool = False
    autostart: bool = False  # the launch file configures and activates it
    component: bool = False
    diagnostics: bool = False  # a diagnostic_updater Updater reports the node's status on /diagnostics
    publishers: tuple[Topic, ...] = ()
    subscribers: tuple[Topic, ...] = ()
    service_servers: tuple[Service, ...] = ()
    service_clients: tuple[Service, ...] = ()
    action_servers: tuple[Action, ...] = ()
    action_clients: tuple[Action, ...] = ()
    timers: tuple[Timer, ...] = ()
    parameters: tuple[Parameter, ...] = ()
    # ROS 2: its distro's client libraries call post-set parameters callbacks (not Humble's).
    post_set_callbacks: bool = True
    executor: str = DEFAULT_EXECUTOR
    threads: int = 0  # of a multi-threaded executor; 0: one per core
    callback_groups: tuple[CallbackGroup, ...] = ()
    remappings: tuple[tuple[str, str], ...] = ()  # (from, to), applied by the launch file

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
        """Stem of the template-owned base file: talker_base.py / talker_base.hpp."""
        return self.name + layout.BASE_SUFFIX

    @property
    def user_file(self) -> str:
        """The user-owned source file, relative to the package folder."""
        return layout.user_file(self.package, self.name, self.ros, self.language)

    @property
    def base_file(self) -> str:
        """The template-owned base class file, relative to the package folder."""
        return layout.base_file(self.package, self.name, self.ros, self.language)

    @property
    def config_file(self) -> str:
        return layout.config_file(self.name)

    @property
    def executable(self) -> str:
        return layout.executable(self.name, self.ros, self.language)

    @property
    def starts_itself(self) -> bool:
        """A lifecycle node that configures and activates itself when its AUTOSTART_PARAMETER is true.

        A component, since no launch_ros action drives a node loaded into a container; and a node
        answered autostart, whose launch file sets it where the distro's launch_ros cannot drive
        the node in that format (rna.launch_features.autostart_form)."""
        return self.lifecycle and (self.component or self.autostart)

    def parameter_rules(self, parameter: Parameter) -> tuple[str, ...]:
        """The rules a parameter's values keep, in words (rna.parameters.rules)."""
        return parameter_rules.rules(parameter, self.ros)

    def parameter_comment(self, parameter: Parameter) -> str:
        """The config file's comment above a parameter: its description and rules."""
        return parameter_rules.comment(parameter, self.ros)

    def parameter_checks(self, parameter: Parameter) -> tuple[tuple[str, str], ...]:
        """(rule, reason) of each rule the node's own code checks (rna.parameters.checks)."""
        return parameter_rules.checks(parameter, self.ros)

    @property
    def checks_parameters(self) -> bool:
        """The base class itself checks rules of some parameter (beyond ROS 2's ranges and read-only)."""
        return any(self.parameter_checks(parameter) for parameter in self.parameters)

    @property
    def on_set_parameters(self) -> bool:
        """A ROS 2 base class has an on-set parameters callback: to refuse a set that breaks a rule,
        or, where no post-set callback follows a set (Humble), to update its view of them."""
        return self.ros == 2 and bool(self.parameters) and (self.checks_parameters or not self.post_set_callbacks)

    @property
    def diagnostics_members(self) -> tuple[str, ...]:
        """Members the base class declares for the diagnostics updater (ROS 1 drives it by a timer)."""
        if not self.diagnostics:
            return ()
        return ("updater", "diagnostics_timer") if self.ros == 1 else ("updater",)

    @property
    def test_file(self) -> str:
        """The node's unit test (ROS 2), relative to the package folder."""
        return layout.node_test(self.name, self.language)

    @property
    def test_target(self) -> str:
        """The CMake test (and gtest executable) of the node's unit test: the file's stem."""
        return self.test_file.rsplit("/", 1)[-1].rsplit(".", 1)[0]

    def resolved(self, name: str, namespace: str = "/") -> str:
        """A topic, service or action name of this node as the ROS graph lists it."""
        return names.fully_qualified(name, self.name, namespace)

    def launched(self, name: str, namespace: str = "/") -> str:
        """A name of this node as the graph lists it once the launch file's remappings apply.

        A rule matches the name both resolve to (ROS 1 and 2 alike expand a rule's relative
        and private names in the node's namespace); the first rule that matches wins.
        """
        resolved = self.resolved(name, namespace)
        for source, target in self.remappings:
            if self.resolved(source, namespace) == resolved:
                return self.resolved(target, namespace)
        return resolved

    def graph_entries(self, endpoints, namespace: str = "/",
                      launched: bool = False) -> tuple[tuple[str, str], ...]:
        """(name, type) of each endpoint as graph queries list them: ('/chatter', 'std_msgs/msg/String');
        `launched`: as the launch file starts the node, remapped."""
        resolve = self.launched if launched else self.resolved
        return tuple((resolve(e.topic if isinstance(e, Topic) else e.name, namespace), e.type.full_name)
                     for e in endpoints)

    @property
    def callback_endpoints(self) -> tuple:
        """The endpoints with callbacks an executor runs, which callback groups can hold."""
        return (self.subscribers + self.service_servers + self.service_clients + self.action_servers
                + self.action_clients + self.timers)

    def callback_group(self, endpoint) -> CallbackGroup | None:
        """The group an endpoint's callbacks are in, or None: the node's default group."""
        return next((group for group in self.callback_groups if endpoint in group.members), None)

    @property
    def grouped_endpoints(self) -> tuple:
        """The endpoints in a callback group of their own."""
        return tuple(endpoint for group in self.callback_groups for endpoint in group.members)

    @property
    def multi_threaded(self) -> bool:
        return self.executor == "multi_threaded"

    def goal_topics(self, actions, namespace: str = "/", launched: bool = False) -> tuple[tuple[str, str], ...]:
        """ROS 1: (name, type) of each action's goal topic, which actionlib's server subscribes to."""
        return tuple((f"{name}/goal", f"{type_name}ActionGoal")
                     for name, type_name in self.graph_entries(actions, namespace, launched))

    def goal_services(self, actions, namespace: str = "/", launched: bool = False) -> tuple[tuple[str, str], ...]:
        """(name, type) of each action's goal service (ROS 2), which rclcpp's graph queries list."""
        return tuple((f"{name}/_action/send_goal", f"{type_name}_SendGoal")
                     for name, type_name in self.graph_entries(actions, namespace, launched))

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

    @property
    def driver_timer(self) -> Timer | None:
        """The timer whose starter code publishes and calls: the first one, if it has work."""
        if self.timers and (self.publishers or self.service_clients or self.action_clients):
            return self.timers[0]
        return None

    @property
    def starter_log_throttle(self) -> float | None:
        """Seconds between the starter code's "Publishing" logs when its timer fires faster than
        twice a second (a control loop logs once a second, not on every tick) or it relays a
        sensor stream, else None."""
        fast_timer = self.driver_timer and self.driver_timer.period < 0.5
        return 1.0 if fast_timer or (self.relay and self.relay.starter_log_throttle) else None

    @property
    def relay(self) -> Topic | None:
        """The subscription whose starter callback publishes, in a node with publishers and no timer.

        A node that turns what it hears into what it says (a detector between a camera and
        a controller) then passes data along a chain of generated nodes with no code added.
        """
        return self.subscribers[0] if self.publishers and not self.timers and self.subscribers else None

    @property
    def message_variables(self) -> dict[Topic, str]:
        """The starter code's variable for each publisher's message: `msg`, or `<id>_msg` for
        several, or beside the `msg` a relay subscription's callback receives."""
        if len(self.publishers) == 1 and not self.relay:
            return {self.publishers[0]: "msg"}
        return {topic: f"{topic.id}_msg" for topic in self.publishers}

    @property
    def starter_built_messages(self) -> tuple[Topic, ...]:
        """The publishers whose messages the starter code builds; a relay passes on a message of its own type."""
        if not self.starter_publishes:
            return ()
        return tuple(t for t in self.publishers if not (self.relay and t.type == self.relay.type))

    @property
    def starter_publishes(self) -> bool:
        """The starter code publishes: from the driving timer, or from the relay subscription."""
        return bool(self.publishers) and bool(self.driver_timer or self.relay)

    @property
    def starter_counter(self) -> str:
        """The member the starter code counts its messages in: `count`, unless the node has a use for it."""
        taken = {*BASE_MEMBERS, *(e.member for e in self.endpoints), *(p.name for p in self.parameters)}
        candidates = itertools.chain(["count"], (f"count{n}" for n in itertools.count(2)))
        return next(name for name in candidates if name not in taken)

    @property
    def starter_interfaces(self) -> tuple[InterfaceType, ...]:
        """The interface types the starter code in the user's file names, sorted, each once."""
        used = [action.type for action in self.action_servers] + [t.type for t in self.starter_built_messages]
        if self.driver_timer:
            used += [endpoint.type for endpoint in self.service_clients + self.action_clients]
        return tuple(sorted(set(used), key=lambda t: t.full_name))

    @property
    def features(self) -> frozenset[str]:
        return features.node_features(self)

    @property
    def dependencies(self) -> tuple[str, ...]:
        """ROS packages the node's code uses, sorted."""
        return tuple(sorted({t.package for t in self.interfaces} | features.packages(self)))


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
    launch_format: str = layout.DEFAULT_LAUNCH_FORMAT  # ROS 2: or "python", "yaml"
    # The lab's own (extensions/lab.yml): dependencies of every package, header lines, files.
    lab_dependencies: tuple[tuple[str, str], ...] = ()
    lab_header: str = ""
    lab_files: tuple[dict, ...] = ()

    @property
    def ros(self) -> int:
        return distros.generation(self.ros_distro)

    @property
    def autostart_form(self) -> str:
        """How its launch file has an autostart lifecycle node configured and activated:
        "launch_ros" or "parameter" (rna.launch_features.autostart_form)."""
        return launch_features.autostart_form(self.ros_distro, self.launch_format) if self.ros == 2 else "parameter"

    def intra_process(self, node: Node) -> bool:
        """A component whose messages a container passes by pointer: the launch file loads it with
        use_intra_process_comms, which every QoS of its topics allows (qos.intra_process_error)."""
        return node.component and not any(intra_process_error(topic.qos, self.ros_distro)
                                           for topic in node.publishers + node.subscribers)

    @property
    def tests_own_graph(self) -> bool:
        """Its node unit tests can switch discovery off (distros.DISCOVERY_OFF_DISTROS).

        rmw_dds_common answers a graph query by node name with the first node of that name in
        the domain, whichever process holds it: a robot, a simulation, another package's test.
        """
        return self.ros_distro in distros.DISCOVERY_OFF_DISTROS

    @property
    def dir(self) -> str:
        """The package folder within the destination: the destination itself for a node."""
        return layout.package_dir(self.name, self.target)

    @property
    def launch_file(self) -> str:
        return layout.launch_file(self.name, self.ros, self.launch_format)

    @property
    def launch_arguments(self) -> tuple[LaunchArgument, ...]:
        return LAUNCH_ARGUMENTS if self.ros == 2 else ROS1_LAUNCH_ARGUMENTS

    @property
    def container_executable(self) -> str:
        """The component container the launch file loads components into by default: a
        multi-threaded one when a component's answers give it a multi-threaded executor."""
        threaded = any(node.component and node.multi_threaded for node in self.nodes)
        return "component_container_mt" if threaded else "component_container"

    @property
    def launch_file_name(self) -> str:
        """What `ros2 launch <package>` / `roslaunch <package>` is given."""
        return posixpath.basename(self.launch_file)

    @property
    def launch_glob(self) -> str:
        """What setup.py installs from launch/: the launch file in any format, and the user's own."""
        return layout.LAUNCH_GLOB

    @property
    def launch_test_file(self) -> str:
        """The test that starts the launch file and checks the graph: launch_testing, or a rostest file."""
        return layout.launch_test(self.name, self.ros)

    @property
    def graph_test_script(self) -> str:
        """ROS 1: the script the rostest file runs to check the graph."""
        return layout.graph_test_script(self.name)

    @property
    def test_dependencies(self) -> tuple[str, ...]:
        """package.xml's <test_depend>s: the generated tests' packages the nodes do not already need."""
        wanted = set(features.TEST_PACKAGES[self.build_type])
        if self.build_type == "ament_cmake":
            wanted |= {"ament_cmake_gtest"} if self.cpp_nodes else set()
            wanted |= {"ament_cmake_pytest"} if self.python_nodes else set()
        return tuple(sorted(wanted - {dependency.name for dependency in self.dependencies}))

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

    @property
    def python_init_file(self) -> str:
        """The Python package's __init__.py within the package folder, or "" without Python code."""
        return f"{layout.python_package_dir(self.name, self.ros)}/__init__.py" if self.python_dir else ""

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
        """The definitions of one kind, sorted by name as catkin_lint wants the FILES lists that name them."""
        return tuple(sorted((d for d in self.definitions if d.kind == kind), key=lambda d: d.name))

    @property
    def interface_dependencies(self) -> tuple[str, ...]:
        """Packages the generated interfaces need, sorted."""
        deps = {package for definition in self.definitions for package in definition.packages}
        if self.definitions_of("action"):
            deps |= {"actionlib_msgs", "std_msgs"} if self.ros == 1 else {"action_msgs"}
        return tuple(sorted(deps))

    @property
    def named_inside_a_dependency(self) -> bool:
        """Whether a dependency's name holds the package's (std_srvs holds `vs`): catkin_lint takes
        it for the package's name written out instead of ${PROJECT_NAME}, a false notice."""
        names = {dependency.name for dependency in self.dependencies} | set(self.interface_dependencies)
        return any(self.name in name for name in names - {self.interfaces_package})

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
    def lab_extra_dependencies(self) -> tuple[tuple[str, str], ...]:
        """(tag, package) the lab adds that the nodes do not already depend on."""
        named = {dependency.name for dependency in self.dependencies}
        return tuple((tag, name) for tag, name in self.lab_dependencies if name not in named and name != self.name)

    @property
    def cpp_dependencies(self) -> tuple[str, ...]:
        return tuple(dep.name for dep in self.dependencies if dep.build)

    @property
    def copyright_line(self) -> str:
        return f"Copyright {self.copyright_year} {self.copyright_holder}"

    def header(self, comment: str) -> str:
        """The copyright and license comment block that starts each source file, then the lab's lines."""
        block = self.license.header(self.copyright_line, comment)
        if self.lab_header:
            block += f"\n{comment}\n" + "\n".join(f"{comment} {line}".rstrip() for line in self.lab_header.splitlines())
        return block

    @property
    def license_text(self) -> str:
        return self.license.text(self.copyright_line)
