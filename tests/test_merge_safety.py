"""`copier update` never loses a line the user wrote: realistic edits x template and answer changes.

A "lived-in" package carries every kind of edit people make to a generated package (code
in callbacks, helper methods, imports and includes, build lines and dependencies after the
managed blocks, new files, tuned parameters, extra launch actions, README paragraphs).
Each scenario crosses it with one change (a node added or removed, an endpoint or a
parameter added to the edited node or to another one, a default changed, the template
upgraded from each release) and requires exit code 0, no conflict markers, the user's
files untouched and every line the user wrote still in place.

The conflict scenarios edit lines INSIDE a managed block that the change also rewrites:
there a conflict cannot be avoided, and `copier update` must exit 1, name the file and
leave the user's line on the "before updating" side of the conflict.
"""

from __future__ import annotations

import re
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import pytest
import yaml
from catkin_pkg.package import parse_package

if "support.template_repo" not in sys.modules:  # its asserts explain themselves too
    pytest.register_assert_rewrite("support.template_repo")
from rna.update import resolve  # noqa: E402
from support.generation import git  # noqa: E402
from support.template_repo import (  # noqa: E402
    FLAVORS, NEW_VERSION, PACKAGE, RELEASES, Flavor, answers_of, append_after, broken_packages, commit_all,
    conflict_excerpts, conflict_regions, conflicted_files, conflicts_of, find_node, insert_before, kept_of,
    missing_block, replace_text, run_update, to_port_of, write_new_file,
)

pytest_plugins = ("support.template_repo",)
pytestmark = pytest.mark.update


# ─── Recording what the user wrote ────────────────────────────────────────────


@dataclass
class Edits:
    """Applies edits to a project and remembers each block of lines the user wrote."""

    project: Path
    blocks: list[tuple[str, str, list[str]]] = field(default_factory=list)  # (label, path, lines)
    owned: dict[str, str] = field(default_factory=dict)  # files the user owns: path -> content

    def after(self, label: str, path: str, anchor: str, text: str, occurrence: int | None = None) -> None:
        self.blocks.append((label, path, append_after(self.project / path, anchor, text, occurrence)))

    def before(self, label: str, path: str, anchor: str, text: str) -> None:
        self.blocks.append((label, path, insert_before(self.project / path, anchor, text)))

    def replace(self, label: str, path: str, old: str, new: str) -> None:
        self.blocks.append((label, path, replace_text(self.project / path, old, new)))

    def new_file(self, label: str, path: str, text: str, executable: bool = False) -> None:
        self.blocks.append((label, path, write_new_file(self.project / path, text, executable)))

    def own(self, path: str) -> None:
        """The whole file is the user's: after the update it must be byte for byte the same."""
        self.owned[path] = (self.project / path).read_text()

    def commit(self) -> None:
        for path in list(self.owned):
            self.own(path)
        commit_all(self.project, "my edits")

    def problems(self) -> list[str]:
        found = [f"[{label}] {problem}" for label, path, lines in self.blocks
                 if (problem := missing_block(self.project / path, lines))]
        found += [f"{path}: the user's file was changed by the update" for path, text in self.owned.items()
                  if not (self.project / path).is_file() or (self.project / path).read_text() != text]
        return found


# ─── The suite's figure ───────────────────────────────────────────────────────
# Every scenario counts the user's lines the update lost and whether it exited 0 with a
# package that colcon or catkin cannot read (the `figure` fixture, support/template_repo.py);
# conftest.py prints the sums after the run ("merge safety: ..."): both must be 0.


def written(edits: Edits) -> list[tuple[str, list[str]]]:
    """The user's lines of a set of edits: each block, and each whole file the user owns."""
    return [(path, lines) for _, path, lines in edits.blocks] + [
        (path, text.split("\n")) for path, text in edits.owned.items()]


# ─── The edits of a lived-in package ──────────────────────────────────────────

EDITED_NODES = ("driver", "monitor")  # user files edited; `logger` is the "other" node


def edit_python_node(edits: Edits, path: str, node: str, ros1: bool) -> None:
    log = "rospy.loginfo(" if ros1 else "self.get_logger().info("
    callback, between = {
        "driver": (f"{log}'Received a message on odom')", "    def on_odom(self, msg):"),
        "monitor": (f"{log}'Answering a reset request')", "    def on_reset_request(self, request"),
    }[node]
    edits.after("code in a callback", path, callback,
                "        # mine: remember what came last, for the control loop\n"
                "        self.last_seen = math.floor(10.0)")
    edits.before("a helper method between methods", path, between,
                 "    def clamp(self, value, limit=1.0):\n"
                 "        \"\"\"Keep a command inside +-limit (mine).\"\"\"\n"
                 "        return max(-limit, min(limit, value))\n")
    edits.replace("a helper method at the end of the class", path, "\n\n\ndef main(",
                  "\n\n    def distance_to(self, x, y):\n"
                  "        \"\"\"Distance from the origin (mine).\"\"\"\n"
                  "        return math.hypot(x, y)\n\n\ndef main(")
    edits.before("an extra import", path, "import rospy" if ros1 else "import rclpy", "import math\n")
    edits.own(path)


def edit_cpp_node(edits: Edits, path: str, ros1: bool) -> None:
    log = 'ROS_INFO("Received a message on odom");' if ros1 else \
        'RCLCPP_INFO(get_logger(), "Received a message on odom");'
    position = "msg->pose.pose.position.x" if ros1 else "msg.pose.pose.position.x"
    edits.after("code in a callback", path, log,
                f"    // mine: remember where the robot is\n    last_x_ = {position};")
    edits.before("a helper method between methods", path, "  /// Handles a message from odom.",
                 "  /// Keeps a command inside +-limit (mine).\n"
                 "  static double clamp(double value, double limit)\n"
                 "  {\n"
                 "    return std::max(-limit, std::min(limit, value));\n"
                 "  }\n")
    edits.after("a member and a helper method at the end of the class", path, "std::size_t count_ = 0;",
                "  double last_x_ = 0.0;\n"
                "\n"
                "  double distance_to(double x, double y) const\n"
                "  {\n"
                "    return std::hypot(x - last_x_, y);\n"
                "  }")
    edits.before("extra includes", path, "#include <cstddef>", "#include <algorithm>\n#include <cmath>")
    edits.own(path)


