"""The questions as users meet them: the copier CLI, non-interactive and at a terminal."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pexpect
import pytest
import yaml
from copier._cli import CopierApp
from support.generation import FIXED_ANSWERS, answers_of
from support.terminal import spawn_copier

COPIER = str(Path(sys.executable).with_name("copier"))


def copy_arguments(template: Path, destination: Path, *args: str) -> list[str]:
    data = [f"--data={key}={value}" for key, value in FIXED_ANSWERS.items()]
    return ["copy", "--trust", "--defaults", "--vcs-ref=HEAD", *data, *args, str(template), str(destination)]


def copier_copy(template: Path, destination: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([COPIER, *copy_arguments(template, destination, *args)], capture_output=True, text=True,
                          stdin=subprocess.DEVNULL, timeout=120)


def copier_cli_in_process(capsys, template: Path, destination: Path, *args: str) -> tuple[int, str]:
    """The same command through Copier's command-line app, run in this process: about 0.1 s
    instead of 0.7 s for a new interpreter and Copier's imports; its exit code and stderr.
    An exception the app does not turn into a message reaches the test."""
    capsys.readouterr()
    _, code = CopierApp.run(["copier", *copy_arguments(template, destination, *args)], exit=False)
    return code, capsys.readouterr().err


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--data", "package_name=My-Bad Pkg"],
         "invalid answer to 'package_name': use my_bad_pkg: 'My-Bad Pkg' breaks REP 144"),
        (["--data", "maintainer_email=nobody"],
         "invalid answer to 'maintainer_email': write it as name@host.domain: 'nobody' is not an e-mail"),
        (["--data", "nodes=[{name: Talker}]"],
         "invalid answer to 'nodes': use talker: 'Talker' is not a valid node name"),
        (["--data", "nodes=[{name: t, publishers: ['a b:std_msgs/msg/String']}]"],
         "invalid answer to 'nodes': node 't': publisher: topic 'a b'"),
        (["--data", "nodes=[{name: t, subscribers: [x:std_srvs/srv/Empty]}]"],
         "invalid answer to 'nodes': node 't': give a message type here: 'std_srvs/srv/Empty' is a service type"),
        (["--data", "nodes=[{name: t, language: cpp}]"], "an ament_python package holds Python nodes only"),
        # Choices and YAML that Copier itself would refuse with a traceback (issue 8).
        (["--data", "ros_distro=foxy"], "invalid answer to 'ros_distro': 'foxy' is not one of"),
        (["--data", "license=WTFPL"], "invalid answer to 'license': 'WTFPL' is not one of"),
        (["--data", "ros_distro=noetic", "--data", "build_type=ament_python"],
         "invalid answer to 'build_type': 'ament_python' is not one of catkin for ROS 1"),
        (["--data", "ros_distro=noetic", "--data", "launch_format=python"],
         "invalid answer to 'launch_format': roslaunch (ROS 1) reads XML launch files only: python is for ROS 2"),
        (["--data", "launch_format=json"], "invalid answer to 'launch_format': 'json' is not one of xml, python, yaml"),
        (["--data", "build_type=ament_python", "--data", "interfaces_location=package"],
         "invalid answer to 'interfaces_location': an ament_python package cannot build interfaces"),
        # Choices that depend on answers not given: the defaults (issue 25).
        (["--data", "build_type=catkin"], "invalid answer to 'build_type': 'catkin' is not one of ament_cmake, "
                                          "ament_python for ROS 2"),
        (["--data", "interfaces_location=package"],
         "invalid answer to 'interfaces_location': an ament_python package cannot build interfaces"),
        (["--data", "ros_distro=kilted", "--data", "launch_format=toml"],
         "invalid answer to 'launch_format': 'toml' is not one of xml, python, yaml"),
        (["--data", "nodes=- name: [unclosed"], "invalid answer to 'nodes': not valid YAML"),
        (["--data", "nodes=[{name: t, publishers: ['v:geometry_msgs/msg/Twst']}]"],
         "did you mean geometry_msgs/msg/Twist?"),
    ],
)
def test_bad_answers_give_one_line_and_write_nothing(template_folder, tmp_path, capsys, args, message):
    # In process; the tests below run the installed `copier` command for the same path.
    destination = tmp_path / "out"
    code, stderr = copier_cli_in_process(capsys, template_folder, destination, *args)
    assert code == 1
    assert "Traceback" not in stderr
    errors = [line for line in stderr.splitlines() if "invalid answer" in line]
    assert len(errors) == 1 and message in errors[0], stderr
    assert not destination.exists()


def test_a_data_file_choice_that_the_other_answers_rule_out_gives_one_line(template_folder, tmp_path, capsys):
    data = tmp_path / "answers.yml"
    data.write_text("ros_distro: noetic\nbuild_type: ament_cmake\n")
    destination = tmp_path / "out"
    code, stderr = copier_cli_in_process(capsys, template_folder, destination, "--data-file", str(data))
    assert code == 1 and "Traceback" not in stderr and not destination.exists(), stderr
    assert stderr.strip().splitlines()[-1] == ("rna-template: invalid answer to 'build_type': 'ament_cmake' is not "
                                               "one of catkin for ROS 1"), stderr


def test_bad_answers_leave_an_existing_folder_untouched(template_folder, tmp_path):
    destination = tmp_path / "existing"
    destination.mkdir()
    (destination / "notes.txt").write_text("mine\n")
    data = tmp_path / "bad.yml"
    data.write_text(yaml.safe_dump({"package_name": "ok_name", "nodes": [{"name": "a", "timers": [0]}]}))
    result = copier_copy(template_folder, destination, "--data-file", str(data))
    assert result.returncode == 1, result.stderr
    assert "invalid answer to 'nodes': node 'a': timer 'timer': give a period of more than 0 s" in result.stderr
    assert [p.name for p in destination.iterdir()] == ["notes.txt"]


def test_without_trust_copier_refuses_the_extensions(template_dir, tmp_path):
    result = subprocess.run([COPIER, "copy", "--defaults", "--vcs-ref=HEAD", str(template_dir), str(tmp_path / "x")],
                            capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=120)
    assert result.returncode == 4
    assert "unsafe" in result.stderr


def test_defaults_through_the_cli(template_dir, tmp_path):
    result = copier_copy(template_dir, tmp_path / "demo_pkg")
    assert result.returncode == 0, result.stderr
    assert answers_of(tmp_path / "demo_pkg")["package_name"] == "demo_pkg"
    assert (tmp_path / "demo_pkg" / "demo_pkg" / "demo_pkg" / "talker.py").is_file()


# ----------------------------------------------------------------------------- at a terminal

DOWN = "\x1b[B"


@pytest.fixture
def terminal(template_dir, tmp_path):
    """Start `copier copy` in a pseudo-terminal, as a person would."""
    child = spawn_copier(["copy", "--trust", "--vcs-ref=HEAD", str(template_dir), str(tmp_path / "mover")], (50, 200))
    child.logfile_read = (tmp_path / "terminal.log").open("w")
    yield child
    child.close(force=True)


def answer(child: pexpect.spawn, prompt: str, keys: str) -> None:
    child.expect(prompt)
    child.send(keys + "\r")


def test_one_node_prompt_by_prompt_without_yaml(terminal, tmp_path):
    child = terminal
    answer(child, "Package name", "\b" * 20 + "Bad Name")
    child.expect("REP 144")  # the validator keeps the prompt open
    child.send("\b" * 20 + "mover\r")
    answer(child, "full name", "\b" * 60 + "Ada Lovelace")
    answer(child, "e-mail", "\b" * 80 + "ada@example.com")
    answer(child, "License", "")
    answer(child, "Copyright holder", "")
    answer(child, "ROS distribution", "")
    answer(child, "ament_python holds", DOWN)  # ament_cmake
    answer(child, "Format of the package's launch file", DOWN)  # Python
    answer(child, "describe the package's nodes", DOWN)  # one node
    answer(child, "Language of the node", DOWN)  # Python, through ament_cmake_python
    answer(child, "Node name", "\b" * 10 + "motion_control")
    answer(child, "Topics it publishes", "cmd_vel:geometry_msgs/msg/Twist")
    answer(child, "Topics it subscribes to", "odom:nav_msgs/msg/Odometry, scan:sensor_msgs/msg/LaserScan")
    answer(child, "Services it offers", "")
    answer(child, "Services it calls", "reset:std_srvs/srv/Trigger")
    answer(child, "Actions it executes", "")
    answer(child, "Actions it sends goals to", "")
    answer(child, "Timers", "0.1")
    answer(child, "Parameters", "max_speed:double=0.5")
    answer(child, "One sentence", "")
    answer(child, "GitHub Actions workflow", "")
    child.expect(pexpect.EOF, timeout=60)
    child.close()
    assert child.exitstatus == 0, (tmp_path / "terminal.log").read_text()

    answers = answers_of(tmp_path / "mover")
    assert (answers["build_type"], answers["launch_format"]) == ("ament_cmake", "python")
    assert (tmp_path / "mover" / "mover" / "launch" / "mover.launch.py").is_file()
    node = answers["nodes"][0]
    assert (node["name"], node["language"]) == ("motion_control", "python")
    assert node["subscribers"] == ["odom:nav_msgs/msg/Odometry", "scan:sensor_msgs/msg/LaserScan"]
    # The default, as much as fits the prompt's line: all of it, at 200 columns (87 characters).
    assert answers["description"] == (
        "The motion_control node publishes cmd_vel, subscribes to odom and scan and calls reset")
    base = (tmp_path / "mover" / "mover" / "mover" / "motion_control_base.py").read_text()
    assert "def on_scan(self, msg):" in base
    assert "self.declare_parameter('max_speed', 0.5)" in base
    assert shutil.which("git")


def test_interfaces_in_the_workspace_are_offered(template_dir, tmp_path):
    """The type questions list the .msg/.srv/.action files found around the destination."""
    existing = tmp_path / "ws" / "src" / "nav_interfaces"
    (existing / "msg").mkdir(parents=True)
    (existing / "package.xml").write_text("<package format='3'><name>nav_interfaces</name></package>")
    (existing / "msg" / "Goal.msg").write_text("float64 x\n")
    child = spawn_copier(["copy", "--trust", "--vcs-ref=HEAD", str(template_dir),
                          str(tmp_path / "ws" / "src" / "planner")], (50, 250))
    child.logfile_read = (tmp_path / "terminal.log").open("w")
    try:
        for prompt in ("Package name", "full name", "e-mail", "License", "Copyright holder", "ROS distribution",
                       "ament_python holds", "Format of the package's launch file"):
            answer(child, prompt, "")
        answer(child, "describe the package's nodes", DOWN)
        answer(child, "Node name", "")
        child.expect("Topics it publishes")
        child.expect(r"Found in your workspace: nav_interfaces/msg/Goal")
        child.send("goal:nav_interfaces/msg/Goal\r")
        for prompt in ("subscribes to", "Services it offers", "Services it calls", "Actions it executes",
                       "Actions it sends", "Timers", "Parameters", "One sentence",
                       "GitHub Actions workflow"):
            answer(child, prompt, "")
        child.expect(pexpect.EOF, timeout=60)
    finally:
        child.close(force=True)
    assert child.exitstatus == 0, (tmp_path / "terminal.log").read_text()
    assert answers_of(tmp_path / "ws" / "src" / "planner")["nodes"][0]["publishers"] == ["goal:nav_interfaces/msg/Goal"]
