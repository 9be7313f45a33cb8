"""What launch and launch_ros offer a generated launch file, per ROS 2 distro: the one home of that table.

Each entry is an entity of the XML/YAML front-ends (with the attributes launch reads for it)
or a name of the Python API (with its keyword arguments), and, where not every offered
distro's first release had it, the release of launch_ros that brought it to each distro, from
the packages' changelogs as released to the distros (ros2/launch_ros, its tags and the
rosdistro release notes):

- LifecycleNode(autostart=...): launch_ros 0.28.1 (rolling, April 2025; so every Kilted
  release), 0.26.7 on Jazzy (April 2025); never backported to Humble.
- <lifecycle_node> (with autostart) in XML and YAML: 0.29.4 (rolling, November 2025), 0.26.12
  on Jazzy (June 2026), 0.28.6 on Kilted (July 2026); not on Humble.

A generated file uses a feature only where every release of the answered distro has it (the
distro's first release is as new as the feature), so that it runs on any installation of
that distro; Rolling is taken at its newest. Elsewhere the template writes another form
(rna.launch_features.autostart_form). The template renders with this table and the test
suite's static reading of launch files (tests/support/launch_files.py) refuses what it says
a distro lacks.
"""

from __future__ import annotations

from . import distros

# The launch_ros version each distro was first released with (rolling: None, the newest). A
# distro branches from rolling's last release before it: Humble at 0.19.2 (April 2022), Jazzy
# at 0.26.5 (March 2024), Kilted at 0.28.1 (April 2025).
FIRST_RELEASE = {"humble": "0.19.2", "jazzy": "0.26.5", "kilted": "0.28.1", "rolling": None}

# Entities of the XML and YAML front-ends the template writes, and the attributes launch and
# launch_ros read for each (launch's Action: if, unless; ExecuteProcess: output; launch_ros's
# Node, ComposableNodeContainer, ComposableNode; launch's DeclareLaunchArgument). All of them
# are in Humble's launch_ros 0.19.2 already, but lifecycle_node.
_NODE = {"pkg", "exec", "name", "namespace", "output", "if", "unless", "param", "remap", "args", "ros_args"}
FRONTEND = {
    "arg": {"name", "default", "description", "choice"},
    "node": _NODE,
    "lifecycle_node": _NODE | {"autostart"},
    "node_container": _NODE | {"composable_node"},
    "composable_node": {"pkg", "plugin", "name", "namespace", "param", "remap", "extra_arg", "if", "unless"},
    "param": {"from", "name", "value"},
    "remap": {"from", "to"},
    "extra_arg": {"name", "value"},
}
# Names a Python launch file may use: the module that exports each, and its keyword arguments.
_PY_NODE = {"package", "executable", "name", "namespace", "output", "parameters", "condition", "remappings",
            "arguments", "ros_arguments"}
PYTHON_API = {
    "LaunchDescription": ("launch", set()),
    "DeclareLaunchArgument": ("launch.actions", {"default_value", "description", "choices"}),
    "IfCondition": ("launch.conditions", set()),
    "UnlessCondition": ("launch.conditions", set()),
    "LaunchConfiguration": ("launch.substitutions", set()),
    "PathJoinSubstitution": ("launch.substitutions", set()),
    "Node": ("launch_ros.actions", _PY_NODE),
    "LifecycleNode": ("launch_ros.actions", _PY_NODE | {"autostart"}),
    "ComposableNodeContainer": ("launch_ros.actions", _PY_NODE | {"composable_node_descriptions"}),
    "ComposableNode": ("launch_ros.descriptions", {"package", "plugin", "name", "namespace", "parameters",
                                                   "remappings", "extra_arguments", "condition"}),
    "FindPackageShare": ("launch_ros.substitutions", set()),
}

# The features not every offered distro's first release has: the launch_ros release that
# brought each to each distro (None: no release of the distro has it).
SINCE: dict[str, dict[str, str | None]] = {
    # launch_ros#482 (rolling), #533 (Jazzy), #532 (Kilted): the front-end entity, autostart included.
    "<lifecycle_node>": {"humble": None, "jazzy": "0.26.12", "kilted": "0.28.6", "rolling": "0.29.4"},
    # launch_ros#430 (rolling), #438 (Jazzy): the autostart argument of the Python action.
    "LifecycleNode(autostart)": {"humble": None, "jazzy": "0.26.7", "kilted": "0.28.1", "rolling": "0.28.1"},
}


def _version(text: str) -> tuple[int, ...]:
    return tuple(int(part) for part in text.split("."))


def available(feature: str, distro: str) -> bool:
    """Whether every release of the distro's launch_ros has the feature (Rolling: its newest)."""
    if distro not in distros.ROS2_DISTROS:
        raise ValueError(f"{distro} is not a ROS 2 distro")
    since = SINCE[feature][distro] if feature in SINCE else "0"
    if since is None:
        return False
    first = FIRST_RELEASE[distro]
    return first is None or _version(since) <= _version(first)


def frontend(distro: str) -> dict[str, set[str]]:
    """The XML/YAML entities and their attributes a launch file for the distro may use."""
    entities = dict(FRONTEND)
    if not available("<lifecycle_node>", distro):
        del entities["lifecycle_node"]
    return entities


def python_api(distro: str) -> dict[str, tuple[str, set[str]]]:
    """The Python launch names, their modules and keyword arguments a launch file for the distro may use."""
    names = dict(PYTHON_API)
    if not available("LifecycleNode(autostart)", distro):
        module, keywords = names["LifecycleNode"]
        names["LifecycleNode"] = (module, keywords - {"autostart"})
    return names


def autostart_form(distro: str, launch_format: str) -> str:
    """How the launch file has a lifecycle node configured and activated once it is up.

    "launch_ros": launch_ros's lifecycle node does it (<lifecycle_node autostart="true">,
    LifecycleNode(autostart=True)), where every release of the distro has it for the format;
    "parameter": the node does it itself, its `autostart` parameter set to true by the launch
    file (rna.model.AUTOSTART_PARAMETER), which works with any launch_ros.
    """
    feature = "LifecycleNode(autostart)" if launch_format == "python" else "<lifecycle_node>"
    return "launch_ros" if available(feature, distro) else "parameter"