def lived_in(project: Path, flavor: Flavor) -> Edits:
    """Every kind of edit of the issue, in one package; committed."""
    edits = Edits(project)
    for node in EDITED_NODES:
        path = flavor.user_file(node)
        if flavor.language(node) == "cpp":
            edit_cpp_node(edits, path, flavor.ros1)
        else:
            edit_python_node(edits, path, node, flavor.ros1)

    edits.after("a <depend> after END", flavor.package_xml,
                "<!-- END rna-template: add your own dependencies below -->",
                f"  <depend>tf2_ros</depend>\n  <exec_depend>{'rviz' if flavor.ros1 else 'rviz2'}</exec_depend>")

    if flavor.name == "ament_python":
        edits.after("a console_scripts entry point after END", flavor.build_file,
                    "# END rna-template: add your own executables below",
                    "            'calibrate = robot.calibrate:main',")
        edits.after("a data_files line", flavor.build_file, "glob('config/*.yaml')),",
                    "        ('share/' + package_name + '/maps', glob('maps/*.yaml')),")
        edits.new_file("a new executable module", "robot/robot/calibrate.py",
                       '"""Calibrates the driver (mine)."""\n\n\ndef main():\n    print(\'calibrating\')\n')
    elif flavor.name == "ament_cmake":
        edits.after("find_package() after END", flavor.build_file,
                    "# END rna-template: add your own find_package() calls below",
                    "find_package(tf2_ros REQUIRED)")
        edits.after("a target, target_link_libraries() and install() after END", flavor.build_file,
                    "# END rna-template: add your own targets below",
                    "target_link_libraries(driver PRIVATE tf2_ros::tf2_ros)\n"
                    "\n"
                    "add_executable(calibrate src/calibrate.cpp)\n"
                    "target_link_libraries(calibrate PRIVATE rclcpp::rclcpp tf2_ros::tf2_ros)\n"
                    "install(TARGETS calibrate DESTINATION lib/${PROJECT_NAME})")
        edits.new_file("a new C++ source", "robot/src/calibrate.cpp", "int main() { return 0; }  // mine\n")
    else:
        edits.replace("a component added to find_package()", flavor.build_file,
                      "find_package(catkin REQUIRED COMPONENTS ${node_dependencies})",
                      "find_package(catkin REQUIRED COMPONENTS ${node_dependencies} tf2_ros)")
        edits.replace("a package added to catkin_package()", flavor.build_file,
                      "  CATKIN_DEPENDS ${node_dependencies}\n",
                      "  CATKIN_DEPENDS ${node_dependencies} tf2_ros\n")
        edits.after("a target, target_link_libraries() and install() after END", flavor.build_file,
                    "# END rna-template: add your own targets below",
                    "add_executable(calibrate src/calibrate.cpp)\n"
                    "target_link_libraries(calibrate ${catkin_LIBRARIES})\n"
                    "install(TARGETS calibrate RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})")
        edits.new_file("a new C++ source", "robot/src/calibrate.cpp", "int main() { return 0; }  // mine\n")

    utility = {"ament_python": "robot/robot/geometry_utils.py", "ament_cmake": "robot/robot/geometry_utils.py",
               "catkin": "robot/src/robot/geometry_utils.py"}[flavor.name]
    edits.new_file("a utility module", utility,
                   '"""Geometry helpers (mine)."""\n\nimport math\n\n\ndef wrap(angle):\n'
                   '    return math.atan2(math.sin(angle), math.cos(angle))\n')
    if flavor.ros1:
        edits.new_file("a second launch file", "robot/launch/sim.launch",
                       '<launch>\n  <include file="$(find robot)/launch/robot.launch"/>\n'
                       '  <param name="use_sim_time" value="true"/>\n</launch>\n')
    else:
        edits.new_file("a second launch file", "robot/launch/sim.launch.xml",
                       '<launch>\n  <include file="$(find-pkg-share robot)/launch/robot.launch.xml"/>\n'
                       '  <set_parameter name="use_sim_time" value="true"/>\n</launch>\n')

    edits.replace("a tuned parameter with a comment", flavor.config_file("driver"), "gain: 1.0",
                  "gain: 1.8  # tuned on the real robot")
    edits.before("a comment above a parameter", flavor.config_file("driver"), "frame_id: base_link",
                 ("" if flavor.ros1 else "    ") + "# the odometry frame of the real robot")
    edits.replace("a tuned parameter", flavor.config_file("monitor"), "limit: 5", "limit: 9")
    edits.after("a parameter of the user's own, commented", flavor.config_file("monitor"), "limit: 9",
                ("" if flavor.ros1 else "    ") + "alarm_delay: 2.5  # mine: seconds before the alarm")

    if flavor.ros1:
        edits.after("an extra <node> after END", flavor.launch_file, "<!-- END rna-template",
                    '  <node pkg="rviz" type="rviz" name="rviz" args="-d $(find robot)/config/robot.rviz"/>')
    else:
        edits.after("an extra <node> after END", flavor.launch_file, "<!-- END rna-template",
                    '  <node pkg="rviz2" exec="rviz2" name="rviz" output="screen">\n'
                    '    <param name="use_sim_time" value="false"/>\n'
                    '  </node>')

    edits.before("a README section", "README.md", "## Build and run",
                 "## Hardware\n\nThe driver talks to the motor controller over CAN at 500 kbit/s;\n"
                 "see the wiring diagram in docs/wiring.pdf.\n")
    edits.replace("a README paragraph edited", "README.md",
                  "override it in your class to act on the messages.",
                  "override it in your class to act on the messages. Ask the lab before changing the answers.")
    edits.commit()
    return edits


# ─── The changes ──────────────────────────────────────────────────────────────


def new_node(flavor: Flavor) -> dict:
    node = {"name": "planner", "subscribers": ["scan:sensor_msgs/msg/LaserScan:sensor_data"],
            "publishers": ["path:nav_msgs/msg/Path"], "parameters": ["horizon:double=2.0"], "timers": ["0.2"]}
    if flavor.name != "ament_python":
        node["language"] = "cpp" if flavor.name == "ament_cmake" else "python"
    return node


def add_to(names: tuple[str, ...], kind: str, value: str) -> Callable[[Flavor, list[dict]], list[dict]]:
    def change(flavor: Flavor, nodes: list[dict]) -> list[dict]:
        for name in names:
            node = find_node(nodes, name)
            node[kind] = node.get(kind, []) + [value]
        return nodes
    return change


def set_default(node_name: str, parameter: str, value: str) -> Callable[[Flavor, list[dict]], list[dict]]:
    def change(flavor: Flavor, nodes: list[dict]) -> list[dict]:
        node = find_node(nodes, node_name)
        node["parameters"] = [f"{parameter}:{p.split(':')[1].split('=')[0]}={value}"
                              if isinstance(p, str) and p.split(":")[0] == parameter else p
                              for p in node["parameters"]]
        return nodes
    return change


def remove(name: str) -> Callable[[Flavor, list[dict]], list[dict]]:
    return lambda flavor, nodes: [node for node in nodes if node["name"] != name]


@dataclass(frozen=True)
class Change:
    nodes: Callable[[Flavor, list[dict]], list[dict]] | None  # None: the template upgrade from `release`
    effect: Callable[[Path, Flavor], bool]  # did the update do what the change asks?
    release: str = NEW_VERSION  # the version the package is made with


def text(project: Path, path: str) -> str:
    return (project / path).read_text() if (project / path).is_file() else ""


