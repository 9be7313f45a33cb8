"""What the generated code does differently per ROS 2 distro, checked statically for each of them.

Kilted and Jazzy are also built and run in the ros tier (PyPI wheels); Humble and Rolling
have no wheels, so the forms the template chooses for them are checked here only. One
package per distro holds every construct whose spelling depends on the distro: a C++ node
with a timer, a Python action server, a lifecycle node the launch file starts, a CI
workflow. docs/pages/reference/testing.md's table of distros says the same.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest
import yaml
from rna import AnswerError, build_package
from rna import launch_features
from rna.distros import DISCOVERY_OFF_DISTROS, ROS2_DISTROS, UBUNTU
from support.generation import VALID, generate
from support.packages import package_dir

ANSWERS = {
    "package_name": "rover", "build_type": "ament_cmake", "ci_workflow": True,
    "nodes": [
        {"name": "driver", "language": "cpp", "timers": [0.1], "publishers": ["odom:nav_msgs/msg/Odometry"]},
        {"name": "planner", "language": "python", "action_servers": ["fibonacci:test_msgs/action/Fibonacci"]},
        {"name": "beacon", "language": "python", "lifecycle": True},
    ],
}


@pytest.fixture(scope="module")
def packages(template_folder, tmp_path_factory) -> dict:
    """The package generated once for each ROS 2 distro, its lifecycle node started by the launch file."""
    made = {}
    for distro in ROS2_DISTROS:
        answers = {**ANSWERS, "ros_distro": distro}
        answers["nodes"] = [*ANSWERS["nodes"][:2], {**ANSWERS["nodes"][2], "autostart": True}]
        destination = tmp_path_factory.mktemp(distro)
        generate(template_folder, destination, answers)
        made[distro] = package_dir(destination)
    return made


@pytest.mark.parametrize("distro", ROS2_DISTROS)
def test_cpp_timers_use_the_distros_create_timer(packages, distro):
    """Humble's Node has no create_timer member (Jazzy's rclcpp added it): its free function, on the node's clock."""
    base = (packages[distro] / "include" / "rover" / "driver_base.hpp").read_text()
    if distro == "humble":
        assert "rclcpp::create_timer(\n      this, get_clock(), std::chrono" in base
    else:
        assert "= create_timer(\n      std::chrono" in base and "rclcpp::create_timer" not in base
    assert "wall_timer" not in base  # ROS time, on every distro


@pytest.mark.parametrize("distro", ROS2_DISTROS)
def test_cmake_uses_the_targets_every_distro_has(packages, distro):
    """target_link_libraries() with exported targets: ament_target_dependencies() is deprecated from Kilted."""
    cmake = (packages[distro] / "CMakeLists.txt").read_text()
    assert "ament_target_dependencies" not in cmake
    assert "${nav_msgs_TARGETS}" in cmake and "rclcpp::rclcpp" in cmake


@pytest.mark.parametrize("distro", ROS2_DISTROS)
def test_python_goals_use_the_rclpy_api_every_distro_has(packages, distro):
    """Executor.create_future() is new in Kilted's rclpy; Future(executor=...) is in Humble's already."""
    base = (packages[distro] / "rover" / "planner_base.py").read_text()
    assert "finished = Future(executor=self.executor)" in base
    assert "self.executor.create_future" not in base


@pytest.mark.parametrize("distro", ROS2_DISTROS)
def test_python_main_shuts_its_executor_down_then_destroys_its_node_before_ros(packages, distro):
    """Jazzy's rclpy prints a traceback from an executor collected after ROS shut down, and
    leaves the node to the collector (the ros tier checks nothing is left, on the distros it runs)."""
    main = (packages[distro] / "rover" / "beacon_base.py").read_text()  # run(), which main() calls
    assert main.index("executor.shutdown()") < main.index("node.destroy_node()") < main.index("rclpy.try_shutdown()")


