"""Unit tests of the pure functions in extensions/rna: names, interface types, parameters, dialects."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
import yaml
from rna import build_package, configs, distros, launch_features, names
from rna.dialects import Ros1Cpp, Ros1Python, Ros2Cpp, Ros2Python, cpp, python
from rna.interfaces import InterfaceType, parse_interface
from rna.licenses import LICENSES
from rna.parameters import ParameterType, coerce_default, infer_type, on_step, parse_type
from rna.replies import replies
from support.generation import VALID, example


@pytest.mark.parametrize(("feature", "distro", "available"), [
    ("<lifecycle_node>", "humble", False), ("<lifecycle_node>", "jazzy", False), ("<lifecycle_node>", "kilted", False),
    ("<lifecycle_node>", "rolling", True), ("LifecycleNode(autostart)", "humble", False),
    ("LifecycleNode(autostart)", "jazzy", False), ("LifecycleNode(autostart)", "kilted", True),
    ("LifecycleNode(autostart)", "rolling", True), ("node_container", "humble", True)])
def test_a_launch_feature_counts_when_every_release_of_the_distro_has_it(feature, distro, available):
    """Jazzy got LifecycleNode(autostart) in 0.26.7, after its first release (0.26.5); Kilted's
    first (0.28.1) had it."""
    assert launch_features.available(feature, distro) is available


def test_the_launch_table_covers_every_ros2_distro():
    for feature, releases in launch_features.SINCE.items():
        assert set(releases) == set(distros.ROS2_DISTROS), feature
    assert set(launch_features.FIRST_RELEASE) == set(distros.ROS2_DISTROS)
    assert "lifecycle_node" not in launch_features.frontend("kilted") and "lifecycle_node" in launch_features.frontend(
        "rolling")
    assert "autostart" not in launch_features.python_api("jazzy")["LifecycleNode"][1]
    with pytest.raises(ValueError, match="noetic is not a ROS 2 distro"):
        launch_features.available("<lifecycle_node>", "noetic")


@pytest.mark.parametrize("name", ["turtlesim", "my_robot2", "a1", "target_tracking"])
def test_package_names_following_rep_144(name):
    assert names.package_name_error(name) is None


@pytest.mark.parametrize(
    ("name", "rule"),
    [
        ("My-Bad Pkg", "REP 144"),
        ("2robot", "REP 144"),
        ("robot__arm", "REP 144"),
        ("robot_", "REP 144"),
        ("Robot", "REP 144"),
        ("r", "at least two characters"),
        ("class", "Python keyword"),
        ("namespace", "C++ keyword"),
        ("", "give a"),
    ],
)
def test_package_names_breaking_a_rule(name, rule):
    assert rule in names.package_name_error(name)


@pytest.mark.parametrize(
    ("name", "rule"),
    [
        ("Talker", "lower_snake_case"),
        ("talker-1", "lower_snake_case"),
        ("9lives", "lower_snake_case"),
        ("talker_base", "_base"),
        ("import", "Python keyword"),
        ("x" * 40, "at most 39"),
        ("o", "ambiguous (E742)"),
        ("i", "ambiguous (E742)"),
    ],
)
def test_node_names_breaking_a_rule(name, rule):
    assert rule in names.node_name_error(name)


@pytest.mark.parametrize("topic", ["chatter", "/cmd_vel", "~/status", "camera/depth/points", "/a_1/B2",
                                   "{node}/status", "~/{node}_raw", "/cam_{node}/image", "{node}"])
def test_valid_topic_names(topic):
    assert names.topic_name_error(topic) is None


def test_ros_2_resolves_the_node_substitution_where_the_code_and_the_tests_name_it():
    assert names.fully_qualified("{node}/status", "driver") == "/driver/status"
    assert names.fully_qualified("~/{node}_raw", "driver", "/robot") == "/robot/driver/driver_raw"
    assert names.graph_name("{node}/status", "driver") == "driver/status"
    assert names.identifier_from_name("cam_{node}/image") == "cam_node_image"


@pytest.mark.parametrize(
    ("topic", "rule"),
    [
        ("", "give a"),
        ("cmd vel", "letters, digits and '_'"),
        ("/2d/scan", "does not start with a digit"),
        ("scan/", "must not end with '/'"),
        ("a//b", "'//'"),
        ("~scan", "'~' must be followed by '/'"),
        ("a/~/b", "letters, digits and '_'"),
        ("{ns}/status", "{ns} is the node's namespace, '/' for a node started in none (as the launch file starts "
                        "it), and ROS refuses the name it then makes; 'status' is resolved"),
        ("/{namespace}/{node}", "'{node}' is resolved in the node's namespace"),
        ("{name}/x", "{name} is no substitution ROS 2 resolves here; {node}, the node's name, is"),
        ("a{node", "does not enclose a substitution"),
        ("{no/de}/x", "does not enclose a substitution"),
        ("/", "give a name after its prefix"),
    ],
)
def test_topic_names_breaking_a_rule(topic, rule):
    assert rule in names.topic_name_error(topic)


def test_ros_1_names_have_no_substitution():
    assert "substitutions like {node} are ROS 2's; a ROS 1 name has none" in names.topic_name_error("{node}/x", ros=1)


@pytest.mark.parametrize(
    ("name", "snake"),
    [("PointCloud2", "point_cloud2"), ("SetBool", "set_bool"), ("IMU", "imu"), ("GetMapROI", "get_map_roi")],
)
def test_camel_to_snake_follows_rosidl(name, snake):
    assert names.camel_to_snake(name) == snake


@pytest.mark.parametrize(
    ("topic", "identifier"),
    [("/camera/depth/points", "camera_depth_points"), ("~/cmdVel", "cmd_vel"), ("chatter", "chatter")],
)
def test_identifiers_come_from_the_names_users_give(topic, identifier):
    assert names.identifier_from_name(topic) == identifier


@pytest.mark.parametrize(("name", "namespace", "resolved"), [
    ("chatter", "/", "/chatter"),
    ("/camera/depth/points", "/", "/camera/depth/points"),
    ("~/state", "/", "/driver/state"),
    ("~/state", "/robot", "/robot/driver/state"),
    ("scan", "/robot/", "/robot/scan"),
])
def test_names_resolve_as_graph_queries_list_them(name, namespace, resolved):
    assert names.fully_qualified(name, "driver", namespace) == resolved


def test_members_get_a_suffix_once():
    assert names.with_suffix("cmd_vel", "publisher") == "cmd_vel_publisher"
    assert names.with_suffix("timer", "timer") == "timer"
    assert names.with_suffix("fast_timer", "timer") == "fast_timer"


@pytest.mark.parametrize(
    ("folder", "package"),
    [("my_pkg", "my_pkg"), ("My-Robot", "my_robot"), ("rna_demo", "rna_demo"), ("2fast", "fast"),
     ("TargetTracking", "target_tracking"), ("---", "my_package")],
)
def test_package_name_defaults_from_the_folder(folder, package):
    assert names.package_name_from_folder(folder) == package


def test_interface_spelling_ros2():
    twist = parse_interface("geometry_msgs/msg/PointCloud2", "msg")
    assert Ros2Cpp.header(twist) == "geometry_msgs/msg/point_cloud2.hpp"
    assert Ros2Cpp.full_type(twist) == "geometry_msgs::msg::PointCloud2"
    assert Ros2Python.module(twist) == "geometry_msgs.msg"
    assert twist.full_name == "geometry_msgs/msg/PointCloud2"
    action = parse_interface("test_msgs/Fibonacci", "action")
    assert action.full_name == "test_msgs/action/Fibonacci"
    assert Ros2Cpp.header(action) == "test_msgs/action/fibonacci.hpp"


def test_interface_spelling_ros1():
    action = parse_interface("actionlib_tutorials/action/Fibonacci", "action", ros=1)
    assert Ros1Cpp.header(action) == "actionlib_tutorials/FibonacciAction.h"

    assert Ros1Python.module(action) == "actionlib_tutorials.msg"
    service = parse_interface("std_srvs/srv/SetBool", "srv", ros=1)
    assert service.full_name == "std_srvs/SetBool"
    assert Ros1Cpp.header(service) == "std_srvs/SetBool.h"


@pytest.mark.parametrize(
    ("text", "kind", "rule"),
    [
        ("std_srvs/srv/Trigger", "msg", "give a message type here: 'std_srvs/srv/Trigger' is a service type"),
        ("String", "msg", "write it as"),
        ("std_msgs/msg/string", "msg", "CamelCase"),
        ("Std-Msgs/msg/String", "msg", "REP 144"),
        ("std_msgs/foo/String", "msg", "msg, srv or action"),
        (None, "srv", "give a service type"),
    ],
)
def test_interface_types_breaking_a_rule(text, kind, rule):
    with pytest.raises(ValueError, match=rule):
        parse_interface(text, kind)


def test_simple_std_msgs_types_have_a_data_field():
    assert parse_interface("std_msgs/msg/String", "msg").data_field == "string"
    assert parse_interface("std_msgs/msg/Float64", "msg").data_field == "float"
    assert parse_interface("std_msgs/msg/Header", "msg").data_field is None
    assert InterfaceType("geometry_msgs", "msg", "Twist").data_field is None


@pytest.mark.parametrize(
    ("text", "expected"),
    [("double", ParameterType("double")), ("float", ParameterType("double")),
     ("int[]", ParameterType("int", True)), ("string_array", ParameterType("string", True)),
     ("Bool", ParameterType("bool"))],
)
def test_parameter_types(text, expected):
    assert parse_type(text) == expected


def test_parameter_type_errors():
    with pytest.raises(ValueError, match="is not one of"):
        parse_type("complex")
    with pytest.raises(ValueError, match="empty list"):
        infer_type([])
    with pytest.raises(ValueError, match="mixes types"):
        infer_type([1, "a"])
    with pytest.raises(ValueError, match="is not an int"):
        coerce_default(1.5, ParameterType("int"))
    with pytest.raises(ValueError, match="not a list"):
        coerce_default(1.0, ParameterType("double", True))


def test_parameter_values_are_spelled_per_language():
    assert infer_type([1, 2.5]) == ParameterType("double", True)
    assert coerce_default(2, ParameterType("double")) == 2.0
    assert python.literal("it's") == '"it\'s"'
    assert python.literal([True, False]) == "[True, False]"
    assert cpp.literal(2.0, ParameterType("double")) == "2.0"
    assert cpp.literal([1, 2], ParameterType("int", True)) == "std::vector<int64_t>{1, 2}"
    assert cpp.literal([1, 2], ParameterType("int", True), Ros1Cpp.SCALARS) == "std::vector<int>{1, 2}"
    assert cpp.literal('say "hi"', ParameterType("string")) == '"say \\"hi\\""'
    assert configs.yaml_literal("true") == "'true'"
    assert configs.yaml_literal(1.0) == "1.0"
    assert configs.yaml_literal([0.5, 1e-06]) == "[0.5, 1.0e-06]"
    # Plain on its own line, not in a list: a comma, a bracket, a leading '?' (found by the generative tier).
    strings = ["a, b", "??/$(find x)", "[x]", "{y}", "#c", "a: b", "- z"]
    assert yaml.safe_load("k: " + configs.yaml_literal(strings))["k"] == strings


@pytest.mark.parametrize(
    ("value", "spelled"),
    [(1e308, "1.0e+308"), (-1e-06, "-1.0e-06"), (5e-324, "5.0e-324"), (1.5e-07, "1.5e-07"), (-0.0, "-0.0"),
     (2.0**53, "9007199254740992.0"), (math.inf, ".inf"), (-math.inf, "-.inf"), (math.nan, ".nan")],
)
def test_yaml_floats_read_back_as_floats_in_yaml_1_1(value, spelled):
    """PyYAML and rosparam read `1e+308` as a string: a float needs a '.' before its exponent."""
    assert configs.yaml_literal(value) == spelled
    back = yaml.safe_load(spelled)
    assert isinstance(back, float)
    assert back == value or (math.isnan(back) and math.isnan(value))


def test_extreme_numbers_are_literals_of_their_language():
    assert python.literal(1e308) == "1e+308"
    assert [python.literal(x) for x in (math.inf, -math.inf)] == ["float('inf')", "float('-inf')"]
    assert math.isnan(eval(python.literal(math.nan)))  # noqa: S307 - our own literal
    assert cpp.literal(1e308, ParameterType("double")) == "1e+308"
    # -9223372036854775808 is the negation of a literal too large for int64_t.
    assert cpp.literal(-2**63, ParameterType("int")) == "(-9223372036854775807 - 1)"
    assert cpp.literal(2**63 - 1, ParameterType("int")) == "9223372036854775807"
    with pytest.raises(ValueError, match="finite"):
        cpp.literal(math.inf, ParameterType("double"))


def test_python_imports_follow_the_google_order():
    block = python.import_block([
        "std_msgs.msg:String", "rclpy", "time", "rclpy.node:Node",
        "rclpy.action:ActionServer", "rclpy.action:CancelResponse", "my_pkg.talker_base:TalkerBase",
    ])
    assert block == (
        "import time\n\n"
        "from my_pkg.talker_base import TalkerBase\n\n"
        "import rclpy\nfrom rclpy.action import ActionServer, CancelResponse\nfrom rclpy.node import Node\n\n"
        "from std_msgs.msg import String"
    )


def test_cpp_includes_put_standard_headers_first():
    assert cpp.include_block(["rclcpp/rclcpp.hpp", "<string>", "<chrono>", "std_msgs/msg/string.hpp"]) == (
        '#include <chrono>\n#include <string>\n\n#include "rclcpp/rclcpp.hpp"\n#include "std_msgs/msg/string.hpp"'
    )


@pytest.mark.parametrize("spdx", sorted(LICENSES))
def test_license_headers_are_comment_blocks_with_the_copyright_first(spdx):
    header = LICENSES[spdx].header("Copyright 2026 Ada Lovelace", "//")
    lines = header.splitlines()
    assert lines[0] == "// Copyright 2026 Ada Lovelace"
    assert all(line == "//" or line.startswith("// ") for line in lines)
    assert "Copyright 2026 Ada Lovelace" in LICENSES[spdx].text("Copyright 2026 Ada Lovelace") or spdx in (
        "Apache-2.0", "GPL-3.0-or-later", "LGPL-3.0-or-later")


def test_long_python_text_is_split_to_fit():
    assert python.text_literal("short", 16, 8) == "'short'"
    long = python.text_literal("word " * 40, 16, 8)
    lines = long.splitlines()
    assert lines[0] == "(" and all(len(line) <= 99 for line in lines)
    assert eval(long) == "word " * 40  # noqa: S307 - our own literal


@settings(max_examples=200)
@given(text=st.text(min_size=1, max_size=400), column=st.integers(4, 40), indent=st.sampled_from([4, 8, 12]))
def test_python_text_fits_with_its_trailing_comma_whatever_it_escapes(text, column, indent):
    # Escapes (`\u200b`, `\\`) widen a part's spelling; the last part is followed by `),`.
    spelled = python.text_literal(text, column, indent)
    lines = (" " * column + spelled + ",").splitlines()
    assert all(len(line) <= 99 for line in lines), lines
    assert eval(spelled) == text  # noqa: S307 - our own literal


@pytest.mark.parametrize(("value", "low", "high", "step", "scalar", "taken"), [
    (6, 0, 10, 3, "int", True), (5, 0, 10, 3, "int", False), (10, 0, 10, 3, "int", True), (5, 0, 10, 0, "int", True),
    (0.3, 0.0, 1.0, 0.1, "double", True), (0.25, 0.0, 1.0, 0.1, "double", False), (1.0, 0.0, 1.0, 0.3, "double", True),
    (1e308, -1e308, 1e308, 1e-300, "double", True),  # rclcpp's arithmetic overflows to infinity, and takes it
])
def test_ros2_takes_a_ranged_value_on_a_step_only(value, low, high, step, scalar, taken):
    assert on_step(value, low, high, step, scalar) is taken


def test_a_double_written_with_an_exponent_and_no_dot_is_a_double():
    # YAML 1.1 reads 1e-3 as a string: the answers mean a number.
    assert infer_type("1e-3") == ParameterType("double")
    assert coerce_default("1e-3", ParameterType("double")) == 0.001
    assert coerce_default(["2E5", 1], ParameterType("double", True)) == [200000.0, 1.0]
    assert infer_type("1e-3x") == ParameterType("string")
    assert coerce_default("1e-3", ParameterType("string")) == "1e-3"


def test_a_service_starter_answers_what_a_caller_reads_as_success():
    package = build_package({**VALID, **example("tracker")})
    assert replies(InterfaceType("std_srvs", "srv", "Trigger")) == (("success", True), ("message", "done"))
    assert replies(InterfaceType("std_srvs", "srv", "SetBool", ros=1)) == (("success", True), ("message", "done"))
    own = InterfaceType("tracker_interfaces", "srv", "SetTarget")
    assert replies(own, package.definitions, package.interfaces_home) == (("accepted", True),)
    assert replies(InterfaceType("std_srvs", "srv", "Empty")) == ()
    assert replies(InterfaceType("other_pkg", "srv", "SetTarget"), package.definitions, package.interfaces_home) == ()
