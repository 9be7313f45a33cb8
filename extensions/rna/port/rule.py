"""One rewrite of the port, ROS 1 form -> ROS 2 form (rna.port.rules holds the table)."""

from __future__ import annotations

from dataclasses import dataclass

TODO = "TODO(port)"


@dataclass(frozen=True)
class Rule:
    key: str
    language: str  # Python, C++, CMake, package.xml, launch, config
    ros1: str  # the ROS 1 form, as written in code
    ros2: str  # what it becomes; for a `todo` rule, the ROS 2 equivalent the TODO names
    note: str = ""
    todo: bool = False

    @property
    def comment(self) -> str:
        """The text of a TODO(port) comment naming this rule's ROS 2 equivalent."""
        return f"{TODO}: {self.ros2}" + (f" ({self.note})" if self.note else "")
