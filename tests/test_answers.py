"""The answers: every rule the model enforces has a failing case, and the short forms work."""

from __future__ import annotations

import copy

import pytest
import yaml
from rna import AnswerError, Answers, build_package, question_error
from rna.answers import check_given
from rna.dialects import dialect
from support.generation import ROOT, VALID


def answers(**changes):
    result = copy.deepcopy(VALID)
    result.update(changes)
    return result


def node(**fields):
    return answers(nodes=[{"name": "driver", **fields}])


def error_of(values) -> AnswerError:
    with pytest.raises(AnswerError) as caught:
        build_package(values)
    return caught.value


BROKEN = [
    # (answers, question, rule)
    (answers(package_name="My-Bad Pkg"), "package_name", "REP 144"),
    (answers(description=""), "description", "one line"),
    (answers(maintainer="a\nb"), "maintainer", "one line"),
    (answers(maintainer_email="ada"), "maintainer_email", "not an e-mail address"),
    (answers(license="WTFPL"), "license", "is not one of"),
    (answers(copyright_holder=" "), "copyright_holder", "one line"),
    (answers(copyright_year="soon"), "copyright_year", "not a year"),
    (answers(ros_distro="foxy"), "ros_distro", "is not one of"),
    (answers(build_type="catkin"), "build_type", "for ROS 2"),
    (answers(launch_format="json"), "launch_format", "'json' is not one of xml, python, yaml"),
    (answers(ros_distro="noetic", build_type="catkin", launch_format="yaml"), "launch_format",
     "roslaunch (ROS 1) reads XML launch files only: yaml is for ROS 2"),
    (answers(nodes=[]), "nodes", "at least one node"),
    (answers(nodes="- name: [unclosed"), "nodes", "not valid YAML"),
    (answers(nodes=[{"name": "Driver"}]), "nodes", "lower_snake_case"),
    (answers(nodes=[["driver"]]), "nodes", "write each node as a mapping"),
    (answers(nodes=[{"language": "python"}]), "nodes", "give a node name"),
    (node(publishers={"topic": "chatter"}), "nodes", "write publishers as a list"),
    (node(publishers=[["chatter", "std_msgs/msg/String"]]), "nodes", "write a publisher as 'topic:type'"),
    (node(service_servers=[3]), "nodes", "write a service server as 'name:type'"),
    (answers(nodes=[{"name": "a"}, {"name": "a"}]), "nodes", "node 'a' and node 'a' both use the name 'a'"),
    (answers(nodes=[{"name": "a", "publisher": []}]), "nodes", "did you mean 'publishers'"),
    (node(language="rust"), "nodes", "use cpp or python: language 'rust' is neither"),
    (answers(build_type="ament_python", nodes=[{"name": "a", "language": "cpp"}]), "nodes", "Python nodes only"),
    (node(component=True, language="python"), "nodes", "components are C++ nodes"),
    (node(lifecycle="yes"), "nodes", "true or false"),
    (node(diagnostics="yes"), "nodes", "set diagnostics to true or false"),
    (node(diagnostics=True, timers=["diagnostics:1"]), "nodes", "the diagnostics updater"),
    (node(autostart=True), "nodes", "autostart is for lifecycle nodes"),
    (answers(ros_distro="humble", nodes=[{"name": "a", "lifecycle": True, "autostart": True,
                                          "parameters": ["autostart=true"]}]), "nodes",
     "the parameter a lifecycle node starts itself by and parameter 'autostart'"),
    (node(description="two\nlines"), "nodes", "one line"),
    (node(publishers=["chatter"]), "nodes", "write it as topic:type"),
    (node(publishers=["bad topic:std_msgs/msg/String"]), "nodes", "letters, digits and '_'"),
    (node(publishers=["chatter:std_srvs/srv/Trigger"]), "nodes",
     "give a message type here: 'std_srvs/srv/Trigger' is a service type"),
    (node(publishers=["chatter:std_msgs/msg/String:fast"]), "nodes", "give qos as a history depth"),
    (node(publishers=[{"topic": "chatter", "type": "std_msgs/msg/String", "qos": 0}]), "nodes", "between 1 and 10000"),
    (node(publishers=["chatter:std_msgs/msg/String", "chatter:std_msgs/msg/Int32"]), "nodes",
     "both use the name 'chatter'"),
    (node(publishers=[{"topic": "a", "type": "std_msgs/msg/String", "id": "class"}]), "nodes", "Python keyword"),
    (node(subscribers=["/a/b:std_msgs/msg/String", "a_b:std_msgs/msg/String"]), "nodes",
     "both use the name 'a_b_subscription'"),
    (node(subscribers=["configure:std_msgs/msg/String"]), "nodes", "a lifecycle callback"),
    (node(subscribers=["odom_request:nav_msgs/msg/Odometry"], service_servers=["odom:std_srvs/srv/Trigger"]),
     "nodes", "both use the name 'on_odom_request'"),
    (node(service_servers=["reset"]), "nodes", "write it as name:type"),
    (node(service_clients=["reset:std_msgs/msg/String"]), "nodes",
     "give a service type here: 'std_msgs/msg/String' is a message type"),
    (node(action_servers=["move:nav2_msgs/srv/Move"]), "nodes", "give an action type here"),
    (node(action_clients=[{"name": "~", "type": "test_msgs/action/Fibonacci"}]), "nodes",
     "give a name after its prefix"),
    (node(timers=["fast"]), "nodes", "give the period in seconds, e.g. 0.1: 'fast' is not a number"),
    (node(timers=[[1]]), "nodes", "write a timer as a period in seconds"),
    (node(publishers=[{"topic": "a", "type": "std_msgs/msg/String", "qos": True}]), "nodes",
     "give qos as a history depth"),
    (node(timers=[0]), "nodes", "more than 0 s"),
    (node(timers=[1e-10]), "nodes", "give a period of at least a nanosecond"),
    (node(timers=[{"name": "Fast", "period": 1}]), "nodes", "lower_snake_case"),
    (node(timers=[0.1, 0.2]), "nodes", "both use the name 'timer'"),
    (node(parameters=["Rate:double=1.0"]), "nodes", "lower_snake_case"),
    (node(parameters=["rate"]), "nodes", "give a type or a default"),
    (node(parameters=["rate:complex=1"]), "nodes", "is not one of"),
    (node(parameters=["rate:int=1.5"]), "nodes", "is not an int"),
    (node(parameters=["rate:double=[1"]), "nodes", "write the default as YAML"),
    (node(parameters=[{"name": "", "default": 1}]), "nodes", "give a parameter name"),
    (node(parameters=[7]), "nodes", "write a parameter as 'name:type=default'"),
    (node(parameters=[{"name": "rate", "type": 2}]), "nodes", "is not one of"),
    (node(parameters=[{"name": "when", "default": {"a": 1}}]), "nodes", "cannot tell the type"),
    (node(parameters=[{"name": "gains", "default": [1, "a"]}]), "nodes", "mixes types"),
    (node(parameters=[{"name": "r", "default": 1.0, "description": ["a"]}]), "nodes", "one line of text"),
    (node(parameters=[{"name": "r", "default": 1.0, "range": [0]}]), "nodes", "[min, max] or [min, max, step]"),
    (node(parameters=[{"name": "r", "default": 1.0, "range": [0, "9"]}]), "nodes", "range bounds must be numbers"),
    (node(parameters=[{"name": "r", "default": 1.0, "range": {"min": 0, "max": 2, "step": -1}}]), "nodes",
     "range step must not be negative"),
    (node(parameters=[{"name": "r", "default": 1.0, "range": {"mn": 0}}]), "nodes", "did you mean 'min'"),
    (node(parameters=["gains:double[]=[]"]), "nodes", "give it a default that is not empty"),
    (node(parameters=[{"name": "r", "type": "string", "range": [0, 1]}]), "nodes", "only int and double"),
    (node(parameters=[{"name": "r", "default": 5, "range": [0, 1]}]), "nodes", "outside the range"),
    (node(parameters=[{"name": "r", "default": 0, "range": [2, 1]}]), "nodes", "above its maximum"),
    (node(parameters=[{"name": "r", "default": 1, "range": [0, 1.5]}]), "nodes", "whole-number"),
    (node(parameters=[{"name": "r", "default": 5, "range": [0, 10, 3]}]), "nodes",
     "default 5 is not the minimum 0 plus a whole number of steps of 3"),
    (node(parameters=[{"name": "r", "default": 0.25, "range": [0.0, 1.0, 0.1]}]), "nodes", "whole number of steps"),
    (node(parameters=[{"name": "r", "default": 1, "read_only": "no"}]), "nodes", "true or false"),
    (node(parameters=["rate=1.0", "rate=2.0"]), "nodes", "both use the name 'rate'"),
    # Answers that passed the rules but broke the build or the run (issue 8).
    (answers(package_name="p" * 40), "package_name", "at most 39"),
    (answers(package_name="test"), "package_name", "find_packages"),
    (answers(package_name="json"), "package_name", "standard library"),
    (answers(package_name="rclpy", build_type="ament_python", nodes=[{"name": "a"}]), "package_name",
     "a package its nodes use"),
    (answers(package_name="std_msgs", nodes=[{"name": "a", "publishers": ["x:std_msgs/msg/String"]}]),
     "package_name", "a package its nodes use"),
    (answers(description="one\rline"), "description", "printable"),
    (answers(maintainer="Ada\tLovelace"), "maintainer", "printable"),
    (answers(maintainer_email="ada@localhost"), "maintainer_email", "catkin_pkg"),
    (answers(copyright_holder="Lab\\"), "copyright_holder", "C++ comment"),
    (answers(copyright_holder="Lab ??/"), "copyright_holder", "C++ comment"),
    (answers(nodes=[{"name": "n" * 40}]), "nodes", "at most 39"),
    (answers(package_name="p" * 39, build_type="ament_cmake", nodes=[{"name": "n" * 35, "language": "cpp"}]),
     "nodes", "74 characters together: a C++ node's have at most 73"),
    (node(description="bell\a"), "nodes", "printable"),
    (node(parameters=["use_sim_time=true"]), "nodes", "declared by ROS 2 itself"),
    (node(parameters=["start_type_description_service=true"]), "nodes", "declared by ROS 2 itself"),
    (answers(build_type="ament_cmake", nodes=[{"name": "camera", "language": "cpp", "component": True,
                                                "lifecycle": True, "parameters": ["autostart=true"]}]),
     "nodes", "the parameter a lifecycle node starts itself by and parameter 'autostart'"),
    (node(parameters=["lambda=1"]), "nodes", "Python keyword"),
    (answers(ros_distro="noetic", build_type="catkin", nodes=[{"name": "a", "parameters": ["l=1.0"]}]),
     "nodes", "self.l in Python, which flake8 refuses as ambiguous (E741)"),
    (node(parameters=[{"name": "big", "default": 2**63}]), "nodes", "64-bit integer"),
    (node(parameters=[{"name": "big", "type": "int[]", "default": [1, -2**63 - 1]}]), "nodes", "64-bit integer"),
    (node(parameters=[{"name": "r", "default": 1, "range": [0, 2**64]}]), "nodes", "64-bit integer"),
    (answers(ros_distro="noetic", build_type="catkin", nodes=[{"name": "a", "parameters": ["big=2147483648"]}]),
     "nodes", "does not fit a 32-bit integer (ROS 1's parameter server)"),
    (answers(ros_distro="noetic", build_type="catkin",
             nodes=[{"name": "a", "parameters": ["big:int[]=[-2147483649]"]}]), "nodes", "32-bit integer"),
    (node(parameters=[{"name": "r", "default": "x", "description": "two\nlines"}]), "nodes", "printable"),
    (node(publishers=["/" + "a" * 80 + ":std_msgs/msg/String"]), "nodes", "at most 80"),
    (node(publishers=[{"topic": "a", "type": "std_msgs/msg/String", "id": "b" * 51}]), "nodes", "at most 50"),
    (node(subscribers=["/_1/x:std_msgs/msg/String"]), "nodes", "'1_x', does not start with a letter"),
    (node(service_servers=["~/_:std_srvs/srv/Trigger"]), "nodes", "'', does not start with a letter"),
    (node(publishers=["a:my_msgs/msg/" + "A" * 51]), "nodes", "at most 50"),
    (node(publishers=["a:my_msgs/msg/None"]), "nodes", "Python keyword"),
    (answers(interfaces={"messages": [{"name": "None", "fields": ["int32 x"]}]}), "interfaces", "Python keyword"),
    (answers(interfaces={"messages": [{"name": "GetMapROI", "fields": ["int32 x"]},
                                      {"name": "GetMapRoi", "fields": ["int32 x"]}]}), "interfaces", "get_map_roi"),
    (answers(ros_distro="noetic", build_type="catkin", interfaces={
        "messages": [{"name": "SetRequest", "fields": ["int32 x"]}],
        "services": [{"name": "Set", "request": ["int32 x"], "response": []}]}), "interfaces",
     "message generation already makes"),
    (answers(ros_distro="noetic", build_type="catkin", interfaces={
        "messages": [{"name": "GoGoal", "fields": ["int32 x"]}],
        "actions": [{"name": "Go", "goal": ["int32 x"], "result": [], "feedback": []}]}), "interfaces",
     "the action 'Go'"),
    (node(publishers=["cmd_vel:geometry_msgs/msg/Twst"]), "nodes", "did you mean geometry_msgs/msg/Twist?"),
    (answers(ros_distro="noetic", build_type="catkin", nodes=[{"name": "a", "subscribers": ["x:geometry_msgs/Twst"]}]),
     "nodes", "did you mean geometry_msgs/Twist? 'geometry_msgs/Twst' is not a message of geometry_msgs in noetic"),
    (node(service_servers=["get:std_srvs/srv/String"]), "nodes", "is not a service of std_srvs"),
    (answers(ros_distro="noetic", build_type="catkin", package_name="robot", nodes=[
        {"name": "robot", "language": "python"}]), "nodes", "shadow the Python module 'robot'"),
    (answers(ros_distro="noetic", build_type="catkin", nodes=[
        {"name": "std_msgs", "language": "python", "publishers": ["x:std_msgs/msg/String"]}]), "nodes",
     "shadow the Python module 'std_msgs'"),
]