CHANGES = {
    "add-a-node": Change(
        lambda flavor, nodes: nodes + [new_node(flavor)],
        lambda p, f: (p / f.config_file("planner")).is_file() and "planner" in text(p, f.launch_file)),
    "add-a-subscriber-to-the-edited-nodes": Change(
        add_to(EDITED_NODES, "subscribers", "scan:sensor_msgs/msg/LaserScan"),
        lambda p, f: all("on_scan(" in text(p, f.base_file(n)) for n in EDITED_NODES)),
    "add-a-publisher-to-the-edited-node": Change(
        add_to(("driver",), "publishers", "status:std_msgs/msg/String"),
        lambda p, f: "status_publisher" in text(p, f.base_file("driver"))),
    "add-a-service-to-the-edited-node": Change(
        add_to(("driver",), "service_servers", "calibrate:std_srvs/srv/Trigger"),
        lambda p, f: "on_calibrate_request(" in text(p, f.base_file("driver"))),
    "add-a-subscriber-to-another-node": Change(
        add_to(("logger",), "subscribers", "odom:nav_msgs/msg/Odometry"),
        lambda p, f: "on_odom(" in text(p, f.base_file("logger"))),
    "add-a-publisher-to-another-node": Change(
        add_to(("logger",), "publishers", "status:std_msgs/msg/String"),
        lambda p, f: "status_publisher" in text(p, f.base_file("logger"))),
    "add-a-service-to-another-node": Change(
        add_to(("logger",), "service_servers", "clear:std_srvs/srv/Empty"),
        lambda p, f: "on_clear_request(" in text(p, f.base_file("logger"))),
    "add-a-parameter-to-the-edited-node": Change(
        add_to(("driver",), "parameters", "timeout:double=0.5"),
        lambda p, f: "timeout: 0.5" in text(p, f.config_file("driver"))),
    # monitor's only parameter, limit, is tuned: the new one goes right after its line
    "add-a-parameter-after-a-tuned-one": Change(
        add_to(("monitor",), "parameters", "window:int=10"),
        lambda p, f: "window: 10" in text(p, f.config_file("monitor"))),
    # frame_id's line is right after the tuned gain's line in config/driver.yaml
    "change-the-default-next-to-a-tuned-parameter": Change(
        set_default("driver", "frame_id", "odom"),
        lambda p, f: "frame_id: odom" in text(p, f.config_file("driver"))),
    # max_speed's line is two lines below the tuned gain's
    "change-the-default-of-another-parameter": Change(
        set_default("driver", "max_speed", "0.9"),
        lambda p, f: "max_speed: 0.9" in text(p, f.config_file("driver"))),
    "remove-another-node": Change(
        remove("logger"),
        lambda p, f: not (p / f.config_file("logger")).exists() and "logger" not in text(p, f.launch_file)),
    **{f"template-upgrade-from-{release.removeprefix('v')}": Change(
        None, lambda p, f: answers_of(p)["_commit"] == NEW_VERSION, release) for release in RELEASES},
}


def apply_change(project: Path, flavor: Flavor, change: Change):
    if change.nodes is None:
        return run_update(project, vcs_ref=NEW_VERSION)
    return run_update(project, {"nodes": change.nodes(flavor, flavor.answers["nodes"])})


# ─── Scenarios without conflicts ──────────────────────────────────────────────


@pytest.mark.parametrize("change_name", CHANGES)
@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_user_lines_survive(project, figure, flavor_name, change_name):
    flavor = Flavor(flavor_name)
    change = CHANGES[change_name]
    destination = project(flavor_name, change.release)
    edits = lived_in(destination, flavor)

    result = apply_change(destination, flavor, change)
    figure(result, destination, written(edits))

    problems = edits.problems()
    conflicts = conflicted_files(destination)
    report = "\n".join([f"exit code {result.returncode}", *[f"conflict: {c}" for c in conflicts], *problems])
    assert result.returncode == 0 and not conflicts and not problems, (
        f"{report}\n{conflict_excerpts(destination)}\n{result}")
    assert change.effect(destination, flavor), f"the update did not apply '{change_name}'\n{result}"


# ─── Scenarios with an unavoidable conflict ───────────────────────────────────


@dataclass(frozen=True)
class Conflict:
    flavor: str
    path: Callable[[Flavor], str]
    edit: Callable[[Path, Flavor], list[str]]  # returns the user's lines
    nodes: Callable[[Flavor, list[dict]], list[dict]]


def edit_dependency_line(project: Path, flavor: Flavor) -> list[str]:
    tag = "exec_depend" if flavor.name == "ament_python" else "depend"
    return replace_text(project / flavor.package_xml, f"  <{tag}>diagnostic_msgs</{tag}>",
                        f'  <{tag} version_gte="1.12">diagnostic_msgs</{tag}>')


def tune_gain(project: Path, flavor: Flavor) -> list[str]:
    return [line.strip() for line in replace_text(project / flavor.config_file("driver"), "gain: 1.0", "gain: 1.8")]


def set_gain_default(flavor: Flavor, nodes: list[dict]) -> list[dict]:
    find_node(nodes, "driver")["parameters"][0]["default"] = 2.5
    return nodes


def link_inside_the_block(project: Path, flavor: Flavor) -> list[str]:
    return replace_text(project / flavor.build_file, "  ${rcl_interfaces_TARGETS}\n  rclcpp::rclcpp)",
                        "  ${rcl_interfaces_TARGETS}\n  rclcpp::rclcpp\n  tf2_ros::tf2_ros)")[-1:]


def remap_inside_a_generated_node(project: Path, flavor: Flavor) -> list[str]:
    anchor = "config/logger.yaml"
    return append_after(project / flavor.launch_file, anchor,
                        ['    <remap from="/diagnostics" to="/robot/diagnostics"/>'])


def dependency_in_the_catkin_list(project: Path, flavor: Flavor) -> list[str]:
    return append_after(project / flavor.build_file, "  std_srvs", ["  tf2_ros"])


def readme_row(project: Path, flavor: Flavor) -> list[str]:
    language = "C++" if flavor.language("driver") == "cpp" else "Python"
    return replace_text(project / "README.md", f"| `driver` | {language} | Publishes cmd_vel and subscribes to odom. |",
                        f"| `driver` | {language} | Publishes cmd_vel and subscribes to odom; drives the base. |")


CONFLICTS = {
    **{f"{name}-edited-depend-line-of-a-removed-node": Conflict(
        name, lambda f: f.package_xml, edit_dependency_line, remove("logger")) for name in FLAVORS},
    **{f"{name}-tuned-parameter-whose-default-changes": Conflict(
        name, lambda f: f.config_file("driver"), tune_gain, set_gain_default) for name in FLAVORS},
    "ament_cmake-link-library-added-inside-the-block": Conflict(
        "ament_cmake", lambda f: f.build_file, link_inside_the_block,
        add_to(("driver",), "subscribers", "scan:sensor_msgs/msg/LaserScan")),
    "ament_python-remap-inside-a-generated-launch-node": Conflict(
        "ament_python", lambda f: f.launch_file, remap_inside_a_generated_node, remove("logger")),
    "catkin-remap-inside-a-generated-launch-node": Conflict(
        "catkin", lambda f: f.launch_file, remap_inside_a_generated_node, remove("logger")),
    "catkin-package-added-inside-node_dependencies": Conflict(
        "catkin", lambda f: f.build_file, dependency_in_the_catkin_list,
        lambda f, nodes: nodes + [{"name": "marker", "language": "python",
                                   "publishers": ["markers:visualization_msgs/msg/MarkerArray"]}]),
    "ament_python-readme-row-of-a-grown-node": Conflict(
        "ament_python", lambda f: "README.md", readme_row,
        add_to(("driver",), "subscribers", "scan:sensor_msgs/msg/LaserScan")),
}


