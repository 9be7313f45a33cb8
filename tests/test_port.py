"""update tier: a catkin package ported to ROS 2 by `copier update -d ros_distro=<ROS 2 distro>`.

The port's promise, checked with copier and git only (the ros1 and ros tiers build and run
ported packages: tests/test_port_ros.py; a lived-in package's every line: test_merge_safety):

- a drawn catkin package whose user files are untouched becomes exactly what a fresh ROS 2
  copy of the same answers is, byte for byte (else the answers break a ROS 2 rule and the
  update stops in one line, writing nothing);
- a name ROS 2 refuses is reported in one line, never renamed;
- a node added to a package the template did not make is ported once the package is ROS 2's.
"""

from __future__ import annotations

import shutil
import sys
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings

if "support.template_repo" not in sys.modules:  # its asserts explain themselves too
    pytest.register_assert_rewrite("support.template_repo")
from support import existing_packages  # noqa: E402
from support.generation import add_node  # noqa: E402
from support.strategies import valid_answers  # noqa: E402
from support.template_repo import (  # noqa: E402
    NEW_VERSION, commit_all, generate_project, git, replace_text, run_update, tree_differences, user_answers,
)

pytest_plugins = ("support.template_repo",)
pytestmark = pytest.mark.update

PORT_TO = "kilted"


def refused_in_one_line(result, project: Path, head: str) -> str:
    """The update's one-line refusal; asserts nothing was written."""
    assert result.returncode != 0, f"the update went ahead\n{result}"
    refusals = [line for line in result.output.splitlines() if line.startswith("rna-template: ")]
    assert len(refusals) == 1, f"no one-line refusal\n{result}"
    assert git("status", "--porcelain", "--untracked-files=all", cwd=project).stdout == "", (
        f"the refused update wrote files\n{result}")
    assert git("rev-parse", "HEAD", cwd=project).stdout == head
    return refusals[0]


# Each drawn package takes three renders (copy, update, fresh copy): a few a run, cheap.
@settings(max_examples=6, deadline=None, suppress_health_check=(HealthCheck.function_scoped_fixture,
                                                                 HealthCheck.too_slow, HealthCheck.data_too_large))
@given(valid_answers(ros=1, interfaces=True, max_nodes=3))
def test_an_untouched_catkin_package_ports_to_exactly_a_fresh_ros2_copy(current_template, answers):
    answers = {key: value for key, value in answers.items() if key != "_expected"}
    with tempfile.TemporaryDirectory(prefix="rna-port-") as scratch:
        project = generate_project(current_template, Path(scratch) / "ws" / "project", answers, vcs_ref=NEW_VERSION)
        head = git("rev-parse", "HEAD", cwd=project).stdout

        result = run_update(project, {"ros_distro": PORT_TO}, vcs_ref=NEW_VERSION)

        ported = {**user_answers(project), "build_type": "ament_cmake"} if result.returncode == 0 else None
        if ported is None:  # a ROS 2 rule these ROS 1 answers break: said in one line, nothing written
            refusal = refused_in_one_line(result, project, head)
            assert "invalid answer to" in refusal, refusal
            return
        assert "ported to ROS 2" not in result.stdout, f"untouched files need no porting\n{result}"
        fresh = generate_project(current_template, Path(scratch) / "fresh", {**answers, **ported},
                                 vcs_ref=NEW_VERSION)
        assert tree_differences(project, fresh) == [], result


def test_a_name_ros2_refuses_is_reported_never_renamed(current_template, tmp_path):
    """ROS 1 lets a node have a parameter named use_sim_time; ROS 2 declares it on every node."""
    answers = {"package_name": "clock", "ros_distro": "noetic",
               "nodes": [{"name": "ticker", "language": "python", "parameters": ["use_sim_time:bool=false"],
                          "timers": [0.5]}]}
    project = generate_project(current_template, tmp_path / "clock", answers)
    head = git("rev-parse", "HEAD", cwd=project).stdout

    refusal = refused_in_one_line(run_update(project, {"ros_distro": PORT_TO}, vcs_ref="HEAD"), project, head)

    assert "'nodes'" in refusal and "use_sim_time" in refusal and "ROS 2" in refusal, refusal


def test_a_type_ros2_lacks_is_reported_with_what_it_has(current_template, tmp_path):
    answers = {"package_name": "watcher", "ros_distro": "noetic",
               "nodes": [{"name": "watch", "language": "python",
                          "subscribers": ["status:actionlib_msgs/msg/GoalStatusArray"]}]}
    project = generate_project(current_template, tmp_path / "watcher", answers)
    head = git("rev-parse", "HEAD", cwd=project).stdout

    refusal = refused_in_one_line(run_update(project, {"ros_distro": PORT_TO}, vcs_ref="HEAD"), project, head)

    assert "actionlib_msgs is a ROS 1 package" in refusal and "action_msgs" in refusal, refusal


