"""Executors and callback groups (issue 28): what the answers accept, and the code they make.

The user's file keeps a thin main(): everything that spins and stops a node is in its base
file, so that switching executor through `copier update` never touches the user's file.
The ros tier runs these nodes (tests/test_ros2.py: a slow service against a timer on each
executor); C++ is reviewed against a real rclcpp outside CI.
"""

from __future__ import annotations

import ast
import re

import pytest
from rna import AnswerError, build_package, distros
from rna.answers.nodes import Types, parse_node
from support.generation import FIXED_ANSWERS
from support.packages import model_of, package_dir


def node(language: str = "python", distro: str = "jazzy", build_type: str | None = None, **answers):
    ros = distros.generation(distro)
    build_type = build_type or ("catkin" if ros == 1 else "ament_cmake" if language == "cpp" else "ament_python")
    return parse_node({"name": "server", "language": language, **answers}, package="robot", build_type=build_type,
                      types=Types(ros, distro=distro))


SERVER = {"publishers": ["beat:std_msgs/msg/Int32"], "timers": ["beat:0.05"],
          "service_servers": ["reset:std_srvs/srv/Trigger"], "subscribers": ["odom:nav_msgs/msg/Odometry"],
          "action_clients": ["dock:test_msgs/action/Fibonacci"]}


@pytest.mark.parametrize(("language", "distro", "executor", "accepted"), [
    ("cpp", "humble", "static", True), ("cpp", "jazzy", "static", True), ("cpp", "kilted", "static", False),
    ("cpp", "rolling", "static", False), ("cpp", "humble", "events", False), ("cpp", "jazzy", "events", True),
    ("cpp", "kilted", "events", True), ("python", "jazzy", "static", False), ("python", "kilted", "events", False),
    ("python", "humble", "multi_threaded", True), ("cpp", "noetic", "multi_threaded", True),
    ("cpp", "noetic", "events", False), ("python", "noetic", "multi_threaded", False),
    ("python", "noetic", "single_threaded", True),
])
def test_each_executor_where_the_distros_client_library_has_it(language, distro, executor, accepted):
    error = distros.executor_error(executor, distros.generation(distro), language, distro)
    assert (error is None) == accepted, error
    if not accepted:
        with pytest.raises(ValueError, match=re.escape(error)):
            node(language, distro, executor=executor)
        assert "\n" not in error


def test_an_executor_refused_is_one_line_naming_the_question_and_the_node():
    answers = {**FIXED_ANSWERS, "package_name": "robot", "description": "d", "license": "MIT", "ros_distro": "kilted",
               "build_type": "ament_cmake", "nodes": [{"name": "driver", "language": "cpp", "executor": "static"}]}
    with pytest.raises(AnswerError) as raised:
        build_package(answers)
    assert str(raised.value) == ("invalid answer to 'nodes': node 'driver': kilted's rclcpp deprecates "
                                 "StaticSingleThreadedExecutor (SingleThreadedExecutor has its speed-ups now): use "
                                 "single_threaded")


@pytest.mark.parametrize(("answers", "message"), [
    ({"executor": "parallel"}, "executor 'parallel' is not one of single_threaded, multi_threaded, static, events"),
    ({"threads": 2}, "threads is for a multi_threaded executor: set executor: multi_threaded as well"),
    ({"executor": "multi_threaded", "threads": 0}, "threads must be a whole number from 1 to 256"),
    ({"executor": "multi_threaded", "threads": True}, "threads must be a whole number from 1 to 256"),
    ({"callback_groups": [{"name": "g", "members": ["beat"]}], "timers": []},
     "callback group 'g': 'beat' is a publisher, which has no callback to run"),
    ({"callback_groups": [{"name": "g", "members": ["nothing"]}]},
     "callback group 'g': 'nothing' is none of the node's subscribers, services, actions or timers"),
    ({"callback_groups": [{"name": "g", "members": []}]}, "callback group 'g': list its members"),
    ({"callback_groups": [{"name": "g", "type": "shared", "members": ["reset"]}]},
     "callback group 'g': type 'shared' is not one of mutually_exclusive, reentrant"),
    ({"callback_groups": [{"name": "a", "members": ["reset"]}, {"name": "b", "members": ["reset"]}]},
     "the service server 'reset' is in callback groups 'a' and 'b': a callback is in one group"),
    ({"callback_groups": [{"name": "a", "members": ["reset"]}, {"name": "a", "members": ["odom"]}]},
     "callback group 'a' and callback group 'a' both use the name 'a'"),
    ({"callback_groups": [{"name": "Group", "members": ["reset"]}]},
     "callback group 'Group': use group: it must be lower_snake_case"),
    ({"service_clients": ["odom:std_srvs/srv/Trigger"], "callback_groups": [{"name": "g", "members": ["odom"]}]},
     "'odom' names subscriber 'odom' and service client 'odom': give one an `id` to tell them apart"),
    ({"remappings": ["odom:=pose"]}, "remappings must be a mapping of names, from: to"),
    ({"remappings": {"odom": "odom"}}, "remappings: 'odom' is remapped to itself"),
    ({"remappings": {"odom": "a", "/odom": "b"}}, "remappings: 'odom' and '/odom' are one name to the node"),
    ({"remappings": {"odom": "bad name"}}, "remappings: remapped 'bad name'"),
])
def test_broken_executor_group_and_remapping_answers_say_which_rule(answers, message):
    with pytest.raises(ValueError) as raised:
        node(**{**SERVER, **answers})
    assert str(raised.value).startswith("node 'server': ") and message in str(raised.value), raised.value