@pytest.mark.parametrize("case", CONFLICTS)
def test_edit_inside_a_managed_block_conflicts_loudly(project, figure, case):
    conflict = CONFLICTS[case]
    flavor = Flavor(conflict.flavor)
    destination = project(conflict.flavor)
    path = conflict.path(flavor)
    user_lines = conflict.edit(destination, flavor)
    commit_all(destination, "an edit inside a managed block")

    result = run_update(destination, {"nodes": conflict.nodes(flavor, flavor.answers["nodes"])})
    figure(result, destination, [(path, user_lines)])

    assert result.returncode == 1, f"expected exit code 1 for a conflict in {path}\n{result}"
    assert path in conflicts_of(result.output), f"{path} is not named as a conflict\n{result}"
    assert path in conflicted_files(destination)
    regions = conflict_regions((destination / path).read_text())
    assert regions, f"no conflict block in {path}\n{(destination / path).read_text()}"
    ours = [line.strip() for region, _ in regions for line in region]
    for line in user_lines:
        assert line.strip() in ours, (f"the user's line {line.strip()!r} is not on the 'before updating' side "
                                      f"in {path}:\n{(destination / path).read_text()}")


# ─── Files the answers stop making ────────────────────────────────────────────
# Any file the user edited is kept when the new answers no longer make it, and the
# update fails naming it and why: the user decides what becomes of it.


def with_languages(flavor: Flavor, nodes: list[dict]) -> list[dict]:
    """The nodes with each one's language written out (as the answers file stores them)."""
    return [{**node, "language": flavor.language(node["name"])} for node in nodes]


def interfaces_added(project: Path, flavor: Flavor) -> None:
    """The package as it is after an update that gave it a message, committed."""
    nodes = with_languages(flavor, flavor.answers["nodes"])
    find_node(nodes, "driver")["publishers"] = ["target:Target"]
    result = run_update(project, {"interfaces": {"messages": [{"name": "Target", "fields": ["float64 x"]}]},
                                  "nodes": nodes})
    assert result.returncode == 0, result
    commit_all(project, "a message")


@dataclass(frozen=True)
class Dropped:
    """An edit to a file, then an answer change after which the template no longer makes that file."""

    flavor: str
    edit: Callable[[Path, Flavor], dict[str, list[str]]]  # returns path -> the user's lines
    answers: Callable[[Flavor], dict]
    why: str  # a word the reason given must hold
    prepare: Callable[[Path, Flavor], None] | None = None


def console_script(project: Path, flavor: Flavor) -> dict[str, list[str]]:
    return {flavor.build_file: append_after(project / flavor.build_file,
                                            "# END rna-template: add your own executables below",
                                            ["            'calibrate = robot.calibrate:main',"])}


def find_package_line(project: Path, flavor: Flavor) -> dict[str, list[str]]:
    return {flavor.build_file: append_after(project / flavor.build_file,
                                            "# END rna-template: add your own find_package() calls below",
                                            ["find_package(tf2_ros REQUIRED)"])}


def init_docstring(project: Path, flavor: Flavor) -> dict[str, list[str]]:
    path = f"{PACKAGE}/{PACKAGE}/__init__.py"
    return {path: write_over(project / path, ['"""The robot\'s Python code (mine)."""', ""])}


def write_over(path: Path, lines: list[str]) -> list[str]:
    path.write_text("\n".join(lines))
    return lines


def interfaces_build_files(project: Path, flavor: Flavor) -> dict[str, list[str]]:
    home = f"{PACKAGE}_interfaces"
    end = "<!-- END rna-template: add your own dependencies below -->"
    return {f"{home}/package.xml": append_after(project / home / "package.xml", end, ["  <depend>std_msgs</depend>"]),
            f"{home}/CMakeLists.txt": append_after(project / home / "CMakeLists.txt", "project(robot_interfaces)",
                                                   ["# mine: the robot's messages"])}


def tuned_config(project: Path, flavor: Flavor) -> dict[str, list[str]]:
    path = flavor.config_file("driver")
    return {path: replace_text(project / path, "max_speed: 0.5", "max_speed: 0.8")}


def without(name: str) -> Callable[[Flavor], dict]:
    return lambda flavor: {"nodes": with_languages(flavor, [n for n in flavor.answers["nodes"] if n["name"] != name])}


DROPPED = {
    "ament_python-setup.py-when-the-build-type-changes": Dropped(
        "ament_python", console_script,
        lambda f: {"build_type": "ament_cmake", "nodes": with_languages(f, f.answers["nodes"])}, "ament_cmake"),
    "ament_cmake-CMakeLists.txt-when-the-build-type-changes": Dropped(
        "ament_cmake", find_package_line,
        lambda f: {"build_type": "ament_python", "nodes": [{"name": "monitor", **find_node(f.answers["nodes"],
                                                                                         "monitor")}]},
        "ament_python"),
    "ament_cmake-__init__.py-when-the-last-python-node-goes": Dropped(
        "ament_cmake", init_docstring, without("monitor"), "Python"),
    **{f"{name}-interfaces-package-when-the-interfaces-go": Dropped(
        name, interfaces_build_files, lambda f: {"interfaces": {}, "nodes": with_languages(f, f.answers["nodes"])},
        "interfaces", prepare=interfaces_added) for name in ("ament_cmake", "catkin")},
    **{f"{name}-tuned-config-of-a-removed-node": Dropped(name, tuned_config, without("driver"), "driver")
       for name in FLAVORS},
}


@pytest.mark.parametrize("case", DROPPED)
def test_an_edited_file_the_answers_no_longer_make_is_kept_and_named(project, figure, case):
    dropped = DROPPED[case]
    flavor = Flavor(dropped.flavor)
    destination = project(dropped.flavor)
    if dropped.prepare:
        dropped.prepare(destination, flavor)
    edits = dropped.edit(destination, flavor)
    commit_all(destination, "my edits")

    result = run_update(destination, dropped.answers(flavor))
    figure(result, destination, list(edits.items()))

    assert result.returncode != 0, f"the update exited 0 although it dropped files the user edited\n{result}"
    kept = kept_of(result.output)
    for path, lines in edits.items():
        assert missing_block(destination / path, lines) is None, f"{path} lost the user's lines\n{result}"
        assert path in kept, f"{path} is not named as kept\n{result}"
        assert dropped.why in kept[path], f"the reason for keeping {path} does not say {dropped.why!r}: {kept[path]}"
    assert not conflicted_files(destination), conflict_excerpts(destination)
    assert broken_packages(destination) == [], result


# ─── Managed blocks and the user's own lines ──────────────────────────────────
# A dependency the user declares below a block's END marker is the user's: when the
# answers come to need it too, the block leaves it out (package.xml must still parse).

PACKAGE_XML_END = "<!-- END rna-template: add your own dependencies below -->"


