"""ROS 2 Python (rclpy): imports, QoS, parameter descriptors and the starter code's samples."""

from __future__ import annotations

from ..wording import threads_text
from .lines import BREAK
from .python import PythonDialect, import_block, literal


class Ros2Python(PythonDialect):
    @property
    def base_imports(self) -> str:
        """Imports of the generated <node>_base.py."""
        return import_block([*(self._import(t) for t in self.node.interfaces), *self._needs("base")])

    @property
    def node_imports(self) -> str:
        """Imports of the user's <node>.py: what its starter code uses."""
        node = self.node
        return import_block([*self._needs("user"), f"{self.base_module}:{node.base_class_name}",
                             f"{self.base_module}:run", *(self._import(t) for t in node.starter_interfaces)])

    @property
    def executor(self) -> str:
        """The executor run() spins the node on, as made in the base module."""
        node = self.node
        if node.multi_threaded:
            return f"MultiThreadedExecutor(num_threads={node.threads})" if node.threads else "MultiThreadedExecutor()"
        return "SingleThreadedExecutor()"

    @property
    def executor_text(self) -> str:
        """The executor, in words."""
        node = self.node
        if not node.multi_threaded:
            return "a single-threaded executor, in the thread that calls run()"
        return f"a multi-threaded executor with {threads_text(node)}"

    def test_imports(self, discovery_off: bool) -> str:
        """Imports of the node's unit test (test/test_node_<node>.py); `discovery_off`: its
        context starts with ROS_AUTOMATIC_DISCOVERY_RANGE patched into os.environ."""
        node = self.node
        environment = ["os", "unittest:mock"] if discovery_off else []
        actions = [f"rclpy.action:get_action_{role}_names_and_types_by_node"
                   for role in ("client", "server") if getattr(node, f"action_{role}s")]
        return import_block([*environment, "pytest", "rclpy", *actions,
                             f"{node.package}.{node.name}:{node.class_name}"])

    @staticmethod
    def qos(qos) -> str:
        """The qos_profile argument when it is a depth or one of rclpy's preset profiles, else ''."""
        if qos.profile:
            return f"qos_profile_{qos.profile}"
        return str(qos.depth) if qos.is_plain else ""

    def qos_arg(self, topic) -> str:
        """The qos_profile argument of a topic: a depth, a preset, or the QoSProfile built before."""
        return self.qos(topic.qos) or f"{topic.id}_qos"

    @staticmethod
    def qos_statement(topic) -> str:
        """The statement building a topic's QoSProfile, where a depth or a preset does not say it; else ''."""
        qos = topic.qos
        if qos.profile or qos.is_plain:
            return ""
        fields = ["history=HistoryPolicy.KEEP_ALL" if qos.history == "keep_all" else f"depth={qos.depth}"]
        if qos.reliability != "reliable":
            fields.append(f"reliability=ReliabilityPolicy.{qos.reliability.upper()}")
        if qos.durability != "volatile":
            fields.append(f"durability=DurabilityPolicy.{qos.durability.upper()}")
        return f"{topic.id}_qos = QoSProfile({BREAK}" + f",{BREAK} ".join(fields) + ")"

    @staticmethod
    def period(timer) -> str:
        return str(timer.period)

    @staticmethod
    def descriptor(parameter, indent: int = 12) -> str:
        """The ParameterDescriptor argument of declare_parameter(), one field per line."""
        fields = []
        if parameter.description:
            fields.append(f"description={literal(parameter.description, split=True)}")
        if parameter.read_only:
            fields.append("read_only=True")
        if parameter.range:
            low, high, step = (literal(value) for value in parameter.range)
            range_class = "IntegerRange" if parameter.range_kind == "integer_range" else "FloatingPointRange"
            inner = " " * (indent + 8)
            bounds = f"from_value={low}, to_value={high}, step={step}"
            # The range ends the descriptor and the call: ')]))' must fit 99 columns too.
            if len(inner) + len(range_class) + len(bounds) + 5 > 99:
                bounds = f"\n{inner}    " + f",\n{inner}    ".join(bounds.split(", "))
            fields.append(f"{parameter.range_kind}=[\n{inner}{range_class}({bounds})]")
        pad = " " * (indent + 4)
        return "ParameterDescriptor(\n" + ",\n".join(pad + field for field in fields) + ")"
