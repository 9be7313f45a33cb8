"""QoS of topics (rna.qos): presets, policies, which pairs connect, and how each language spells them."""

from __future__ import annotations

import pytest
from rna import build_package, qos
from rna.dialects import Ros2Cpp, Ros2Python
from rna.dialects.lines import BREAK
from support.generation import VALID


@pytest.mark.parametrize(("answer", "expected"), [
    (10, qos.PRESETS["default"]),
    ("20", qos.Qos(depth=20)),
    ("latched", qos.Qos(depth=1, durability="transient_local", preset="latched")),
    ({"preset": "latched", "depth": 5}, qos.Qos(depth=5, durability="transient_local")),
    ({"reliability": "best_effort", "depth": 5}, qos.PRESETS["sensor_data"]),  # named when it equals a preset
    ({"history": "keep_all", "reliability": "best_effort"}, qos.Qos(reliability="best_effort", history="keep_all")),
    ({"preset": "system_default"}, qos.PRESETS["system_default"]),
])
def test_an_answer_reads_as_its_policies(answer, expected):
    assert qos.parse(answer) == expected


@pytest.mark.parametrize(("answer", "rule"), [
    (0, "between 1 and 10000"), ("fast", "or one of default, sensor_data"), (True, "history depth"),
    ({"reliability": "sometimes"}, "give qos reliability one of reliable, best_effort"),
    ({"history": "keep_all", "depth": 5}, "keep history keep_last: depth applies to it"),
    ({"preset": "system_default", "depth": 5}, "give qos preset system_default no other key"),
    ({"colour": 1}, "has no key 'colour'"),
])
def test_a_wrong_answer_names_its_rule(answer, rule):
    with pytest.raises(ValueError, match=rule):
        qos.parse(answer)


def test_a_subscriber_asking_more_than_the_publisher_offers_never_hears_it():
    sensor, latched, plain = qos.PRESETS["sensor_data"], qos.PRESETS["latched"], qos.PRESETS["default"]
    assert qos.mismatch(sensor, plain) == "it subscribes reliable and the publisher is best_effort"
    assert qos.mismatch(plain, latched) == "it subscribes transient_local and the publisher is volatile"
    assert qos.mismatch(plain, sensor) is None and qos.mismatch(latched, plain) is None
    assert qos.mismatch(qos.PRESETS["system_default"], plain) is None  # unknown here: not refused


def nodes(*items, **answers):
    return build_package({**VALID, **answers, "nodes": list(items)}).nodes


def test_the_packages_own_nodes_agree_on_types_and_qos():
    with pytest.raises(ValueError, match=r"topic 'x': give both the same qos preset: node 'b' never hears node 'a': "
                                         r"it subscribes reliable"):
        nodes({"name": "a", "publishers": ["x:std_msgs/msg/String:sensor_data"]},
              {"name": "b", "subscribers": ["/x:std_msgs/msg/String"]})
    with pytest.raises(ValueError, match=r"service 's': give its nodes one type: node 'a' uses std_srvs/srv/Trigger "
                                         r"and node 'b' "):
        nodes({"name": "a", "service_servers": ["s:std_srvs/srv/Trigger"]},
              {"name": "b", "service_clients": ["s:std_srvs/srv/SetBool"]})
    # ROS 1 has no such QoS; private names meet no other node's.
    nodes({"name": "a", "publishers": ["x:std_msgs/String:sensor_data"]},
          {"name": "b", "subscribers": ["x:std_msgs/String"]}, ros_distro="noetic", build_type="catkin")
    nodes({"name": "a", "publishers": ["~/x:std_msgs/msg/String"]},
          {"name": "b", "subscribers": ["~/x:std_msgs/msg/Int32"]})


def test_each_language_spells_the_policies():
    node = nodes({"name": "a", "language": "python", "publishers": [
        "plain:std_msgs/msg/String:20", "scan:std_msgs/msg/String:sensor_data", "mode:std_msgs/msg/String:latched",
        {"topic": "log", "type": "std_msgs/msg/String", "qos": {"history": "keep_all", "reliability": "best_effort"}},
    ]}, build_type="ament_cmake")[0]
    plain, scan, mode, log = node.publishers
    cpp = Ros2Cpp(node)
    assert [cpp.qos(t.qos) for t in (plain, scan, mode, log)] == [
        "20", "rclcpp::SensorDataQoS()", "rclcpp::QoS(1).transient_local()",
        "rclcpp::QoS(rclcpp::KeepAll()).best_effort()"]
    python = Ros2Python(node)
    assert [python.qos_arg(t) for t in (plain, scan, mode, log)] == [
        "20", "qos_profile_sensor_data", "mode_qos", "log_qos"]
    assert python.qos_statement(mode).replace(BREAK, "") == (
        "mode_qos = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)")
    assert python.qos_statement(log).replace(BREAK, "") == (
        "log_qos = QoSProfile(history=HistoryPolicy.KEEP_ALL, reliability=ReliabilityPolicy.BEST_EFFORT)")
    assert python.qos_statement(plain) == ""
    assert {"rclpy.qos:QoSProfile", "rclpy.qos:HistoryPolicy", "rclpy.qos:ReliabilityPolicy",
            "rclpy.qos:DurabilityPolicy", "rclpy.qos:qos_profile_sensor_data"} <= set(python._needs("base"))


def test_ros1_takes_the_queue_size_and_latching():
    latched, keep_all = qos.parse("latched"), qos.parse({"history": "keep_all"})
    assert (latched.queue_size, latched.latched) == (1, True)
    assert (keep_all.queue_size, keep_all.latched) == (0, False)


@pytest.mark.parametrize(("answer", "ros", "publisher", "words"), [
    ("latched", 2, True, "latched"), ("default", 2, False, "default (depth 10)"),
    ({"reliability": "best_effort", "depth": 3}, 2, True, "best_effort, depth 3"),
    ("latched", 1, True, "queue 1, latched"), ("latched", 1, False, "queue 1"),
    ({"history": "keep_all"}, 1, True, "queue 0"),
])
def test_the_readme_says_the_qos_in_the_words_of_the_ros_generation(answer, ros, publisher, words):
    assert qos.describe(qos.parse(answer), ros, publisher) == words