@pytest.mark.parametrize(("values", "question", "rule"), BROKEN)
def test_each_rule_names_the_question_and_the_rule(values, question, rule):
    error = error_of(values)
    assert error.question == question
    assert rule in str(error)
    assert "\n" not in str(error)
    assert str(error).startswith(f"invalid answer to '{question}': ")


def test_node_errors_say_which_node():
    error = error_of(node(publishers=["bad topic:std_msgs/msg/String"]))
    assert "node 'driver': publisher: topic 'bad topic'" in str(error)


@pytest.mark.parametrize(("values", "question", "rule"), BROKEN)
def test_errors_name_the_node_and_the_question_once(values, question, rule):
    error = str(error_of(values))
    assert error.count("invalid answer") == 1
    assert error.count("node '") <= 2  # 'node a and node a both use' names two
    assert "node 'driver': node 'driver'" not in error


def test_short_and_long_forms_give_the_same_model():
    short = build_package(node(
        publishers=["cmd_vel:geometry_msgs/msg/Twist:sensor_data"],
        service_clients=["reset:std_srvs/Trigger"],
        timers=["control_loop:0.05"],
        parameters=["gain:double=2", "frame_id=base_link", "gains:double[]=[1, 2.5]"],
    ))
    long = build_package(node(
        publishers=[{"topic": "cmd_vel", "type": "geometry_msgs/msg/Twist", "qos": "sensor_data"}],
        service_clients=[{"name": "reset", "type": "std_srvs/srv/Trigger"}],
        timers=[{"name": "control_loop", "period": 0.05}],
        parameters=[{"name": "gain", "type": "double", "default": 2.0},
                    {"name": "frame_id", "default": "base_link"},
                    {"name": "gains", "type": "double[]", "default": [1.0, 2.5]}],
    ))
    assert short == long


