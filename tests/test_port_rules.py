"""The port's rules (extensions/rna/port), as pure functions of text: each rule, and properties.

A rewriter's promise: every ROS 1 call a rule names is rewritten to ROS 2's; every other
ROS 1 line is left as it was under a TODO(port) comment; every line naming no ROS 1 thing
is kept as written; the result is code that reads (Python parses), and porting it again
changes nothing. Drawn files (hypothesis) of common ROS 1 statements hold the rewriters to
that; the examples below pin each rule's spelling.
"""

from __future__ import annotations

import ast
import re
import sys

import pytest
from hypothesis import given
from hypothesis import strategies as st

from rna.port import api, build, code, cpp, dependencies, python, rules
from support.generation import ROOT

sys.path.insert(0, str(ROOT / "docs" / "hooks"))
import reference  # noqa: E402 - the docs' hook, which renders the rule table

NODE = python.Context(
    base_class="TalkerBase", logger="talker", parameters=frozenset({"rate"}), subscribers=frozenset({"chatter"}),
    timers=frozenset({"timer"}), service_clients=frozenset({"reset"}), action_clients=frozenset({"dock"}),
    action_results=(("approach", "Approach.Result"),),
    callbacks=tuple((callback.method.format(id=endpoint), callback) for kind, endpoint in (
        ("timer", "timer"), ("subscriber", "chatter"), ("service_server", "reset"), ("service_client", "reset"),
        ("action_server", "approach"), ("action_client", "dock")) for callback in api.PYTHON_CALLBACKS
        if callback.endpoint == kind),
    kinds={("std_srvs", "Trigger"): "srv", ("my_msgs", "Approach"): "action", ("my_msgs", "Dock"): "action",
           ("std_msgs", "String"): "msg"})


def in_node(body: str, method: str = "on_timer(self, event)") -> str:
    """`body` (statements, 8 columns in) in a method of the node's class."""
    return f"import rospy\n\n\nclass Talker(TalkerBase):\n    def {method}:\n{body}"


def ported_body(body: str, method: str = "on_timer(self, event)") -> str:
    """The ported method's body (the lines after its def line)."""
    lines = python.port(in_node(body, method), NODE).text.split("\n")
    start = next(index for index, line in enumerate(lines) if line.startswith("    def "))
    return "\n".join(lines[start + 1:])


# --- Python, rule by rule

@pytest.mark.parametrize(("ros1", "ros2"), [
    ("rospy.loginfo('x')", "self.get_logger().info('x')"),
    ("rospy.logwarn('gain %s', self.rate)", "self.get_logger().warning(f\"gain {self.get_parameter('rate').value}\")"),
    ("rospy.logerr('%.2f m', d)", "self.get_logger().error(f'{d:.2f} m')"),
    ("rospy.logdebug('%d of %d', a, b)", "self.get_logger().debug('%d of %d' % (a, b))"),
    ("rospy.loginfo_throttle(2.0, 'x %s', a)", "self.get_logger().info(f'x {a}', throttle_duration_sec=2.0)"),
    ("rospy.logfatal_once('x')", "self.get_logger().fatal('x', once=True)"),
    ("t = rospy.Time.now()", "t = self.get_clock().now()"),
    ("msg.header.stamp = rospy.Time.now()", "msg.header.stamp = self.get_clock().now().to_msg()"),
    ("s = rospy.get_time()", "s = self.get_clock().now().nanoseconds / 1e9"),
    ("d = rospy.Duration(1, 5)", "d = Duration(seconds=1, nanoseconds=5)"),
    ("d = rospy.Duration.from_sec(0.5)", "d = Duration(seconds=0.5)"),
    ("s = (now - then).to_sec()", "s = (now - then).nanoseconds / 1e9"),
    ("s = msg.header.stamp.to_sec()", "s = Time.from_msg(msg.header.stamp).nanoseconds / 1e9"),
    ("n = msg.header.stamp.secs", "n = msg.header.stamp.sec"),
    ("age = (rospy.Time.now() - msg.header.stamp).to_sec()",
     "age = (self.get_clock().now() - Time.from_msg(msg.header.stamp)).nanoseconds / 1e9"),
    ("old = msg.header.stamp < self.last", "old = Time.from_msg(msg.header.stamp) < self.last"),
    ("msg.header.stamp = rospy.Time.now() + rospy.Duration(0.5)",
     "msg.header.stamp = (self.get_clock().now() + Duration(seconds=0.5)).to_msg()"),
    ("out.header.stamp = msg.header.stamp", "out.header.stamp = msg.header.stamp"),
    ("now = rospy.Time.now()\n        msg.header.stamp = now",
     "now = self.get_clock().now()\n        msg.header.stamp = now.to_msg()"),
    ("now = 3\n        msg.header.stamp = now", "now = 3\n        msg.header.stamp = now"),
    ("rospy.sleep(0.5)", "time.sleep(0.5)"),
    ("rospy.sleep(rospy.Duration(2))", "time.sleep(2)"),
    ("rate = rospy.Rate(10)", "rate = self.create_rate(10)"),
    ("go = not rospy.is_shutdown()", "go = self.context.ok()"),
    ("stop = rospy.is_shutdown()", "stop = not self.context.ok()"),
    ("rospy.on_shutdown(self.stop)", "self.context.on_shutdown(self.stop)"),
    ("p = rospy.Publisher('out', String, queue_size=5)", "p = self.create_publisher(String, 'out', 5)"),
    ("s = rospy.Subscriber('in', String, self.got)", "s = self.create_subscription(String, 'in', self.got, 10)"),
    ("t = rospy.Timer(rospy.Duration(0.1), self.tick)", "t = self.create_timer(0.1, self.tick)"),
    ("r = rospy.get_param('~rate', 2.0)", "r = self.get_parameter('rate').value"),
    ("r = self.rate * 2", "r = self.get_parameter('rate').value * 2"),
    ("self.chatter_subscriber.unregister()", "self.chatter_subscription.unregister()"),
    ("self.timer_timer.shutdown()", "self.timer_timer.cancel()"),
    ("self.dock_action_client.wait_for_server(rospy.Duration(0.1))",
     "self.dock_action_client.wait_for_server(timeout_sec=0.1)"),
    ("self.reset_client.wait_for_service(timeout=2)", "self.reset_client.wait_for_service(timeout_sec=2)"),
])
def test_each_python_rule(ros1, ros2):
    assert ported_body(f"        {ros1}\n").strip() == ros2


