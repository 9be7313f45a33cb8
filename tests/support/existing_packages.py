"""Packages the template did not make, written the way ros2 pkg create / catkin_create_pkg do,
each with one hand-written node, for the tests that add a node to them."""

from __future__ import annotations

import textwrap
from pathlib import Path


def _manifest(name: str, buildtool: str, depends: list[str], build_type: str | None) -> str:
    export = f"\n  <export>\n    <build_type>{build_type}</build_type>\n  </export>" if build_type else ""
    lines = "".join(f"  <depend>{d}</depend>\n" for d in depends)
    return textwrap.dedent(f"""\
        <?xml version="1.0"?>
        <package format="3">
          <name>{name}</name>
          <version>0.0.1</version>
          <description>Drives the robot around the lab; written by hand</description>
          <maintainer email="grace@example.com">Grace Hopper</maintainer>
          <license>Apache-2.0</license>

          <buildtool_depend>{buildtool}</buildtool_depend>

        """) + lines + export + "\n</package>\n"


RCLPY_TALKER = '''\
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import String


class HandTalker(Node):

    def __init__(self):
        super().__init__('hand_talker')
        self.publisher = self.create_publisher(String, 'chatter', 10)
        self.timer = self.create_timer(0.2, self.tick)
        self.count = 0

    def tick(self):
        self.publisher.publish(String(data=f'Hello by hand: {self.count}'))
        self.count += 1


def main():
    rclpy.init()
    node = HandTalker()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
'''


def ament_python(folder: Path, name: str = "hand_robot") -> Path:
    """An ament_python package with a talker (entry point hand_talker) on /chatter."""
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(_manifest(name, "ament_python", [], "ament_python").replace(
        "\n  <export>", "  <exec_depend>rclpy</exec_depend>\n  <exec_depend>std_msgs</exec_depend>\n\n  <export>"))
    (folder / "resource").mkdir()
    (folder / "resource" / name).write_text("")
    (folder / name).mkdir()
    (folder / name / "__init__.py").write_text("")
    (folder / name / "hand_talker.py").write_text(RCLPY_TALKER)
    (folder / "setup.cfg").write_text(
        f"[develop]\nscript_dir=$base/lib/{name}\n[install]\ninstall_scripts=$base/lib/{name}\n")
    (folder / "setup.py").write_text(textwrap.dedent(f"""\
        from setuptools import find_packages, setup

        package_name = '{name}'

        setup(
            name=package_name,
            version='0.0.1',
            packages=find_packages(exclude=['test']),
            data_files=[
                ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
                ('share/' + package_name, ['package.xml']),
            ],
            install_requires=['setuptools'],
            zip_safe=True,
            maintainer='Grace Hopper',
            maintainer_email='grace@example.com',
            description='Drives the robot around the lab; written by hand',
            license='Apache-2.0',
            entry_points={{
                'console_scripts': [
                    'hand_talker = {name}.hand_talker:main',
                ],
            }},
        )
        """))
    return folder


def ament_cmake(folder: Path, name: str = "hand_driver") -> Path:
    """An ament_cmake package with a C++ executable, as `ros2 pkg create` lays it out."""
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(_manifest(name, "ament_cmake", ["rclcpp"], "ament_cmake").replace(
        "\n  <export>", "\n  <test_depend>ament_lint_auto</test_depend>\n\n  <export>"))
    (folder / "src").mkdir()
    (folder / "src" / "driver.cpp").write_text("int main() {return 0;}\n")
    (folder / "CMakeLists.txt").write_text(textwrap.dedent(f"""\
        cmake_minimum_required(VERSION 3.8)
        project({name})

        find_package(ament_cmake REQUIRED)

        add_executable(driver src/driver.cpp)
        install(TARGETS driver DESTINATION lib/${{PROJECT_NAME}})

        if(BUILD_TESTING)
          find_package(ament_lint_auto REQUIRED)
          ament_lint_auto_find_test_dependencies()
        endif()

        ament_package()
        """))
    return folder


ROSCPP_TALKER = '''\
#include "ros/ros.h"
#include "std_msgs/String.h"

int main(int argc, char ** argv)
{
  ros::init(argc, argv, "hand_talker");
  ros::NodeHandle node_handle;
  ros::Publisher publisher = node_handle.advertise<std_msgs::String>("chatter", 10);
  ros::Rate rate(5.0);
  while (ros::ok()) {
    std_msgs::String msg;
    msg.data = "Hello by hand";
    publisher.publish(msg);
    ros::spinOnce();
    rate.sleep();
  }
  return 0;
}
'''


def catkin(folder: Path, name: str = "hand_rover") -> Path:
    """A catkin package with a roscpp talker on /chatter, as catkin_create_pkg lays it out."""
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(_manifest(name, "catkin", ["roscpp", "std_msgs"], None))
    (folder / "src").mkdir()
    (folder / "src" / "hand_talker.cpp").write_text(ROSCPP_TALKER)
    (folder / "CMakeLists.txt").write_text(textwrap.dedent(f"""\
        cmake_minimum_required(VERSION 3.0.2)
        project({name})

        find_package(catkin REQUIRED COMPONENTS
          roscpp
          std_msgs
        )

        catkin_package(
          CATKIN_DEPENDS roscpp std_msgs
        )

        include_directories(${{catkin_INCLUDE_DIRS}})

        add_executable(hand_talker src/hand_talker.cpp)
        target_link_libraries(hand_talker ${{catkin_LIBRARIES}})
        install(TARGETS hand_talker RUNTIME DESTINATION ${{CATKIN_PACKAGE_BIN_DESTINATION}})
        """))
    return folder
