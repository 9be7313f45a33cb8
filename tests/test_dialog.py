"""The nodes dialog: many nodes without YAML, at a first copy and in `copier update`.

The pure parts of extensions/rna/dialog.py are driven by a scripted asker; a newcomer drives
`copier copy` and `copier update` at a real terminal in tests/test_replay.py.
"""

from __future__ import annotations

import pexpect
import pytest
import yaml
from rna import dialog
from rna.answers.nodes import Types
from support.generation import answers_of, generate, git, subprocess_env
from support.terminal import Terminal

# ----------------------------------------------------------------------------- the pure parts


class Script(dialog.Asker):
    """Answers from a list; an answer its validator refuses is kept in `refused` and the next one is taken."""

    def __init__(self, answers: list[str]):
        self.answers = list(answers)
        self.refused: list[tuple[str, str]] = []
        self.said: list[str] = []
        self.menus: list[list[str]] = []

    def select(self, message, choices, default=None):
        self.menus.append(list(choices))
        wanted = self.answers.pop(0)
        picked = [choice for choice in choices if choice.startswith(wanted)]
        assert picked, (wanted, choices)
        return picked[0]

    def text(self, message, default="", validate=None, complete=()):
        while True:
            answer = self.answers.pop(0) or default
            answer = "" if answer == "\b" else answer  # the default erased
            error = validate(answer) if validate else None
            if not error:
                return answer
            self.refused.append((answer, error))

    def say(self, line):
        self.said.append(line)

    def confirm(self, message, default=False):
        self.said.append(message)
        return self.answers.pop(0) == "y"


def rules(build_type="ament_python", distro="jazzy") -> dialog.Rules:
    return dialog.Rules("pkg", build_type, Types(2, distro=distro))


def test_endpoints_read_as_their_short_forms():
    assert dialog.entry_text("publishers", "cmd_vel:geometry_msgs/msg/Twist") == "cmd_vel:geometry_msgs/msg/Twist"
    assert dialog.entry_text("subscribers", {"topic": "scan", "type": "sensor_msgs/msg/LaserScan",
                                             "qos": "sensor_data"}) == "scan:sensor_msgs/msg/LaserScan:sensor_data"
    assert dialog.entry_text("timers", 0.5) == "timer:0.5"
    assert dialog.entry_text("timers", {"name": "loop", "period": 0.1}) == "loop:0.1"
    assert dialog.entry_text("parameters", {"name": "rate", "type": "double", "default": 2.0}) == "rate:double=2.0"


def test_a_timer_is_named_timer_unless_named():
    assert [dialog.timer_name(entry) for entry in (0.5, "1.0", "loop:0.1", {"period": 2})] == [
        "timer", "timer", "loop", "timer"]


def test_a_node_in_one_line():
    node = {"name": "talker", "language": "python", "publishers": ["a:std_msgs/msg/String"], "timers": [0.5, 1]}
    assert dialog.node_line(node) == "talker (Python): 1 publisher, 2 timers"
    assert dialog.node_line({"name": "idle"}) == "idle: nothing yet"


def test_a_menu_line_says_less_to_fit_and_is_cut_only_when_nothing_fits():
    node = {"name": "driver", "language": "python", "publishers": ["a:std_msgs/msg/String"], "timers": [0.5],
            "parameters": ["p:int=1"]}
    forms = dialog.node_forms(node)
    assert forms[0] == "driver (Python): 1 publisher, 1 timer, 1 parameter"
    assert dialog.fitting(forms, 45) == "driver: 1 publisher, 1 timer, 1 parameter"
    assert dialog.fitting(forms, 40) == "driver: 3 endpoints and parameters"
    assert dialog.fitting(forms, 12) == "driver"
    assert dialog.fitting(forms, 5) == "dr…er"
    assert dialog.entry_forms(dialog.KIND_OF["publishers"], "cmd_vel:geometry_msgs/msg/Twist") == [
        "publisher cmd_vel:geometry_msgs/msg/Twist", "publisher cmd_vel (Twist)", "publisher cmd_vel"]