@pytest.mark.parametrize("spelled", ["true", "True", "yes", "on", "false", "No", "off", "y", "1"])
def test_a_boolean_is_spelled_the_same_way_in_short_and_long_forms(spelled):
    """YAML's spellings of true and false, and nothing else, wherever a boolean is written."""
    forms = [node(parameters=[f"flag:bool={spelled}"]), node(parameters=[f"flag={spelled}"]),
             node(parameters=yaml.safe_load(f"[{{name: flag, type: bool, default: {spelled}}}]")),
             node(parameters=yaml.safe_load(f"[{{name: flag, default: {spelled}}}]"))]
    read = []
    for form in forms:
        try:
            parameter = build_package(form).nodes[0].parameters[0]
            read.append((parameter.type.scalar, parameter.default))
        except AnswerError:
            read.append("refused")
    flag = yaml.safe_load(spelled)
    expected = ("bool", flag) if isinstance(flag, bool) else "refused"
    assert read[0] == read[2] == expected
    assert read[1] == read[3]  # untyped: a bool, or the type the text reads as
    assert (read[1][0] == "bool") == isinstance(flag, bool)
    lifecycle = yaml.safe_load(f"[{{name: a, lifecycle: {spelled}}}]")
    try:
        assert build_package(answers(nodes=lifecycle)).nodes[0].lifecycle is flag
    except AnswerError as error:
        assert not isinstance(flag, bool) and "set lifecycle to true or false" in str(error)