@pytest.mark.parametrize(("ros1", "rule"), [
    ("rospy.set_param('x', 1)", "py.todo.global_param"),
    ("v = rospy.get_param('/x')", "py.todo.global_param"),
    ("v = rospy.get_param('~undeclared', 1)", "py.todo.param"),
    ("n = msg.header.seq", "py.todo.header_seq"),
    ("rospy.wait_for_service('reset')", "py.todo.service_call"),
    ("answer = self.reset_client(request)", "py.todo.service_call"),
    ("self.rate = 3.0", "py.todo.global_param"),
    ("rospy.spin()", "py.todo.main"),
    ("m = rospy.wait_for_message('x', String)", "py.todo.wait_for_message"),
    ("rospy.Subscriber('in', String, self.got, callback_args=1)", "py.todo.callback_args"),
    ("x = rospy.something_new()", "py.todo.other"),
    ("print(event.current_real)", "py.todo.timer_event"),
])
def test_a_line_no_rule_rewrites_stays_marked(ros1, rule):
    ported = python.port(in_node(f"        {ros1}\n"), NODE)
    assert [key for _, key in ported.todos] == [rule]
    lines = ported.text.split("\n")
    index = next(i for i, line in enumerate(lines) if line.strip() == ros1.strip())
    above = "\n".join(lines[max(0, index - 3):index])
    assert "# TODO(port): " in above and rules.rule(rule).ros2.split()[0] in above, ported.text


def test_callbacks_take_ros2_parameters_and_give_the_users_names_their_meaning_back():
    text = python.port(
        "import rospy\n\n\nclass Talker(TalkerBase):\n"
        "    def on_reset_response(self, answer):\n        \"\"\"Mine.\"\"\"\n        print(answer.success)\n\n"
        "    def on_dock_result(self, status, result):\n        print(status)\n\n"
        "    def on_dock_feedback(self, feedback):\n        print(feedback.left)\n\n"
        "    def on_reset_request(self, request):\n        return make(request)\n\n"
        "    def __init__(self):\n        super().__init__()\n", NODE).text
    assert "def on_reset_response(self, future):\n        \"\"\"Mine.\"\"\"\n        answer = future.result()\n" in text
    assert "def on_dock_result(self, future):\n        status = future.result().status\n        print" in text
    assert "result = future.result().result" not in text  # unused: no line for it (flake8 F841)
    assert "def on_dock_feedback(self, feedback_msg):\n        feedback = feedback_msg.feedback\n" in text
    assert "def on_reset_request(self, request, response):" in text
    assert "def __init__(self, **kwargs):\n        super().__init__(**kwargs)" in text


