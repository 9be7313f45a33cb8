"""One node added to a package the template did not make: its files, and the smallest build-file edits."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from catkin_pkg.package import parse_package
from rna import build_package, integrate
from support import existing_packages
from copier_glue import answer_error
from support.generation import FIXED_ANSWERS, add_node, copier_installed_by_pipx, generate

COPIER = str(Path(sys.executable).with_name("copier"))

LISTENER = {"node_name": "listener", "node_subscribers": "chatter:std_msgs/msg/String",
            "node_publishers": "heard:std_msgs/msg/Int32", "node_timers": "1.0"}


def snapshot(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): p.read_text() for p in folder.rglob("*") if p.is_file()}





@pytest.mark.parametrize(
    ("make", "language", "user_file", "base_file"),
    [
        (existing_packages.ament_python, "python", "hand_robot/listener.py", "hand_robot/listener_base.py"),
        (existing_packages.ament_cmake, "cpp", "src/listener.cpp", "include/hand_driver/listener_base.hpp"),
        (existing_packages.ament_cmake, "python", "hand_driver/listener.py", "hand_driver/listener_base.py"),
        (existing_packages.catkin, "cpp", "src/listener.cpp", "include/hand_rover/listener_base.h"),
    ],
)
def test_node_lands_in_the_package_with_only_its_own_files(template_dir, tmp_path, make, language, user_file,
                                                           base_file):
    package = make(tmp_path / "pkg")
    before = snapshot(package)
    add_node(template_dir, package, {**LISTENER, "node_language": language})
    after = snapshot(package)

    answers = yaml.safe_load((package / ".copier-answers.rna-listener.yml").read_text())
    assert answers["target"] == "node"
    assert answers["package_name"] == parse_package(str(package / "package.xml")).name
    assert answers["maintainer"] == "Grace Hopper"  # read from the package.xml
    new = set(after) - set(before)
    assert {user_file, base_file, "config/listener.yaml", ".copier-answers.rna-listener.yml"} <= new
    assert not new & {"README.md", "LICENSE", "setup.cfg"} and not any(p.startswith(("launch", "test")) for p in new)
    for path, text in before.items():  # the user's files: unchanged but for the node's blocks
        if after[path] != text:
            assert path in ("package.xml", "CMakeLists.txt", "setup.py"), path
            outside = [line for line in after[path].splitlines()
                       if line.strip() and line not in text.splitlines()]
            assert all("listener" in after[path] for _ in outside)
    manifest = parse_package(str(package / "package.xml"))
    manifest.validate()
    declared = {d.name for d in manifest.build_depends + manifest.exec_depends}
    assert "std_msgs" in declared
    assert ("rclpy" if language == "python" and "ament" in str(make) else "std_msgs") in declared


def test_build_file_edits_are_idempotent_blocks(tmp_path):
    answers = {**FIXED_ANSWERS, "package_name": "hand_driver", "description": "d", "license": "MIT",
               "ros_distro": "jazzy", "build_type": "ament_cmake", "target": "node",
               "nodes": [{"name": "listener", "subscribers": ["chatter:std_msgs/msg/String"]}]}
    package = existing_packages.ament_cmake(tmp_path / "pkg")
    model = build_package(answers)
    cmake = (package / "CMakeLists.txt").read_text()
    once, explained = integrate.ament_cmake_lists(cmake, model)
    twice, _ = integrate.ament_cmake_lists(once, model)
    assert once == twice and explained == ["CMakeLists.txt: builds and installs listener and config/listener.yaml"]
    assert once.index("# BEGIN rna-template: node listener") < once.index("if(BUILD_TESTING)")
    assert "target_link_libraries(listener PRIVATE rclcpp::rclcpp ${std_msgs_TARGETS})" in once
    grown = build_package({**answers, "nodes": [{"name": "listener", "subscribers": ["chatter:std_msgs/msg/String"],
                                                  "publishers": ["pose:geometry_msgs/msg/Pose"]}]})
    regrown, _ = integrate.ament_cmake_lists(once, grown)
    assert regrown.count("BEGIN rna-template: node listener") == 1
    assert "find_package(geometry_msgs REQUIRED)" in regrown
    xml, explained = integrate.package_xml((package / "package.xml").read_text(), grown)
    assert explained == ["package.xml: declares geometry_msgs (depend)", "package.xml: declares std_msgs (depend)"]
    assert integrate.package_xml(xml, grown)[0] == xml


def catkin_model(language: str = "cpp", **node) -> object:
    return build_package({**FIXED_ANSWERS, "package_name": "hand_rover", "description": "d", "license": "MIT",
                          "ros_distro": "noetic", "build_type": "catkin", "target": "node",
                          "nodes": [{"name": "listener", "language": language, **node}]})


def test_catkin_components_are_appended_to_the_users_own_call(tmp_path):
    """The user's find_package(catkin ...) gains what the node needs at its end, in its own layout;
    every other line stays as it was."""
    package = existing_packages.catkin(tmp_path / "pkg")
    model = catkin_model(subscribers=["odom:nav_msgs/msg/Odometry"])
    cmake = (package / "CMakeLists.txt").read_text()
    text, explained = integrate.catkin_cmake_lists(cmake, model)
    assert "find_package(catkin REQUIRED COMPONENTS\n  roscpp\n  std_msgs\n  nav_msgs\n)" in text
    assert explained[0] == "CMakeLists.txt: find_package(catkin) also finds nav_msgs"
    assert set(cmake.splitlines()) <= set(text.splitlines())
    comment = "## as in find_package(catkin REQUIRED COMPONENTS xyz)\n"
    quoted = cmake.replace("find_package(catkin", comment + "find_package(catkin")
    assert integrate.catkin_cmake_lists(quoted, model)[0] == text.replace("find_package(catkin",
                                                                          comment + "find_package(catkin", 1)
    for call, grown in (
            ("find_package(catkin REQUIRED COMPONENTS roscpp std_msgs)",
             "find_package(catkin REQUIRED COMPONENTS roscpp std_msgs nav_msgs)"),
            ("find_package(catkin REQUIRED)", "find_package(catkin REQUIRED COMPONENTS nav_msgs roscpp)"),
            ("find_package(catkin REQUIRED COMPONENTS\n\troscpp # the client\n)",
             "find_package(catkin REQUIRED COMPONENTS\n\troscpp # the client\n\tnav_msgs\n)"),
            ("find_package(catkin REQUIRED COMPONENTS\n  roscpp std_msgs)",
             "find_package(catkin REQUIRED COMPONENTS\n  roscpp std_msgs nav_msgs)")):
        text, _ = integrate.catkin_cmake_lists(cmake.replace("find_package(catkin REQUIRED COMPONENTS\n  roscpp\n"
                                                             "  std_msgs\n)", call), model)
        assert grown in text, text
        assert integrate.catkin_cmake_lists(text, model)[0] == text


def test_a_python_node_in_a_catkin_package_of_scripts_gets_catkin_python_setup_in_a_block(tmp_path):
    package = existing_packages.catkin(tmp_path / "pkg")
    cmake = (package / "CMakeLists.txt").read_text()
    text, explained = integrate.catkin_cmake_lists(cmake, catkin_model("python"))
    setup = text.index("# BEGIN rna-template: the nodes' Python package (setup.py)\ncatkin_python_setup()\n"
                       "# END rna-template: the nodes' Python package\n")
    assert text.index("find_package(catkin") < setup < text.index("catkin_package(")
    assert "CMakeLists.txt: catkin_python_setup() installs the Python package of setup.py" in explained
    assert integrate.catkin_cmake_lists(text, catkin_model("python"))[0] == text
    with_setup = cmake.replace("catkin_package(", "catkin_python_setup()\n\ncatkin_package(")
    assert "BEGIN rna-template: the nodes' Python" not in integrate.catkin_cmake_lists(with_setup,
                                                                                      catkin_model("python"))[0]
    with pytest.raises(ValueError, match="does not install the Python package hand_rover"):
        integrate.catkin_setup_py("setup(packages=['other'], package_dir={'': 'src'})\n", catkin_model("python"))


def test_a_node_never_lands_on_an_existing_file(template_dir, tmp_path):
    package = existing_packages.ament_cmake(tmp_path / "pkg")
    (package / "config").mkdir()
    (package / "config" / "listener.yaml").write_text("mine: 1\n")
    before = snapshot(package)
    data = [f"--data={key}={value}" for key, value in {**LISTENER, "node_language": "cpp"}.items()]
    result = subprocess.run([COPIER, "copy", "--trust", "--defaults", "--vcs-ref=HEAD", *data, str(template_dir),
                             str(package)], capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=120)
    assert result.returncode == 1
    assert "choose another node name: config/listener.yaml already exists in hand_driver" in result.stderr
    assert "Traceback" not in result.stderr
    assert snapshot(package) == before


def test_a_build_file_without_its_anchor_is_reported(template_dir, tmp_path):
    package = existing_packages.catkin(tmp_path / "pkg")
    cmake = package / "CMakeLists.txt"
    cmake.write_text(cmake.read_text().replace("find_package(catkin", "find_package(Boost"))
    result = subprocess.run([COPIER, "copy", "--trust", "--defaults", "--vcs-ref=HEAD", "--data=node_language=python",
                             "--data=node_name=watcher", str(template_dir), str(package)],
                            capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=120)
    assert result.returncode != 0
    assert "could not add the watcher node to CMakeLists.txt" in result.stderr
    assert "find_package(catkin REQUIRED COMPONENTS ...)" in result.stderr


def test_a_destination_without_a_package_gets_a_package(template_dir, tmp_path):
    generate(template_dir, tmp_path / "fresh")
    assert yaml.safe_load((tmp_path / "fresh" / ".copier-answers.yml").read_text())["target"] == "package"
    assert (tmp_path / "fresh" / "fresh" / "package.xml").is_file()
    assert not list(tmp_path.glob("fresh/.copier-answers.rna-*"))


def _git(folder: Path, *args: str) -> None:
    subprocess.run(["git", "-c", "user.name=t", "-c", "user.email=t@example.com", *args], cwd=folder, check=True,
                   capture_output=True)


@pytest.mark.update
def test_the_added_node_grows_with_copier_update(template_dir, tmp_path):
    package = existing_packages.ament_cmake(tmp_path / "pkg")
    _git(package, "init", "-q")
    _git(package, "add", "-A")
    _git(package, "commit", "-qm", "mine")
    add_node(template_dir, package, {**LISTENER, "node_language": "cpp"})
    (package / "src" / "listener.cpp").write_text((package / "src" / "listener.cpp").read_text() + "// my code\n")
    cmake_before = (package / "CMakeLists.txt").read_text()
    _git(package, "add", "-A")
    _git(package, "commit", "-qm", "the listener node, edited")

    # Grown: what it had (the starter overrides its timer's callback) and a publisher.
    grown = ("[{name: listener, subscribers: [chatter:std_msgs/msg/String], timers: [1.0],"
             " publishers: [heard:std_msgs/msg/Int32, pose:geometry_msgs/msg/Pose]}]")
    result = subprocess.run([COPIER, "update", "--trust", "--defaults", "--answers-file",
                             ".copier-answers.rna-listener.yml", f"--data=nodes={grown}"],
                            cwd=package, capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
    assert (package / "src" / "listener.cpp").read_text().endswith("// my code\n")
    assert "pose_publisher_" in (package / "include" / "hand_driver" / "listener_base.hpp").read_text()
    cmake = (package / "CMakeLists.txt").read_text()
    assert "find_package(geometry_msgs REQUIRED)" in cmake and cmake.count("BEGIN rna-template: node listener") == 1
    outside = [line for line in cmake_before.splitlines() if "listener" not in line and "find_package" not in line]
    assert all(line in cmake.splitlines() for line in outside)
    assert "<depend>geometry_msgs</depend>" in (package / "package.xml").read_text()


def test_long_names_in_a_setup_py_fit_99_columns(tmp_path):
    package = existing_packages.ament_python(tmp_path / "pkg")
    name, node = "p" * 39, "n" * 39
    model = build_package({**FIXED_ANSWERS, "package_name": name, "description": "d", "license": "MIT",
                           "ros_distro": "jazzy", "build_type": "ament_python", "target": "node",
                           "nodes": [{"name": node}]})
    text, _ = integrate.setup_py((package / "setup.py").read_text(), model)
    assert max(len(line) for line in text.splitlines()) <= 99
    assert f"'{node} = '\n            '{name}.{node}:main'," in text
    compile(text, "setup.py", "exec")
    assert integrate.setup_py(text, model)[0] == text


def test_a_name_whose_files_are_there_is_refused_at_the_name_question(tmp_path):
    """The clash is the node name prompt's own error (Copier's validator), leading with the fix."""
    package = existing_packages.ament_cmake(tmp_path / "pkg")
    (package / "config").mkdir()
    (package / "config" / "listener.yaml").write_text("mine: 1\n")
    context = {"_copier_conf": {"dst_path": str(package), "data": {}}, "target": "node",
               "package_name": "hand_driver", "ros_distro": "jazzy", "build_type": "ament_cmake"}
    error = answer_error({**context, "node_name": "listener"}, "node_name")
    assert error == "choose another name: config/listener.yaml is already in the package"
    assert answer_error({**context, "node_name": "hearer"}, "node_name") == ""


@pytest.mark.parametrize("node", ["listener", "n" * 39])
def test_the_message_after_adding_a_node_keeps_to_80_columns(template_dir, tmp_path, node):
    """The update command breaks before `--answers-file` when a long node name would pass 80 columns."""
    package = existing_packages.ament_cmake(tmp_path / "pkg")
    result = subprocess.run([COPIER, "copy", "--trust", "--defaults", "--vcs-ref=HEAD", "--data=copyright_year=2026",
                             f"--data=node_name={node}", str(template_dir), str(package)],
                            capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=120,
                            env={**copier_installed_by_pipx(), "NO_COLOR": "1"})
    assert result.returncode == 0, result.stderr
    message = result.stderr[result.stderr.index(f"The {node} node is added."):].splitlines()
    assert not [line for line in message if len(line) > 79], message
    command = " ".join(line.strip().removesuffix("\\").strip() for line in message[message.index("  git add -A ."):])
    assert f"copier update --trust --answers-file .copier-answers.rna-{node}.yml" in command