@pytest.mark.parametrize(("key", "entry"), [
    ("publishers", "scan:sensor_msgs/msg/LaserScan:sensor_data"), ("subscribers", "odom:nav_msgs/msg/Odometry"),
    ("service_servers", "reset:std_srvs/srv/Trigger"), ("timers", 0.5), ("timers", "loop:0.1"),
    ("parameters", "rate:double=10.0"), ("parameters", "names:string[]=[a, b]"), ("parameters", "flag:bool"),
    ("publishers", {"topic": "cmd", "type": "geometry_msgs/msg/Twist", "id": "command"}),
    ("parameters", {"name": "gain", "type": "double", "default": 1.0, "description": "How hard"}),
])
def test_an_entry_is_kept_in_the_form_it_was_given(key, entry):
    """Read into its keys and written back, an entry is what it was: a short form stays one."""
    assert dialog.entry_value(key, dialog.entry_mapping(key, entry)) == entry


def test_every_key_of_an_entry_is_one_the_nodes_answer_reads():
    """ENTRY_FIELDS and NODE_SETTINGS name keys of `nodes` (answers/nodes.py checks them)."""
    from rna.answers import nodes

    for key, fields in dialog.ENTRY_FIELDS.items():
        entry = {field.key: None for field in fields}
        if key == "parameters":
            entry = {"name": "p", "type": "double", "default": 1.0, "description": "d", "read_only": True,
                     "range": [0.0, 2.0]}
        elif key == "timers":
            entry = {"name": "t", "period": 1.0}
        elif key in ("publishers", "subscribers"):
            entry = {"topic": "t", "type": "std_msgs/msg/String", "qos": "sensor_data"}
        else:
            entry = {"name": "t", "type": {"srv": "std_srvs/srv/Trigger",
                                           "action": "test_msgs/action/Fibonacci"}[dialog.KIND_OF[key].interface]}
        assert {field.key for field in fields} >= set(entry)
        nodes.parse_node({"name": "n", key: [entry]}, package="pkg", build_type="ament_python", types=Types(2))
    assert {setting.key for setting in dialog.NODE_SETTINGS} <= set(nodes._NODE_KEYS)


def test_types_offered_start_with_the_packages_own_then_the_workspace_then_common_ones():
    offered = dialog.type_choices("msg", 2, "jazzy", found=["nav_interfaces/msg/Goal", "nav_interfaces/srv/Go"],
                                  own=["Target"])
    assert offered[:3] == ["Target", "nav_interfaces/msg/Goal", "std_msgs/msg/Bool"]
    assert "nav_interfaces/srv/Go" not in offered
    assert "geometry_msgs/msg/Twist" in offered and "std_srvs/srv/Trigger" not in offered
    assert "std_srvs/srv/Trigger" in dialog.type_choices("srv", 2, "jazzy")
    assert "std_msgs/String" in dialog.type_choices("msg", 1, "noetic")


def test_the_dialog_builds_nodes_in_the_short_forms():
    script = Script([
        "Add a node", "", "Edit talker", "Add a publisher", "", "Add a timer", "\b", "Done with",
        "Add a node", "Bad Name", "driver",
        "Add a publisher", "cmd vel", "cmd_vel", "geometry_msgs/msg/Twst", "geometry_msgs/msg/Twist",
        "Add a subscriber", "scan", "sensor_msgs/msg/LaserScan:sensor_data",
        "Add a timer", "", "abc", "0.1", "Add a timer", "", "0.2",
        "Add a parameter", "max_speed", "double", "fast", "0.5",
        "Add a service server", "reset", "std_srvs/srv/Trigger",
        "Edit service server", "Remove this", "Rename", "talker", "motor_driver",
        "Done with", "Remove listener", "n", "Remove listener", "y", "Done"])
    nodes = dialog.Dialog(yaml.safe_load("[{name: talker, timers: [0.5]}, {name: listener}]"), rules(),
                          script).run()
    assert nodes == [
        {"name": "talker", "timers": [0.5], "language": "python"},
        {"name": "motor_driver", "language": "python", "publishers": ["cmd_vel:geometry_msgs/msg/Twist"],
         "subscribers": ["scan:sensor_msgs/msg/LaserScan:sensor_data"], "timers": ["timer:0.1", "timer2:0.2"],
         "parameters": ["max_speed:double=0.5"]},
    ]
    refused = dict(script.refused)
    assert refused["Bad Name"].startswith("use bad_name: 'Bad Name' is not a valid node name")
    assert refused["cmd vel"].startswith("topic 'cmd vel': use cmd_vel: ")
    # The whole node is read as the `nodes` answer is: the error names the node.
    assert refused["geometry_msgs/msg/Twst"].startswith("node 'driver': did you mean geometry_msgs/msg/Twist? ")
    assert refused["abc"].startswith("node 'driver': timer 'timer'")
    assert refused["fast"].startswith("node 'driver': parameter 'max_speed'")
    assert refused["talker"] == "choose another name: there is a node 'talker' already"
    assert "Node driver (Python): nothing yet" in script.said


