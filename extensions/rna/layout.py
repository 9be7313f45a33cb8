"""Where the files of a generated package go: the one home of every path.

Paths of a node's files are relative to its package folder; the package folder is the
destination's `<package>/`, or the destination itself for a node added to a package the
template did not make (target 'node'). copier.yml reads the globs of the files users own
from here (`_skip_if_exists`), the templates name their files after the model's paths,
and the after-update step and the tests ask the model.
"""

from __future__ import annotations

# A node's files, by (ROS generation, language); {package} and {name} are filled in.
USER_FILES = {
    (2, "cpp"): "src/{name}.cpp",
    (1, "cpp"): "src/{name}.cpp",
    (2, "python"): "{package}/{name}.py",
    (1, "python"): "scripts/{name}.py",
}
BASE_FILES = {
    (2, "cpp"): "include/{package}/{name}_base.hpp",
    (1, "cpp"): "include/{package}/{name}_base.h",
    (2, "python"): "{package}/{name}_base.py",
    (1, "python"): "src/{package}/{name}_base.py",
}
PYTHON_PACKAGE_DIRS = {2: "{package}", 1: "src/{package}"}
CONFIG_FILE = "config/{name}.yaml"
# The package's launch file, by (ROS generation, format): roslaunch reads XML only; ROS 2's
# `ros2 launch` reads launch_ros Python, XML and YAML (launch_xml, launch_yaml), by suffix.
LAUNCH_FILES = {
    (2, "xml"): "launch/{package}.launch.xml",
    (2, "python"): "launch/{package}.launch.py",
    (2, "yaml"): "launch/{package}.launch.yaml",
    (1, "xml"): "launch/{package}.launch",
}
LAUNCH_FORMATS = {2: ("xml", "python", "yaml"), 1: ("xml",)}
LAUNCH_FORMAT_NAMES = {"xml": "XML", "python": "Python", "yaml": "YAML"}
DEFAULT_LAUNCH_FORMAT = "xml"
# What setup.py installs from launch/: every ROS 2 format above (and the users' own files in
# them), as the ROS 2 documentation's packaging guide globs them.
LAUNCH_GLOB = "launch/*launch.[pxy][yma]*"
# The generated tests (ROS 1 has none per node: a rospy or roscpp node needs a master, so its
# test is the package's rostest). The names keep a node's test clear of the lint tests (a node
# named flake8), and every test that starts ROS sorts after test_flake8.py: pytest runs an
# ament_python package's files in that order, and flake8's worker processes, forked from a
# process with DDS threads, can hang. ROS 1's names leave the package's name out: catkin_lint
# wants ${PROJECT_NAME} in CMakeLists.txt.
NODE_TESTS = {"cpp": "test/test_node_{name}.cpp", "python": "test/test_node_{name}.py"}
LAUNCH_TESTS = {2: "test/test_launch.py", 1: "test/graph.test"}
GRAPH_TEST_SCRIPT = "test/test_graph.py"  # ROS 1: what the rostest file runs
BASE_SUFFIX = "_base"

# Files of a whole package, which a node added to an existing package never writes, but
# these, when the package has none: a catkin package's setup.py, which installs the Python
# package a ROS 1 Python node's base class is in (a package of rospy scripts has none;
# `_skip_if_exists` keeps the user's).
PACKAGE_FILES = (".gitignore", "README.md", "LICENSE", "package.xml", "CMakeLists.txt", "setup.py", "setup.cfg",
                 "resource", "test", "launch")
NODE_PACKAGE_FILES = {1: ("setup.py",)}
ANSWERS_FILE = ".copier-answers.yml"


def answers_file_name(target: object, nodes: object, node_name: object) -> str:
    """The answers file: `.copier-answers.yml`, or for a node added to a package (target 'node')
    `.copier-answers.rna-<node>.yml`, so that each node added keeps answers of its own."""
    if target != "node":
        return ANSWERS_FILE
    first = nodes[0] if isinstance(nodes, list) and nodes else {}
    name = first.get("name") if isinstance(first, dict) else first
    return f".copier-answers.rna-{name or node_name or 'node'}.yml"


def package_files_excluded(ros: int) -> str:
    """The files of a whole package a node added to a package of ROS generation `ros` does not
    write, one per line, as `_exclude` patterns of the destination's root."""
    kept = NODE_PACKAGE_FILES.get(ros, ())
    return "\n".join("/" + path for path in PACKAGE_FILES if path not in kept)


def user_file(package: str, name: str, ros: int, language: str) -> str:
    return USER_FILES[(ros, language)].format(package=package, name=name)


def base_file(package: str, name: str, ros: int, language: str) -> str:
    return BASE_FILES[(ros, language)].format(package=package, name=name)


def config_file(name: str) -> str:
    return CONFIG_FILE.format(name=name)


def node_files(package: str, name: str, ros: int, language: str) -> tuple[str, ...]:
    """The files a node brings (its own and its base file, its config), within its package."""
    return (user_file(package, name, ros, language), base_file(package, name, ros, language), config_file(name))


def node_test(name: str, language: str) -> str:
    return NODE_TESTS[language].format(name=name)


def launch_test(package: str, ros: int) -> str:
    return LAUNCH_TESTS[ros].format(package=package)


def graph_test_script(package: str) -> str:
    return GRAPH_TEST_SCRIPT.format(package=package)


def executable(name: str, ros: int, language: str) -> str:
    """What rosrun / ros2 run starts: ROS 1 Python scripts keep their .py."""
    return f"{name}.py" if ros == 1 and language == "python" else name


def launch_file(package: str, ros: int, launch_format: str = DEFAULT_LAUNCH_FORMAT) -> str:
    """The package's launch file, relative to its package folder."""
    return LAUNCH_FILES[(ros, launch_format)].format(package=package)


def launch_format_error(launch_format: object, ros: int) -> str | None:
    """Why a package of this ROS generation cannot have its launch file in this format, or None."""
    allowed = LAUNCH_FORMATS[ros]
    if launch_format in allowed:
        return None
    if ros == 1 and launch_format in LAUNCH_FORMATS[2]:
        return f"roslaunch (ROS 1) reads XML launch files only: {launch_format} is for ROS 2"
    return f"'{launch_format}' is not one of {', '.join(allowed)}"


def python_package_dir(package: str, ros: int) -> str:
    return PYTHON_PACKAGE_DIRS[ros].format(package=package)


def package_dir(package: str, target: str) -> str:
    """The package folder within the destination."""
    return "." if target == "node" else package


def _in_package(path: str, package: str, target: str) -> str:
    return path if target == "node" else f"{package}/{path}"


def user_files_glob(package: str, target: str, ros: int, language: str) -> str:
    """The destination-relative glob of one kind of user-owned file (for `_skip_if_exists`)."""
    return _in_package(USER_FILES[(ros, language)].format(package=package, name="*"), package, target)


def base_files_glob(package: str, target: str, ros: int, language: str) -> str:
    return _in_package(BASE_FILES[(ros, language)].format(package=package, name="*"), package, target)


def python_init_file(package: str, target: str, ros: int) -> str:
    """The destination-relative path of the Python package's __init__.py."""
    return _in_package(python_package_dir(package, ros) + "/__init__.py", package, target)