def test_prompt_answers_are_comma_separated_short_forms():
    package = build_package(node(publishers="a:std_msgs/msg/String, b:std_msgs/msg/Int32",
                                 parameters="gains:double[]=[1.0, 2.0], name=x"))
    assert [t.topic for t in package.nodes[0].publishers] == ["a", "b"]
    assert [p.default for p in package.nodes[0].parameters] == [[1.0, 2.0], "x"]


def test_generated_names_come_from_what_the_user_named():
    package = build_package(node(
        publishers=["cmd_vel:geometry_msgs/msg/Twist"],
        subscribers=["/camera/depth/points:sensor_msgs/msg/PointCloud2"],
        service_servers=["reset:std_srvs/srv/Trigger"],
        action_clients=["navigate:test_msgs/action/Fibonacci"],
        timers=[0.1],
    ))
    driver = package.nodes[0]
    assert driver.class_name == "Driver"
    assert driver.publishers[0].member == "cmd_vel_publisher"
    assert driver.subscribers[0].callback == "on_camera_depth_points"
    assert driver.service_servers[0].callback == "on_reset_request"
    assert driver.action_clients[0].callbacks["send"] == "send_navigate_goal"
    assert driver.timers[0].member == "timer"
    assert dialect(driver).period(driver.timers[0]) == "std::chrono::milliseconds(100)"