def test_an_ament_cmake_node_asks_its_language_and_a_package_keeps_one_node():
    script = Script(["Remove listener", "y", "Edit talker", "Language", "Python", "Done with", "Remove talker", "y",
                     "Done", "Add a node", "C++", "solo", "Done with", "Done"])
    nodes = dialog.Dialog([{"name": "talker"}, {"name": "listener"}], rules("ament_cmake"), script).run()
    assert nodes == [{"name": "solo", "language": "cpp"}]
    assert script.said[-2] == "Add a node first: a package needs one."


def test_a_name_is_checked_with_the_language_asked_before_it():
    """A ROS 1 Python script named like a module it imports is refused at the name, added or renamed."""
    script = Script(["Add a node", "Python", "pkg", "driver", "Add a publisher", "pose",
                     "geometry_msgs/Pose", "Rename", "geometry_msgs", "mover", "Done with", "Done"])
    nodes = dialog.Dialog([], dialog.Rules("pkg", "catkin", Types(1, distro="noetic")), script).run()
    assert nodes == [{"name": "mover", "language": "python", "publishers": ["pose:geometry_msgs/Pose"]}]
    assert [answer for answer, _ in script.refused] == ["pkg", "geometry_msgs"]
    assert "would shadow the Python module 'pkg'" in script.refused[0][1]
    assert "would shadow the Python module 'geometry_msgs'" in script.refused[1][1]


def test_lifecycle_and_component_are_switched_on_and_off_within_the_rules():
    script = Script(["Edit talker", "Lifecycle node: no", "Component", "Language", "Python", "Component", "Done with",
                     "Done"])
    nodes = dialog.Dialog([{"name": "talker", "language": "cpp"}], rules("ament_cmake"), script).run()
    assert nodes == [{"name": "talker", "language": "cpp", "lifecycle": True}]
    # A component is C++: the language stays, said why; then the component goes.
    assert ("node 'talker': make it a C++ node to make it a component: components are C++ nodes "
            "(rclcpp_components)") in script.said
    assert "Lifecycle node: yes" in script.menus[2] and "Component (rclcpp_components): yes" in script.menus[3]


def test_diagnostics_are_switched_on_and_off_in_both_generations():
    script = Script(["Edit talker", "Diagnostics", "Done with", "Done"])
    nodes = dialog.Dialog([{"name": "talker", "language": "cpp"}], rules("ament_cmake"), script).run()
    assert nodes == [{"name": "talker", "language": "cpp", "diagnostics": True}]
    assert "Diagnostics (diagnostic_updater, on /diagnostics): no" in script.menus[1]
    script = Script(["Edit talker", "Diagnostics", "Diagnostics", "Done with", "Done"])
    ros1 = dialog.Rules("pkg", "catkin", Types(1, distro="noetic"))
    nodes = dialog.Dialog([{"name": "talker", "language": "python"}], ros1, script).run()
    assert nodes == [{"name": "talker", "language": "python"}]
    assert "Diagnostics (diagnostic_updater, on /diagnostics): yes" in script.menus[2]


def test_autostart_is_offered_to_lifecycle_nodes_and_goes_with_lifecycle():
    script = Script(["Edit talker", "Lifecycle node: no", "Configured and activated", "Done with", "Edit talker",
                     "Lifecycle node: yes", "Done with", "Done"])
    nodes = dialog.Dialog([{"name": "talker"}], rules("ament_python"), script).run()
    assert nodes == [{"name": "talker", "language": "python"}]
    assert not any("autostart" in choice for choice in script.menus[1])  # not a lifecycle node yet
    assert "Configured and activated by the launch file (autostart): yes" in script.menus[3]
    assert not any("autostart" in choice for choice in script.menus[6])  # no longer one


