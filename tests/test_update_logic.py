"""The after-update steps of rna/update/, as pure functions on text (copier update itself: test_update.py)."""

from __future__ import annotations

import shutil

import rna
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from rna.update import blocks, config_merge, drift, kept, merge, protect, refusals, rename_answers, renames, resolve
from support.generation import VALID

ROS2_CONFIG = "/**:\n  ros__parameters:\n    # Gain\n    gain: {gain}\n\n    frame_id: {frame}\n\n"


def test_config_files_merge_by_parameter():
    old = ROS2_CONFIG.format(gain=1.0, frame="odom")
    mine = ROS2_CONFIG.format(gain=1.8, frame="odom") + "    mine: true\n"
    new = ROS2_CONFIG.format(gain=1.0, frame="map")
    merged = config_merge.merge(old, mine, new)
    assert config_merge.parameters(merged.text) == {"gain": 1.8, "frame_id": "map", "mine": True}
    assert "    # Gain\n    gain: 1.8\n" in merged.text and not merged.conflicts
    conflict = config_merge.merge(old, mine, ROS2_CONFIG.format(gain=2.0, frame="odom"))
    assert conflict.conflicts == {"gain": (1.8, 2.0)} and "gain: 1.8" in conflict.text
    assert not config_merge.merge(old, mine, ROS2_CONFIG.format(gain=1.8, frame="odom")).conflicts  # same value
    ros1 = config_merge.merge("gain: 1.0\n", "gain: 3.0\n", "gain: 1.0\n\nrate: 5\n")
    assert config_merge.parameters(ros1.text) == {"gain": 3.0, "rate": 5}
    assert config_merge.merge("a: [", "a: 1", "a: 2") is None


HEADER = "# Parameters of the driver node.\n"


def test_a_config_merge_keeps_the_users_comments_and_layout():
    old = HEADER + "# Proportional gain\ngain: 1.0\n\nframe_id: odom\n\nmax_speed: 0.5\n\nold: 1\n"
    mine = (HEADER + "# Proportional gain\ngain: 1.8  # tuned, March\n# the lidar's frame\nframe_id: odom\n"
            "max_speed: 0.5\nstop: 0.3  # mine\n\nold: 1\n")
    new = HEADER + "# Proportional gain (P)\ngain: 1.0\n\nframe_id: odom\n\nmax_speed: 0.9\n\n# New\nnew: 2\n"
    merged = config_merge.merge(old, mine, new, ({"gain": "Proportional gain"},
                                                 {"gain": "Proportional gain (P)", "new": "New"}))
    assert merged.text == (HEADER + "# Proportional gain (P)\ngain: 1.8  # tuned, March\n# the lidar's frame\n"
                           "frame_id: odom\nmax_speed: 0.9\n# New\nnew: 2\nstop: 0.3  # mine\n")


def test_a_config_merge_tells_the_files_header_from_a_parameters_comment():
    """A ROS 1 file's first parameter follows the header: its comment (description, rules) is added
    below the header, and a comment of the user's there is the parameter's, changed as one."""
    old = HEADER + "rate: 1.0\n\nlimit: 5\n"
    new = HEADER + "# 0.0 to 5.0\nrate: 1.0\n\n# 0 to 10\nlimit: 5\n"
    merged = config_merge.merge(old, old.replace("rate: 1.0", "rate: 2.0"), new, ({}, {"rate": "0.0 to 5.0",
                                                                                       "limit": "0 to 10"}))
    assert merged.text == HEADER + "# 0.0 to 5.0\nrate: 2.0\n\n# 0 to 10\nlimit: 5\n"
    widened = config_merge.merge(new, merged.text, new.replace("5.0", "9.0"), ({"rate": "0.0 to 5.0"},
                                                                               {"rate": "0.0 to 9.0"}))
    assert widened.text == HEADER + "# 0.0 to 9.0\nrate: 2.0\n\n# 0 to 10\nlimit: 5\n"