def test_the_action_servers_calls_go_to_the_goal_handle():
    body = ("        server = self.approach_action_server\n"
            "        for _ in range(3):\n"
            "            if server.is_preempt_requested():\n"
            "                server.set_preempted()\n"
            "                return\n"
            "            server.publish_feedback(fb)\n"
            "        server.set_succeeded(ApproachResult(reached=True))\n")
    text = python.port(in_node(body, "execute_approach(self, goal)"), NODE).text
    assert "server =" not in text
    assert "def execute_approach(self, goal_handle):" in text
    assert ("            if goal_handle.is_cancel_requested:\n                goal_handle.canceled()\n"
            "                return Approach.Result()\n") in text
    assert "goal_handle.publish_feedback(fb)" in text
    assert "        goal_handle.succeed()\n        return ApproachResult(reached=True)" in text


def test_types_and_imports():
    text = python.port("import rospy\nfrom actionlib_msgs.msg import GoalStatus\n"
                       "from my_msgs.msg import ApproachGoal, Target\nfrom std_srvs.srv import TriggerResponse\n\n"
                       "g = ApproachGoal(distance=1)\nr = TriggerResponse()\nok = s == GoalStatus.SUCCEEDED\n",
                       python.Context(kinds=NODE.kinds)).text
    assert text == ("from action_msgs.msg import GoalStatus\nfrom my_msgs.action import Approach\n"
                    "from my_msgs.msg import Target\nfrom std_srvs.srv import Trigger\n\n"
                    "g = Approach.Goal(distance=1)\nr = Trigger.Response()\nok = s == GoalStatus.STATUS_SUCCEEDED\n")


def test_code_outside_the_node_logs_to_a_named_logger_and_imports_what_it_uses():
    text = python.port('"""Helpers."""\n\nimport rospy\n\n\ndef warn(x):\n    rospy.logwarn(\'x=%s\', x)\n'
                       "    return rospy.Time.now()\n", python.Context(logger="robot")).text
    assert text == ('"""Helpers."""\n\nfrom rclpy.clock import Clock\nfrom rclpy.logging import get_logger\n\n\n'
                    "def warn(x):\n    get_logger('robot').warning(f'x={x}')\n    return Clock().now()\n")


LONG_LOG = ("        self.get_logger().info(f\"talker says {msg.data} after {elapsed:.1f} s at "
            "{self.get_parameter('rate').value} Hz\")")


@pytest.mark.parametrize(("line", "broken"), [
    (LONG_LOG, ["        self.get_logger().info(",
                "            f\"talker says {msg.data} after {elapsed:.1f} s at {self.get_parameter('rate').value} \"",
                "            'Hz')"]),
    ("        self.get_logger().info(f'mover got target at x={msg.x:.1f} in {msg.header.frame_id} (stamped)')",
     ["        self.get_logger().info(",
      "            f'mover got target at x={msg.x:.1f} in {msg.header.frame_id} (stamped)')"]),
    # no call: after its first bracket that holds something; a block's header 8 deeper (flake8 E125)
    ("        age_of_the_target = (self.get_clock().now() - Time.from_msg(msg.header.stamp)).nanoseconds / 1e9",
     ["        age_of_the_target = (",
      "            self.get_clock().now() - Time.from_msg(msg.header.stamp)).nanoseconds / 1e9"]),
    ("        while self.context.ok() and Time.from_msg(msg.header.stamp) < self.last_stamp_of_the_targets:",
     ["        while self.context.ok() and Time.from_msg(",
      "                msg.header.stamp) < self.last_stamp_of_the_targets:"]),
])
def test_a_rewrite_longer_than_flake8s_lines_is_broken_as_ros2_code_is(line, broken):
    assert python.wrapped(line, set()).split("\n") == broken


def test_a_long_line_stays_when_it_was_the_users_or_has_no_place_to_break():
    assert python.wrapped(LONG_LOG, {LONG_LOG}) == LONG_LOG  # as long before the port: the user's
    unbreakable = "        x = " + "y" * 95
    assert python.wrapped(unbreakable, set()) == unbreakable


def test_a_file_that_is_not_python_is_marked_at_its_top():
    ported = python.port("def broken(:\n", NODE)
    assert ported.text.startswith("# TODO(port): this file is not Python") and len(ported.todos) == 1


