"""The ROS targets: distributions, their generation, and the build types and languages each holds."""

from __future__ import annotations

ROS2_DISTROS = ("humble", "jazzy", "kilted", "rolling")
ROS1_DISTROS = ("noetic",)
DISTROS = ROS2_DISTROS + ROS1_DISTROS

# The Ubuntu release each distribution's binary packages are built for (REP 2000), which a
# CI runner for it uses.
UBUNTU = {"humble": "22.04", "jazzy": "24.04", "kilted": "24.04", "rolling": "24.04", "noetic": "20.04"}

# The languages each build type builds, the first one being the default for a node.
BUILD_TYPES = {
    "ament_python": ("python",),
    "ament_cmake": ("cpp", "python"),  # Python through ament_cmake_python
    "catkin": ("cpp", "python"),
}
BUILD_TYPES_OF = {2: ("ament_cmake", "ament_python"), 1: ("catkin",)}
# Build types that can run the interface generators (rosidl, message_generation) themselves.
BUILDS_INTERFACES = ("ament_cmake", "catkin")
LANGUAGES = {"cpp": "cpp", "c++": "cpp", "python": "python", "py": "python"}
LANGUAGE_NAMES = {"cpp": "C++", "python": "Python"}
# Distributions whose rcl reads ROS_AUTOMATIC_DISCOVERY_RANGE (from Iron on): OFF keeps a
# process's participant from discovering any other, so a node unit test's graph holds its own
# nodes only. Humble has ROS_LOCALHOST_ONLY, which still discovers the machine's processes.
DISCOVERY_OFF_DISTROS = ("jazzy", "kilted", "rolling")


def generation(distro: object) -> int:
    """1 for a ROS 1 distribution, 2 otherwise."""
    return 1 if distro in ROS1_DISTROS else 2


def ports(before: object, after: object) -> bool:
    """Whether changing the distro `before` to `after` ports a ROS 1 package to ROS 2."""
    return generation(before) == 1 and generation(after) == 2


def languages(build_type: str) -> tuple[str, ...]:
    return BUILD_TYPES.get(build_type, ("cpp", "python"))


def default_language(build_type: str) -> str:
    return languages(build_type)[0]


def node_language(build_type: str, asked: object) -> str:
    """The language of a node answered at the prompt: the one asked when the build type holds it."""
    return asked if asked in languages(build_type) else default_language(build_type)


def language_error(build_type: str, language: str) -> str | None:
    """Why a build type cannot hold a node of this language, or None."""
    if language in languages(build_type):
        return None
    takes = " and ".join(LANGUAGE_NAMES[name] for name in languages(build_type))
    needs = next(name for name, held in BUILD_TYPES.items() if language in held)
    return (f"an {build_type} package holds {takes} nodes only; choose build_type {needs} "
            f"for {LANGUAGE_NAMES[language]}")