def declarations(package_xml: Path, name: str) -> list[str]:
    return [line.strip() for line in package_xml.read_text().splitlines()
            if re.fullmatch(rf"\s*<(\w+)>{name}</\1>\s*", line)]


@dataclass(frozen=True)
class Declared:
    flavor: str
    lines: dict[Callable[[Flavor], str], tuple[str, list[str]]]  # file -> (anchor, the user's lines)
    nodes: Callable[[Flavor, list[dict]], list[dict]]
    package_xml: str = f"{PACKAGE}/package.xml"
    interfaces: dict | None = None  # given with the change
    prepare: Callable[[Path, Flavor], None] | None = None


def add_scan(flavor: Flavor, nodes: list[dict]) -> list[dict]:
    return add_to(("driver", "monitor"), "subscribers", "scan:sensor_msgs/msg/LaserScan")(flavor, nodes)


def point_field(project: Path, flavor: Flavor) -> None:
    interfaces_added(project, flavor)


DECLARED = {
    "ament_python-exec_depend": Declared(
        "ament_python", {lambda f: f.package_xml: (PACKAGE_XML_END, ["  <exec_depend>sensor_msgs</exec_depend>"])},
        add_scan),
    "ament_cmake-depend-and-find_package": Declared(
        "ament_cmake", {lambda f: f.package_xml: (PACKAGE_XML_END, ["  <depend>sensor_msgs</depend>"]),
                        lambda f: f.build_file: ("# END rna-template: add your own find_package() calls below",
                                                 ["find_package(sensor_msgs REQUIRED)"])},
        add_scan),
    "ament_cmake-exec_depend-only": Declared(
        "ament_cmake", {lambda f: f.package_xml: (PACKAGE_XML_END, ["  <exec_depend>sensor_msgs</exec_depend>"])},
        add_scan),
    "catkin-depend": Declared(
        "catkin", {lambda f: f.package_xml: (PACKAGE_XML_END, ["  <depend>sensor_msgs</depend>"])}, add_scan),
    **{f"{name}-interfaces-package": Declared(
        name, {lambda f: f"{PACKAGE}_interfaces/package.xml": (PACKAGE_XML_END, ["  <depend>geometry_msgs</depend>"])},
        lambda f, nodes: with_languages(f, nodes), package_xml=f"{PACKAGE}_interfaces/package.xml",
        interfaces={"messages": [{"name": "Target", "fields": ["float64 x", "geometry_msgs/Point p"]}]},
        prepare=interfaces_added) for name in ("ament_cmake", "catkin")},
}


@pytest.mark.parametrize("case", DECLARED)
def test_a_dependency_the_user_declared_is_never_declared_twice(project, figure, case):
    declared = DECLARED[case]
    flavor = Flavor(declared.flavor)
    destination = project(declared.flavor)
    if declared.prepare:
        declared.prepare(destination, flavor)
    edits = Edits(destination)
    for path, (anchor, lines) in declared.lines.items():
        edits.after("the user's own dependency", path(flavor), anchor, "\n".join(lines))
    edits.commit()
    nodes = declared.nodes(flavor, flavor.answers["nodes"])
    if declared.interfaces:
        find_node(nodes, "driver")["publishers"] = ["target:Target"]

    result = run_update(destination, {"nodes": nodes, **({"interfaces": declared.interfaces}
                                                           if declared.interfaces else {})})
    figure(result, destination, written(edits))

    assert result.returncode == 0 and not conflicted_files(destination), f"{conflict_excerpts(destination)}{result}"
    assert edits.problems() == []
    assert broken_packages(destination) == [], result
    package_xml = destination / declared.package_xml
    name = "geometry_msgs" if declared.interfaces else "sensor_msgs"
    found = declarations(package_xml, name)
    assert found and all(tag.count("depend") == 2 for tag in found), package_xml.read_text()
    tags = [re.match(r"<(\w+)>", line)[1] for line in found]
    assert len(tags) == len(set(tags)) and not ("depend" in tags and len(tags) > 1), package_xml.read_text()
    if flavor.name != "ament_python" and not declared.interfaces:
        model = parse_package(str(package_xml))
        assert name in {d.name for d in model.build_depends} & {d.name for d in model.exec_depends}
    cmake = destination / flavor.build_file
    if flavor.name == "ament_cmake" and not declared.interfaces:
        assert cmake.read_text().count(f"find_package({name} REQUIRED)") == 1, cmake.read_text()


# The user's own code includes (imports) a message package the answers used; the answers
# stop using it: the update must say that the package leaves package.xml while the code uses it.

USES_NAV_MSGS = {
    "ament_python": ("import rclpy", "from nav_msgs.msg import Odometry\n"),
    "ament_cmake": ("#include <cstddef>", '#include "nav_msgs/msg/odometry.hpp"'),
    "catkin": ("#include <cstddef>", "#include <nav_msgs/Odometry.h>"),
}


@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_a_dependency_the_users_code_still_uses_is_not_dropped_silently(project, figure, flavor_name):
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    anchor, line = USES_NAV_MSGS[flavor_name]
    edits = Edits(destination)
    edits.before("an include of the old message package", flavor.user_file("driver"), anchor, line)
    edits.commit()
    nodes = flavor.answers["nodes"]
    find_node(nodes, "driver")["subscribers"] = ["odom:geometry_msgs/msg/PoseStamped"]

    result = run_update(destination, {"nodes": nodes})
    figure(result, destination, written(edits))

    assert edits.problems() == []
    still = "nav_msgs" in {d.name for d in (lambda p: p.build_depends + p.exec_depends)(
        parse_package(str(destination / flavor.package_xml)))}
    said = "nav_msgs" in result.output and flavor.user_file("driver") in result.output
    assert still or (said and result.returncode != 0), f"nav_msgs was dropped without a word\n{result}"


# ─── Config files keep the user's text ────────────────────────────────────────
# Comments, order and layout of a tuned config file survive a changed default or a new
# parameter, whatever --conflict says.

SLIP = "the wheels slip above this"


def tuned_with_comments(project: Path, flavor: Flavor) -> Edits:
    edits = Edits(project)
    path, indent = flavor.config_file("driver"), "" if flavor.ros1 else "    "
    edits.replace("a tuned value with a comment", path, "gain: 1.0", "gain: 1.8  # tuned on the real robot, March")
    edits.before("a comment above a parameter", path, "frame_id: base_link", f"{indent}# the frame of the lidar")
    # no blank line, and a comment on a line the user does not tune (its default changes below)
    replace_text(project / path, f"\n\n{indent}max_speed: 0.5\n", f"\n{indent}max_speed: 0.5  # {SLIP}\n")
    edits.after("a parameter of the user's own", path, "max_speed: 0.5", f"{indent}stop_distance: 0.3  # mine")
    edits.commit()
    return edits


def config_change(flavor: Flavor) -> list[dict]:
    nodes = set_default("driver", "max_speed", "0.9")(flavor, flavor.answers["nodes"])
    return add_to(("driver",), "parameters", "timeout:double=0.5")(flavor, nodes)