# --- Python, drawn files

NAMES = st.sampled_from(["a", "value", "msg.data", "self.count", "x.y"])
NUMBERS = st.sampled_from(["0.5", "1", "2.0", "10"])
FORMATS = st.sampled_from(["'plain'", "'one %s'", "'two %s and %.2f'", "'%d items'", "\"it's %s\"", "'100%% %s'"])


@st.composite
def ros1_statement(draw) -> str:
    kind = draw(st.integers(0, 13))
    if kind == 0:
        fmt = draw(FORMATS)
        count = len(re.findall(r"%[^%]", fmt.replace("%%", "")))
        args = "".join(", " + draw(NAMES) for _ in range(count))
        level = draw(st.sampled_from(["debug", "info", "warn", "err", "fatal"]))
        form = draw(st.sampled_from(["", "_once", "_throttle"]))
        period = f"{draw(NUMBERS)}, " if form == "_throttle" else ""
        return f"rospy.log{level}{form}({period}{fmt}{args})"
    return draw(st.sampled_from([
        "t = rospy.Time.now()", "msg.header.stamp = rospy.Time.now()", f"d = rospy.Duration({draw(NUMBERS)})",
        f"rospy.sleep({draw(NUMBERS)})", f"s = {draw(NAMES)}.to_sec()", "if rospy.is_shutdown():\n    return",
        "v = rospy.get_param('~rate', 1.0)", "rospy.set_param('x', 1)", f"y = {draw(NAMES)} + 1",
        "rate = rospy.Rate(5)", "print(msg.header.seq)", "rospy.some_call()", "rospy.spin()",
        "age_of_the_last_target_seen = (rospy.Time.now() - msg.header.stamp).to_sec()",
    ]))


@st.composite
def ros1_files(draw) -> str:
    statements = draw(st.lists(ros1_statement(), min_size=1, max_size=8))
    body = "".join("".join(f"        {line}\n" for line in statement.split("\n")) for statement in statements)
    helper = "".join("".join(f"    {line}\n" for line in statement.split("\n")) for statement in
                     draw(st.lists(ros1_statement(), max_size=3))) or "    pass\n"
    return (f"import rospy\nimport math  # mine\n\n\nclass Talker(TalkerBase):\n    def on_timer(self, event):\n"
            f"{body}\n\ndef helper(x):\n{helper}")


ROS1_NAMES = re.compile(r"\brospy\b")


@given(ros1_files())
def test_drawn_python_ports_to_python_with_every_ros1_line_marked_and_the_rest_kept(text):
    ported = python.port(text, NODE)
    ast.parse(ported.text)  # reads as Python
    lines = ported.text.split("\n")
    assert all(len(line) <= python.WIDTH for line in lines if line not in text.split("\n")), ported.text
    for index, line in enumerate(lines):
        if ROS1_NAMES.search(line) and not line.lstrip().startswith("#"):
            above = [previous for previous in lines[:index] if previous.strip()][-3:]
            assert any("TODO(port)" in previous for previous in above), f"unmarked: {line}\n{ported.text}"
    kept = [line for line in text.split("\n") if line.strip() and not ROS1_NAMES.search(line)
            and ".to_sec()" not in line and "self.rate" not in line and "event" not in line and ".seq" not in line]
    assert [line for line in kept if line not in lines] == [], ported.text
    assert len([line for line in lines if "TODO(port)" in line and line.strip().startswith("# TODO")]) >= len(
        {line for line, _ in ported.todos})
    again = python.port(ported.text, NODE)
    assert again.text == ported.text and not again.rewrites, "a second port changed the file"


# --- C++

CPP = cpp.Context(
    class_name="Talker", base_class="TalkerBase", logger="talker", parameters=(("rate", "as_double"),),
    publishers=frozenset({"chatter"}), subscribers=frozenset({"odom"}), timers=frozenset({"timer"}),
    service_clients=(("reset", "Trigger"),), action_clients=frozenset({"dock"}),
    kinds={("std_msgs", "String"): "msg", ("std_srvs", "Trigger"): "srv", ("nav_msgs", "Odometry"): "msg"})


def cpp_in_node(body: str) -> str:
    return f"class Talker : public TalkerBase\n{{\nprotected:\n  void work()\n  {{\n{body}  }}\n}};\n"