@pytest.mark.parametrize("distro", ROS2_DISTROS)
def test_lifecycle_autostart_in_the_form_every_release_of_the_distros_launch_ros_reads(packages, distro):
    """<lifecycle_node autostart="true"> where every release of the distro's launch_ros has it
    (Rolling's newest; Jazzy's from 0.26.12, Kilted's from 0.28.6 only); elsewhere a plain
    <node> whose own autostart parameter the launch file sets, which any launch_ros reads."""
    launch = ET.parse(packages[distro] / "launch" / "rover.launch.xml").getroot()
    started = {node.get("exec"): node for node in launch if node.tag != "arg"}
    beacon = started["beacon"]
    assert beacon.get("namespace") == "$(var namespace)"  # launch_ros requires one of a lifecycle node
    if distro == "rolling":
        assert beacon.tag == "lifecycle_node" and beacon.get("autostart") == "true"
    else:
        assert beacon.tag == "node" and "autostart" not in beacon.attrib
        assert {"name": "autostart", "value": "true"} in [p.attrib for p in beacon.findall("param")]
    # The node declares the parameter, whichever form the launch file uses.
    assert "'autostart'" in (packages[distro] / "rover" / "beacon_base.py").read_text()
    assert launch_features.autostart_form(distro, "python") == (
        "launch_ros" if distro in ("kilted", "rolling") else "parameter")


@pytest.mark.parametrize("distro", ROS2_DISTROS)
def test_node_unit_tests_switch_discovery_off_where_rcl_reads_it(packages, distro):
    """ROS_AUTOMATIC_DISCOVERY_RANGE came with Iron: from Jazzy on, a node's unit test starts
    its context with discovery off, so another process's node of the same name cannot answer
    its graph queries (the ros tier runs that, on Kilted); Humble's tests are left as they were."""
    python = (packages[distro] / "test" / "test_node_planner.py").read_text()
    cpp = (packages[distro] / "test" / "test_node_driver.cpp").read_text()
    patch = "with mock.patch.dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE='OFF'):\n        context = rclpy.Context()"
    setenv = 'ASSERT_TRUE(rcutils_set_env(kDiscoveryRange, "OFF"));'
    if distro in DISCOVERY_OFF_DISTROS:
        assert patch in python and python.index(patch) < python.index("rclpy.init(context=context)")
        assert "import os\nfrom unittest import mock\n" in python
        assert setenv in cpp and cpp.index(setenv) < cpp.index("context_->init(0, nullptr)")
        restore = "rcutils_set_env(kDiscoveryRange, before.empty() ? nullptr : before.c_str())"
        assert cpp.index("context_->init(0, nullptr)") < cpp.index(restore)
        assert 'constexpr char kDiscoveryRange[] = "ROS_AUTOMATIC_DISCOVERY_RANGE";' in cpp
        assert '#include "rcutils/env.h"' in cpp
    else:
        assert "ROS_AUTOMATIC_DISCOVERY_RANGE" not in python + cpp
        assert "import os" not in python and "rcutils/env.h" not in cpp
    # The README says which tests want a domain of their own.
    readme = " ".join((packages[distro].parent / "README.md").read_text().split())
    assert "colcon test --packages-select rover colcon test-result --verbose" in readme
    assert ("The node tests keep their ROS graph to their own process. The launch test looks"
            in readme) == (distro in DISCOVERY_OFF_DISTROS)
    assert ("The node and launch tests look nodes up" in readme) == (distro not in DISCOVERY_OFF_DISTROS)


@pytest.mark.parametrize("distro", ROS2_DISTROS)
def test_ci_workflow_and_readme_name_the_distro(packages, distro):
    workflow = yaml.safe_load((packages[distro].parent / ".github" / "workflows" / "ci.yml").read_text())
    job = next(iter(workflow["jobs"].values()))
    assert job["runs-on"] == f"ubuntu-{UBUNTU[distro]}"
    assert str(workflow).count(distro) >= 2  # setup-ros and action-ros-ci
    assert f"source /opt/ros/{distro}/setup.bash" in (packages[distro].parent / "README.md").read_text()


@pytest.mark.parametrize(("distro", "refused"), [("humble", True), ("jazzy", False), ("kilted", False),
                                                 ("rolling", False)])
def test_types_are_checked_against_the_distros_own_catalogue(distro, refused):
    """nav_msgs/msg/Goals came with Jazzy: refused for Humble, where it does not exist."""
    answers = {**VALID, "ros_distro": distro,
               "nodes": [{"name": "n", "language": "python", "publishers": ["goals:nav_msgs/msg/Goals"]}]}
    if refused:
        with pytest.raises(AnswerError, match=f"not a message of nav_msgs in {distro}"):
            build_package(answers)
    else:
        build_package(answers)
