"""Custom interfaces: field rules, interfaces found on disk, and the generated interface packages."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest
from catkin_pkg.package import parse_package
from rna import AnswerError, build_package
from rna.answers.interfaces import parse_definitions
from rna.definitions import parse_field
from rna.workspace import find_interfaces
from support.generation import VALID, answers_of, example

TRACKER_INTERFACES = example("tracker")["interfaces"]
TRACKER_NODES = example("tracker")["nodes"]


def field(text: str, ros: int = 2, local: tuple[str, ...] = ()):
    return parse_field(text, package="pkg_interfaces", local_names=set(local), ros=ros)


@pytest.mark.parametrize(
    ("text", "line"),
    [("float64 x", "float64 x"), ("  uint8[]   data ", "uint8[] data"), ("float64[3] xyz", "float64[3] xyz"),
     ("string<=10 name", "string<=10 name"), ("int32[<=5] few", "int32[<=5] few"),
     ('string frame_id "map"', 'string frame_id "map"'), ("float64 gain 1.5", "float64 gain 1.5"),
     ("int32[] ids [1, 2]", "int32[] ids [1, 2]"), ("int32 MAX_SPEED=10", "int32 MAX_SPEED=10"),
     ("geometry_msgs/Point p", "geometry_msgs/Point p"), ("geometry_msgs/msg/Point p", "geometry_msgs/Point p"),
     ("pkg_interfaces/Target t", "Target t")],
)
def test_fields_are_written_back_normalised(text, line):
    assert field(text, local=("Target",)).line == line


@pytest.mark.parametrize(
    ("text", "ros", "rule"),
    [
        ("float64", 2, "write the type then the name"),
        ("float64 X", 2, "field names are lower_snake_case"),
        ("float64 bad__name", 2, "lower_snake_case"),
        ("float64 class", 2, "Python keyword"),
        ("float64 int", 2, r"C\+\+ keyword"),
        ("int32 max=3", 2, "constant names are UPPER_CASE"),
        ("float65 x", 2, "not a ROS 2 primitive type or a CamelCase message"),
        ("Unknown x", 2, "unknown type 'Unknown'"),
        ("geometry_msgs/point p", 2, "is not a message type"),
        ("std_srvs/srv/Trigger t", 2, "a field's type is a message"),
        ("int8 x 300", 2, "300 is not a valid int8 value"),
        ("bool on 1", 2, "is not a valid bool value"),
        ("string s plain", 2, "is not a valid string value"),
        ("int32[] ids 3", 2, "an array's value is a list"),
        ("int32[] MAX=3", 2, "constants have a primitive, non-array type"),
        ("float64<=3 x", 2, "only strings take a bound"),
        ("string<=10 name", 1, "bounded strings and arrays are ROS 2 features"),
        ("int32[<=5] few", 1, "ROS 2 features"),
        ("float64 x 1.0", 1, "default values are a ROS 2 feature"),
        ("wstring w", 1, "not a ROS 1 primitive"),
        ("time MAX=3", 2, "constants have a primitive, non-array type"),
        ("float64! x", 2, "is not a type"),
        ("int32[] ids [1, 2", 2, "cannot read the value"),
        ("geometry_msgs/Point p 1", 2, "only primitive types take a value"),
    ],
)
def test_field_rules(text, ros, rule):
    with pytest.raises(ValueError, match=rule):
        field(text, ros)


def test_ros1_header_and_time_are_understood():
    assert field("Header header", 1).package == "std_msgs"
    assert field("time stamp", 1).line == "time stamp"


def test_ros1_spellings_are_ros2_messages_on_ros2():
    """Answers written for ROS 1 stay valid when the package is ported (copier update -d ros_distro=...)."""
    assert field("Header header", 2).line == "std_msgs/Header header"
    assert field("time stamp", 2).line == "builtin_interfaces/Time stamp"
    assert field("duration[] waits", 2).line == "builtin_interfaces/Duration[] waits"
    assert field("time stamp", 2).package == "builtin_interfaces"


@pytest.mark.parametrize(
    ("interfaces", "rule"),
    [
        ({"message": []}, "unknown key 'message'"),
        ({"messages": [{"name": "target", "fields": []}]}, "names are CamelCase"),
        ({"messages": [{"name": "A", "fields": ["int32 a", "int32 a"]}]}, "has 'a' twice"),
        ({"messages": [{"name": "A"}], "services": [{"name": "A"}]}, "the name is used twice"),
        ({"messages": [{"name": "A", "fields": ["A a"]}]}, "cannot contain itself"),
        ({"services": [{"name": "S", "goal": []}]}, "unknown key 'goal'"),
        ({"actions": [{"name": "Go", "goal": "float64"}]}, "write the type then the name"),
        ("messages: [", "not valid YAML"),
        ({"messages": {"name": "A"}}, "messages must be a list"),
        ({"services": ["SetTarget"]}, "each of services is a mapping"),
        ({"messages": [{"name": "A", "fields": {"x": "float64"}}]}, "fields is a list of lines"),
        ({"messages": [{"name": "A", "fields": [""]}]}, "a field is a line like"),
        ([], "a mapping with messages"),
    ],
)
def test_definition_rules(interfaces, rule):
    with pytest.raises(ValueError, match=rule):
        parse_definitions(interfaces, package="p_interfaces", ros=2)


def test_definitions_render_as_interface_files():
    definitions = parse_definitions(TRACKER_INTERFACES, package="tracker_interfaces", ros=2)
    target, array, service, action = definitions
    assert target.text == ('float64 x\nfloat64 y\nstring frame_id "map"\nint32 MAX_TARGETS=5\n'
                           'geometry_msgs/Point position\n')
    assert array.packages == {"std_msgs"}
    assert service.file_name == "srv/SetTarget.srv"
    assert service.text == "Target target\n---\nbool accepted\n"
    assert action.text == "float64 distance\n---\nbool reached\n---\nfloat64 remaining\n"


def test_nodes_name_their_own_interfaces_bare_or_in_full():
    answers = {**copy.deepcopy(VALID), "build_type": "ament_python", "package_name": "tracker",
               "interfaces": TRACKER_INTERFACES, "nodes": TRACKER_NODES}
    package = build_package(answers)
    detector, mover = package.nodes
    assert detector.publishers[0].type.full_name == "tracker_interfaces/msg/TargetArray"
    assert mover.subscribers[0].type == detector.publishers[1].type
    assert package.interfaces_package == "tracker_interfaces"
    assert package.interface_dependencies == ("action_msgs", "geometry_msgs", "std_msgs")
    assert [d.name for d in package.dependencies] == ["action_msgs", "rclpy", "tracker_interfaces"]

    same = build_package({**answers, "build_type": "ament_cmake", "interfaces_location": "package",
                          "nodes": [{"name": "mover", "subscribers": ["t:Target", "u:tracker/msg/Target"]}]})
    assert same.builds_interfaces and same.interfaces_package == ""
    assert same.nodes[0].subscribers[0].type.full_name == "tracker/msg/Target"
    assert "tracker" not in [d.name for d in same.dependencies]


@pytest.mark.parametrize(
    ("changes", "question", "rule"),
    [
        ({"interfaces": {"messages": [{"name": "T", "fields": ["flaot64 x"]}]}}, "interfaces", "primitive type"),
        ({"interfaces_location": "package"}, "interfaces_location", "cannot build interfaces"),
        ({"nodes": [{"name": "a", "publishers": ["t:Missing"]}]}, "nodes",
         "write it as package/msg/Type, e.g. std_msgs/msg/String"),
    ],
)
def test_interface_answers_break_rules_with_one_line(changes, question, rule):
    answers = {**copy.deepcopy(VALID), "build_type": "ament_python", "package_name": "tracker",
               "interfaces": TRACKER_INTERFACES, "nodes": TRACKER_NODES, **changes}
    with pytest.raises(AnswerError) as caught:
        build_package(answers)
    assert caught.value.question == question and rule in str(caught.value)


def test_interfaces_on_disk_are_found_around_the_destination(tmp_path):
    src = tmp_path / "ws" / "src"
    for package, files in {"nav_interfaces": ["msg/Goal.msg", "srv/Plan.srv"],
                           "deep/arm_msgs": ["action/Reach.action", "msg/Joint.msg"]}.items():
        folder = src / package
        (folder / "msg").mkdir(parents=True)
        (folder / "package.xml").write_text(f"<package><name>{Path(package).name}</name></package>")
        for name in files:
            (folder / name).parent.mkdir(exist_ok=True)
            (folder / name).write_text("int32 a\n")
    (src / "build" / "ignored").mkdir(parents=True)
    (src / "build" / "ignored" / "package.xml").write_text("<package><name>ignored</name></package>")
    destination = src / "new_robot"
    assert find_interfaces(destination) == ["arm_msgs/action/Reach", "arm_msgs/msg/Joint",
                                            "nav_interfaces/msg/Goal", "nav_interfaces/srv/Plan"]


@pytest.mark.parametrize("ros_distro", ["jazzy", "noetic"])
def test_separate_interfaces_package_is_generated_beside(make_package, ros_distro):
    interfaces = copy.deepcopy(TRACKER_INTERFACES)
    if ros_distro == "noetic":  # no default values in ROS 1
        interfaces["messages"][0]["fields"][2] = "string frame_id"
    destination = make_package({"package_name": "tracker", "ros_distro": ros_distro, "interfaces": interfaces,
                                "nodes": [{**node, "language": "python"} for node in TRACKER_NODES]})
    interfaces = destination / "tracker_interfaces"
    package = parse_package(str(interfaces / "package.xml"))
    package.validate()
    depends = {d.name for d in package.build_depends}
    assert {"action_msgs" if ros_distro == "jazzy" else "actionlib_msgs", "geometry_msgs", "std_msgs"} <= depends
    if ros_distro == "jazzy":
        assert [g.name for g in package.member_of_groups] == ["rosidl_interface_packages"]
    assert (interfaces / "msg" / "Target.msg").read_text().endswith("geometry_msgs/Point position\n")
    assert (interfaces / "action" / "Approach.action").is_file()
    cmake = (interfaces / "CMakeLists.txt").read_text()
    assert ("rosidl_generate_interfaces" in cmake) == (ros_distro == "jazzy")
    assert ("add_action_files(FILES\n  Approach.action\n)" in cmake) == (ros_distro == "noetic")
    main = parse_package(str(destination / "tracker" / "package.xml"))
    assert "tracker_interfaces" in {d.name for d in main.exec_depends}
    assert not (destination / "tracker" / "msg").exists()


def test_same_package_interfaces(make_package):
    destination = make_package({"package_name": "tracker", "build_type": "ament_cmake",
                                "interfaces_location": "package",
                                "interfaces": TRACKER_INTERFACES, "nodes": [
                                    {"name": "mover", "subscribers": ["t:Target"]},
                                    {"name": "viewer", "language": "python", "subscribers": ["t:Target"]}]})
    assert not (destination / "tracker_interfaces").exists()
    package = destination / "tracker"
    assert (package / "srv" / "SetTarget.srv").is_file()
    cmake = (package / "CMakeLists.txt").read_text()
    assert '"${cpp_typesupport_target}"' in cmake
    assert 'install(DIRECTORY ${PROJECT_NAME}/ DESTINATION "${PYTHON_INSTALL_DIR}/${PROJECT_NAME}"' in cmake
    assert "ament_python_install_package" not in cmake
    manifest = parse_package(str(package / "package.xml"))
    assert [g.name for g in manifest.member_of_groups] == ["rosidl_interface_packages"]
    assert answers_of(destination)["interfaces_location"] == "package"


@pytest.mark.parametrize("location", ["separate", "package"])
def test_ros1_interface_files_are_listed_sorted_as_catkin_lint_asks(make_package, location):
    """catkin_lint -W2: `list FILES should be sorted` (by code point, upper case first), whatever the answers' order."""
    destination = make_package({"package_name": "rover", "ros_distro": "noetic", "interfaces_location": location,
                                "interfaces": {"actions": [{"name": "State", "goal": ["bool ok"]},
                                                           {"name": "R0", "goal": ["bool ok"]},
                                                           {"name": "Rb", "goal": ["bool ok"]}]},
                                "nodes": [{"name": "mover", "action_servers": ["go:State"]}]})
    home = "rover" if location == "package" else "rover_interfaces"
    cmake = (destination / home / "CMakeLists.txt").read_text()
    assert "add_action_files(FILES\n  R0.action\n  Rb.action\n  State.action\n)" in cmake