@pytest.mark.parametrize(("ros1", "ros2"), [
    ('ROS_INFO("x %d", a);', 'RCLCPP_INFO(get_logger(), "x %d", a);'),
    ('ROS_WARN_STREAM("x " << a);', 'RCLCPP_WARN_STREAM(get_logger(), "x " << a);'),
    ('ROS_ERROR_THROTTLE(2.0, "x");', 'RCLCPP_ERROR_THROTTLE(get_logger(), *get_clock(), 2000, "x");'),
    ('ROS_INFO_ONCE("x");', 'RCLCPP_INFO_ONCE(get_logger(), "x");'),
    ('ROS_DEBUG_COND(a > 1, "x");', 'RCLCPP_DEBUG_EXPRESSION(get_logger(), a > 1, "x");'),
    ("auto t = ros::Time::now();", "auto t = now();"),
    ("auto d = ros::Duration(0.5);", "auto d = rclcpp::Duration::from_seconds(0.5);"),
    ("ros::Duration(0.25).sleep();", "rclcpp::sleep_for(std::chrono::milliseconds(250));"),
    ("ros::Rate rate(10.0);", "rclcpp::Rate rate(10.0);"),
    ("while (ros::ok()) {}", "while (rclcpp::ok()) {}"),
    ("double s = t.toSec();", "double s = t.seconds();"),
    ("double s = msg.header.stamp.toSec();", "double s = rclcpp::Time(msg.header.stamp).seconds();"),
    ("double a = (ros::Time::now() - msg->header.stamp).toSec();",
     "double a = (now() - rclcpp::Time(msg->header.stamp)).seconds();"),
    ("bool old = msgs[0].header.stamp < last;", "bool old = rclcpp::Time(msgs[0].header.stamp) < last;"),
    ("auto t = msg->header.stamp + ros::Duration(1.0);",
     "auto t = rclcpp::Time(msg->header.stamp) + rclcpp::Duration::from_seconds(1.0);"),
    ("uint32_t n = msg.header.stamp.nsec;", "uint32_t n = msg.header.stamp.nanosec;"),
    ("msg.header.stamp = ros::Time::now();", "msg.header.stamp = now();"),
    ("ros::Time now = ros::Time::now();", "rclcpp::Time now = this->now();"),
    ("out->header.stamp = msg->header.stamp;", "out->header.stamp = msg->header.stamp;"),
    ("chatter_publisher_.publish(msg);", "chatter_publisher_->publish(msg);"),
    ("if (reset_client_.exists()) {}", "if (reset_client_->service_is_ready()) {}"),
    ("call_reset(Trigger::Request());", "call_reset(std::make_shared<Trigger::Request>());"),
    ("if (dock_action_client_.isServerConnected()) {}", "if (dock_action_client_->action_server_is_ready()) {}"),
    ("double r = rate_ * 2;", 'double r = get_parameter("rate").as_double() * 2;'),
    ("std_msgs::String s;", "std_msgs::msg::String s;"),
    ("std_srvs::TriggerRequest r;", "std_srvs::srv::Trigger::Request r;"),
    ("nav_msgs::Odometry::ConstPtr o;", "nav_msgs::msg::Odometry::ConstSharedPtr o;"),
    ("boost::shared_ptr<int> p;", "std::shared_ptr<int> p;"),
])
def test_each_cpp_rule(ros1, ros2):
    text = cpp.port(cpp_in_node(f"    {ros1}\n"), CPP).text
    assert f"    {ros2}\n" in text, text


@pytest.mark.parametrize(("ros1", "rule"), [
    ("ros::NodeHandle nh;", "cpp.todo.node_handle"),
    ("rate_ = 3.0;", "cpp.todo.parameter_written"),
    ("reset_client_.call(srv);", "cpp.todo.service_call"),
    ("ros::spinOnce();", "cpp.todo.main"),
    ('ros::param::set("/speed", 1.0);', "cpp.todo.global_param"),
    ("auto t = ros::Time(1.5);", "cpp.todo.time"),
    ("ros::master::check();", "cpp.todo.other"),
])
def test_a_cpp_line_no_rule_rewrites_stays_marked(ros1, rule):
    ported = cpp.port(cpp_in_node(f"    {ros1}\n"), CPP)
    assert [key for _, key in ported.todos] == [rule], ported.todos
    assert f"    // TODO(port): {rules.rule(rule).ros2.split()[0]}" in ported.text and ros1 in ported.text