@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_a_config_merge_keeps_the_users_text_whatever_the_conflict_mode(project, figure, flavor_name):
    flavor = Flavor(flavor_name)
    outcomes = {}
    for mode in ("inline", "rej"):
        destination = project(flavor_name, name=mode)
        edits = tuned_with_comments(destination, flavor)
        result = run_update(destination, {"nodes": config_change(flavor)}, extra_args=("--conflict", mode))
        figure(result, destination, written(edits))
        assert result.returncode == 0 and not conflicted_files(destination), (
            f"--conflict {mode}: {conflict_excerpts(destination)}\n{result}")
        assert edits.problems() == [], f"--conflict {mode}\n{result}"
        text = (destination / flavor.config_file("driver")).read_text()
        values = yaml.safe_load(text)
        values = values if flavor.ros1 else values["/**"]["ros__parameters"]
        assert values == {"gain": 1.8, "frame_id": "base_link", "max_speed": 0.9, "stop_distance": 0.3,
                          "timeout": 0.5}, f"--conflict {mode}:\n{text}"
        indent = "" if flavor.ros1 else "    "
        assert f"frame_id: base_link\n{indent}max_speed: 0.9  # {SLIP}\n" in text, f"the user's text is lost:\n{text}"
        outcomes[mode] = text
    assert outcomes["inline"] == outcomes["rej"]


@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_a_real_config_conflict_is_loud_whatever_the_conflict_mode(project, flavor_name):
    """The user tuned gain and its default changed too: the user decides, in both modes."""
    flavor = Flavor(flavor_name)
    for mode in ("inline", "rej"):
        destination = project(flavor_name, name=mode)
        tuned_with_comments(destination, flavor)
        nodes = set_gain_default(flavor, config_change(flavor))
        result = run_update(destination, {"nodes": nodes}, extra_args=("--conflict", mode))
        path = flavor.config_file("driver")
        assert result.returncode == 1 and path in str(result), f"--conflict {mode}\n{result}"
        conflicts = conflicted_files(destination)
        assert (path if mode == "inline" else f"{path}.rej") in conflicts, f"--conflict {mode}: {conflicts}"
        text = (destination / path).read_text()
        assert f"max_speed: 0.9  # {SLIP}" in text and "timeout: 0.5" in text, (
            f"--conflict {mode}: the rest is merged\n{text}")
        assert "# the frame of the lidar" in text and "stop_distance: 0.3  # mine" in text, text


# ─── Between ROS generations ──────────────────────────────────────────────────
# ROS 1 -> ROS 2 is a port (rna/update/port.py): the lived-in catkin package keeps every
# line its user wrote, as written or in its ROS 2 form. ROS 2 -> ROS 1 is refused before
# anything is written, in one line naming the question and what to do instead.

SWITCHES = {
    "ament_python-to-noetic": ("ament_python", {"ros_distro": "noetic"}),
    "ament_cmake-to-noetic": ("ament_cmake", {"ros_distro": "noetic"}),
}


@pytest.mark.parametrize("case", SWITCHES)
def test_ros2_to_ros1_is_refused_before_anything_is_written(project, figure, case):
    flavor_name, change = SWITCHES[case]
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    edits = lived_in(destination, flavor)
    head = git("rev-parse", "HEAD", cwd=destination).stdout

    result = run_update(destination, {**change, "nodes": with_languages(flavor, flavor.answers["nodes"])})
    figure(result, destination, written(edits))

    assert result.returncode != 0, f"the update went ahead\n{result}"
    refusals = [line for line in result.output.splitlines() if line.startswith("rna-template: ")]
    assert len(refusals) == 1, f"no one-line refusal\n{result}"
    assert "'ros_distro'" in refusals[0] and "ROS 1" in refusals[0] and "Keep ros_distro" in refusals[0], refusals[0]
    assert git("status", "--porcelain", "--untracked-files=all", cwd=destination).stdout == "", (
        f"the refused update wrote files\n{result}")
    assert git("rev-parse", "HEAD", cwd=destination).stdout == head


# Where the port puts each file of the lived-in catkin package, and each of its user's lines
# that ROS 2 writes otherwise (config files' lines move under ros__parameters, 4 columns in).
PORTED_PATHS = {"robot/scripts/monitor.py": "robot/robot/monitor.py",
                "robot/src/robot/geometry_utils.py": "robot/robot/geometry_utils.py",
                "robot/launch/robot.launch": "robot/launch/robot.launch.xml",
                "robot/launch/sim.launch": "robot/launch/sim.launch.xml"}
PORTED_LINES = {
    "    last_x_ = msg->pose.pose.position.x;": "    last_x_ = msg.pose.pose.position.x;",
    "  <exec_depend>rviz</exec_depend>": "  <exec_depend>rviz2</exec_depend>",
    "find_package(catkin REQUIRED COMPONENTS ${node_dependencies} tf2_ros)": "find_package(tf2_ros REQUIRED)",
    "  CATKIN_DEPENDS ${node_dependencies} tf2_ros": "ament_export_dependencies(tf2_ros)",
    "target_link_libraries(calibrate ${catkin_LIBRARIES})": "# target_link_libraries(calibrate ${catkin_LIBRARIES})",
    "install(TARGETS calibrate RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})":
        "install(TARGETS calibrate RUNTIME DESTINATION lib/${PROJECT_NAME})",
    '  <include file="$(find robot)/launch/robot.launch"/>':
        '  <include file="$(find-pkg-share robot)/launch/robot.launch.xml"/>',
    '  <param name="use_sim_time" value="true"/>': '  <set_parameter name="use_sim_time" value="true"/>',
    '  <node pkg="rviz" type="rviz" name="rviz" args="-d $(find robot)/config/robot.rviz"/>':
        '  <node pkg="rviz2" exec="rviz2" name="rviz" args="-d $(find-pkg-share robot)/config/robot.rviz"/>',
}


def ported(user_lines: list[tuple[str, list[str]]]) -> list[tuple[str, list[str]]]:
    """The user's lines of the lived-in catkin package as the port to ROS 2 writes them."""
    found = []
    for path, lines in user_lines:
        config = "/config/" in path
        found.append((PORTED_PATHS.get(path, path),
                      [("    " + line if config and line.strip() else PORTED_LINES.get(line, line)) for line in lines]))
    return found


@pytest.mark.parametrize("distro", ["jazzy", "humble"])
def test_a_lived_in_catkin_package_ported_to_ros2_keeps_every_line(project, figure, distro):
    flavor = Flavor("catkin")
    destination = project("catkin")
    edits = lived_in(destination, flavor)
    head = git("rev-parse", "HEAD", cwd=destination).stdout

    result = run_update(destination, {"ros_distro": distro})
    # every block the user wrote (the whole files they own change as a whole: ported)
    expected = ported([(path, lines) for _, path, lines in edits.blocks])
    figure(result, destination, expected)

    # The one line no rule ports (calibrate linked catkin's libraries) is marked: the user must act.
    assert result.returncode == 1 and "1 line left marked TODO(port)" in result.stdout, result
    assert "robot/CMakeLists.txt: 3 rewrites, 1 TODO(port)" in result.stdout, result
    for path, lines in expected:
        text = (destination / path).read_text() if (destination / path).is_file() else ""
        missing = [line for line in lines if line.strip() and line not in text]
        assert not missing, f"{path}: {missing}\n{result}"
    assert broken_packages(destination) == [], result
    assert conflicted_files(destination) == [], conflict_excerpts(destination)
    ros1_files = [path for path in ("robot/scripts", "robot/src/robot", "robot/include/robot/driver_base.h",
                                    "robot/launch/robot.launch", "robot/test/graph.test", "robot/setup.py")
                  if (destination / path).exists()]
    assert ros1_files == [], ros1_files
    text = (destination / "robot/src/driver.cpp").read_text() + (destination / "robot/robot/monitor.py").read_text()
    assert "ros::" not in text and "rospy" not in text and "ROS_INFO" not in text, text
    assert git("rev-parse", "HEAD", cwd=destination).stdout == head, "the update committed"