def test_the_executor_callback_groups_and_remappings_are_edited_within_the_rules(monkeypatch):
    """They have a menu of their own, one entry of the node's menu saying what they are."""
    monkeypatch.setattr(dialog.terminal, "width", lambda: 79)  # an 80-column terminal
    script = Script([
        "Edit server", "Executor,", "Executor:", "multi_threaded", "0", "2",
        "Add a callback group", "Bad Group", "requests", "reentrant", "nothing", "reset, beat",
        "Add a remapping", "cmd vel", "beat", "beat", "/robot/beat", "Back",
        "Done with", "Edit server", "Executor,", "Remove remapping", "Remove callback group",
        "Executor:", "single_threaded", "Back", "Done with", "Done"])
    server = {"name": "server", "language": "python", "publishers": ["beat:std_msgs/msg/Int32"],
              "timers": ["beat:0.05"], "service_servers": ["reset:std_srvs/srv/Trigger"]}
    edited = dialog.Dialog([dict(server)], rules(), script)
    nodes = edited.run()
    assert nodes == [server]
    assert "Executor, callback groups, remappings: single_threaded" in script.menus[1]
    assert script.menus[3] == ["single_threaded", "multi_threaded"]  # rclpy has no static executor
    assert "Executor: multi_threaded, 2 threads" in script.menus[4]  # the node's, once its executor is chosen
    assert "Executor, groups, remaps: multi_threaded (2 threads), 1 group, 1 remap" in script.menus[8]  # 80 columns
    after = script.menus[11]  # before anything is removed
    assert "Remove callback group requests (reentrant): reset, beat" in after
    assert "Remove remapping beat -> /robot/beat" in after
    refused = dict(script.refused)
    assert refused["0"] == "a whole number of threads, 1 or more"
    assert refused["Bad Group"] == "callback group 'Bad Group': use bad_group: it must be lower_snake_case"
    assert "'nothing' is none of the node's subscribers, services, actions or timers" in refused["nothing"]
    assert refused["cmd vel"].startswith("remapped 'cmd vel'")
    assert refused["beat"] == "node 'server': remappings: 'beat' is remapped to itself"


def test_the_executor_is_offered_as_the_language_and_distro_have_it():
    script = Script(["Edit driver", "Executor,", "Executor:", "static", "Back", "Done with", "Done"])
    nodes = dialog.Dialog([{"name": "driver", "language": "cpp"}], rules("ament_cmake", "humble"), script).run()
    assert nodes == [{"name": "driver", "language": "cpp", "executor": "static"}]
    assert script.menus[3] == ["single_threaded", "multi_threaded", "static"]  # Humble's rclcpp: no events
    ros1 = dialog.Rules("pkg", "catkin", Types(1, distro="noetic"))
    script = Script(["Edit talker", "Executor,", "Back", "Done with", "Done"])
    dialog.Dialog([{"name": "talker", "language": "python"}], ros1, script).run()
    assert not any("callback group" in choice for menu in script.menus for choice in menu)  # a ROS 2 feature
    assert "Add a remapping (launch file)" in script.menus[2]


def test_ros1_types_and_long_forms_kept():
    """A catkin node names ROS 1 types; endpoints written as mappings stay as they are, and can go."""
    script = Script(["Edit driver", "Edit subscriber", "Remove this", "Add a publisher", "odom", "nav_msgs/Odometr",
                     "nav_msgs/Odometry", "Done with", "Done"])
    start = [{"name": "driver", "language": "cpp", "subscribers": [{"topic": "cmd_vel", "type": "geometry_msgs/Twist"}],
              "parameters": [{"name": "rate", "type": "double", "default": 10.0}]}]
    nodes = dialog.Dialog(start, dialog.Rules("pkg", "catkin", Types(1, distro="noetic")), script).run()
    assert nodes == [{"name": "driver", "language": "cpp", "parameters": [{"name": "rate", "type": "double",
                                                                          "default": 10.0}],
                      "publishers": ["odom:nav_msgs/Odometry"]}]
    assert "Edit parameter rate:double=10.0" in script.menus[1]
    assert "did you mean nav_msgs/Odometry?" in dict(script.refused)["nav_msgs/Odometr"]