def test_a_cpp_rewrite_longer_than_cpplints_lines_is_broken_as_uncrustify_wants():
    body = ('    ROS_INFO("talker says %s after %.1f s at %.1f Hz", msg.data.c_str(), elapsed, rate_hz);\n'
            '    ROS_INFO(\n      "mover got target at x=%.1f in %s (stamped %.3f, %.3f s ago), and more", msg->x);\n'
            '    ROS_WARN("a message long enough to need cutting once it is ported, with more words than fit");\n'
            '    ROS_INFO_STREAM("the rate is now, as the parameter says it is, in hertz, about: " << hz << " Hz");\n'
            "    double r = std::max(ros::Time::now().toSec(), 1.0) + std::min(ros::Time::now().toSec(), 2.0);\n")
    ported = cpp.port(cpp_in_node(body), CPP)
    assert ported.text == cpp_in_node(
        "    RCLCPP_INFO(\n"
        '      get_logger(), "talker says %s after %.1f s at %.1f Hz", msg.data.c_str(), elapsed, rate_hz);\n'
        "    RCLCPP_INFO(\n"
        "      get_logger(),\n"
        '      "mover got target at x=%.1f in %s (stamped %.3f, %.3f s ago), and more", msg->x);\n'
        "    RCLCPP_WARN(\n"
        '      get_logger(), "a message long enough to need cutting once it is ported, with more words than "\n'
        '      "fit");\n'
        "    RCLCPP_INFO_STREAM(\n"
        '      get_logger(), "the rate is now, as the parameter says it is, in hertz, about: " << hz <<\n'
        '        " Hz");\n'
        "    double r = std::max(now().seconds(), 1.0) + std::min(now().seconds(), 2.0);\n"), ported.text
    long = "    " + "x" * 100 + "();"
    assert cpp.wrapped(long, {long}) == long  # as long before the port: the user's
    sum_of_calls = "    double r = std::max(" + "a" * 50 + ", 1.0) + std::min(" + "b" * 50 + ", 2.0);"
    # no call the statement ends with (uncrustify breaks an expression otherwise): left as it is
    assert cpp.wrapped(sum_of_calls, set()) == sum_of_calls


def test_each_line_is_listed_once_from_what_it_was_to_what_it_is():
    ported = cpp.port(cpp_in_node('    ROS_INFO("at %f", ros::Time::now().toSec());\n'), CPP)
    assert [(r.rule, r.before, r.after) for r in ported.rewrites] == [
        ("cpp.now, cpp.to_sec, cpp.log", 'ROS_INFO("at %f", ros::Time::now().toSec());',
         'RCLCPP_INFO(get_logger(), "at %f", now().seconds());')]


def test_a_statement_over_several_lines_is_marked_above_its_first_line():
    """Marked inside its call's arguments, a port of the ported file would mark it again once the call is
    broken (found on ros_tutorials' turtlesim: a port of a ported file changed it)."""
    body = ("    ros::Timer timer = nh.createTimer(ros::Duration(0.016), boost::bind(&Talker::tick, this, "
            "boost::placeholders::_1));\n")
    ported = cpp.port(cpp_in_node(body), CPP)
    assert ported.text == cpp_in_node(
        "    // TODO(port): write it with rclcpp\n"
        "    ros::Timer timer = nh.createTimer(\n"
        "      rclcpp::Duration::from_seconds(0.016),\n"
        "      boost::bind(&Talker::tick, this, boost::placeholders::_1));\n"), ported.text
    assert cpp.port(ported.text, CPP).text == ported.text


def test_cpp_includes():
    text = cpp.port('#include "ros/ros.h"\n#include "std_msgs/String.h"\n#include "std_srvs/Trigger.h"\n'
                    '#include <actionlib/client/simple_action_client.h>\n#include <vector>\n', CPP).text
    assert text == ('#include "rclcpp/rclcpp.hpp"\n#include "std_msgs/msg/string.hpp"\n'
                    '#include "std_srvs/srv/trigger.hpp"\n#include <vector>\n')


@st.composite
def cpp_files(draw) -> str:
    statements = draw(st.lists(st.sampled_from([
        'ROS_INFO("n %d", count_);', 'ROS_WARN_STREAM("x " << x);', 'ROS_INFO_THROTTLE(1.0, "t");',
        "auto t = ros::Time::now();", "ros::Duration(0.1).sleep();", "if (!ros::ok()) { return; }",
        "chatter_publisher_.publish(msg);", "double r = rate_;", "ros::NodeHandle nh;", "int mine = 3;  // mine",
        'ROS_INFO("a message of %s, long enough to need a break once ported: %.2f", name.c_str(), rate_);',
        "double age = (ros::Time::now() - msg->header.stamp).toSec();",
        'std::string s = "ros::ok() in a string";', "// ros::spin() in a comment",
    ]), min_size=1, max_size=8))
    return cpp_in_node("".join(f"    {statement}\n" for statement in statements))