# ─── Answers changed by hand ──────────────────────────────────────────────────
# Copier renders the old version from the answers file: edited by hand, it would take the
# edits as the package's old answers and change nothing. The update stops before writing.

HAND_EDITS = {
    "a-parameter-added": ("    - limit:int=5\n", "    - limit:int=5\n    - timeout:double=0.5\n"),
    "the-description": ("\ndescription: ", "\ndescription: Mine. "),
}


@pytest.mark.parametrize("edit", HAND_EDITS)
def test_an_answers_file_edited_by_hand_stops_the_update_with_the_safe_way(project, edit):
    destination = project("ament_python")
    replace_text(destination / ".copier-answers.yml", *HAND_EDITS[edit])
    commit_all(destination, "answers edited by hand")
    head = git("rev-parse", "HEAD", cwd=destination).stdout

    result = run_update(destination)

    assert result.returncode != 0, f"the update went ahead\n{result}"
    refusals = [line for line in result.output.splitlines() if line.startswith("rna-template: ")]
    assert len(refusals) == 1 and ".copier-answers.yml" in refusals[0] and "--data" in refusals[0], result
    assert git("status", "--porcelain", "--untracked-files=all", cwd=destination).stdout == "", result
    assert git("rev-parse", "HEAD", cwd=destination).stdout == head


def test_answers_changed_through_the_update_are_not_taken_for_hand_edits(project):
    destination = project("ament_python")
    nodes = with_languages(Flavor("ament_python"), Flavor("ament_python").answers["nodes"])
    find_node(nodes, "driver").setdefault("parameters", []).append("timeout:double=0.5")
    assert run_update(destination, {"nodes": nodes}).returncode == 0
    commit_all(destination, "a parameter")
    result = run_update(destination, {"description": "Drives the robot, and more"})
    assert result.returncode == 0, result


# ─── What an edited user file must follow ─────────────────────────────────────
# The user's class builds on its base class: when the answers change what it builds on (a
# callback's message type, lifecycle, diagnostics, the license in its header), the update names the
# file and writes the new starter beside it, under a name build tools and linters skip.


def retype_odom(flavor: Flavor, nodes: list[dict]) -> list[dict]:
    driver = find_node(nodes, "driver")
    driver["subscribers"] = ["odom:geometry_msgs/msg/PoseStamped"]
    return nodes


def lifecycle_driver(flavor: Flavor, nodes: list[dict]) -> list[dict]:
    find_node(nodes, "driver")["lifecycle"] = True
    return nodes


def diagnostics_driver(flavor: Flavor, nodes: list[dict]) -> list[dict]:
    find_node(nodes, "driver")["diagnostics"] = True
    return nodes


def changed_nodes(change: Callable[[Flavor, list[dict]], list[dict]]) -> Callable[[Flavor], dict]:
    return lambda flavor: {"nodes": change(flavor, with_languages(flavor, flavor.answers["nodes"]))}


DRIFTS = {
    **{f"{name}-callback-message-type": (name, changed_nodes(retype_odom), "PoseStamped now") for name in FLAVORS},
    **{f"{name}-lifecycle-switched-on": (name, changed_nodes(lifecycle_driver), "lifecycle")
       for name in ("ament_python", "ament_cmake")},
    **{f"{name}-diagnostics-switched-on": (name, changed_nodes(diagnostics_driver), "diagnostics updater")
       for name in FLAVORS},
    **{f"{name}-license": (name, lambda f: {"license": "MIT", **changed_nodes(lambda _, nodes: nodes)(f)}, "MIT")
       for name in FLAVORS},
    # the user's on_odom() overrides a callback nothing calls any more: dead code in Python, flagged all the same
    "ament_python-callback-whose-subscriber-is-removed": (
        "ament_python", changed_nodes(lambda _, nodes: [{**node, "subscribers": []} if node["name"] == "driver"
                                                        else node for node in nodes]), "never called"),
}


@pytest.mark.parametrize("case", DRIFTS)
def test_an_edited_user_file_is_told_what_to_follow_with_the_new_starter_beside_it(project, figure, case):
    flavor_name, answers, why = DRIFTS[case]
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    edits = lived_in(destination, flavor)
    path = flavor.user_file("driver")

    result = run_update(destination, answers(flavor))
    figure(result, destination, written(edits))

    assert result.returncode == 1, f"the update did not stop for the user to port {path}\n{result}"
    to_port = to_port_of(result.output)
    assert path in to_port and why in to_port[path], f"{path} is not named with {why!r}\n{result}"
    starter = destination / f"{path}.new-starter"
    assert starter.is_file() and starter.name in to_port[path], result
    assert starter.read_text() != (destination / path).read_text()
    assert edits.problems() == [], "\n".join(edits.problems())
    assert broken_packages(destination) == [], result
    assert not conflicted_files(destination), conflict_excerpts(destination)


# ─── Renames ──────────────────────────────────────────────────────────────────
# A node answer that says what it was renamed from (`renamed_from`) carries the user's
# node file (class and base renamed, every line of theirs kept), the tuned config values,
# the lines inside the node's launch entry and the user's build-file lines that name its
# target; the answers file records the new name only.

RENAMED = "base_controller"

# The user's lines that name the driver's target, executable or module, outside the blocks.
NAMES_THE_TARGET = {
    "ament_python": (lambda f: f.build_file, "# END rna-template: add your own executables below",
                     "            'drive = robot.driver:main',"),
    "ament_cmake": (lambda f: f.build_file, "# END rna-template: add your own targets below",
                    "target_compile_definitions(driver PRIVATE USE_CAN=1)"),
    "catkin": (lambda f: f.build_file, "# END rna-template: add your own targets below",
               "target_compile_definitions(${PROJECT_NAME}_driver PRIVATE USE_CAN=1)"),
}


def renamed_driver(flavor: Flavor) -> dict:
    nodes = with_languages(flavor, flavor.answers["nodes"])
    driver = find_node(nodes, "driver")
    driver["name"], driver["renamed_from"] = RENAMED, "driver"
    return {"nodes": nodes}


def renamed_text(line: str) -> str:
    """A line of the build or launch file as the rename leaves it: the driver's target named anew."""
    return re.sub(r"(?<![A-Za-z0-9_])((?:\$\{PROJECT_NAME\}_)?)driver(?![A-Za-z0-9_])", rf"\g<1>{RENAMED}", line)