def test_without_a_terminal_the_dialog_asks_nothing_and_keeps_the_nodes(template_dir, tmp_path):
    """--defaults (or no terminal): the dialog's nodes are those it starts from, the demo."""
    generate(template_dir, tmp_path / "demo", {"node_setup": "dialog"})
    assert [node["name"] for node in answers_of(tmp_path / "demo")["nodes"]] == ["talker", "listener"]


# ----------------------------------------------------------------------------- at an 80x24 terminal

DOWN = "\x1b[B"


# What the newcomer below makes, and the next test starts from.
THREE_NODES = [
    {"language": "python", "name": "driver", "publishers": ["odom:nav_msgs/msg/Odometry"],
     "subscribers": ["cmd_vel:geometry_msgs/msg/Twist"]},
    {"language": "python", "name": "planner", "publishers": ["cmd_vel:geometry_msgs/msg/Twist"],
     "service_servers": ["replan:std_srvs/srv/Trigger"]},
    {"language": "python", "name": "monitor", "parameters": ["limit:double=2.5"],
     "subscribers": ["odom:nav_msgs/msg/Odometry"]},
]


def committed_package(template_dir, destination, nodes) -> None:
    """A package generated and committed to git, as `copier update` needs it."""
    generate(template_dir, destination, {"package_name": "rover", "nodes": nodes})
    git("init", "-q", "-b", "main", cwd=destination)
    git("add", "-A", cwd=destination)
    git("commit", "-q", "-m", "rover from rna-template", cwd=destination)


@pytest.mark.update  # the flow as it was before the dialog: in the update tier
def test_an_update_can_still_edit_the_nodes_as_yaml(template_dir, tmp_path):
    """Answering No shows the nodes as YAML, as before."""
    destination = tmp_path / "rover"
    committed_package(template_dir, destination, THREE_NODES)
    terminal = Terminal(["update", "--trust", "--vcs-ref=HEAD"], tmp_path / "update.log", cwd=destination,
                        env=subprocess_env())
    # Each prompt of an update in turn, with the keys that keep its answer (YAML ends with Esc, Enter).
    try:
        for prompt in ("Package name", "full name", "e-mail", "License", "Copyright holder", "ROS distribution",
                       "ament_python holds", "Format of the package's launch file"):
            terminal.answer(prompt, "")
        terminal.answer("Messages, services and actions", "\x1b")
        terminal.child.expect_exact("step by step? (else as YAML)")
        terminal.child.send("n")  # a yes/no prompt takes one key
        terminal.answer("The package's nodes, as a YAML list", "\x1b")
        terminal.answer("One sentence", "")
        terminal.answer("GitHub Actions workflow", "")
        terminal.child.expect(pexpect.EOF, timeout=60)
    finally:
        terminal.close()
    assert terminal.child.exitstatus == 0, (tmp_path / "update.log").read_text()
    assert answers_of(destination)["nodes"] == THREE_NODES


def test_a_node_of_the_package_renamed_in_the_dialog_says_its_old_name():
    script = Script(["Edit talker", "Rename", "speaker", "Rename", "announcer", "Done with",
                     "Add a node", "fresh", "Rename", "newer", "Done with",
                     "Edit listener", "Rename", "hearer", "Rename", "listener", "Done with", "Done"])
    nodes = dialog.Dialog([{"name": "talker"}, {"name": "listener"}], rules(), script, existing=True).run()
    assert nodes == [{"name": "announcer", "language": "python", "renamed_from": "talker"},
                     {"name": "listener", "language": "python"}, {"name": "newer", "language": "python"}]
    first_copy = dialog.Dialog([{"name": "talker"}], rules(), Script(["Edit talker", "Rename", "speaker",
                                                                     "Done with", "Done"])).run()
    assert first_copy == [{"name": "speaker", "language": "python"}]


