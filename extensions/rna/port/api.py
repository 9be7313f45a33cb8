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
    Member("parameter", "self.{name}", "self.params.{name}",
           "a ROS 1 node keeps each parameter in a member; a ROS 2 node's base class keeps their current "
           "values in self.params"),
)

# The constructor: ROS 2's base class takes Node's keyword arguments and passes them on.
PYTHON_CONSTRUCTOR = (("def __init__(self):", "def __init__(self, **kwargs):"),
                      ("super().__init__()", "super().__init__(**kwargs)"))


@dataclass(frozen=True)
class CppCallback:
    """A virtual method of the C++ base class the user's class overrides.

    Its ROS 2 declaration is the new base class's (or starter's), with the user's names
    put back where `ros2` keeps them; `uses` rewrites what the body does with a parameter
    whose type changed (a ConstPtr that is a reference now, a reference that is a
    shared_ptr now): (index of the ROS 1 parameter, pattern with {name}, replacement).
    """

    endpoint: str
    method: str
    ros1: tuple[str, ...]
    ros2: tuple[str, ...]
    prologue: tuple[str, ...] = ()  # per ROS 1 parameter, "" for none
    uses: tuple[tuple[int, str, str], ...] = ()
    note: str = ""


_ARROW = (r"\b{name}\s*->\s*", "{name}.")
_DEREFERENCED = (r"(?<![\w)\]])\*\s*{name}\b", "{name}")
_DOT = (r"\b{name}\s*\.\s*", "{name}->")
CPP_CALLBACKS = (
    CppCallback("timer", "on_{id}", ("event",), (), note="(void)event goes; other uses are marked TODO(port)"),
    CppCallback("subscriber", "on_{id}", ("msg",), ("{0}",), uses=((0, *_ARROW), (0, *_DEREFERENCED)),
                note="a const reference instead of a ConstPtr: msg->x is msg.x"),
    CppCallback("service_server", "on_{id}_request", ("request", "response"), ("{0}", "{1}"),
                uses=((0, *_DOT), (1, *_DOT)),
                note="shared_ptrs instead of references, returning void: return true is return, "
                     "return false is marked (a ROS 2 service cannot fail)"),
    CppCallback("service_client", "on_{id}_response", ("response",), ("{0}",), uses=((0, *_DOT),),
                note="a shared_ptr instead of a reference"),
    CppCallback("action_server", "execute_{id}", ("goal",), ("goal_handle",),
                ("const auto {0} = goal_handle->get_goal();",),
                note="the action server's calls in it go to goal_handle"),
    CppCallback("action_client", "on_{id}_feedback", ("feedback",), ("{0}",)),
    CppCallback("action_client", "on_{id}_result", ("state", "result"), ("wrapped_result",),
                ("", "const auto {1} = wrapped_result.result;"),
                note="state == SimpleClientGoalState::SUCCEEDED is wrapped_result.code == ResultCode::SUCCEEDED"),
)

CPP_MEMBERS = (
    Member("publisher", "{id}_publisher_.publish(msg)", "{id}_publisher_->publish(msg)"),
    Member("subscriber", "{id}_subscriber_", "{id}_subscription_", "rclcpp's class is a Subscription"),
    Member("timer", "{id}_timer_.stop(), .start()", "{id}_timer_->cancel(), ->reset()"),
    Member("service_client", "{id}_client_.exists()", "{id}_client_->service_is_ready()"),
    Member("service_call", "call_{id}(request)", "call_{id}(std::make_shared<Type::Request>(request))"),
    Member("action_client", "{id}_action_client_.isServerConnected()",
           "{id}_action_client_->action_server_is_ready()"),
    Member("action_server", "{id}_action_server_.setSucceeded(result), .setAborted, .setPreempted, "
           ".publishFeedback(feedback), .isPreemptRequested()",
           "goal_handle->succeed(result), ->abort, ->canceled (results and feedback as shared_ptrs), "
           "->publish_feedback(feedback), ->is_canceling()"),
    Member("parameter", "{name}_", "params().{name}",
           "a ROS 1 node keeps each parameter in a member; a ROS 2 node's base class keeps their current "
           "values in params()"),
)
# The constructor takes rclcpp's NodeOptions and passes them to the base class.
CPP_CONSTRUCTOR = ("Driver()", "explicit Driver(const rclcpp::NodeOptions & options = rclcpp::NodeOptions())\n"
                   "  : DriverBase(options)")
# ROS 2's accessor of a parameter's value, by the parameter's type.
CPP_PARAMETER_ACCESSORS = {"bool": "as_bool", "int": "as_int", "double": "as_double", "string": "as_string",
                           "bool[]": "as_bool_array", "int[]": "as_integer_array", "double[]": "as_double_array",
                           "string[]": "as_string_array"}


def parameter_read(language: str, name: str) -> str:
    """How ROS 2 code reads the node's parameter `name`: the base class's typed, current view."""
    return f"self.params.{name}" if language == "python" else f"params().{name}"


EXECUTE_CALLS = "py.api.action_server.calls"


def key(language: str, callback) -> str:
    """The rule key of a callback's entry: py.api.subscriber.on_x."""
    return f"{'py' if language == 'python' else 'cpp'}.api.{callback.endpoint}.{callback.method.replace('{id}', 'x')}"


def callbacks(language: str) -> tuple:
    return PYTHON_CALLBACKS if language == "python" else CPP_CALLBACKS


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
        found.append(Rule(key("python", callback), "Python", ros1, ros2, callback.note))
    found.append(Rule(EXECUTE_CALLS, "Python", "self.<id>_action_server.set_succeeded(result), set_aborted, "
                      "set_preempted, publish_feedback(feedback), is_preempt_requested() in execute_<id>",
                      "goal_handle.succeed() and return result, abort(), canceled(), publish_feedback(feedback), "
                      "is_cancel_requested"))
    for member in PYTHON_MEMBERS:
        found.append(Rule(f"py.api.{member.endpoint}", "Python", member.ros1.replace("{id}", "<id>").replace(
            "{name}", "<parameter>"), member.ros2.replace("{id}", "<id>").replace("{name}", "<parameter>"),
            member.note))
    found.append(Rule("py.api.constructor", "Python", " ".join(old for old, _ in PYTHON_CONSTRUCTOR),
                      " ".join(new for _, new in PYTHON_CONSTRUCTOR)))
    for callback in CPP_CALLBACKS:
        method = callback.method.replace("{id}", "<id>")
        ros2 = [name.format(*callback.ros1) for name in callback.ros2]
        lines = [line.format(*callback.ros1) for line in callback.prologue if line]
        found.append(Rule(key("cpp", callback), "C++",
                          f"{method}({', '.join(callback.ros1)})",
                          f"{method}({', '.join(ros2)})" + (": " + " ".join(lines) if lines else ""), callback.note))
    for member in CPP_MEMBERS:
        found.append(Rule(f"cpp.api.{member.endpoint}", "C++", member.ros1.replace("{id}", "<id>").replace(
            "{name}", "<parameter>"), member.ros2.replace("{id}", "<id>").replace("{name}", "<parameter>"),
            member.note))
    found.append(Rule("cpp.api.constructor", "C++", "Node()", "explicit Node(const rclcpp::NodeOptions & options = "
                      "rclcpp::NodeOptions()) : NodeBase(options)"))
    return tuple(found)


RULES = rules()
BY_KEY = {rule.key: rule for rule in RULES}
