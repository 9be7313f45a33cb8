"""ros1 tier: generated catkin packages built with catkin_make and run on real ROS 1.

ROS 1 comes from Debian's own packages (tests/support/ros1.py installs them when
missing and run as root). The 12 node pairs of ROS Node Automator's plan: C++ and
Python senders and receivers for topics, services and actionlib, every combination,
each run against a private master inside its own network namespace.
"""

from __future__ import annotations

import contextlib
import random
import re
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

import pytest
from support import existing_packages, interrupts, real_packages
from support import ros1 as ros1_support
from support.drawn import Linter, check_drawn, code_linters, thorough, whole
from support.generation import VARIANTS, add_node, copy_template, example, generate
from support.processes import NodeProcess, assert_clean_exit, started
from support.strategies import valid_answers

pytestmark = pytest.mark.ros1

SERVER_PARAMETERS = [
    {"name": "rate", "default": 1.5, "description": "Work rate in Hz"},
    "label:string=plain",
    "limits:int[]=[1, 2]",
    "verbose=false",
]


def _node(role: str, language: str, **endpoints) -> dict:
    return {"name": f"{'cpp' if language == 'cpp' else 'py'}_{role}", "language": language, **endpoints}


PAIRS_PACKAGE = {
    "package_name": "pairs",
    "ros_distro": "noetic",
    "description": "Senders and receivers for every pair of languages",
    "nodes": [
        node
        for language in ("cpp", "python")
        for node in (
            _node("talker", language, publishers=["chatter:std_msgs/msg/String"], timers=[0.2]),
            _node("listener", language, subscribers=["chatter:std_msgs/msg/String"]),
            _node("server", language, service_servers=["reset:std_srvs/srv/Trigger"],
                  parameters=SERVER_PARAMETERS),
            _node("client", language, service_clients=["reset:std_srvs/srv/Trigger"], timers=[0.2]),
            _node("action_server", language, action_servers=["count:actionlib/action/Test"]),
            _node("action_client", language, action_clients=["count:actionlib/action/Test"], timers=[0.2]),
        )
    ],
}

# (sender, receiver, what the receiving side prints for each exchange)
TOPIC = [r'I heard: "Hello World: \d+"']
SERVICE = ["reset answered"]
ACTION = ["Feedback on the count goal", "The count goal succeeded"]
PAIRS = {
    f"{kind}-{sender_language}-to-{receiver_language}": (
        f"{sender_language}_{sender}", f"{receiver_language}_{receiver}", expected)
    for kind, sender, receiver, expected in (
        ("topic", "talker", "listener", TOPIC),
        ("service", "server", "client", SERVICE),
        ("action", "action_server", "action_client", ACTION),
    )
    for sender_language in ("cpp", "py")
    for receiver_language in ("cpp", "py")
}



@dataclass
class CatkinWorkspace:
    path: Path
    ros1: ros1_support.Ros1Environment
    logs: Path

    def executable(self, package: str, node: str) -> Path:
        name = f"{node}.py" if node.startswith("py_") else node
        return self.path / "devel" / "lib" / package / name

    @contextlib.contextmanager
    def network(self, name: str):
        """A private namespace with a master in it: (argv prefix, environment)."""
        with ros1_support.netns_prefix() as prefix:
            env = self.ros1.workspace_env(self.path / "devel", self.ros1.env(
                ros1_support.free_port(), self.logs / name / "ros_home"))
            with ros1_support.master(env, self.logs / name / "master.log", prefix):
                yield prefix, env

    def node(self, prefix, env, package: str, node: str, *args: str, log: Path) -> NodeProcess:
        return NodeProcess([*prefix, str(self.executable(package, node)), *args], env=env, log_path=log)