@given(cpp_files())
def test_drawn_cpp_is_ported_with_every_ros1_line_marked_and_the_rest_kept(text):
    ported = cpp.port(text, CPP)
    code_only = cpp.mask(ported.text)
    assert code_only.count("(") == code_only.count(")") and code_only.count("{") == code_only.count("}")
    lines, masked = ported.text.split("\n"), code_only.split("\n")
    for index, line in enumerate(masked):
        if re.search(r"\bros::|\bROS_[A-Z]", line):
            assert "TODO(port)" in "\n".join(lines[max(0, index - 3):index]), f"unmarked: {lines[index]}"
    for mine in ("int mine = 3;  // mine", '"ros::ok() in a string"', "// ros::spin() in a comment"):
        assert mine not in text or mine in ported.text, ported.text
    assert all(len(line) <= cpp.WIDTH for line in lines if line not in text.split("\n")), ported.text
    assert cpp.port(ported.text, CPP).text == ported.text, "a second port changed the file"


# --- build files, launch, config

def test_cmake_commands_of_the_user():
    context = build.CMakeContext("robot", ("driver",), frozenset({"rclcpp"}))
    lines, rewrites, todos = build.port_cmake_lines([
        "find_package(catkin REQUIRED COMPONENTS roscpp tf sensor_msgs)",
        "target_link_libraries(${PROJECT_NAME}_driver ${catkin_LIBRARIES} yaml-cpp)",
        "add_dependencies(${PROJECT_NAME}_driver ${catkin_EXPORTED_TARGETS})",
        "install(DIRECTORY maps DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})",
        "catkin_install_python(PROGRAMS scripts/tool.py",
        "  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})",
        "add_rostest(test/my.test)",
        "find_package(Eigen3 REQUIRED)",
    ], 10, context)
    assert lines == [
        "find_package(tf2_ros REQUIRED)", "find_package(sensor_msgs REQUIRED)",
        "target_link_libraries(driver PRIVATE yaml-cpp)",
        "install(DIRECTORY maps DESTINATION share/${PROJECT_NAME})",
        "install(PROGRAMS scripts/tool.py", "  DESTINATION lib/${PROJECT_NAME})",
        "# TODO(port): add_launch_test() (launch_testing_ament_cmake)", "# add_rostest(test/my.test)",
        "find_package(Eigen3 REQUIRED)"]
    assert todos == 1 and len(rewrites) == 5 and rewrites[0].startswith("line 10: ")


def test_user_lines_go_after_the_same_blocks_end_in_ros2():
    generated = "a\n# BEGIN rna-template: x\nroscpp\n# END rna-template: add your own targets below\nb\n"
    mine = generated.replace("below\n", "below\nadd_executable(tool src/tool.cpp)\n")
    fresh = "z\n# BEGIN rna-template: y\nrclcpp\n# END rna-template: add your own targets below\nw\nament_package()\n"
    carried = build.carry_cmake(mine, generated, fresh, build.CMakeContext("robot", ()))
    assert carried.text == fresh.replace("below\n", "below\nadd_executable(tool src/tool.cpp)\n")


def test_package_xml_dependencies_are_named_as_ros2_names_them():
    lines, rewrites, todos = build.port_package_xml_lines(
        ["  <depend>roscpp</depend>", "  <exec_depend>rviz</exec_depend>", "  <depend>dynamic_reconfigure</depend>",
         "  <depend>eigen</depend>", "  <buildtool_depend>catkin</buildtool_depend>"], 1, ("cpp",))
    assert lines == ["  <depend>rclcpp</depend>", "  <exec_depend>rviz2</exec_depend>",
                     "  <!-- TODO(port): dynamic_reconfigure: ROS 2 parameters take its place -->",
                     "  <!-- (add_on_set_parameters_callback) -->", "  <!-- <depend>dynamic_reconfigure</depend> -->",
                     "  <depend>eigen</depend>"]
    assert todos == 1 and len(rewrites) == 3