def test_dependencies_are_exactly_what_the_nodes_use():
    package = build_package(answers(nodes=[
        {"name": "driver", "publishers": ["cmd_vel:geometry_msgs/msg/Twist"], "action_servers":
         ["dock:test_msgs/action/Fibonacci"]},
        {"name": "monitor", "language": "python", "subscribers": ["odom:nav_msgs/msg/Odometry"],
         "parameters": [{"name": "rate", "default": 1.0, "description": "Checks per second"}]},
    ]))
    assert [(d.name, d.tag) for d in package.dependencies] == [
        ("geometry_msgs", "depend"), ("nav_msgs", "exec_depend"), ("rcl_interfaces", "exec_depend"),
        ("rclcpp", "depend"), ("rclcpp_action", "depend"), ("rclpy", "exec_depend"),
        ("test_msgs", "depend"),
    ]


def test_python_names_avoid_clashes():
    package = build_package(answers(build_type="ament_python", nodes=[{
        "name": "odometry",
        "subscribers": ["odom:nav_msgs/msg/Odometry", "pose:geometry_msgs/msg/Pose", "p2:turtlesim/msg/Pose"],
    }]))
    types = {t.full_name: name for t, name in dialect(package.nodes[0]).types.items()}
    assert types == {"nav_msgs/msg/Odometry": "NavMsgsOdometry", "geometry_msgs/msg/Pose": "GeometryMsgsPose",
                     "turtlesim/msg/Pose": "TurtlesimPose"}