@pytest.fixture(scope="session")
def catkin_ws(ros1, template_dir, tmp_path_factory) -> CatkinWorkspace:
    """The pairs package and a small launch-file package, generated and built once."""
    path = tmp_path_factory.mktemp("catkin_ws")
    generate(template_dir, path / "src" / "pairs", PAIRS_PACKAGE)
    generate(template_dir, path / "src" / "bringup", LAUNCHED_PACKAGE)
    # Every endpoint kind, parameter type and both languages: compiled with -Werror.
    generate(template_dir, path / "src" / "everything", example(VARIANTS["ros1"], package_name="everything"))
    # Long names and awkward text must compile with -Werror too (escapes, aliases, line breaks).
    generate(template_dir, path / "src" / "long_names", example("long_names_ros1"))
    awkward = example("awkward_text", ros_distro="noetic")
    awkward.pop("build_type")
    generate(template_dir, path / "src" / "awkward", awkward)
    generate(template_dir, path / "src" / "tracker", TRACKER)
    generate(template_dir, path / "src" / "tracker_same", TRACKER_SAME)
    generate(template_dir, path / "src" / "diagnosed", DIAGNOSED)
    generate(template_dir, path / "src" / "long_goals", LONG_GOALS)
    _make_goals_long(path / "src" / "long_goals")
    # A C++ node added to a catkin package written by hand.
    add_node(template_dir, existing_packages.catkin(path / "src" / "hand_rover"),
             {"node_name": "listener", "node_subscribers": "chatter:std_msgs/msg/String"})
    # Packages shaped like real ones (rospy scripts without setup.py; roscpp as catkin_create_pkg
    # makes it): a node added to each, then grown by copier update.
    for name in REAL_PACKAGES:
        _, grown = real_packages.grown(template_dir, path / "src" / name, name)
        assert grown.returncode == 0, grown
    config = path / "src" / "bringup" / "bringup" / "config" / "talker.yaml"
    config.write_text(config.read_text().replace("rate: 1.5", "rate: 2.5"))  # tuned by a user
    workspace = CatkinWorkspace(path, ros1, tmp_path_factory.mktemp("ros1_logs"))
    ros1.catkin_make(path, ros1.env(ros1_support.free_port(), workspace.logs / "build_home"),
                     "-DCMAKE_CXX_FLAGS=-Werror")
    return workspace


@pytest.mark.parametrize("pair", sorted(PAIRS))
def test_generated_pair_exchanges(catkin_ws, pair):
    sender, receiver, expected = PAIRS[pair]
    logs = catkin_ws.logs / pair
    with catkin_ws.network(pair) as (prefix, env):
        receiving = catkin_ws.node(prefix, env, "pairs", receiver, log=logs / f"{receiver}.log")
        sending = catkin_ws.node(prefix, env, "pairs", sender, log=logs / f"{sender}.log")
        with started(receiving, sending):
            for pattern in expected:
                receiving.wait_for(pattern, timeout=30)
            for process in (receiving, sending):
                assert_clean_exit(process, process.interrupt())


@pytest.mark.parametrize("package", ["tracker", "tracker_same"])
@pytest.mark.parametrize(("sender", "receiver"), [("cpp_detector", "py_mover"), ("py_detector", "cpp_mover")])
def test_custom_interfaces_between_languages(catkin_ws, package, sender, receiver):
    name = f"{package}-{sender}-{receiver}"
    with catkin_ws.network(name) as (prefix, env):
        receiving = catkin_ws.node(prefix, env, package, receiver, log=catkin_ws.logs / name / "receiver.log")
        sending = catkin_ws.node(prefix, env, package, sender, log=catkin_ws.logs / name / "sender.log")
        with started(receiving, sending):
            receiving.wait_for("Received a message on target", timeout=30)
            receiving.wait_for("Answering a set_target request")
            sending.wait_for("set_target answered")
            sending.wait_for("Feedback on the approach goal")
            sending.wait_for("The approach goal succeeded")
            for process in (receiving, sending):
                assert_clean_exit(process, process.interrupt())


DIAGNOSED = {"package_name": "diagnosed", "ros_distro": "noetic",
             "description": "Talker and listener reporting their status on diagnostics",
             "nodes": [_node("talker", "cpp", diagnostics=True, publishers=["chatter:std_msgs/msg/String"],
                             timers=[0.2]),
                       _node("listener", "python", diagnostics=True, subscribers=["chatter:std_msgs/msg/String"])]}


def test_diagnostics_reach_another_process(catkin_ws):
    """C++ and Python nodes with `diagnostics: true` publish the starter's status on /diagnostics."""
    logs = catkin_ws.logs / "diagnostics"
    with catkin_ws.network("diagnostics") as (prefix, env):
        nodes = [catkin_ws.node(prefix, env, "diagnosed", name, log=logs / f"{name}.log")
                 for name in ("cpp_talker", "py_listener")]
        echo = NodeProcess([*prefix, "rostopic", "echo", "/diagnostics"], env={**env, "PYTHONUNBUFFERED": "1"},
                           log_path=logs / "echo.log")
        with started(*nodes, echo):
            for name in ("cpp_talker", "py_listener"):
                # A status of the node's task, as its starter fills it in: OK, "Running", no hardware.
                echo.wait_for(rf'level: 0\s+name: "/?{name}: Status"\s+message: "Running"\s+hardware_id: "none"',
                              timeout=30)
            for process in nodes:
                assert_clean_exit(process, process.interrupt())
            echo.interrupt()


