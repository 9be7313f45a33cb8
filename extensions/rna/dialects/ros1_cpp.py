"""ROS 1 C++ (roscpp): types and headers of messages, and parameter types of the parameter server."""

from __future__ import annotations

from ..wording import threads_text
from .cpp import _SCALARS, CppDialect


class Ros1Cpp(CppDialect):
    HEADER_EXTENSION = "h"
    # roscpp's parameter server keeps integers as int (XmlRpc).
    SCALARS = {**_SCALARS, "int": "int"}

    @property
    def executor_text(self) -> str:
        """How the node's callbacks are handled, in words."""
        node = self.node
        if not node.multi_threaded:
            return "one thread (ros::spin())"
        return f"a ros::MultiThreadedSpinner of {threads_text(node)}"

    @staticmethod
    def header(interface) -> str:
        suffix = "Action" if interface.kind == "action" else ""
        return f"{interface.package}/{interface.name}{suffix}.h"

    # The types ROS 1 generates for an action, each aliased in the base class.
    ACTION_PARTS = ("Action", "Goal", "Result", "Feedback")

    def type(self, interface) -> str:
        """The alias of a message or service, or of an action's FooAction type."""
        return self.alias_names[interface] + ("Action" if interface.kind == "action" else "")

    def part(self, interface, part: str) -> str:
        """A service's Request/Response, an action's Goal/Result/Feedback type, or their ConstPtr."""
        if interface.kind == "srv":
            return f"{self.type(interface)}::{part}"
        stem, pointer = part.removesuffix("ConstPtr"), part.endswith("ConstPtr")
        return self.alias_names[interface] + stem + ("::ConstPtr" if pointer else "")

    @property
    def aliases(self) -> list[tuple[str, str]]:
        """(alias, what it names) for each `using` of the base class."""
        aliases = []
        for interface in self.node.interfaces:
            alias, full = self.alias_names[interface], f"{interface.package}::{interface.name}"
            parts = self.ACTION_PARTS if interface.kind == "action" else ("",)
            aliases += [(alias + part, full + part) for part in parts]
        return aliases

    @property
    def header_guard(self) -> str:
        """cpplint's style (ROS 2's too), so the same style checks pass on both generations."""
        return f"{self.node.package}__{self.node.base_name}_H_".upper()

    @staticmethod
    def period(timer) -> str:
        return str(timer.period)
