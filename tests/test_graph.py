"""The package README's picture of the system: the Mermaid chart and the tables (rna.graph)."""

from __future__ import annotations

from rna import build_package, graph
from support.generation import VALID, example, generate
from support.packages import table_rows_of_wrong_width


def package(**changes):
    return build_package({**VALID, **changes})


def test_writers_point_to_readers_through_topics_services_and_actions():
    lines = graph.mermaid_lines(package(**example("tracker")).nodes)
    assert lines[0] == "flowchart LR"
    assert '  n0(["detector"])' in lines and '  n1(["mover"])' in lines
    assert '  t1["target<br/>tracker_interfaces/msg/Target"]' in lines
    assert '  s2{{"set_target<br/>tracker_interfaces/srv/SetTarget"}}' in lines
    assert '  a3[["approach<br/>tracker_interfaces/action/Approach"]]' in lines
    # Published by the detector, read by the mover; requests go from client to server.
    assert lines[-7:] == ["  n0 --> t0", "  n0 --> t1", "  n0 -.-> s2", "  n0 ==> a3", "  t1 --> n1",
                          "  s2 -.-> n1", "  a3 ==> n1"]


def test_a_topic_is_one_vertex_whatever_its_leading_slash_and_an_edge_is_drawn_once():
    nodes = package(nodes=[
        {"name": "a", "publishers": ["odom:nav_msgs/msg/Odometry"], "subscribers": ["odom:nav_msgs/msg/Odometry"]},
        {"name": "b", "subscribers": ["/odom:nav_msgs/msg/Odometry", "/scan:sensor_msgs/msg/LaserScan"]},
    ]).nodes
    lines = graph.mermaid_lines(nodes)
    assert [line for line in lines if line.startswith("  t") and "[" in line] == [
        '  t0["odom<br/>nav_msgs/msg/Odometry"]', '  t1["/scan<br/>sensor_msgs/msg/LaserScan"]']
    assert lines.count("  n0 --> t0") == 1 and "  t0 --> n0" in lines and "  t0 --> n1" in lines
    assert "  t1 --> n1" in lines


def test_ros1_types_are_named_as_ros1_tools_name_them():
    nodes = package(ros_distro="noetic", build_type="catkin",
                    nodes=[{"name": "a", "publishers": ["pose:geometry_msgs/Pose"]}]).nodes
    assert '  t0["pose<br/>geometry_msgs/Pose"]' in graph.mermaid_lines(nodes)


def test_a_code_span_keeps_backticks_and_pipes_in_one_cell():
    assert graph.markdown_code("a|b") == "`a\\|b`"
    assert graph.markdown_code("x ``y`` z") == "```x ``y`` z```"
    assert graph.markdown_code("`edge`") == "`` `edge` ``"


def test_parameter_rows_stay_one_line_whatever_the_default():
    node = package(nodes=[{"name": "a", "parameters": [
        {"name": "text", "type": "string", "default": "two\nlines | and `ticks`", "description": "A <b>  b"},
        "gains:double[]=[1.5, 2]", "on=true",
        {"name": "mode", "default": "a|b", "one_of": ["a|b", "<c>"], "read_only": True}]}]).nodes[0]
    rows = graph.parameter_rows(node)
    assert rows[0] == ('`text`', '`string`', '``"two\\nlines \\| and `ticks`"``', "", "A &lt;b&gt; b")
    assert rows[3][3] == "one of: a\\|b, &lt;c&gt;; read-only"  # the values it takes, escaped as the others
    assert rows[1][1:3] == ("`double[]`", "`[1.5, 2.0]`") and rows[2][1:3] == ("`bool`", "`true`")
    assert all("\n" not in cell for row in rows for cell in row)


def test_endpoints_and_timers_read_as_what_the_node_does():
    node = package(**example("tracker")).nodes[0]
    assert graph.endpoint_rows(node)[0] == ("publishes", "`targets`", "`tracker_interfaces/msg/TargetArray`",
                                            "default (depth 10)")
    assert graph.endpoint_rows(node)[-1] == ("timer", "`timer`", "every 0.2 s", "")
    chain = package(**example("data_chain")).nodes
    assert [row[3] for row in graph.endpoint_rows(chain[1])] == [
        "default (depth 10)", "transient_local, depth 5", "sensor_data"]
    ros1 = package(**example("robot_ros1"), build_type="catkin").nodes[0]
    assert [row[3] for row in graph.endpoint_rows(ros1)][:4] == ["queue 10", "queue 10", "queue 1, latched", "queue 10"]


def test_interfaces_show_their_parts():
    rows = graph.interface_rows(package(**example("tracker")))
    assert ("`tracker_interfaces/srv/SetTarget`", "`Target target` --- `bool accepted`") in rows


def test_the_generated_readme_shows_the_graph_and_the_tables(template_folder, tmp_path):
    destination = tmp_path / "out"
    generate(template_folder, destination, example("tracker"))
    text = (destination / "README.md").read_text()
    assert "```mermaid\nflowchart LR\n" in text
    assert "### mover\n\n| Through | Name | Type | QoS |" in text
    assert "`tracker_interfaces`, a package beside this one" in text
    assert not table_rows_of_wrong_width(text)