LONG_GOALS = {"package_name": "long_goals", "ros_distro": "noetic", "description": "Goals that run for a while",
              "nodes": [_node(role, language, **endpoints) for language in ("cpp", "python") for role, endpoints in (
                  ("action_server", {"action_servers": ["count:actionlib/action/Test"]}),
                  ("stubborn_server", {"action_servers": ["count:actionlib/action/Test"]}),
                  ("action_client", {"action_clients": ["count:actionlib/action/Test"], "timers": [0.2]}))]}


def _make_goals_long(destination: Path) -> None:
    """Edit the servers' own files as a user would: goals of 30 s; the stubborn servers' goals
    look at ros::ok() / rospy.is_shutdown() only, not at preemption."""
    sources = destination / "long_goals"
    edits = {"src/cpp_action_server.cpp": [("step < 3;", "step < 300;")],
             "scripts/py_action_server.py": [("range(3)", "range(300)")],
             "src/cpp_stubborn_server.cpp": [("step < 3;", "step < 300;"),
                                             ("server.isPreemptRequested() || !ros::ok()", "!ros::ok()")],
             "scripts/py_stubborn_server.py": [("range(3)", "range(300)"),
                                               ("server.is_preempt_requested() or rospy.is_shutdown()",
                                                "rospy.is_shutdown()")]}
    for name, replacements in edits.items():
        path = sources / name
        text = path.read_text()
        for old, new in replacements:
            assert text.count(old) == 1, f"the starter code of {name} changed: no {old!r}"
            text = text.replace(old, new)
        path.write_text(text)


@pytest.mark.parametrize("client", ["cpp_action_client", "py_action_client"])
@pytest.mark.parametrize(("server", "ending"), [
    ("cpp_action_server", "PREEMPTED"), ("py_action_server", "PREEMPTED"),
    ("cpp_stubborn_server", "ABORTED"), ("py_stubborn_server", "ABORTED")])
def test_a_goal_running_when_its_server_stops_ends_for_the_client(catkin_ws, server, ending, client):
    """Ctrl-C mid-goal: the goal is preempted while the server can still send the result (as
    actionlib's tutorial ends a goal when ROS stops), aborted if it ignores that for a second;
    the client hears how it ended instead of waiting forever, and the server exits cleanly."""
    logs = catkin_ws.logs / f"goal_stop_{server}_{client}"
    with catkin_ws.network(f"goal_stop_{server}_{client}") as (prefix, env):
        server_process = catkin_ws.node(prefix, env, "long_goals", server, log=logs / "server.log")
        client_process = catkin_ws.node(prefix, env, "long_goals", client, log=logs / "client.log")
        with started(server_process, client_process):
            client_process.wait_for("Feedback on the count goal", timeout=30)
            assert_clean_exit(server_process, server_process.interrupt())
            status = {"PREEMPTED": 2, "ABORTED": 4}[ending]
            client_process.wait_for(rf"The count goal ended (as {ending}|with status {status})", timeout=5)
            assert_clean_exit(client_process, client_process.interrupt())


def test_node_added_to_a_hand_written_package_runs(catkin_ws):
    with catkin_ws.network("hand_rover") as (prefix, env):
        talker = NodeProcess([*prefix, str(catkin_ws.path / "devel" / "lib" / "hand_rover" / "hand_talker")],
                             env=env, log_path=catkin_ws.logs / "hand_rover" / "talker.log")
        listener = catkin_ws.node(prefix, env, "hand_rover", "listener", log=catkin_ws.logs / "hand_rover" / "l.log")
        with started(talker, listener):
            listener.wait_for(r'I heard: "Hello by hand"', timeout=30)
            for process in (listener, talker):
                assert_clean_exit(process, process.interrupt())


REAL_PACKAGES = {"rospy_tools": ("talker.py", "chatter_monitor.py"), "roscpp_bringup": ("talker", "chatter_monitor")}


