"""How generated code is spelled: one module per dialect, the only place that spells code.

A dialect is bound to one node and answers everything its templates need: the include
or import blocks, the name of each interface type, QoS, timer periods, parameter types
and literals, and the text of the starter code. Shared spellings of a language live in
`cpp` and `python`; `ros2_cpp`, `ros2_python`, `ros1_cpp` and `ros1_python` are the
dialects.
"""

from __future__ import annotations

from .ros1_cpp import Ros1Cpp
from .ros1_python import Ros1Python
from .ros2_cpp import Ros2Cpp
from .ros2_python import Ros2Python

DIALECTS = {(2, "cpp"): Ros2Cpp, (2, "python"): Ros2Python, (1, "cpp"): Ros1Cpp, (1, "python"): Ros1Python}


def dialect(node):
    """The dialect that spells this node's code."""
    return DIALECTS[(node.ros, node.language)](node)


__all__ = ["DIALECTS", "Ros1Cpp", "Ros1Python", "Ros2Cpp", "Ros2Python", "dialect"]
