"""The launch file in XML, Python or YAML (`launch_format`): each starts the same nodes the same way.

launch and launch_ros are not on the package registries, so the files are read statically
(tests/support/launch_files.py) into one description and compared across the formats.
"""

from __future__ import annotations

import fnmatch
import re
import xml.etree.ElementTree as ET

import pytest
from rna import build_package, launch_features, layout
from rna.distros import ROS2_DISTROS
from support.generation import example
from support.launch_files import description, expected_description
from support.packages import dependencies, package_dir

FORMATS = layout.LAUNCH_FORMATS[2]
SUFFIXES = {"xml": ".launch.xml", "python": ".launch.py", "yaml": ".launch.yaml"}


def _nodes(*nodes: dict) -> list[dict]:
    return list(nodes)


# Answer sets for each kind of node the launch file starts differently.
MATRIX = {
    "lifecycle": {"package_name": "managed", "build_type": "ament_python", "nodes": _nodes(
        {"name": "driver", "lifecycle": True, "timers": [0.1]},
        {"name": "monitor", "lifecycle": True, "autostart": True, "subscribers": ["odom:nav_msgs/msg/Odometry"]})},
    "components": {**example("camera_components"), "package_name": "pipeline"},
    "mixed": {"package_name": "mixed", "build_type": "ament_cmake", "ros_distro": "kilted", "nodes": _nodes(
        {"name": "camera", "language": "cpp", "component": True, "lifecycle": True, "autostart": True},
        {"name": "viewer", "language": "cpp", "component": True},
        {"name": "planner", "language": "cpp", "lifecycle": True},
        {"name": "logger", "language": "python", "parameters": ["rate:double=2.0"]})},
    "many": {"package_name": "fleet", "build_type": "ament_python",
             "nodes": [{"name": f"robot_{number}"} for number in range(7)]},
    "simulated": {**example("sim_robot"), "ros_distro": "kilted"},
    # Remapped components on a multi-threaded executor: component_container_mt by default.
    "threaded_components": {"package_name": "threaded", "build_type": "ament_cmake", "nodes": _nodes(
        {"name": "camera", "language": "cpp", "component": True, "executor": "multi_threaded",
         "publishers": ["image:sensor_msgs/msg/Image"], "remappings": {"image": "camera/image_raw"}},
        {"name": "viewer", "language": "cpp", "component": True, "lifecycle": True, "autostart": True,
         "subscribers": ["image:sensor_msgs/msg/Image"], "remappings": {"image": "camera/image_raw", "~/x": "/y"}})},
    "humble": {"package_name": "old_robot", "ros_distro": "humble", "build_type": "ament_cmake", "nodes": _nodes(
        {"name": "driver", "language": "cpp", "lifecycle": True, "component": True},
        {"name": "helper", "language": "python"})},
}


@pytest.mark.parametrize("package", [("p", ros, f) for ros, formats in layout.LAUNCH_FORMATS.items()
                                     for f in formats])
def test_each_format_has_its_file_name_and_setup_py_installs_it(package):
    name, ros, launch_format = package
    path = layout.launch_file(name, ros, launch_format)
    assert path == ("launch/p.launch" if ros == 1 else f"launch/p{SUFFIXES[launch_format]}")
    assert fnmatch.fnmatch(path, layout.LAUNCH_GLOB) == (ros == 2)
    assert layout.launch_format_error(launch_format, ros) is None


def test_ros1_launch_files_are_xml_only():
    assert layout.launch_format_error("python", 1) == ("roslaunch (ROS 1) reads XML launch files only: "
                                                       "python is for ROS 2")
    assert layout.launch_format_error("json", 2) == "'json' is not one of xml, python, yaml"


def _started(description: dict) -> dict:
    """The description with how each node is started left out: launch_ros or the node's own parameter."""
    return {**description, "nodes": [{**node, "autostart": bool(node["autostart"])} for node in description["nodes"]]}


CASES = [(case, MATRIX[case].get("ros_distro", distro)) for case in sorted(MATRIX)
         for distro in (ROS2_DISTROS if case in ("lifecycle", "components") else ("jazzy",))]