def test_roslaunch_lines_as_ros2_xml():
    context = build.LaunchContext("robot", (("monitor.py", "monitor"),), launch_files=(("sim.launch",
                                                                                          "sim.launch.xml"),))
    lines, rewrites, todos = build.port_launch_lines([
        '<node pkg="robot" type="monitor.py" name="m" ns="a" required="true">',
        '  <rosparam command="load" file="$(find robot)/config/m.yaml"/>',
        '  <param name="gain" value="2" type="double"/>',
        "</node>",
        '<param name="use_sim_time" value="true"/>',
        '<include file="$(find robot)/launch/sim.launch"/>',
        '<include file="$(find other)/launch/x.launch"/>',
        '<group ns="left">',
        "</group>",
    ], 1, context)
    assert lines[:4] == [
        '<node pkg="robot" exec="monitor" name="m" namespace="a" on_exit="shutdown">',
        '  <param from="$(find-pkg-share robot)/config/m.yaml"/>', '  <param name="gain" value="2"/>', "</node>"]
    assert '<set_parameter name="use_sim_time" value="true"/>' in lines
    assert '<include file="$(find-pkg-share robot)/launch/sim.launch.xml"/>' in lines
    assert '<include file="$(find other)/launch/x.launch"/>' in lines and todos == 1
    assert '<group>' in lines and '  <push-ros-namespace namespace="left"/>' in lines


def test_config_in_ros__parameters_form():
    ros1 = "# heading\n# more\n# Work rate in Hz\nrate: 1.5\n\nmine: 2  # tuned\n"
    assert build.ros2_config(ros1, 2) == (
        "# heading\n# more\n/**:\n  ros__parameters:\n    # Work rate in Hz\n    rate: 1.5\n\n    mine: 2  # tuned\n")
    assert build.ros2_config("# heading\n{}\n", 1) == "# heading\n/**:\n  ros__parameters: {}\n"


def test_dependencies():
    assert dependencies.ros2_names("roscpp") == ("rclcpp",)
    assert dependencies.ros2_names("actionlib", ("python",)) == ("rclpy",)
    assert dependencies.ros2_names("actionlib", ("cpp", "python")) == ("rclcpp_action", "rclpy")
    assert dependencies.ros2_names("geometry_msgs") == ("geometry_msgs",)
    assert dependencies.ros2_names("dynamic_reconfigure") is None


TIMER_NODE = python.Context(base_class="TBase", callbacks=tuple(
    (c.method.format(id="timer"), c) for c in api.PYTHON_CALLBACKS if c.endpoint == "timer"))


def test_a_node_file_keeps_the_users_method_whole():
    old = "import rospy\n\n\nclass T(TBase):\n    def on_timer(self, event):\n        a()\n        b()\n"
    new = "import rclpy\n\n\nclass T(TBase):\n    def on_timer(self):\n        b()\n        a()\n"
    mine = old.replace("        a()\n        b()\n", "        c()\n")
    result = code.port_python(mine, old, new, TIMER_NODE)
    assert result.text == "import rclpy\n\n\nclass T(TBase):\n    def on_timer(self):\n        c()\n"
    assert not result.conflicted


def test_a_starter_line_no_rule_ports_in_a_users_method_is_counted():
    """The user's method is theirs whole, the ROS 1 starter's lines in it too: one no rule ports is an item."""
    old = "import rospy\n\n\nclass T(TBase):\n    def on_timer(self, event):\n        rospy.starter_call()\n"
    new = "import rclpy\n\n\nclass T(TBase):\n    def on_timer(self):\n        pass\n"
    mine = old.replace("        rospy.starter_call()\n", "        rospy.starter_call()\n        c()\n")
    result = code.port_python(mine, old, new, TIMER_NODE)
    assert "# TODO(port)" in result.text and result.todos == 1, result.text


# --- the one table

def test_every_rule_a_rewriter_names_is_in_the_table():
    sources = "\n".join(path.read_text() for path in (ROOT / "extensions" / "rna" / "port").glob("*.py"))
    sources += (ROOT / "extensions" / "rna" / "update" / "port.py").read_text()
    named = set(re.findall(r"\"((?:py|cpp|cmake|xml|launch|config)\.[a-z_]+(?:\.[a-z_]+)*)\"", sources))
    named -= {"py.api", "cpp.api"}  # prefixes of keys made from the API table
    assert named - set(rules.BY_KEY) == set()
    assert len(rules.BY_KEY) == len(rules.RULES), "two rules share a key"


def test_the_docs_show_every_rule():
    table = reference.port_rules_table()
    assert all(f"`{rule.key}`" in table for rule in rules.RULES)
    page = (ROOT / "docs" / "pages" / "reference" / "port-rules.md").read_text()
    assert "<!-- rna: port rules -->" in page
