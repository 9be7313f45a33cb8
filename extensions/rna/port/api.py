"""The base-class API a node's code calls, ROS 1 -> ROS 2: the one table of it.

A node's file subclasses its generated base class and overrides its callbacks, calls its
members (publishers, clients...) and reads its parameters. Both generations' base classes
give these the same names and meanings; where ROS 2 passes something else (a future
instead of a response, a goal handle instead of a goal) the ported callback gets ROS 2's
parameters and starts with the lines that give the user's ROS 1 names their meaning back
(`response = future.result()`), so the body the user wrote reads the same.

In a callback's entry, `ros2` names its ROS 2 parameters: `{0}` is the name the user's
code gives the first ROS 1 parameter (kept), any other name is ROS 2's. `prologue` lines
set each ROS 1 parameter the body uses from the ROS 2 ones.
"""

from __future__ import annotations

from dataclasses import dataclass

from .rule import Rule


@dataclass(frozen=True)
class Callback:
    """A method the base class calls and the user's class overrides, in one language."""

    endpoint: str  # what the model calls it: timer, subscriber, service_server, ...
    method: str  # the name, `{id}` being the endpoint's
    ros1: tuple[str, ...]  # its parameters in ROS 1 (after self), as the starter names them
    ros2: tuple[str, ...]  # in ROS 2: `{0}`... keep the user's names of the ROS 1 parameters
    prologue: tuple[str, ...] = ()  # `{0} = future.result()`: one per ROS 1 parameter, in order
    note: str = ""


PYTHON_CALLBACKS = (
    Callback("timer", "on_{id}", ("event",), (), note="uses of the event are marked TODO(port)"),
    Callback("subscriber", "on_{id}", ("msg",), ("{0}",)),
    Callback("service_server", "on_{id}_request", ("request",), ("{0}", "response"),
             note="the response the method returns is sent, as in ROS 1"),
    Callback("service_client", "on_{id}_response", ("response",), ("future",), ("{0} = future.result()",)),
    Callback("action_server", "execute_{id}", ("goal",), ("goal_handle",), ("{0} = goal_handle.request",),
             note="the action server's calls in it go to goal_handle, and it returns the result"),
    Callback("action_client", "on_{id}_feedback", ("feedback",), ("feedback_msg",),
             ("{0} = feedback_msg.feedback",)),
    Callback("action_client", "on_{id}_result", ("status", "result"), ("future",),
             ("{0} = future.result().status", "{1} = future.result().result")),
)


@dataclass(frozen=True)
class Member:
    """A member of the base class the user's code uses, renamed or called otherwise in ROS 2."""

    endpoint: str
    ros1: str  # `{id}_subscriber`
    ros2: str
    note: str = ""


PYTHON_MEMBERS = (
    Member("subscriber", "self.{id}_subscriber", "self.{id}_subscription", "rclpy's class is a Subscription"),
    Member("timer", "self.{id}_timer.shutdown()", "self.{id}_timer.cancel()"),
    Member("parameter", "self.{name}", "self.get_parameter('{name}').value",
           "a ROS 1 node keeps each parameter in a member; a ROS 2 node asks for its current value"),
)

# The constructor: ROS 2's base class takes Node's keyword arguments and passes them on.
PYTHON_CONSTRUCTOR = (("def __init__(self):", "def __init__(self, **kwargs):"),
                      ("super().__init__()", "super().__init__(**kwargs)"))


def parameter_read(language: str, name: str, ros2_type: str = "") -> str:
    """How ROS 2 code reads the node's parameter `name` (the base class's parameter view)."""
    if language == "python":
        return f"self.get_parameter('{name}').value"
    return f'get_parameter("{name}").{ros2_type}()'


def callbacks(language: str) -> tuple[Callback, ...]:
    return PYTHON_CALLBACKS


def rules() -> tuple[Rule, ...]:
    """The table above as rules, for the summary and the docs."""
    found = []
    for callback in PYTHON_CALLBACKS:
        ros1 = f"def {callback.method}(self, {', '.join(callback.ros1)})".replace("{id}", "<id>")
        ros2_names = [name.format(*callback.ros1) for name in callback.ros2]
        ros2 = f"def {callback.method}(self{''.join(', ' + n for n in ros2_names)})".replace("{id}", "<id>")
        lines = [line.format(*callback.ros1) for line in callback.prologue]
        if lines:
            ros2 += ": " + "; ".join(lines)
        found.append(Rule(f"py.api.{callback.method.replace('{id}', 'x')}", "Python", ros1, ros2, callback.note))
    for member in PYTHON_MEMBERS:
        found.append(Rule(f"py.api.{member.endpoint}", "Python", member.ros1.replace("{id}", "<id>").replace(
            "{name}", "<parameter>"), member.ros2.replace("{id}", "<id>").replace("{name}", "<parameter>"),
            member.note))
    found.append(Rule("py.api.constructor", "Python", " ".join(old for old, _ in PYTHON_CONSTRUCTOR),
                      " ".join(new for _, new in PYTHON_CONSTRUCTOR)))
    return tuple(found)


RULES = rules()
BY_KEY = {rule.key: rule for rule in RULES}