def test_callback_groups_and_executors_are_ros2_features_rospy_runs_its_own_threads():
    with pytest.raises(ValueError, match="callback groups are a ROS 2 feature"):
        node("cpp", "noetic", service_servers=["reset:std_srvs/srv/Trigger"],
             callback_groups=[{"name": "g", "members": ["reset"]}])
    with pytest.raises(ValueError, match="rospy runs each subscription, timer and service callback"):
        node("python", "noetic", executor="multi_threaded")


def test_members_are_named_as_written_or_by_their_code_name():
    parsed = node(**SERVER, callback_groups=[
        {"name": "requests", "type": "reentrant", "members": "reset, dock"},
        {"name": "loop", "members": ["beat", "odom"]}])
    requests, loop = parsed.callback_groups
    assert (requests.type, [e.label for e in requests.members]) == (
        "reentrant", ["service server 'reset'", "action client 'dock'"])
    assert [e.label for e in loop.members] == ["timer 'beat'", "subscriber 'odom'"]
    assert parsed.callback_group(parsed.publishers[0]) is None  # publishers have no callbacks


def python_main(path) -> str:
    """The body of main() in a generated Python file, as source."""
    tree = ast.parse(path.read_text())
    (main,) = [statement for statement in tree.body if isinstance(statement, ast.FunctionDef)
               and statement.name == "main"]
    return "\n".join(ast.unparse(statement) for statement in main.body)


def test_python_user_files_keep_a_one_line_main_and_no_ros_plumbing(make_package):
    """Whatever the executor, the user's file calls the base module's run(); signals, executors and
    shutdown are the base module's."""
    destination = make_package({"package_name": "robot", "build_type": "ament_python", "nodes": [
        {"name": "plain", **SERVER},
        {"name": "threaded", **SERVER, "executor": "multi_threaded", "threads": 3,
         "callback_groups": [{"name": "requests", "type": "reentrant", "members": ["reset"]}]},
        {"name": "managed", "lifecycle": True, **SERVER}]})
    package = package_dir(destination)
    for name, class_name in (("plain", "Plain"), ("threaded", "Threaded"), ("managed", "Managed")):
        user = package / "robot" / f"{name}.py"
        assert python_main(user) == f"run({class_name}, args=args)"
        text = user.read_text()
        (imported,) = re.findall(rf"^from robot\.{name}_base import (.*)$", text, re.MULTILINE)
        assert sorted(imported.split(", ")) == sorted([f"{class_name}Base", "run"])
        for plumbing in ("signal", "Executor", "rclpy.init", "try_shutdown", "ExternalShutdownException", "CtrlC"):
            assert plumbing not in text, (user, plumbing)
    threaded = (package / "robot" / "threaded_base.py").read_text()
    assert "executor = MultiThreadedExecutor(num_threads=3)" in threaded
    assert "self.requests_callback_group = ReentrantCallbackGroup()" in threaded
    assert "self.on_reset_request, callback_group=self.requests_callback_group)" in threaded
    assert threaded.count("callback_group=self.") == 1  # the timer and the rest stay in the default group
    plain = (package / "robot" / "plain_base.py").read_text()
    assert "executor = SingleThreadedExecutor()" in plain and "MultiThreaded" not in plain
    # No timeout to wake up to: the executor waits for work as rclpy.spin() does.
    assert "executor.spin_once()" in plain and "timeout_sec" not in plain
    assert "node.finalize()" in (package / "robot" / "managed_base.py").read_text()