def test_a_catkin_package_with_a_cpp_node_is_no_ament_python_package(current_template, tmp_path):
    answers = {"package_name": "mixed", "ros_distro": "noetic",
               "nodes": [{"name": "driver", "language": "cpp"}, {"name": "monitor", "language": "python"}]}
    project = generate_project(current_template, tmp_path / "mixed", answers)
    head = git("rev-parse", "HEAD", cwd=project).stdout

    result = run_update(project, {"ros_distro": PORT_TO, "build_type": "ament_python"}, vcs_ref="HEAD")

    assert "ament_python package holds Python nodes only" in refused_in_one_line(result, project, head)


CATKIN_SETUP_PY = """\
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=['hand_rover'], package_dir={'': 'src'}))
"""

HAND_PORTED_XML = """\
<?xml version="1.0"?>
<package format="3">
  <name>hand_rover</name>
  <version>0.1.0</version>
  <description>The hand_rover package</description>
  <maintainer email="ada@example.com">Ada Lovelace</maintainer>
  <license>Apache-2.0</license>

  <buildtool_depend>ament_cmake</buildtool_depend>

  <depend>rclcpp</depend>
  <depend>std_msgs</depend>

  <export>
    <build_type>ament_cmake</build_type>
  </export>
</package>
"""

HAND_PORTED_CMAKE = """\
cmake_minimum_required(VERSION 3.8)
project(hand_rover)

find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
find_package(std_msgs REQUIRED)

add_executable(hand_talker src/hand_talker.cpp)
target_link_libraries(hand_talker PRIVATE rclcpp::rclcpp ${std_msgs_TARGETS})
install(TARGETS hand_talker DESTINATION lib/${PROJECT_NAME})

"""


@pytest.mark.parametrize("language", ["python", "cpp"])
def test_a_node_in_a_package_the_template_did_not_make_is_ported_once_the_package_is_ros2(
        current_template, tmp_path, language):
    package = existing_packages.catkin(tmp_path / "hand_rover")
    if language == "python":  # a catkin package's Python node needs its Python package (the how-to says so)
        (package / "setup.py").write_text(CATKIN_SETUP_PY)
        cmake = package / "CMakeLists.txt"
        cmake.write_text(cmake.read_text().replace("catkin_package(", "catkin_python_setup()\n\ncatkin_package("))
    add_node(current_template.path, package, {"node_name": "listener", "node_language": language,
                                              "node_subscribers": "chatter:std_msgs/msg/String"})
    answers_file = ".copier-answers.rna-listener.yml"
    user_file = package / ("scripts/listener.py" if language == "python" else "src/listener.cpp")
    text = user_file.read_text()
    assert text.count("I heard") == 1, text
    user_file.write_text(text.replace("I heard", "Rover heard"))  # the user's own words
    git("init", "-q", "-b", "main", cwd=package)
    commit_all(package, "a catkin package with an rna node of mine")
    head = git("rev-parse", "HEAD", cwd=package).stdout

    update = ("--answers-file", answers_file)
    refusal = refused_in_one_line(run_update(package, {"ros_distro": PORT_TO}, vcs_ref="HEAD", extra_args=update),
                                  package, head)
    assert "still a catkin package" in refusal and "package.xml" in refusal, refusal

    # The user ports the package's own files by hand (the node's block is theirs to keep).
    xml, cmake = package / "package.xml", package / "CMakeLists.txt"
    node_block = cmake.read_text()[cmake.read_text().index("# BEGIN rna-template: node listener"):]
    node_block = node_block[:node_block.index("# END rna-template: node listener")]
    xml.write_text(HAND_PORTED_XML)
    if language == "python":
        (package / "setup.py").unlink()
    cmake.write_text(HAND_PORTED_CMAKE + node_block + "# END rna-template: node listener\n\nament_package()\n")
    commit_all(package, "hand_rover ported by hand")

    result = run_update(package, {"ros_distro": PORT_TO}, vcs_ref="HEAD", extra_args=update)

    assert result.returncode == 0, result
    ported = package / ("hand_rover/listener.py" if language == "python" else "src/listener.cpp")
    code = ported.read_text()
    expected = (["self.get_logger().info(f'Rover heard: \"{msg.data}\"')"] if language == "python"
                else ['get_logger(), "Rover heard: \\"%s\\""', "msg.data.c_str()"])
    assert all(part in code for part in expected), code
    assert "rospy" not in code and "ros::" not in code and not (package / "scripts").exists(), code
    cmake_text = cmake.read_text()
    assert "catkin" not in cmake_text and "CATKIN" not in cmake_text, cmake_text
    assert "hand_talker" in cmake_text, "the user's own lines went"
    assert "ros__parameters" in (package / "config" / "listener.yaml").read_text()
    shutil.rmtree(package)