@pytest.mark.parametrize(
    ("question", "value", "rule"),
    [("node_name", "Bad", "lower_snake_case"),
     ("node_publishers", "chatter", "write it as topic:type"),
     ("node_timers", "0", "more than 0 s"),
     ("node_parameters", "x:int=a", "is not an int")],
)
def test_quick_questions_use_the_same_rules(question, value, rule):
    assert rule in question_error(question, {**VALID, question: value})


@pytest.mark.parametrize(
    ("question", "changes", "rule"),
    [("node_name", {"ros_distro": "noetic", "build_type": "catkin", "package_name": "mover",
                    "node_language": "python", "node_name": "mover"}, "would shadow the Python module 'mover'"),
     ("node_name", {"package_name": "p" * 39, "build_type": "ament_cmake", "node_language": "cpp",
                    "node_name": "n" * 39}, "78 characters together"),
     ("node_publishers", {"ros_distro": "noetic", "build_type": "catkin", "node_language": "python",
                          "node_name": "geometry_msgs", "node_publishers": "pose:geometry_msgs/msg/Pose"},
      "would shadow the Python module 'geometry_msgs'")],
)
def test_a_rule_on_the_node_as_a_whole_is_met_at_the_question_that_breaks_it(question, changes, rule):
    """The language is asked before the name, so the name's language rules are known there."""
    assert rule in question_error(question, {**VALID, **changes})
    assert question_error(question, {**VALID, **changes, "node_language": "cpp" if "noetic" in
                                     changes.values() else "python"}) is None


@pytest.mark.parametrize(
    ("question", "changes", "rule"),
    [("target", {"target": "workspace"}, "is not package or node"),
     ("target", {"target": "node", "interfaces": {"messages": [{"name": "A"}]}}, "cannot define interfaces"),
     ("nodes", {"target": "node", "nodes": [{"name": "a"}, {"name": "b"}]}, "give exactly one"),
     ("interfaces_location", {"interfaces_location": "elsewhere"}, "is not separate or package")],
)
def test_where_the_output_goes_has_rules_too(question, changes, rule):
    assert rule in question_error(question, {**VALID, **changes})


def test_several_publishers_get_a_message_variable_each():
    one = build_package(node(publishers=["a:std_msgs/msg/String"], timers=[1])).nodes[0]
    two = build_package(node(publishers=["a:std_msgs/msg/String", "/b/c:std_msgs/msg/Int32"], timers=[1])).nodes[0]
    relay = build_package(node(publishers=["a:std_msgs/msg/String"], subscribers=["b:std_msgs/msg/String"])).nodes[0]
    assert list(one.message_variables.values()) == ["msg"]
    assert list(two.message_variables.values()) == ["a_msg", "b_c_msg"]
    assert list(relay.message_variables.values()) == ["a_msg"]  # beside the `msg` its callback receives


