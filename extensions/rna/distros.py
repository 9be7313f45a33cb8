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
# Distributions whose rclcpp and rclpy call a node's post-set parameters callbacks once a set is in
# place (add_post_set_parameters_callback, from Iron on); Humble has the on-set callbacks only.
POST_SET_CALLBACK_DISTROS = ("jazzy", "kilted", "rolling")


# Executors beyond the single- and multi-threaded ones, by language, and the distros whose
# client library has them (read in each branch of ros2/rclcpp and ros2/rclpy):
# rclcpp::executors::StaticSingleThreadedExecutor is deprecated from rclcpp 29 (Kilted) on, its
# speed-ups now in SingleThreadedExecutor; rclcpp::experimental::executors::EventsExecutor
# exists from Jazzy on. rclpy has no static executor, and its experimental EventsExecutor
# (Jazzy from rclpy 7.1.4, Kilted) ignored SIGINT and SIGTERM when tried with these wheels.
EXECUTOR_DISTROS = {
    ("cpp", "static"): ("humble", "jazzy"),
    ("cpp", "events"): ("jazzy", "kilted", "rolling"),
}
THREADS_MAX = 256


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


def executor_error(executor: str, ros: int, language: str, distro: object = None) -> str | None:
    """Why a node of this language cannot spin on this executor in this distro, or None."""
    if executor == "single_threaded":
        return None
    if ros == 1:
        if language == "python":
            return ("rospy runs each subscription, timer and service callback in a thread of its own: a ROS 1 "
                    "Python node has no executor to choose (leave executor out)")
        if executor != "multi_threaded":
            return (f"executor '{executor}' is a ROS 2 executor: a roscpp node spins single_threaded or "
                    "multi_threaded (ros::MultiThreadedSpinner)")
        return None
    if executor == "multi_threaded":
        return None
    if language == "python":
        if executor == "static":
            return "rclpy has no static executor (rclcpp's StaticSingleThreadedExecutor): use single_threaded"
        return ("rclpy's EventsExecutor is experimental, and with Jazzy's and Kilted's rclpy it ignored Ctrl-C and "
                "SIGTERM when tried: use single_threaded or multi_threaded")
    have = EXECUTOR_DISTROS[(language, executor)]
    if distro is None or distro in have:
        return None
    if executor == "static":
        return (f"{distro}'s rclcpp deprecates StaticSingleThreadedExecutor (SingleThreadedExecutor has its "
                "speed-ups now): use single_threaded")
    return f"{distro}'s rclcpp has no EventsExecutor ({', '.join(have)} have it, as an experimental executor)"