class Recording(Script):
    """A Script that also keeps each text prompt's default and completions."""

    def __init__(self, answers):
        super().__init__(answers)
        self.asked: list[tuple[str, str, list[str]]] = []

    def text(self, message, default="", validate=None, complete=()):
        self.asked.append((message, default, list(complete)))
        return super().text(message, default, validate, complete)


def test_endpoints_and_parameters_are_edited_in_place():
    start = [{"name": "driver", "publishers": ["cmd_vel:geometry_msgs/msg/Twist"],
              "subscribers": ["odom:nav_msgs/Odometry"],
              "parameters": ["rate:double=10.0"]}]
    script = Script(["Edit driver",
                     "Edit publisher", "Type", "geometry_msgs/msg/TwistStamped", "QoS", "sensor_data", "Done",
                     "Edit parameter", "Default", "oops", "20.0", "Description", "Loop rate in Hz", "Read-only", "Done",
                     "Edit parameter", "Name", "loop_rate", "Done",
                     "Done with", "Done"])
    nodes = dialog.Dialog(start, rules(), script).run()
    assert nodes == [{"name": "driver", "language": "python",
                      "publishers": ["cmd_vel:geometry_msgs/msg/TwistStamped:sensor_data"],
                      # The ROS 1 spelling, read as the ROS 2 type it is.
                      "subscribers": ["odom:nav_msgs/msg/Odometry"],
                      "parameters": [{"name": "loop_rate", "type": "double", "default": 20.0,
                                      "description": "Loop rate in Hz", "read_only": True}]}]
    assert dict(script.refused)["oops"].startswith("node 'driver': parameter 'rate': ")


def test_a_type_typed_the_ros1_way_is_kept_the_ros2_way():
    script = Script(["Add a node", "mover", "Add a publisher", "cmd_vel", "geometry_msgs/Twist", "Done with", "Done"])
    assert dialog.Dialog([], rules(), script).run() == [
        {"name": "mover", "language": "python", "publishers": ["cmd_vel:geometry_msgs/msg/Twist"]}]


def test_a_topic_the_package_uses_is_offered_its_type():
    script = Recording(["Add a node", "logger", "Add a subscriber", "/odom", "", "Done with", "Done"])
    nodes = dialog.Dialog([{"name": "driver", "publishers": ["odom:nav_msgs/msg/Odometry"]}], rules(), script).run()
    assert nodes[1]["subscribers"] == ["/odom:nav_msgs/msg/Odometry"]
    message, default, complete = script.asked[-1]
    assert message == "Message type" and default == "nav_msgs/msg/Odometry" and complete[0] == default


def test_removing_a_node_is_confirmed_and_says_what_goes_on_an_update():
    script = Script(["Remove talker", "n", "Remove talker", "y", "Done"])
    nodes = dialog.Dialog([{"name": "talker"}, {"name": "listener"}], rules(), script, existing=True).run()
    assert [node["name"] for node in nodes] == ["listener"]
    assert script.said[0] == "Remove talker? The update deletes its files, your edits too (git keeps them)"
    undone = Script(["Remove talker", "y", "Remove listener", "y", "Undo removing listener", "Undo removing talker",
                     "Done"])
    nodes = dialog.Dialog([{"name": "talker"}, {"name": "listener"}], rules(), undone).run()
    assert [node["name"] for node in nodes] == ["talker", "listener"]
    assert "Undo removing talker" in undone.menus[3] and not any("Undo" in choice for choice in undone.menus[-1])
    fresh = Script(["Remove talker", "y", "Done"])
    dialog.Dialog([{"name": "talker"}, {"name": "listener"}], rules(), fresh).run()
    assert fresh.said[0] == "Remove talker?"


def test_a_node_setting_with_choices_slots_into_the_menu(monkeypatch):
    """A key a later version adds to nodes (a choice) is one row of NODE_SETTINGS: menu, prompt and check follow."""
    monkeypatch.setattr(dialog, "NODE_SETTINGS", (*dialog.NODE_SETTINGS,
                                                  dialog.Setting("description", "Description", ("a", "b"))))
    script = Script(["Edit talker", "Description: (none)", "b", "Done with", "Done"])
    assert dialog.Dialog([{"name": "talker"}], rules(), script).run() == [
        {"name": "talker", "language": "python", "description": "b"}]