def assert_carried(result, destination: Path, figure, carried: list) -> None:
    """The update merged cleanly and every block the user wrote is where the rename moved it
    (`carried`: label, path, lines), counted in the merge-safety figure."""
    figure(result, destination, [(where, lines) for _, where, lines in carried])
    assert result.returncode == 0 and not conflicted_files(destination), f"{conflict_excerpts(destination)}{result}"
    for label, where, lines in carried:
        assert missing_block(destination / where, lines) is None, f"[{label}] {where}\n{result}"


@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_a_renamed_node_carries_the_users_file_values_launch_entry_and_build_lines(project, figure, flavor_name):
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    edits = lived_in(destination, flavor)
    path, anchor, line = NAMES_THE_TARGET[flavor_name]
    edits.after("a line naming the driver's target", path(flavor), anchor, line)
    edits.after("a remap inside the driver's launch entry", flavor.launch_file, "config/driver.yaml",
                '    <remap from="odom" to="/wheel/odom"/>')
    edits.commit()
    old_file, new_file = flavor.user_file("driver"), flavor.user_file(RENAMED, flavor.language("driver"))

    result = run_update(destination, renamed_driver(flavor))

    moved = {old_file: new_file, flavor.config_file("driver"): flavor.config_file(RENAMED)}
    carried = [(label, moved.get(where, where), [renamed_text(line) for line in lines]
                if where in (flavor.build_file, flavor.launch_file) else lines) for label, where, lines in edits.blocks]
    assert_carried(result, destination, figure, carried)
    assert not (destination / old_file).exists() and not (destination / flavor.config_file("driver")).exists()
    code = (destination / new_file).read_text()
    class_name = "BaseController"
    assert f"{class_name}Base" in code and not re.search(r"\bDriver(Base)?\b|driver_base", code), code
    config = (destination / flavor.config_file(RENAMED)).read_text()
    assert "gain: 1.8  # tuned on the real robot" in config and "the odometry frame of the real robot" in config
    launch = (destination / flavor.launch_file).read_text()
    assert f'name="{RENAMED}"' in launch and 'name="driver"' not in launch, launch
    build = (destination / flavor.build_file).read_text()
    assert renamed_text(line) in build and line not in build, build
    answers = (destination / ".copier-answers.yml").read_text()
    assert "renamed_from" not in answers and resolve.edited_by_hand(answers) is False, answers
    assert f"{old_file} -> {new_file}" in result.output.replace("\n", " ").replace("   ", " "), result
    assert broken_packages(destination) == [], result


@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_a_renamed_nodes_config_conflict_is_loud_whatever_the_conflict_mode(project, flavor_name):
    """Renamed while the default of its tuned gain changed: the user decides, the conflict
    marked in the renamed config file or in a .rej beside it, as --conflict asks."""
    flavor = Flavor(flavor_name)
    for mode in ("inline", "rej"):
        destination = project(flavor_name, name=mode)
        tuned_with_comments(destination, flavor)
        answers = renamed_driver(flavor)
        find_node(answers["nodes"], RENAMED)["parameters"][0]["default"] = 2.5
        result = run_update(destination, answers, extra_args=("--conflict", mode))
        path = flavor.config_file(RENAMED)
        assert result.returncode == 1 and path in str(result), f"--conflict {mode}\n{result}"
        conflicts = conflicted_files(destination)
        assert conflicts == [path if mode == "inline" else f"{path}.rej"], f"--conflict {mode}: {conflicts}"
        text = (destination / path).read_text()
        assert "# the frame of the lidar" in text and "stop_distance: 0.3  # mine" in text, text


def test_a_rename_naming_no_node_of_the_package_is_refused(project):
    destination = project("ament_python")
    answers = renamed_driver(Flavor("ament_python"))
    find_node(answers["nodes"], RENAMED)["renamed_from"] = "drvier"
    head = git("rev-parse", "HEAD", cwd=destination).stdout

    result = run_update(destination, answers)

    assert result.returncode != 0 and "renamed_from 'drvier'" in result.output, result
    assert git("status", "--porcelain", "--untracked-files=all", cwd=destination).stdout == "", result
    assert git("rev-parse", "HEAD", cwd=destination).stdout == head


# The package renamed (package_name): its folder, Python package, headers' folder and
# launch file follow, and so do the user's files and every line of theirs that names it.

NEW_PACKAGE = "rover"


def package_renamed(path: str) -> str:
    return "/".join(NEW_PACKAGE if part == PACKAGE else part.replace(f"{PACKAGE}.launch", f"{NEW_PACKAGE}.launch")
                    for part in path.split("/"))


def package_renamed_line(line: str) -> str:
    if line.lstrip().startswith(("#", "<!--", "//")):
        return line
    return re.sub(rf"(?<![A-Za-z0-9_]){PACKAGE}(?![A-Za-z0-9_])", NEW_PACKAGE, line)


@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_a_renamed_package_carries_the_users_files_and_lines(project, figure, flavor_name):
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    edits = lived_in(destination, flavor)

    result = run_update(destination, {"package_name": NEW_PACKAGE,
                                      "nodes": with_languages(flavor, flavor.answers["nodes"])})

    carried = [(label, package_renamed(where), [package_renamed_line(line) for line in lines])
               for label, where, lines in edits.blocks]
    assert_carried(result, destination, figure, carried)
    assert not (destination / PACKAGE).exists(), sorted(p.name for p in (destination / PACKAGE).rglob("*"))
    assert f"<name>{NEW_PACKAGE}</name>" in (destination / NEW_PACKAGE / "package.xml").read_text()
    if flavor.name != "ament_python":
        assert f"project({NEW_PACKAGE})" in (destination / NEW_PACKAGE / "CMakeLists.txt").read_text()
    for path in edits.owned:
        code = (destination / package_renamed(path)).read_text()
        assert not re.search(rf"^(?!\s*(#|//)).*\b{PACKAGE}\b", code, re.M), code
    assert f"{PACKAGE}/ -> {NEW_PACKAGE}/" in result.output, result
    assert broken_packages(destination) == [], result


@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_a_node_and_its_package_renamed_at_once_carry_the_users_file_and_build_lines(project, figure, flavor_name):
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    edits = lived_in(destination, flavor)
    path, anchor, line = NAMES_THE_TARGET[flavor_name]
    edits.after("a line naming the driver's target", path(flavor), anchor, line)
    edits.commit()
    new_file = package_renamed(flavor.user_file(RENAMED, flavor.language("driver")))

    result = run_update(destination, {"package_name": NEW_PACKAGE, **renamed_driver(flavor)})

    assert result.returncode == 0 and not conflicted_files(destination), f"{conflict_excerpts(destination)}{result}"
    code = (destination / new_file).read_text()
    assert "BaseControllerBase" in code, code
    assert not re.search(rf"^(?!\s*(#|//)).*\b({PACKAGE}|driver_base|DriverBase|Driver)\b", code, re.M), code
    build = (destination / package_renamed(flavor.build_file)).read_text()
    assert package_renamed_line(renamed_text(line)) in build, build
    assert broken_packages(destination) == [], result
