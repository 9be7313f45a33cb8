"""ROS 1 packages and their ROS 2 counterparts: the one table the port maps dependencies by.

A package the table does not name is taken to be the same in ROS 2 (message packages,
system libraries: std_msgs, eigen, yaml-cpp...). A package mapped to nothing has no ROS 2
counterpart: a line naming it is carried over commented out, under a TODO(port) note
saying what ROS 2 does instead.
"""

from __future__ import annotations

from collections.abc import Iterable

# ROS 1 package -> its ROS 2 counterparts: one name, one per language ({"cpp": ..., "python": ...}),
# or a note when ROS 2 has none.
ROS2_PACKAGES: dict[str, str | dict[str, str] | None] = {
    "catkin": "ament_cmake",
    "roscpp": "rclcpp",
    "rospy": "rclpy",
    "message_generation": "rosidl_default_generators",
    "message_runtime": "rosidl_default_runtime",
    "actionlib": {"cpp": "rclcpp_action", "python": "rclpy"},
    "actionlib_msgs": "action_msgs",
    "nodelet": "rclcpp_components",
    "roslaunch": "ros2launch",
    "rostest": "launch_testing",
    "rosunit": "ament_cmake_gtest",
    "roslib": {"cpp": "ament_index_cpp", "python": "ament_index_python"},
    "rosconsole": "rcutils",
    "roslint": "ament_lint_auto",
    "rosbag": {"cpp": "rosbag2_cpp", "python": "rosbag2_py"},
    "tf": "tf2_ros",
    "tf_conversions": "tf2_geometry_msgs",
    "eigen_conversions": "tf2_eigen",
    "rviz": "rviz2",
    "rqt_robot_steering": "rqt_robot_steering",
    "python3-catkin-lint": None,
    "python3-nose": "python3-pytest",
    "rosgraph": None,
    "rosservice": None,
    "dynamic_reconfigure": None,
    "xmlrpcpp": None,
    "roscpp_serialization": None,
    "rospack": None,
}

NOTES = {
    "dynamic_reconfigure": "ROS 2 parameters take its place (add_on_set_parameters_callback)",
    "python3-catkin-lint": "catkin_lint checks catkin packages only; ament_lint_auto runs ROS 2's linters",
    "rosgraph": "the ROS 2 graph is the node's: get_topic_names_and_types()",
    "rosservice": "the ROS 2 graph is the node's: get_service_names_and_types()",
    "xmlrpcpp": "ROS 2 has no master and no XML-RPC",
    "roscpp_serialization": "rclcpp::Serialization",
    "rospack": "ament_index_cpp / ament_index_python",
}


def ros2_names(package: str, languages: Iterable[str] = ("cpp", "python")) -> tuple[str, ...] | None:
    """What `package` is in ROS 2 for nodes of `languages`: its names (itself when unmapped), None for nothing."""
    if package not in ROS2_PACKAGES:
        return (package,)
    mapped = ROS2_PACKAGES[package]
    if mapped is None:
        return None
    if isinstance(mapped, str):
        return (mapped,)
    return tuple(dict.fromkeys(mapped[language] for language in languages if language in mapped)) or tuple(
        dict.fromkeys(mapped.values()))


def note(package: str) -> str:
    return NOTES.get(package, "ROS 2 has no such package")