def test_a_config_merge_reads_values_written_over_several_lines():
    old = "/**:\n  ros__parameters:\n    gains: [1.0, 2.0]\n\n    rate: 5\n"
    mine = "/**:\n  ros__parameters:\n    gains:\n      - 1.0\n      - 2.5\n    rate: 5  # Hz\n"
    new = "/**:\n  ros__parameters:\n    gains: [1.0, 2.0]\n\n    rate: 10\n"
    merged = config_merge.merge(old, mine, new)
    assert merged.text == "/**:\n  ros__parameters:\n    gains:\n      - 1.0\n      - 2.5\n    rate: 10  # Hz\n"
    assert config_merge.merge(old, mine, "/**:\n  ros__parameters: {}\n").text == (
        "/**:\n  ros__parameters:\n    gains:\n      - 1.0\n      - 2.5\n")


def test_a_long_list_in_a_config_file_breaks_after_its_commas_and_merges_as_one_value():
    from rna.configs import yaml_entry

    gains = [1.7976931348623157e308, -5e-324] * 12
    entry = yaml_entry("    ", "gains", gains)
    assert entry.splitlines()[0] == "    gains: [" and len(entry.splitlines()) > 2
    assert all(len(line) <= 99 and line.startswith("      ") for line in entry.splitlines()[1:])
    assert yaml_entry("", "gains", [1.0, 2.0]) == "gains: [1.0, 2.0]"
    old = f"/**:\n  ros__parameters:\n{entry}\n\n    rate: 5\n"
    mine = old.replace("rate: 5", "rate: 7")
    merged = config_merge.merge(old, mine, old.replace(entry, yaml_entry("    ", "gains", gains[:-1])))
    assert config_merge.parameters(merged.text) == {"gains": gains[:-1], "rate": 7}
    ros1 = yaml_entry("", "names", ["x" * 30] * 5)
    assert config_merge.parameters(ros1) == {"names": ["x" * 30] * 5} and "\n  x" in ros1


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


PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>robot</name>
  <!-- BEGIN rna-template: dependencies of the nodes -->
  <depend>nav_msgs</depend>
  <depend>sensor_msgs</depend>
  <exec_depend>std_srvs</exec_depend>
  <!-- END rna-template: add your own dependencies below -->
{mine}
</package>
"""


def test_a_block_leaves_out_what_the_users_own_lines_declare():
    text, left_out = blocks.package_xml_without_duplicates(PACKAGE_XML.format(mine="  <depend>sensor_msgs</depend>"))
    assert left_out == ["sensor_msgs"]
    assert text.count("sensor_msgs") == 1 and blocks.package_xml_problems(text) == []
    # only what the user's lines do not give stays in the block
    text, _ = blocks.package_xml_without_duplicates(PACKAGE_XML.format(mine="  <exec_depend>nav_msgs</exec_depend>"))
    assert "  <build_depend>nav_msgs</build_depend>\n  <build_export_depend>nav_msgs</build_export_depend>\n" in text
    assert blocks.package_xml_problems(text) == []
    text, left_out = blocks.package_xml_without_duplicates(PACKAGE_XML.format(mine="  <depend>std_srvs</depend>"))
    assert left_out == ["std_srvs"] and "<exec_depend>std_srvs" not in text
    # a commented-out line of the user's declares nothing
    same = PACKAGE_XML.format(mine="  <!-- <depend>sensor_msgs</depend> -->")
    assert blocks.package_xml_without_duplicates(same) == (same, [])


def test_package_xml_problems_are_the_ones_catkin_pkg_raises():
    assert blocks.package_xml_problems(PACKAGE_XML.format(mine="")) == []
    assert blocks.package_xml_problems(PACKAGE_XML.format(mine="  <depend>nav_msgs</depend>")) == [
        "nav_msgs is declared by <depend> and again by <depend>"]
    assert blocks.package_xml_problems(PACKAGE_XML.format(mine="  <exec_depend>nav_msgs</exec_depend>")) == [
        "nav_msgs is declared by <depend> and again by <exec_depend>"]
    assert blocks.package_xml_problems(PACKAGE_XML.format(mine="  <exec_depend>std_srvs</exec_depend>")) == []
    assert blocks.package_xml_problems("<package>")[0].startswith("it is not well-formed XML")


def test_find_package_lines_the_user_wrote_leave_the_block():
    text = ("# BEGIN rna-template: dependencies\nfind_package(rclcpp REQUIRED)\nfind_package(sensor_msgs REQUIRED)\n"
            "# END rna-template: add your own find_package() calls below\nfind_package(sensor_msgs  REQUIRED)\n")
    merged, left_out = blocks.cmake_without_duplicates(text)
    assert merged.count("sensor_msgs") == 1 and "find_package(rclcpp REQUIRED)" in merged
    assert left_out == ["find_package(sensor_msgs REQUIRED)"]


def test_code_that_uses_a_package():
    assert blocks.uses('#include "nav_msgs/msg/odometry.hpp"\n', "nav_msgs", ".cpp")
    assert blocks.uses("#include <nav_msgs/Odometry.h>\n", "nav_msgs", ".h")
    assert blocks.uses("from nav_msgs.msg import Odometry\n", "nav_msgs", ".py")
    assert blocks.uses("import nav_msgs\n", "nav_msgs", ".py")
    assert not blocks.uses("import nav_msgs_extra\n# from nav_msgs.msg import x\n", "nav_msgs", ".py")
    assert not blocks.uses("// #include <nav_msgs/Odometry.h>\n", "nav_msgs", ".cpp")


def test_changes_that_only_touch_each_other_both_land():
    base = "intro\noverride it in your class.\n\n## Build\n"
    ours = "intro\noverride it in your class. Ask the lab first.\n\n## Build\n"
    theirs = "intro\noverride it in your class.\n\nSee the docs.\n\n## Build\n"
    assert merge.merge3(ours, base, theirs) == (
        "intro\noverride it in your class. Ask the lab first.\n\nSee the docs.\n\n## Build\n", False)
    # a library added inside a list the template grows, next to the line it changes
    base = "libs(\n  a\n  b)\n"
    ours = "libs(\n  a\n  b\n  mine)\n"
    theirs = "libs(\n  a\n  new\n  b)\n"
    assert merge.merge3(ours, base, theirs) == ("libs(\n  a\n  new\n  b\n  mine)\n", False)


def test_whole_methods_both_sides_add_at_one_place_are_both_kept():
    base = "class A:\n\n    def a(self):\n        pass\n\n\ndef main():\n"
    ours = "class A:\n\n    def a(self):\n        pass\n\n    def mine(self):\n        return 1\n\n\ndef main():\n"
    theirs = ("class A:\n\n    def a(self):\n        pass\n\n"
              "    def hook(self, changed):\n        pass\n\n\ndef main():\n")
    assert merge.merge3(ours, base, theirs) == (
        "class A:\n\n    def a(self):\n        pass\n\n    def mine(self):\n        return 1\n\n"
        "    def hook(self, changed):\n        pass\n\n\ndef main():\n", False)
    # one name on both sides, or lines that are not whole methods: still the user's call
    assert merge.merge3(ours, base, theirs.replace("hook", "mine"))[1]
    assert merge.merge3(ours, base, theirs.replace("    def hook(self, changed):\n", "    x = 1\n"))[1]


def test_real_conflicts_stay_marked():
    text, conflicted = merge.merge3("x\nmine\ny\n", "x\nold\ny\n", "x\nnew\ny\n")
    assert conflicted and text == "x\n<<<<<<< before updating\nmine\n=======\nnew\n>>>>>>> after updating\ny\n"
    # both sides added lines at the same place: the order is the user's call
    assert merge.merge3("a\nmine\nb\n", "a\nb\n", "a\nnew\nb\n")[1]
    # the user edited a line the template deletes
    assert merge.merge3("a\nmine\nb\n", "a\nold\nb\n", "a\nb\n")[1]


def test_ros2_to_ros1_is_refused_in_one_line_and_ros1_to_ros2_is_a_port():
    ros2 = {"ros_distro": "jazzy", "build_type": "ament_cmake"}
    error = refusals.switch_error(ros2, {"ros_distro": "noetic"})
    assert error is not None and error.question == "ros_distro"
    assert "ROS 1" in str(error) and "ROS 2" in str(error) and "Keep ros_distro jazzy" in str(error)
    assert "nothing was written" in str(error) and "\n" not in str(error)
    assert refusals.switch_error({"ros_distro": "noetic"}, ros2) is None  # a port (rna/update/port.py)
    assert refusals.switch_error(ros2, {**ros2, "ros_distro": "humble"}) is None  # another ROS 2 distro
    assert refusals.switch_error(ros2, {**ros2, "build_type": "ament_python"}) is None  # a conversion the update makes
    assert refusals.switch_error({}, ros2) is None and refusals.switch_error({"ros_distro": None}, ros2) is None
    # a port renames nodes, not the package: that is an update of its own
    renamed = refusals.switch_error({"ros_distro": "noetic", "package_name": "rover"},
                                    {"ros_distro": "kilted", "package_name": "rover2"})
    assert renamed is not None and renamed.question == "package_name" and "\n" not in str(renamed)
    assert refusals.switch_error({"ros_distro": "noetic", "package_name": "rover"},
                                 {"ros_distro": "noetic", "package_name": "rover2"}) is None


def test_a_node_is_ported_only_once_the_package_around_it_is_ros2():
    node = {"ros_distro": "noetic", "target": "node"}
    error = refusals.port_error(node, {"ros_distro": "kilted"}, {"build_type": "catkin"})
    assert error is not None and error.question == "ros_distro" and "\n" not in str(error)
    assert "package.xml" in str(error) and "nothing was written" in str(error)
    assert refusals.port_error(node, {"ros_distro": "kilted"}, {"build_type": "ament_cmake"}) is None
    package = {**node, "target": "package"}
    assert refusals.port_error(package, {"ros_distro": "kilted"}, {"build_type": "catkin"}) is None
    assert refusals.port_error(node, {"ros_distro": "noetic"}, {"build_type": "catkin"}) is None


ANSWERS_TEXT = ("# Written by Copier: change answers with `copier update`, never by hand (see README.md).\n"
                "# rna-template checksum of the answers below: {checksum}\n"
                "_commit: v0.2.0\n_src_path: /templates/rna\ndescription: Drives the robot\n"
                "nodes:\n-   language: python\n    name: driver\npackage_name: robot\n")
RECORDED = {"_commit": "v0.2.0", "_src_path": "/elsewhere", "description": "Drives the robot",
            "nodes": [{"language": "python", "name": "driver"}], "package_name": "robot"}


@settings(max_examples=300, deadline=None)
@given(st.text(), st.text(alphabet=st.characters(codec="ascii")))
def test_answers_yaml_reads_back_as_the_answers_whatever_their_characters(text, ascii_text):
    """Written all in ASCII, answers_yaml() reads nothing back (the escaped spelling would be
    the same text); either way what it writes reads back as the answers."""
    for answers in ({"description": text, "nodes": [{"name": "n", "description": ascii_text}]},
                    {"label": ascii_text, "text": text}):
        assert yaml.safe_load(resolve.answers_yaml(answers)) == answers
        raw, escaped = (yaml.dump(answers, indent=4, allow_unicode=allow, default_flow_style=False)
                        for allow in (True, False))
        assert raw == escaped or not raw.isascii()


def test_an_answers_file_edited_by_hand_is_told_from_one_copier_wrote():
    text = ANSWERS_TEXT.format(checksum=resolve.checksum(RECORDED))  # Copier's own keys do not count
    assert resolve.edited_by_hand(text) is False
    reformatted = text.replace("-   language: python\n    name: driver\n", "- {name: driver, language: python}\n")
    assert resolve.edited_by_hand(reformatted + "# a comment of mine\n") is False  # the same answers
    assert resolve.edited_by_hand(text.replace("/templates/rna", "/moved/rna")) is False  # the template moved
    assert resolve.edited_by_hand(text.replace("Drives the robot", "Drives the rover")) is True
    assert resolve.edited_by_hand(text.replace("name: driver", "name: driver\n    timers: [0.1]")) is True
    assert resolve.edited_by_hand(text.replace("robot\n", "robot\ninterfaces: {}\n", 1)) is True
    assert resolve.edited_by_hand(ANSWERS_TEXT.replace("# rna-template checksum", "# other")) is None  # 0.2.0
    assert resolve.edited_by_hand("nodes: [") is None
    edited = text.replace("Drives the robot", "Drives the rover")  # read by the caller already
    assert resolve.edited_by_hand(edited, yaml.safe_load(edited)) is True
    assert resolve.edited_by_hand(text, yaml.safe_load(text)) is False


def test_a_hand_edited_answers_file_is_refused_with_the_safe_way():
    error = refusals.hand_edit_error(".copier-answers.yml")
    assert ".copier-answers.yml" in error and "--data" in error and "nothing was written" in error
    assert "\n" not in error


def robot(license: str = "Apache-2.0", **driver) -> rna.Package:
    return rna.build_package({
        "package_name": "robot", "description": "x", "maintainer": "Ada", "maintainer_email": "ada@example.com",
        "license": license, "copyright_holder": "Ada", "copyright_year": 2026, "ros_distro": "jazzy",
        "build_type": "ament_cmake", "target": "package", "interfaces": {},
        "nodes": [{"name": "driver", "language": "cpp", "subscribers": ["odom:nav_msgs/msg/Odometry"],
                   "service_servers": ["reset:std_srvs/srv/Trigger"], **driver}]})


USER_CODE = "void on_odom(const Odometry & msg) override { last_x_ = msg.pose.pose.position.x; }"


def test_what_an_edited_user_file_must_follow():
    old = robot()
    assert drift.reasons(old, old, "driver", USER_CODE) == []
    pose = robot(subscribers=["odom:geometry_msgs/msg/PoseStamped"])
    [reason] = drift.reasons(old, pose, "driver", USER_CODE)
    assert "on_odom" in reason and "geometry_msgs/msg/PoseStamped" in reason and "nav_msgs/msg/Odometry" in reason
    assert drift.reasons(old, pose, "driver", "int main() {}") == []  # the user's code does not override it
    reset = robot(service_servers=["reset:std_srvs/srv/Empty"])
    assert drift.reasons(old, reset, "driver", "void on_reset_request(") != []
    assert "lifecycle" in " ".join(drift.reasons(old, robot(lifecycle=True), "driver", USER_CODE))
    assert "lifecycle" in " ".join(drift.reasons(robot(lifecycle=True), old, "driver", USER_CODE))
    assert "component" in " ".join(drift.reasons(old, robot(component=True), "driver", USER_CODE))
    assert "diagnostics updater now" in " ".join(drift.reasons(old, robot(diagnostics=True), "driver", USER_CODE))
    assert "no longer has a diagnostics" in " ".join(drift.reasons(robot(diagnostics=True), old, "driver", USER_CODE))
    [license] = drift.reasons(old, robot("MIT"), "driver", USER_CODE)
    assert "MIT" in license and "Apache-2.0" in license
    [gone] = drift.reasons(old, robot(subscribers=[]), "driver", USER_CODE)  # an override of nothing
    assert "on_odom" in gone and "no longer" in gone
    assert drift.reasons(old, robot(subscribers=[]), "driver", "int main() {}") == []
    python = {"language": "python", "subscribers": ["odom:nav_msgs/msg/Odometry"]}
    [dead] = drift.reasons(robot(**python), robot(**{**python, "subscribers": []}), "driver",
                           "def on_odom(self, msg):")  # dead code in Python: it builds, and never runs
    assert "on_odom" in dead and "never called" in dead
    assert drift.STARTER_SUFFIX not in (".py", ".cpp", ".hpp", ".h", ".txt")


def test_a_launch_file_of_another_format_is_kept_with_where_its_lines_go():
    old, new = (rna.build_package({**VALID, "launch_format": launch_format}) for launch_format in ("xml", "yaml"))
    assert protect.why_gone("robot_driver/launch/robot_driver.launch.xml", old, new) == (
        "the launch file is YAML now: move what you added into robot_driver/launch/robot_driver.launch.yaml")


# --- renames


def _node(name: str, language: str = "cpp", ros: int = 2) -> rna.model.Node:
    return rna.model.Node(name=name, language=language, package="robot", ros=ros)


def test_a_renamed_nodes_code_keeps_every_user_line_and_renames_what_the_template_owns():
    old, new = _node("driver"), _node("base_controller")
    old_starter = ('// The driver node: your code goes here.\n#include "robot/driver_base.hpp"\n'
                   "class Driver : public DriverBase\n{\n};\n")
    new_starter = old_starter.replace("driver", "base_controller").replace("Driver", "BaseController")
    mine = old_starter.replace("{\n", "{\n  // the driver's wheels: mine\n  Driver * self_ = this;\n") + (
        'int main() { ros::init(argc, argv, "driver"); auto my_driver = robot::Driver(); }\n')
    code = renames.renamed_code(mine, old, new, old_starter, new_starter)
    assert code == (
        '// The base_controller node: your code goes here.\n#include "robot/base_controller_base.hpp"\n'
        "class BaseController : public BaseControllerBase\n{\n  // the driver's wheels: mine\n"
        "  BaseController * self_ = this;\n};\n"
        'int main() { ros::init(argc, argv, "base_controller"); auto my_driver = robot::BaseController(); }\n')


def test_build_and_launch_lines_naming_a_renamed_node_name_the_new_one():
    text = ("add_executable(${PROJECT_NAME}_driver src/driver.cpp)\n"
            "target_link_libraries(driver tf2_ros::tf2_ros)  # mine\n"
            "# the driver's own flags\n"
            "install(PROGRAMS robot/driver.py DESTINATION lib/${PROJECT_NAME} RENAME driver)\n"
            "            'drive = robot.driver:main',\n"
            '  <node pkg="robot" exec="driver" name="driver">\n'
            '    <param from="$(find-pkg-share robot)/config/driver.yaml"/>\n'
            "add_executable(my_driver src/my_driver.cpp) robot_driver driver_base driver2\n")
    renamed = renames.renamed_lines(text, {"driver": "planner"}, "robot")
    assert renamed == (
        "add_executable(${PROJECT_NAME}_planner src/planner.cpp)\n"
        "target_link_libraries(planner tf2_ros::tf2_ros)  # mine\n"
        "# the driver's own flags\n"
        "install(PROGRAMS robot/planner.py DESTINATION lib/${PROJECT_NAME} RENAME planner)\n"
        "            'drive = robot.planner:main',\n"
        '  <node pkg="robot" exec="planner" name="planner">\n'
        '    <param from="$(find-pkg-share robot)/config/planner.yaml"/>\n'
        "add_executable(my_driver src/my_driver.cpp) robot_planner driver_base driver2\n")
    assert renames.still_named(renamed, {"driver": "planner"}, "robot") == []
    assert renames.still_named(text, {"driver": "planner"}, "robot")[:2] == [(1, "driver"), (2, "driver")]


def test_a_rename_must_name_a_node_of_the_package_being_updated():
    previous = {"nodes": [{"name": "driver"}, {"name": "monitor"}]}

    def error(nodes, before=previous, update=True):
        return rename_answers.rename_error(before, {"nodes": nodes}, update=update)

    assert error([{"name": "planner", "renamed_from": "driver"}, "monitor"]) is None
    assert error(["driver", "monitor"]) is None
    assert "'drvier' is no node of the package" in error([{"name": "planner", "renamed_from": "drvier"}])
    assert "still in the nodes" in error([{"name": "planner", "renamed_from": "driver"}, "driver"])
    assert "both renamed from 'driver'" in error([{"name": "a", "renamed_from": "driver"},
                                                 {"name": "b", "renamed_from": "driver"}])
    assert "is for `copier update`" in error([{"name": "a", "renamed_from": "driver"}], before=None, update=False)
    assert error([{"name": "a", "renamed_from": "driver"}], before=None, update=True) is None  # a scratch render


def test_the_answers_file_records_the_new_name_only_with_its_checksum():
    answers = {"_commit": "v1", "package_name": "robot",
               "nodes": [{"name": "planner", "language": "cpp", "renamed_from": "driver"}]}
    text = (f"# Written by Copier\n{resolve.CHECKSUM_LINE}{resolve.checksum(answers)}\n"
            + resolve.answers_yaml(answers))
    consumed = rename_answers.without_renames(text)
    assert "renamed_from" not in consumed and consumed.startswith("# Written by Copier\n")
    assert resolve.edited_by_hand(consumed) is False
    assert rename_answers.without_renames(consumed) is None


def test_a_renamed_node_without_a_language_keeps_the_one_it_had():
    previous = {"build_type": "ament_cmake", "nodes": [{"name": "driver", "language": "python"}]}
    nodes = [{"name": "planner", "renamed_from": "driver"}]
    resolve.keep_languages(nodes, {**previous, "build_type": "ament_python"})
    assert nodes[0]["language"] == "python"


def test_a_renamed_packages_paths_and_words_follow_it():
    names = {"robot": "rover", "robot_interfaces": "rover_interfaces"}
    assert renames.package_path("robot/robot/driver.py", names) == "rover/rover/driver.py"
    assert renames.package_path("robot/include/robot/driver_base.hpp", names) == "rover/include/rover/driver_base.hpp"
    assert renames.package_path("robot/launch/robot.launch.xml", names) == "rover/launch/rover.launch.xml"
    assert renames.package_path("robot_interfaces/msg/Target.msg", names) == "rover_interfaces/msg/Target.msg"
    assert renames.package_path("robot/robot_tools/x.py", names) == "rover/robot_tools/x.py"
    code = ('#include "robot/driver_base.hpp"\n// the robot drives\nnamespace robot\n{\n'
            "auto t = robot_interfaces::msg::Target();  // robot\n}  // namespace robot\nint robot_count = 0;\n")
    assert renames.package_renamed_text(code, names, ".cpp") == (
        '#include "rover/driver_base.hpp"\n// the robot drives\nnamespace rover\n{\n'
        "auto t = rover_interfaces::msg::Target();  // rover\n}  // namespace rover\nint robot_count = 0;\n")
    assert renames.package_renamed_text("# the robot\nfrom robot.helpers import clamp\n", names, ".py") == (
        "# the robot\nfrom rover.helpers import clamp\n")
    assert renames.package_renamed_text("robot", names, ".png") == "robot"


def test_a_kept_render_is_taken_only_for_exactly_the_answers_it_was_rendered_from(tmp_path):
    answers = {"_commit": "v1.0.0", "_src_path": "/t", "package_name": "robot", "nodes": [{"name": "a"}]}
    scratch = tmp_path / "copier._main.old_copy.x1" / "sub"
    (scratch / "robot").mkdir(parents=True)
    (scratch / "robot" / "package.xml").write_text("<package/>")
    (scratch / ".git").mkdir()
    assert kept.kind_of(scratch) == "old" and kept.kind_of(tmp_path / "project") is None
    folder = tmp_path / "kept"
    kept.keep(folder, "old", scratch, yaml.safe_dump(answers))
    files = kept.kept(str(folder), "old", answers)
    assert (files / "robot" / "package.xml").read_text() == "<package/>" and not (files / ".git").exists()
    for other in ({**answers, "_commit": "v1.0.1"}, {**answers, "_src_path": "/u"}, {**answers, "nodes": []},
                  {key: value for key, value in answers.items() if key != "_commit"}):
        assert kept.kept(str(folder), "old", other) is None
    assert kept.kept(str(folder), "new", answers) is None and kept.kept("", "old", answers) is None
    # A later update's render replaces it; the hook runs more than once for one render.
    (scratch / "robot" / "package.xml").write_text("<changed/>")
    kept.keep(folder, "old", scratch, yaml.safe_dump(answers))
    assert (files / "robot" / "package.xml").read_text() == "<package/>"
    later = tmp_path / "copier._main.old_copy.x2"
    shutil.copytree(scratch, later)
    kept.keep(folder, "old", later, yaml.safe_dump(answers))
    assert (files / "robot" / "package.xml").read_text() == "<changed/>"
    kept.discard(str(folder))
    assert kept.kept(str(folder), "old", answers) is None
    # The after-update step finds the folder named in the template clone it runs from.
    clone = tmp_path / "clone"
    clone.mkdir()
    assert kept.pointed(clone) is None
    kept.point(clone, str(folder))
    assert kept.pointed(clone) == str(folder)


OLD_PYTHON_BASE = "class DriverBase(Node):\n    pass\n\n\nclass CtrlC:\n    pass\n"
NEW_PYTHON_BASE = "class DriverBase(Node):\n    pass\n\n\ndef run(make_node, args=None):\n    pass\n"


def test_what_an_edited_user_file_must_follow_from_its_base_file():
    """A name the user's code imports from its base module that the new one lacks; an executor main() misses."""
    python = {"language": "python"}
    old, new = robot(**python).nodes[0], robot(**python).nodes[0]
    main_of_0_3 = "from robot.driver_base import CtrlC, DriverBase\n\ndef main(args=None):\n    ctrl_c = CtrlC()\n"
    [gone] = drift.base_reasons(old, new, main_of_0_3, OLD_PYTHON_BASE, NEW_PYTHON_BASE)
    assert gone.startswith("driver_base.py no longer has CtrlC, which your code uses")
    assert drift.base_reasons(old, new, "run(Driver, args=args)", OLD_PYTHON_BASE, NEW_PYTHON_BASE) == []
    threaded = robot(**python, executor="multi_threaded").nodes[0]
    assert drift.base_reasons(old, threaded, "run(Driver, args=args)", NEW_PYTHON_BASE, NEW_PYTHON_BASE) == []
    cpp, cpp_threaded = robot().nodes[0], robot(executor="multi_threaded", threads=4).nodes[0]
    spun_itself = "rclcpp::spin(node);"
    assert drift.base_reasons(cpp, cpp, spun_itself, None, None) == []  # still one thread: it works as it is
    [executor] = drift.base_reasons(cpp, cpp_threaded, spun_itself, None, None)
    assert executor == "it spins on a multi-threaded executor now, which main() gets by calling Driver::spin()"
    assert drift.base_reasons(cpp, cpp_threaded, "robot::Driver::spin(node);", None, None) == []


