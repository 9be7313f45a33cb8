"""The after-update steps of rna/update/, as pure functions on text (copier update itself: test_update.py)."""

from __future__ import annotations

from rna.update import config_merge, resolve

ROS2_CONFIG = "/**:\n  ros__parameters:\n    # Gain\n    gain: {gain}\n\n    frame_id: {frame}\n\n"


def test_config_files_merge_by_parameter():
    old = ROS2_CONFIG.format(gain=1.0, frame="odom")
    mine = ROS2_CONFIG.format(gain=1.8, frame="odom") + "    mine: true\n"
    new = ROS2_CONFIG.format(gain=1.0, frame="map")
    merged = config_merge.merge(old, mine, new)
    assert config_merge.parameters(merged) == {"gain": 1.8, "frame_id": "map", "mine": True}
    assert "    # Gain\n    gain: 1.8\n" in merged
    assert config_merge.merge(old, mine, ROS2_CONFIG.format(gain=2.0, frame="odom")) is None  # tuned and changed
    assert config_merge.merge(old, mine, ROS2_CONFIG.format(gain=1.8, frame="odom")) is not None  # same value
    ros1 = config_merge.merge("gain: 1.0\n", "gain: 3.0\n", "gain: 1.0\n\nrate: 5\n")
    assert config_merge.parameters(ros1) == {"gain": 3.0, "rate": 5}
    assert config_merge.merge("a: [", "a: 1", "a: 2") is None


def test_the_answers_file_records_each_nodes_language():
    answers = {"build_type": "ament_cmake", "nodes": ["talker", {"name": "listener", "language": "python"},
                                                      {"name": "relay"}]}
    assert resolve.resolved(answers)["nodes"] == [
        {"name": "talker", "language": "cpp"}, {"name": "listener", "language": "python"},
        {"name": "relay", "language": "cpp"}]
    assert resolve.resolved({"ros_distro": "noetic", "nodes": ["a"]})["nodes"] == [{"name": "a", "language": "cpp"}]
    assert resolve.resolved({"nodes": "not a list"}) == {"nodes": "not a list"}


def test_nodes_given_without_a_language_keep_the_one_they_had():
    previous = {"build_type": "ament_python", "nodes": [{"name": "driver"}, "monitor"]}
    nodes = [{"name": "driver"}, "monitor", {"name": "planner"}, {"name": "x", "language": "cpp"}]
    assert resolve.keep_languages(nodes, previous) == ["driver", "monitor"]
    assert nodes == [{"name": "driver", "language": "python"}, {"name": "monitor", "language": "python"},
                     {"name": "planner"}, {"name": "x", "language": "cpp"}]