@pytest.mark.parametrize("package", REAL_PACKAGES)
def test_a_node_added_to_a_real_package_and_grown_runs_with_rosrun(catkin_ws, package):
    """The node hears the package's own talker; started as users start nodes, with rosrun."""
    talker, node = REAL_PACKAGES[package]
    logs = catkin_ws.logs / package
    with catkin_ws.network(package) as (prefix, env):
        talking = NodeProcess([*prefix, "rosrun", package, talker], env=env, log_path=logs / "talker.log")
        monitor = NodeProcess([*prefix, "rosrun", package, node], env=env, log_path=logs / "monitor.log")
        with started(talking, monitor):
            monitor.wait_for(f'I heard: "hello from {package}"', timeout=30)
            assert_clean_exit(monitor, monitor.interrupt())
            talking.interrupt()


def test_parameters_come_from_the_command_line(catkin_ws):
    with catkin_ws.network("params_cli") as (prefix, env):
        for server in ("cpp_server", "py_server"):
            node = catkin_ws.node(prefix, env, "pairs", server, "_rate:=7.0", "_label:=from_cli",
                                  log=catkin_ws.logs / "params_cli" / f"{server}.log")
            with started(node):
                node.wait_for(r"rate: 7(\.0)?\b")
                node.wait_for("label: from_cli")
                node.wait_for(r"verbose: (false|False)")
                assert_clean_exit(node, node.interrupt())


SIGINT_SEED = 8
SIGINT_BATCHES = 5  # each starts two of every rospy node of `pairs`: 60 SIGINTs in all


def test_rospy_nodes_stop_cleanly_on_sigint_at_any_moment(catkin_ws):
    """Talker, listener, service and actionlib servers and clients, stopped at random moments."""
    rng = random.Random(SIGINT_SEED)
    python_nodes = [node["name"] for node in PAIRS_PACKAGE["nodes"] if node["language"] == "python"]
    failures, total = [], 0
    for batch in range(SIGINT_BATCHES):
        logs = catkin_ws.logs / f"sigint_{batch}"
        with catkin_ws.network(f"sigint_{batch}") as (prefix, env):
            runs = []
            for copy in range(2):
                for node in python_nodes:
                    name = f"{node}_{copy}"
                    process = catkin_ws.node(prefix, {**env, "ROS_LOG_DIR": str(logs / name)}, "pairs", node,
                                             f"__name:={name}", log=logs / f"{name}.log")
                    runs.append(interrupts.Run(node, process, logs / name, interrupts.draw_delay(rng)))
            with started(*(run.process for run in runs)):
                failures += interrupts.interrupt_all(runs)
        total += len(runs)
    assert total >= 60
    if failures:
        pytest.fail(interrupts.report(failures, total, SIGINT_SEED), pytrace=False)


def test_generated_packages_pass_catkin_lint(catkin_ws):
    for package in ("pairs/pairs", "bringup/bringup", "everything/everything", "tracker/tracker",
                    "tracker/tracker_interfaces", "tracker_same/tracker_same", "hand_rover", "diagnosed/diagnosed",
                    "long_names/target_tracking_navigation_ros1",
                    "long_names/target_tracking_navigation_ros1_interfaces", "awkward/awkward_text"):
        returncode, output = catkin_ws.ros1.catkin_lint(
            catkin_ws.path / "src" / package, catkin_ws.ros1.env(ros1_support.free_port(), catkin_ws.logs))
        assert returncode == 0, output
        assert "found 0 problems" in output, output


def _ros1_tracker_nodes() -> list[dict]:
    """Senders and receivers of the custom message, service and action, in both languages."""
    nodes = []
    for language in ("cpp", "python"):
        short = "cpp" if language == "cpp" else "py"
        nodes.append({"name": f"{short}_detector", "language": language, "timers": [0.2],
                      "publishers": ["target:Target"], "service_clients": ["set_target:SetTarget"],
                      "action_clients": ["approach:Approach"]})
        nodes.append({"name": f"{short}_mover", "language": language, "subscribers": ["target:Target"],
                      "service_servers": ["set_target:SetTarget"], "action_servers": ["approach:Approach"]})
    return nodes


# ROS 1 has no default values in interface definitions.
TRACKER_INTERFACES = example("tracker")["interfaces"]
ROS1_INTERFACES = {**TRACKER_INTERFACES, "messages": [
    {**TRACKER_INTERFACES["messages"][0], "fields": ["float64 x", "float64 y", "string frame_id",
                                                     "int32 MAX_TARGETS=5", "geometry_msgs/Point position"]},
    TRACKER_INTERFACES["messages"][1]]}
