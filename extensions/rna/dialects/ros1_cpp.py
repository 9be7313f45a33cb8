"""ROS 1 C++ (roscpp): types and headers of messages, and parameter types of the parameter server."""

from __future__ import annotations

from .cpp import _SCALARS, CppDialect


class Ros1Cpp(CppDialect):
    HEADER_EXTENSION = "h"
    # roscpp's parameter server keeps integers as int (XmlRpc).
    SCALARS = {**_SCALARS, "int": "int"}

    @staticmethod
    def header(interface) -> str:
        suffix = "Action" if interface.kind == "action" else ""
        return f"{interface.package}/{interface.name}{suffix}.h"

    @staticmethod
    def type(interface) -> str:
        suffix = "Action" if interface.kind == "action" else ""
        return f"{interface.package}::{interface.name}{suffix}"

    @staticmethod
    def part(interface, part: str) -> str:
        """A service's Request/Response or an action's Goal/Result/Feedback type (and their ConstPtr)."""
        return f"{interface.package}::{interface.name}{part}"

    @property
    def header_guard(self) -> str:
        return f"{self.node.package}_{self.node.base_name}_H".upper()

    @staticmethod
    def period(timer) -> str:
        return str(timer.period)