def test_cpp_main_calls_the_base_classs_spin_on_the_answers_executor(make_package):
    destination = make_package({"package_name": "robot", "build_type": "ament_cmake", "ros_distro": "jazzy",
                                "nodes": [
        {"name": "plain", "language": "cpp", **SERVER},
        {"name": "threaded", "language": "cpp", **SERVER, "executor": "multi_threaded", "threads": 4,
         "callback_groups": [{"name": "requests", "members": ["reset", "odom"]}]},
        {"name": "fixed", "language": "cpp", "executor": "static", "lifecycle": True},
        {"name": "evented", "language": "cpp", "executor": "events"},
        {"name": "camera", "language": "cpp", "component": True, "executor": "multi_threaded"}]})
    package = package_dir(destination)
    executors = {"plain": "rclcpp::executors::SingleThreadedExecutor executor;",
                 "threaded": "rclcpp::executors::MultiThreadedExecutor executor(rclcpp::ExecutorOptions(), 4);",
                 "fixed": "rclcpp::executors::StaticSingleThreadedExecutor executor;",
                 "evented": "rclcpp::experimental::executors::EventsExecutor executor;"}
    for name, declaration in executors.items():
        base = (package / "include" / "robot" / f"{name}_base.hpp").read_text()
        assert declaration in base, name
        assert "executor.add_node(node->get_node_base_interface());" in base
        # rclcpp's handler goes back to SIG_IGN, not SIGINT's default, at rclcpp::shutdown(): a second
        # SIGINT (ros2 launch's, after the terminal's) cannot end the process while the node is destroyed.
        ignored = base.index("std::signal(SIGINT, SIG_IGN);")
        assert base.index("rclcpp::uninstall_signal_handlers();") < ignored
        assert ignored < base.index("rclcpp::install_signal_handlers(handling);") < base.index("executor.spin();")
        user = (package / "src" / f"{name}.cpp").read_text()
        assert f"  robot::{name.title()}::spin(node);\n  rclcpp::shutdown();" in user
        assert "Executor" not in user and "rclcpp::spin(" not in user
    threaded = (package / "include" / "robot" / "threaded_base.hpp").read_text()
    assert ("requests_callback_group_ = create_callback_group(rclcpp::CallbackGroupType::MutuallyExclusive);"
            in threaded)
    assert "rclcpp::ServicesQoS(), requests_callback_group_);" in threaded  # the service
    assert "subscription_options(requests_callback_group_));" in threaded  # the subscription
    camera = (package / "include" / "robot" / "camera_base.hpp").read_text()
    assert "static void spin(" not in camera  # a component's executable is rclcpp_components'
    cmake = (package / "CMakeLists.txt").read_text()
    assert 'EXECUTABLE camera\n  EXECUTOR MultiThreadedExecutor)' in cmake
    assert model_of(destination).container_executable == "component_container_mt"


def test_humble_services_take_its_qos_and_roscpp_a_multi_threaded_spinner(make_package):
    humble = package_dir(make_package({"package_name": "robot", "build_type": "ament_cmake", "ros_distro": "humble",
                                       "nodes": [{"name": "server", "language": "cpp", **SERVER,
                                                  "callback_groups": [{"name": "g", "members": ["reset", "beat"]}]}]}))
    base = (humble / "include" / "robot" / "server_base.hpp").read_text()
    assert "rmw_qos_profile_services_default, g_callback_group_);" in base  # Humble has no rclcpp::ServicesQoS
    assert "}, g_callback_group_);" in base  # rclcpp::create_timer(..., group)
    ros1 = package_dir(make_package({"package_name": "robot", "ros_distro": "noetic", "nodes": [
        {"name": "server", "language": "cpp", "executor": "multi_threaded", "threads": 2},
        {"name": "monitor", "language": "python"}]}))
    assert "ros::MultiThreadedSpinner spinner(2);" in (ros1 / "include" / "robot" / "server_base.h").read_text()
    assert "  robot::Server::spin();\n" in (ros1 / "src" / "server.cpp").read_text()
    assert python_main(ros1 / "scripts" / "monitor.py") == "run(Monitor)"