TRACKER = {"package_name": "tracker", "ros_distro": "noetic",
           "description": "Custom interfaces, used from C++ and Python",
           "interfaces": ROS1_INTERFACES, "nodes": _ros1_tracker_nodes()}
TRACKER_SAME = {**TRACKER, "package_name": "tracker_same", "interfaces_location": "package"}

LAUNCHED_PACKAGE = example("bringup_ros1")


def test_launch_file_starts_every_node_with_its_config(catkin_ws):
    with catkin_ws.network("roslaunch") as (prefix, env):
        launch = NodeProcess([*prefix, "roslaunch", "bringup", "bringup.launch"], env=env,
                             log_path=catkin_ws.logs / "roslaunch" / "roslaunch.log")
        with started(launch):
            launch.wait_for(r"rate: 2\.5", timeout=30)  # the value tuned in config/talker.yaml
            launch.wait_for(r'I heard: "Hello World: \d+"', timeout=30)
            assert_clean_exit(launch, launch.interrupt(timeout=30))


def test_launch_arguments_reach_every_node(catkin_ws):
    """namespace:=robot1 use_sim_time:=true, as roslaunch's summary lists what it starts."""
    with catkin_ws.network("roslaunch_args") as (prefix, env):
        launch = NodeProcess([*prefix, "roslaunch", "bringup", "bringup.launch", "namespace:=robot1",
                              "use_sim_time:=true"], env=env, log_path=catkin_ws.logs / "roslaunch" / "arguments.log")
        with started(launch):
            # The talker's own log line (roslaunch's summary lists the parameter before it starts anything).
            launch.wait_for(r"INFO\].*rate: 2\.5", timeout=30)
            launch.wait_for(r"process\[robot1/listener-\d+\]: started", timeout=30)
            # Started is not up: a rospy node stopped while it still imports rospy (seconds on a loaded
            # machine) prints a KeyboardInterrupt traceback before any of its code runs.
            wait_until_listed(prefix, env, "/robot1/listener")
            summary = launch.output
            assert re.search(r"^ \* /use_sim_time: True$", summary, re.MULTILINE), summary
            assert re.search(r"^ \* /robot1/talker/rate: 2\.5$", summary, re.MULTILINE), summary
            nodes = summary.split("NODES", 1)[1]
            assert re.search(r"^  /robot1/\n    listener \(bringup/listener\.py\)\n    talker \(bringup/talker\)$",
                             nodes, re.MULTILINE), summary
            assert_clean_exit(launch, launch.interrupt(timeout=30))


def wait_until_listed(prefix: list[str], env: dict, node: str, timeout: float = 30.0) -> None:
    """Until the master lists `node` (rospy registers in init_node(), with run() holding Ctrl-C)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        listed = subprocess.run([*prefix, "rosnode", "list"], env=env, capture_output=True, text=True, timeout=30,
                                check=False).stdout.split()
        if node in listed:
            return
        time.sleep(0.2)
    raise AssertionError(f"{node} never registered with the master")


# Drawn packages (issue 8): how many the default profile draws; HYPOTHESIS_PROFILE=thorough draws more.
DRAWN_ROS1 = 16
DRAWN_ROS1_THOROUGH = 150


@pytest.fixture(scope="module")
def plain_template(tmp_path_factory) -> Path:
    """The template as a plain folder: Copier renders it in place, without cloning it for each package."""
    return copy_template(tmp_path_factory.mktemp("plain_template"))


def test_drawn_packages_pass_catkin_lint_and_the_style_checks(ros1, ros2, plain_template, tmp_path):
    """Drawn catkin answer sets (C++ and Python nodes, own interfaces in the package or beside it): catkin_lint
    -W2 reports 0 problems, and the ROS 2 tier's linters (ament_flake8, ament_pep257, ament_cpplint,
    ament_uncrustify, borrowed from its Kilted environment) pass their code (tests/support/drawn.py)."""
    env = ros1.env(ros1_support.free_port(), tmp_path / "ros_home")

    def catkin_lint(paths):
        return ros1.catkin_lint(paths, env)

    linters = [Linter("catkin_lint -W2", catkin_lint, whole,
                      lambda returncode, output: returncode == 0 and "found 0 problems" in output),
               *code_linters(ros2)]
    count = DRAWN_ROS1_THOROUGH if thorough() else DRAWN_ROS1
    drawn, failures = check_drawn(plain_template, tmp_path, valid_answers(ros=1, interfaces=True), count, linters)
    assert drawn == count
    if failures:
        pytest.fail(failures, pytrace=False)