def test_default_description_says_what_the_nodes_do():
    def describe_nodes(answers):
        return Answers(answers).default_description()

    assert describe_nodes({**VALID, "nodes": [
        {"name": "talker", "publishers": ["chatter:std_msgs/msg/String"]},
        {"name": "listener", "subscribers": ["chatter:std_msgs/msg/String"]}]}) == (
        "The talker node publishes chatter; the listener node subscribes to chatter")
    assert describe_nodes({**VALID, "nodes": [{"name": f"n{i}"} for i in range(4)]}) == "Nodes n0, n1, n2 and n3"
    assert describe_nodes({**VALID, "nodes": "not: [valid"}) == "ROS nodes"
    # At a prompt, what fits its line: a longer default would wrap mid-word.
    three = {**VALID, "nodes": [{"name": "driver", "publishers": ["odom:nav_msgs/msg/Odometry"]},
                                {"name": "planner", "publishers": ["cmd_vel:geometry_msgs/msg/Twist"]},
                                {"name": "battery_monitor", "subscribers": ["odom:nav_msgs/msg/Odometry"]}]}
    assert len(describe_nodes(three)) > 77
    assert Answers(three).default_description(77) == "Nodes driver, planner and battery_monitor"
    assert Answers(three).default_description(20) == "3 ROS nodes"


def test_diagnostics_in_both_generations():
    """A node with diagnostics depends on diagnostic_updater (and diagnostic_msgs, for the status levels)."""
    for distro, build_type in (("jazzy", "ament_cmake"), ("noetic", "catkin")):
        package = build_package(answers(ros_distro=distro, build_type=build_type, nodes=[
            {"name": "a", "language": "cpp", "diagnostics": True}, {"name": "b", "language": "python"}]))
        assert [node.diagnostics for node in package.nodes] == [True, False]
        assert {"diagnostic_msgs", "diagnostic_updater"} <= set(package.cpp_dependencies)
        assert "diagnostic_updater" not in package.nodes[1].dependencies
    # ROS 1 keeps parameters in members: `updater` is the base class's; ROS 2 asks for them by name.
    error = error_of(answers(ros_distro="noetic", build_type="catkin",
                             nodes=[{"name": "a", "diagnostics": True, "parameters": ["updater=1"]}]))
    assert "the diagnostics updater and parameter 'updater'" in str(error)
    build_package(answers(nodes=[{"name": "a", "diagnostics": True, "parameters": ["updater=1"]}]))
    build_package(answers(ros_distro="noetic", build_type="catkin", nodes=[{"name": "a", "parameters": ["updater=1"]}]))


def test_ros1_rules():
    error = error_of(answers(ros_distro="noetic", build_type="catkin", nodes=[{"name": "a", "lifecycle": True}]))
    assert "leave out lifecycle and component: they are ROS 2 features" in str(error)
    error = error_of(answers(ros_distro="noetic", build_type="catkin",
                             nodes=[{"name": "a", "parameters": ["node_handle=1"]}]))
    assert "a member of the base class and parameter 'node_handle'" in str(error)
    package = build_package(answers(ros_distro="noetic", build_type="catkin", nodes=[
        {"name": "a", "language": "python", "subscribers": ["odom:nav_msgs/msg/Odometry"],
         "action_clients": ["dock:actionlib/action/Test"]}]))
    a = package.nodes[0]
    assert a.executable == "a.py"
    assert a.subscribers[0].member == "odom_subscriber"
    assert [d.name for d in package.dependencies] == ["actionlib", "actionlib_msgs", "nav_msgs", "rospy"]
    assert all(d.tag == "depend" for d in package.dependencies)


def test_types_of_other_packages_and_newer_rolling_types_stay_allowed():
    build_package(node(publishers=["goals:nav_msgs/msg/Goals"]) | {"ros_distro": "rolling"})
    build_package(node(publishers=["x:my_robot_msgs/msg/Anything"]))


# Each question's `type:` in copier.yml, as the glue reads it for check_given.
QUESTION_TYPES = {name: spec.get("type", "str") for name, spec in
                  yaml.safe_load((ROOT / "copier.yml").read_text()).items() if not name.startswith("_")}


