"""ROS 2 C++ (rclcpp): types, headers, QoS, timer periods, parameter descriptors, CMake targets."""

from __future__ import annotations

from .. import names
from ..wording import threads_text
from .cpp import CppDialect, number
from .lines import BREAK

# The CMake targets of the client libraries; other packages export ${<pkg>_TARGETS}.
_CMAKE_TARGETS = {
    "rclcpp": "rclcpp::rclcpp",
    "rclcpp_action": "rclcpp_action::rclcpp_action",
    "rclcpp_components": "rclcpp_components::component",
    "rclcpp_lifecycle": "rclcpp_lifecycle::rclcpp_lifecycle",
}


_EXECUTOR_CLASSES = {
    "single_threaded": "rclcpp::executors::SingleThreadedExecutor",
    "multi_threaded": "rclcpp::executors::MultiThreadedExecutor",
    "static": "rclcpp::executors::StaticSingleThreadedExecutor",
    "events": "rclcpp::experimental::executors::EventsExecutor",
}


class Ros2Cpp(CppDialect):
    HEADER_EXTENSION = "hpp"

    @staticmethod
    def header(interface) -> str:
        return f"{interface.package}/{interface.kind}/{names.camel_to_snake(interface.name)}.hpp"

    @staticmethod
    def full_type(interface) -> str:
        return f"{interface.package}::{interface.kind}::{interface.name}"

    def part(self, interface, part: str) -> str:
        """A service's Request/Response or an action's Goal/Result/Feedback type."""
        return f"{self.type(interface)}::{part}"

    @property
    def aliases(self) -> list[tuple[str, str]]:
        """(alias, what it names) for each `using` of the base class."""
        node = self.node
        aliases = [(self.type(t), self.full_type(t)) for t in node.interfaces]
        for action in node.action_servers + node.action_clients:
            kind = "ServerGoalHandle" if action.role == "server" else "ClientGoalHandle"
            alias = (self.goal_handle(action), f"rclcpp_action::{kind}<{self.type(action.type)}>")
            if alias not in aliases:  # two servers (or clients) of one type share it
                aliases.append(alias)
        if node.lifecycle:
            aliases.append(("CallbackReturn",
                            "rclcpp_lifecycle::node_interfaces::LifecycleNodeInterface::CallbackReturn"))
        return aliases

    @property
    def executor(self) -> str:
        """The declaration of the executor the base class's spin() spins the node on."""
        node = self.node
        if node.multi_threaded and node.threads:
            return f"rclcpp::executors::MultiThreadedExecutor executor(rclcpp::ExecutorOptions(), {node.threads});"
        return f"{_EXECUTOR_CLASSES[node.executor]} executor;"

    @property
    def executor_text(self) -> str:
        """The executor, in words."""
        node = self.node
        if node.multi_threaded:
            return f"a multi-threaded executor with {threads_text(node)}"
        return {"single_threaded": "a single-threaded executor",
                "static": "a static single-threaded executor (its entities fixed once it spins)",
                "events": "rclcpp's experimental events executor"}[node.executor]

    @property
    def component_executor(self) -> str:
        """What rclcpp_components_register_node's EXECUTOR names for a component's executable, or ''."""
        return "" if self.node.executor == "single_threaded" else _EXECUTOR_CLASSES[self.node.executor].rsplit(
            "::", 1)[-1]

    @property
    def header_guard(self) -> str:
        return f"{self.node.package}__{self.node.base_name}_HPP_".upper()

    def goal_handle(self, action) -> str:
        """The alias the base class declares for the goal handle type of an action server or client."""
        return self.type(action.type) + ("GoalHandle" if action.role == "server" else "ClientGoalHandle")

    @staticmethod
    def qos(qos) -> str:
        """The QoS argument: a depth, rclcpp's preset class, or rclcpp::QoS with its policies set."""
        if qos.profile:
            return {"sensor_data": "rclcpp::SensorDataQoS()", "system_default": "rclcpp::SystemDefaultsQoS()"}[
                qos.profile]
        if qos.is_plain:
            return str(qos.depth)
        text = "rclcpp::QoS(rclcpp::KeepAll())" if qos.history == "keep_all" else f"rclcpp::QoS({qos.depth})"
        return (text + (".best_effort()" if qos.reliability == "best_effort" else "")
                + (".transient_local()" if qos.durability == "transient_local" else ""))

    @staticmethod
    def period(timer) -> str:
        """The period as a std::chrono duration with an exact integer count."""
        for unit, scale in (("seconds", 1), ("milliseconds", 1e3), ("microseconds", 1e6)):
            count = timer.period * scale
            if abs(count - round(count)) < 1e-9 * scale:
                return f"std::chrono::{unit}({round(count)})"
        return f"std::chrono::nanoseconds({round(timer.period * 1e9)})"

    def descriptor(self, parameter, name: str = "descriptor") -> str:
        """Statements that fill a ParameterDescriptor named `name` (4-space indented)."""
        lines = [f"rcl_interfaces::msg::ParameterDescriptor {name};"]
        if parameter.description:
            lines.append(f"{name}.description ={BREAK} {self.string(parameter.description, split=True)};")
        if parameter.read_only:
            lines.append(f"{name}.read_only = true;")
        if parameter.range:
            low, high, step = parameter.range
            kind = parameter.range_kind
            lines += [f"{name}.{kind}.resize(1);",
                      f"{name}.{kind}[0].from_value = {number(low)};",
                      f"{name}.{kind}[0].to_value = {number(high)};",
                      f"{name}.{kind}[0].step = {number(step)};"]
        return "\n    ".join(lines)

    @property
    def cmake_targets(self) -> list[str]:
        """What the node's target links: the client library targets, ${<pkg>_TARGETS} otherwise."""
        # The package's own interfaces: rosidl_get_typesupport_target() names them.
        own = '"${cpp_typesupport_target}"'
        return [own if dep == self.node.package else _CMAKE_TARGETS.get(dep, f"${{{dep}_TARGETS}}")
                for dep in self.node.dependencies]
