"""What each feature of a node needs, per dialect: the packages, and what its files include.

One table per dialect (ROS 2 C++, ROS 2 Python, ROS 1 C++, ROS 1 Python). A feature's
packages go to package.xml and the build files (rna.model); its headers or imports go to
the node's generated base file or to the user's file with the starter code (rna.dialects).
Headers are written '<chrono>' (standard) or 'rclcpp/rclcpp.hpp'; imports 'module' or
'module:Name'.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Needs:
    packages: tuple[str, ...] = ()
    base: tuple[str, ...] = ()  # included or imported by the generated <node>_base file
    user: tuple[str, ...] = ()  # included or imported by the user's file (its starter code)


def node_features(node) -> frozenset[str]:
    """The features of a node, named as in the tables below."""
    parameters = node.parameters
    qos = [topic.qos for topic in node.publishers + node.subscribers]
    found = {
        "node": True,
        # What rospy's own calls wire up in a ROS 1 base class (an action client is actionlib's alone).
        "rospy_wiring": bool(node.parameters or node.diagnostics or set(node.endpoints) - set(node.action_clients)),
        "lifecycle": node.lifecycle,
        "plain": not node.lifecycle,
        "component": node.component,
        "starts_itself": node.starts_itself,
        "diagnostics": node.diagnostics,
        "executable": not node.component,
        "builds_messages": bool(node.starter_built_messages),
        "timers": bool(node.timers),
        "services": bool(node.service_servers or node.service_clients),
        "actions": bool(node.actions),
        "action_servers": bool(node.action_servers),
        "action_clients": bool(node.action_clients),
        "sensor_data_qos": any(q.profile == "sensor_data" for q in qos),
        "system_default_qos": any(q.profile == "system_default" for q in qos),
        "qos_profiles": any(not (q.profile or q.is_plain) for q in qos),  # built by the base class
        "keep_all_history": any(not q.profile and q.history == "keep_all" for q in qos),
        "reliability_policy": any(not q.profile and q.reliability != "reliable" for q in qos),
        "durability_policy": any(not q.profile and q.durability != "volatile" for q in qos),
        "parameter_descriptors": any(p.has_descriptor for p in parameters),
        "integer_ranges": any(p.range and p.type.scalar == "int" for p in parameters),
        "float_ranges": any(p.range and p.type.scalar == "double" for p in parameters),
        "string_parameters": any(p.type.scalar == "string" for p in parameters),
        "array_parameters": any(p.type.is_array for p in parameters),
        node.executor: True,  # single_threaded, multi_threaded, static, events
        "callback_groups": bool(node.callback_groups),
        "mutually_exclusive_groups": any(g.type == "mutually_exclusive" for g in node.callback_groups),
        "reentrant_groups": any(g.type == "reentrant" for g in node.callback_groups),
    }
    return frozenset(name for name, used in found.items() if used)


ROS2_CPP = {
    "node": Needs(("rclcpp",), ("rclcpp/rclcpp.hpp",), ("rclcpp/rclcpp.hpp", "<memory>")),
    "lifecycle": Needs(("lifecycle_msgs", "rclcpp_lifecycle"),
                       ("lifecycle_msgs/msg/state.hpp", "rclcpp_lifecycle/lifecycle_node.hpp",
                        "rclcpp_lifecycle/lifecycle_publisher.hpp")),
    "component": Needs(("rclcpp_components",), user=("rclcpp_components/register_node_macro.hpp",)),
    # spin(): a std::shared_ptr to the node, std::signal to ignore a SIGINT once stopping.
    "executable": Needs(base=("<csignal>", "<memory>")),
    # The autostart parameter (read-only) and the timer that starts the node once it spins.
    "starts_itself": Needs(("rcl_interfaces",), ("<chrono>", "rcl_interfaces/msg/parameter_descriptor.hpp")),
    # The base class owns the Updater; the user's status task sets a DiagnosticStatus level.
    "diagnostics": Needs(("diagnostic_msgs", "diagnostic_updater"),
                         ("diagnostic_updater/diagnostic_status_wrapper.hpp",
                          "diagnostic_updater/diagnostic_updater.hpp"),
                         ("diagnostic_msgs/msg/diagnostic_status.hpp",
                          "diagnostic_updater/diagnostic_status_wrapper.hpp")),
    "timers": Needs(base=("<chrono>",)),
    # The starter code hands each message it builds to publish() as a std::unique_ptr.
    "builds_messages": Needs(user=("<memory>", "<utility>")),
    "services": Needs(base=("<memory>",)),
    "actions": Needs(("rclcpp_action",), ("<memory>", "rclcpp_action/rclcpp_action.hpp")),
    # Each goal in a thread of its own (the base's start_goal_thread()).
    "action_servers": Needs(base=("<chrono>", "<condition_variable>", "<functional>", "<list>", "<memory>",
                                  "<mutex>", "<thread>", "<utility>")),
    "action_clients": Needs(base=("<atomic>",)),
    "parameter_descriptors": Needs(("rcl_interfaces",), ("rcl_interfaces/msg/parameter_descriptor.hpp",)),
    "string_parameters": Needs(base=("<string>",)),
    "array_parameters": Needs(base=("<vector>",)),
}

ROS2_PYTHON = {
    # What the base module's run() uses: the user's main() calls it.
    "node": Needs(("rclpy",), ("os", "signal", "threading", "rclpy", "rclpy.executors:ExternalShutdownException",
                               "rclpy.signals:SignalHandlerOptions")),
    "mutually_exclusive_groups": Needs(base=("rclpy.callback_groups:MutuallyExclusiveCallbackGroup",)),
    "single_threaded": Needs(base=("rclpy.executors:SingleThreadedExecutor",)),
    "multi_threaded": Needs(base=("rclpy.executors:MultiThreadedExecutor",)),
    "reentrant_groups": Needs(base=("rclpy.callback_groups:ReentrantCallbackGroup",)),
    "plain": Needs(base=("rclpy.node:Node",)),
    "diagnostics": Needs(("diagnostic_msgs", "diagnostic_updater"), ("diagnostic_updater",),
                         ("diagnostic_msgs.msg:DiagnosticStatus",)),
    "lifecycle": Needs(base=("rclpy.lifecycle:Node", "rclpy.lifecycle:State",
                             "rclpy.lifecycle:TransitionCallbackReturn")),
    # The read-only autostart parameter a lifecycle node configures and activates itself by.
    "starts_itself": Needs(("rcl_interfaces",), ("rcl_interfaces.msg:ParameterDescriptor",)),
    "sensor_data_qos": Needs(base=("rclpy.qos:qos_profile_sensor_data",)),
    "system_default_qos": Needs(base=("rclpy.qos:qos_profile_system_default",)),
    "qos_profiles": Needs(base=("rclpy.qos:QoSProfile",)),
    "keep_all_history": Needs(base=("rclpy.qos:HistoryPolicy",)),
    "reliability_policy": Needs(base=("rclpy.qos:ReliabilityPolicy",)),
    "durability_policy": Needs(base=("rclpy.qos:DurabilityPolicy",)),
    # threading and Future: each goal runs in a thread of its own (the base's _in_goal_thread).
    "action_servers": Needs(base=("threading", "time", "rclpy.action:ActionServer", "rclpy.action:CancelResponse",
                                  "rclpy.action:GoalResponse", "rclpy.task:Future"),
                            user=("time",)),
    # GoalStatus, to report how a goal ended.
    "action_clients": Needs(("action_msgs",), ("rclpy.action:ActionClient",), ("action_msgs.msg:GoalStatus",)),
    "parameter_descriptors": Needs(("rcl_interfaces",), ("rcl_interfaces.msg:ParameterDescriptor",)),
    "integer_ranges": Needs(base=("rcl_interfaces.msg:IntegerRange",)),
    "float_ranges": Needs(base=("rcl_interfaces.msg:FloatingPointRange",)),
}

ROS1_CPP = {
    "node": Needs(("roscpp",), ("ros/ros.h",), ("ros/ros.h",)),
    "diagnostics": Needs(("diagnostic_msgs", "diagnostic_updater"),
                         ("diagnostic_updater/DiagnosticStatusWrapper.h", "diagnostic_updater/diagnostic_updater.h"),
                         ("diagnostic_msgs/DiagnosticStatus.h", "diagnostic_updater/DiagnosticStatusWrapper.h")),
    "actions": Needs(("actionlib", "actionlib_msgs")),
    # Ctrl-C ends running goals before ROS shuts down: a SIGINT handler, and a cancel of the
    # server's own goals (the base class's stop_running_goals()).
    "action_servers": Needs(base=("<csignal>", "actionlib/server/simple_action_server.h", "actionlib_msgs/GoalID.h")),
    "action_clients": Needs(base=("actionlib/client/simple_action_client.h",)),
    "string_parameters": Needs(base=("<string>",)),
    "array_parameters": Needs(base=("<vector>",)),
}

ROS1_PYTHON = {
    # The base module's run(), which holds Ctrl-C in start-up (rna.dialects.ros1_python adds
    # rospy to the user's file when its starter code logs).
    "node": Needs(("rospy",), ("rospy", "signal")),
    "rospy_wiring": Needs(base=("rospy",)),
    "diagnostics": Needs(("diagnostic_msgs", "diagnostic_updater"), ("diagnostic_updater",),
                         ("diagnostic_msgs.msg:DiagnosticStatus",)),
    "actions": Needs(("actionlib", "actionlib_msgs")),
    # time: a running goal gets a second to end when the node stops (_stop_action_server).
    "action_servers": Needs(base=("time", "actionlib:SimpleActionServer")),
    "action_clients": Needs(base=("actionlib:SimpleActionClient",), user=("actionlib_msgs.msg:GoalStatus",)),
}

TABLES = {(2, "cpp"): ROS2_CPP, (2, "python"): ROS2_PYTHON, (1, "cpp"): ROS1_CPP, (1, "python"): ROS1_PYTHON}


def needs(node) -> list[Needs]:
    """What the node's features need, in its dialect."""
    table = TABLES[(node.ros, node.language)]
    return [table[feature] for feature in sorted(node_features(node)) if feature in table]


def packages(node) -> set[str]:
    return {package for need in needs(node) for package in need.packages}


# What the generated tests use, per build type (rna.model adds gtest/pytest and the linters per
# language). Python unit tests and launch tests drive rclpy; the launch test includes the package's
# launch file through launch's any-format source and finds it with ament_index_python.
TEST_PACKAGES = {
    "ament_python": ("ament_copyright", "ament_flake8", "ament_index_python", "ament_pep257", "launch",
                     "launch_testing", "python3-pytest", "rclpy"),
    "ament_cmake": ("ament_index_python", "ament_lint_auto", "ament_lint_common", "launch", "launch_testing",
                    "launch_testing_ament_cmake", "rclpy"),
    "catkin": ("python3-catkin-lint", "python3-flake8", "python3-nose", "rosgraph", "rosservice",
               "rostest"),
}