@pytest.mark.parametrize("value", [None, ["a list"], {"a": "mapping"}])
@pytest.mark.parametrize("question", sorted(name for name, kind in QUESTION_TYPES.items() if kind == "str"))
def test_given_text_answers_that_copier_cannot_cast_are_one_line(question, value):
    """Copier casts a `type: str` answer given as data, and fails with a traceback on these."""
    with pytest.raises(AnswerError) as caught:
        check_given({question: value}, QUESTION_TYPES)
    assert str(caught.value).startswith(f"invalid answer to '{question}': give text here, not ")


@pytest.mark.parametrize("year", ["soon", "", None, [2026], 2026.5, True, 1969, 10000, "99999"])
def test_a_given_year_that_is_not_one_is_one_line(year):
    with pytest.raises(AnswerError, match="is not a year"):
        check_given({"copyright_year": year}, QUESTION_TYPES)


def test_given_answers_copier_casts_stay_accepted():
    check_given({"copyright_year": "2031", "description": 12, "maintainer": "Ada", "nodes": [{"name": "a"}]},
                QUESTION_TYPES)
    assert build_package(answers(copyright_year="2031")).copyright_year == 2031


def test_an_empty_ros1_python_base_module_imports_what_its_run_uses_only():
    def base_imports(**fields):
        package = build_package(answers(ros_distro="noetic", build_type="catkin",
                                        nodes=[{"name": "a", "language": "python", **fields}]))
        return dialect(package.nodes[0]).base_imports

    # run(): signal holds Ctrl-C while rospy starts the node.
    assert base_imports() == base_imports(timers=[1]) == "import signal\n\nimport rospy"
    assert "import rospy" in base_imports(action_clients=["dock:actionlib/action/Test"])


def test_one_package_s_message_and_service_of_one_name_get_two_names_in_code():
    """nav_msgs has GetMap as a service and (ROS 1) an action: both in a node need names of their own."""
    for language in ("python", "cpp"):
        package = build_package(node(language=language, publishers=["a:my_msgs/msg/Goal"],
                                     service_clients=["b:my_msgs/srv/Goal"], action_clients=["c:other/action/Goal"]))
        names_in_code = dialect(package.nodes[0]).types if language == "python" else dialect(
            package.nodes[0]).alias_names
        assert sorted(names_in_code.values()) == ["MyMsgsMsgGoal", "MyMsgsSrvGoal", "OtherGoal"]


@pytest.mark.parametrize(("distro", "build_type"), [("jazzy", "ament_cmake"), ("noetic", "catkin")])
def test_a_parameter_named_count_is_the_users_and_the_starter_counts_elsewhere(distro, build_type):
    """The starter's message counter is not the base class's: it gives way to the user's names."""
    node = build_package(answers(ros_distro=distro, build_type=build_type, nodes=[
        {"name": "a", "publishers": ["out:std_msgs/msg/Int32"], "timers": [0.5],
         "parameters": ["count:int=3", "count2:int=4"]}])).nodes[0]
    assert node.starter_counter == "count3"
    assert build_package(answers(nodes=[{"name": "a", "timers": [0.5]}])).nodes[0].starter_counter == "count"


def test_a_given_launch_format_is_checked_against_the_given_distro():
    """Copier does not ask launch_format for ROS 1: one given anyway is refused in one line."""
    with pytest.raises(AnswerError, match="'launch_format': roslaunch .ROS 1. reads XML launch files only"):
        check_given({"ros_distro": "noetic", "launch_format": "python"}, QUESTION_TYPES)
    with pytest.raises(AnswerError, match="'launch_format': 'py' is not one of xml, python, yaml"):
        check_given({"launch_format": "py"}, QUESTION_TYPES)
    check_given({"ros_distro": "noetic", "launch_format": "xml"}, QUESTION_TYPES)
    check_given({"launch_format": "yaml"}, QUESTION_TYPES)
    assert build_package(answers(ros_distro="noetic", build_type="catkin")).launch_file .endswith(".launch")