ROVER = {"package_name": "rover", "ros_distro": "noetic",
         "nodes": [{"name": "driver", "language": "cpp", "publishers": ["odom:std_msgs/msg/String"], "timers": [0.5]},
                   {"name": "monitor", "language": "python", "subscribers": ["odom:std_msgs/msg/String"]}]}


def rover_with_user_lines(template, destination: Path) -> Path:
    """A catkin package whose user lines name its nodes: in CMakeLists.txt, the launch file, the C++ node."""
    project = generate_project(template, destination, ROVER)
    package = project / "rover"
    replace_text(package / "CMakeLists.txt", "# END rna-template: add your own targets below\n",
                 "# END rna-template: add your own targets below\n"
                 "target_compile_definitions(${PROJECT_NAME}_driver PRIVATE ROVER_WHEELS=4)\n")
    replace_text(package / "launch" / "rover.launch", "  <!-- END rna-template: add your own nodes below -->\n",
                 "  <!-- END rna-template: add your own nodes below -->\n"
                 '  <node pkg="rover" type="driver" name="spare_driver"/>\n'
                 '  <node pkg="rover" type="monitor.py" name="spare_monitor"/>\n')
    replace_text(package / "src" / "driver.cpp", "    ++count_;\n",
                 '    ++count_;\n    ROS_WARN("count %zu", count_);\n')
    commit_all(project, "my lines")
    return project


def test_nodes_renamed_in_the_port_take_the_users_lines_naming_them_along(current_template, tmp_path):
    project = rover_with_user_lines(current_template, tmp_path / "rover")
    nodes = [{**ROVER["nodes"][0], "name": "pilot", "renamed_from": "driver"},
             {**ROVER["nodes"][1], "name": "watcher", "renamed_from": "monitor"}]

    result = run_update(project, {"ros_distro": PORT_TO, "nodes": nodes}, vcs_ref="HEAD")

    assert result.returncode == 0, result
    package = project / "rover"
    cmake, launch = (package / "CMakeLists.txt").read_text(), (package / "launch" / "rover.launch.xml").read_text()
    assert "target_compile_definitions(pilot PRIVATE ROVER_WHEELS=4)" in cmake, cmake
    assert '<node pkg="rover" exec="pilot" name="spare_driver"/>' in launch, launch
    assert '<node pkg="rover" exec="watcher" name="spare_monitor"/>' in launch, launch
    assert "driver" not in cmake and "monitor" not in cmake.replace("spare_monitor", ""), cmake
    code = (package / "src" / "pilot.cpp").read_text()
    assert "class Pilot : public PilotBase" in code and 'RCLCPP_WARN(get_logger(), "count %zu", count_);' in code
    assert "Driver" not in code and not (package / "src" / "driver.cpp").exists(), code
    assert "naming driver, monitor name pilot, watcher" in " ".join(result.stdout.split()), result


@pytest.mark.parametrize("conflict", ["inline", "rej"])
def test_a_ported_node_file_in_conflict_is_left_as_the_conflict_option_says(current_template, tmp_path, conflict):
    project = rover_with_user_lines(current_template, tmp_path / "rover")
    node = project / "rover" / "src" / "driver.cpp"
    replace_text(node, "  ros::spin();\n", '  ROS_INFO("spinning");\n  ros::spin();\n')  # main() is the template's
    commit_all(project, "main() of mine")

    result = run_update(project, {"ros_distro": PORT_TO}, vcs_ref="HEAD", extra_args=("--conflict", conflict))

    assert result.returncode == 1, result
    code = node.read_text()
    rejected = node.with_name("driver.cpp.rej")
    if conflict == "rej":
        assert "<<<<<<<" not in code and 'RCLCPP_INFO(rclcpp::get_logger("driver"), "spinning");' in code, code
        assert "+  rclcpp::spin(node);" in rejected.read_text() and "rover/src/driver.cpp.rej" in result.stdout
    else:
        assert "<<<<<<< before updating" in code and "rclcpp::spin(node);" in code and not rejected.exists(), code
    assert "each TODO(port) is an item for you" in result.stdout, result
    assert "review with `git add -A . && git diff --staged -M HEAD`" in " ".join(result.stdout.split()), result


def test_a_port_that_renames_the_package_is_refused_in_one_line(current_template, tmp_path):
    """The package moves in an update of its own: with the port, the user's own files would stay behind."""
    project = rover_with_user_lines(current_template, tmp_path / "rover")
    head = git("rev-parse", "HEAD", cwd=project).stdout

    result = run_update(project, {"ros_distro": PORT_TO, "package_name": "rover2"}, vcs_ref="HEAD")

    refusal = refused_in_one_line(result, project, head)
    assert "'package_name'" in refusal and "in an update of its own" in refusal, refusal