@pytest.mark.parametrize(("case", "distro"), CASES)
def test_every_format_starts_the_same_nodes_the_same_way(make_package, case, distro):
    """Each format reads back as the model says, using only what every release of the distro's
    launch_ros has; the three start the same nodes, however each distro's launch_ros lets them."""
    descriptions = {}
    for launch_format in FORMATS:
        answers = {**MATRIX[case], "launch_format": launch_format, "ros_distro": distro}
        model = build_package({"description": "d", "maintainer": "m", "maintainer_email": "m@example.com",
                               "license": "MIT", "copyright_holder": "m", "copyright_year": 2026, **answers})
        destination = make_package(answers)
        package = package_dir(destination)
        launch = package / model.launch_file
        assert sorted(p.name for p in (package / "launch").iterdir()) == [launch.name]
        if launch_format == "python":
            compile(launch.read_text(), str(launch), "exec")
        descriptions[launch_format] = description(launch, distro)
        assert descriptions[launch_format] == expected_description(model), launch_format
        autostarted = [node for node in descriptions[launch_format]["nodes"] if node["autostart"]]
        assert all(node["autostart"] == launch_features.autostart_form(distro, launch_format) for node in autostarted)
        readme = (destination / "README.md").read_text()
        assert f"ros2 launch {model.name} {launch.name}\n" in readme
        assert f"loaded by {model.launch_file}." in (package / "config" / f"{model.nodes[0].name}.yaml").read_text()
        # The launch files are installed to share/<package>/launch, whatever their format.
        if model.build_type == "ament_python":
            assert f"glob('{layout.LAUNCH_GLOB}')" in (package / "setup.py").read_text()
        else:
            assert "install(DIRECTORY config launch DESTINATION share/${PROJECT_NAME})" in (
                package / "CMakeLists.txt").read_text()
        # A Python launch file imports launch and launch_ros: package.xml says so.
        launch_packages = {"launch", "launch_ros"} & dependencies(package / "package.xml")["exec_depend"]
        assert launch_packages == ({"launch", "launch_ros"} if launch_format == "python" else set())
    assert _started(descriptions["xml"]) == _started(descriptions["python"]) == _started(descriptions["yaml"])


def test_the_managed_block_holds_every_node_in_each_format(make_package):
    """The user's own actions go below the END marker; the block between the markers is the template's."""
    for launch_format in FORMATS:
        destination = make_package({**MATRIX["mixed"], "launch_format": launch_format})
        package = package_dir(destination)
        text = next((package / "launch").iterdir()).read_text()
        block = re.search(r"BEGIN rna-template.*?END rna-template", text, re.S)[0]
        assert all(f"{name}" in block for name in ("camera", "viewer", "planner", "logger", "mixed_container"))


def test_launch_arguments_and_remappings_reach_every_node_and_component(make_package):
    answers = {**MATRIX["threaded_components"], "launch_format": "xml"}
    launch = description(package_dir(make_package(answers)) / "launch" / "threaded.launch.xml", "jazzy")
    assert launch["args"] == {"namespace": "", "use_sim_time": "false", "log_level": "info", "container": "false",
                              "container_executable": "component_container_mt"}
    (container,) = launch["containers"]
    everything = [*launch["nodes"], *container["nodes"]]
    assert all(entry["namespace"] == "$(var namespace)" for entry in [*everything, container])
    assert all(("use_sim_time", "$(var use_sim_time)") in entry["params"] for entry in [*everything, container])
    assert all(entry["ros_args"] == "--log-level $(var log_level)" for entry in [*launch["nodes"], container])
    remaps = {entry["name"]: entry["remaps"] for entry in everything}
    assert remaps == {"camera": (("image", "camera/image_raw"),),
                      "viewer": (("image", "camera/image_raw"), ("~/x", "/y"))}


def test_ros1_launch_file_takes_a_namespace_simulated_time_and_remappings(make_package):
    answers = {"package_name": "rover", "ros_distro": "noetic", "nodes": [
        {"name": "driver", "language": "cpp", "publishers": ["cmd_vel:geometry_msgs/msg/Twist"],
         "remappings": {"cmd_vel": "base/cmd_vel"}},
        {"name": "monitor", "language": "python"}]}
    launch = ET.parse(package_dir(make_package(answers)) / "launch" / "rover.launch").getroot()
    assert {arg.get("name"): arg.get("default") for arg in launch.iter("arg")} == {"namespace": "/",
                                                                                    "use_sim_time": "false"}
    (sim_time,) = [param for param in launch.findall("param")]
    assert (sim_time.get("name"), sim_time.get("value")) == ("/use_sim_time", "$(arg use_sim_time)")
    nodes = {node.get("name"): node for node in launch.iter("node")}
    assert all(node.get("ns") == "$(arg namespace)" for node in nodes.values())
    assert [(r.get("from"), r.get("to")) for r in nodes["driver"].iter("remap")] == [("cmd_vel", "base/cmd_vel")]
    assert not list(nodes["monitor"].iter("remap"))