# Values of every parameter type, written as the template writes them (rna.configs.yaml_entry).
PARAMETER_VALUES = st.one_of(
    st.booleans(), st.integers(-(2**63), 2**63 - 1), st.floats(allow_nan=False), st.text(max_size=30),
    st.lists(st.floats(allow_nan=False), max_size=30), st.lists(st.text(max_size=8), max_size=6),
    st.lists(st.integers(-5, 5), max_size=40), st.lists(st.booleans(), max_size=3))
COMMENTS = st.text(st.characters(exclude_categories=("Cc", "Cs", "Zl", "Zp")), max_size=20).map(
    lambda text: "# " + text.strip())


@settings(max_examples=200, deadline=None)
@given(st.dictionaries(st.from_regex(r"[a-z][a-z0-9_]{0,12}", fullmatch=True), st.tuples(PARAMETER_VALUES,
                                                                                         PARAMETER_VALUES),
                       min_size=1, max_size=4),
       st.data(), st.booleans())
def test_a_comment_on_a_line_survives_any_change_of_its_default(parameters, data, ros2):
    """The user comments lines they did not tune (`frame_id: base_link  # must match the URDF`);
    whatever the defaults become, each comment stays on its parameter's line."""
    from rna.configs import yaml_entry

    indent = "    " if ros2 else ""
    head = "/**:\n  ros__parameters:\n" if ros2 else "# Parameters.\n"

    def config(values: dict) -> str:
        return head + "\n\n".join(yaml_entry(indent, name, value) for name, value in values.items()) + "\n"

    old, new = ({name: pair[index] for name, pair in parameters.items()} for index in (0, 1))
    commented = data.draw(st.dictionaries(st.sampled_from(sorted(parameters)), COMMENTS, min_size=1))
    lines = config(old).split("\n")
    for name, comment in commented.items():
        key = next(index for index, line in enumerate(lines) if line.startswith(f"{indent}{name}:"))
        end = key + 1
        while end < len(lines) and lines[end].startswith(indent + "  "):  # a list over several lines
            end += 1
        lines[end - 1] += f"  {comment}"
    mine = "\n".join(lines)
    assert config_merge.parameters(mine) == old  # a comment is no value
    merged = config_merge.merge(config(old), mine, config(new))
    assert merged is not None and not merged.conflicts
    assert config_merge.parameters(merged.text) == new
    for name, comment in commented.items():
        assert f"  {comment}" in merged.text, (name, comment, merged.text)
