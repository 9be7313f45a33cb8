"""Packages shaped like the real ones users add nodes to and grow, written here for the tests.

Each is modelled on the layout of a kind of upstream package (read, not copied): a ROS 2
C++ package of several executables and components in one library (as ros2/demos'
composition), an ament_python package with several entry points and data files (as
ros2/examples' rclpy packages and demo_nodes_py), a catkin package of rospy scripts with no
setup.py (as ros_tutorials' rospy_tutorials), a roscpp catkin package as catkin_create_pkg
lays it out, comment blocks and all (as roscpp_tutorials), and a robot description
package with binary STL meshes, images and RViz configuration (as the robots'
*_description packages). They carry what real packages carry besides: a source in
Latin-1, files with CRLF line ends, a mesh over the update's 1 MiB reading limit, a
symbolic link, a file without a final newline.

`PACKAGES` names each with the node a test adds to it and the answers that grow that
node in a `copier update`; `write(name, folder)` writes one, `grown(...)` writes it, adds
its node and grows it, as a user does (committing in between).
"""

from __future__ import annotations

import difflib
import os
import re
import struct
import subprocess
import sys
import textwrap
import zlib
from dataclasses import dataclass, field
from pathlib import Path

from rna import files

from .generation import git, subprocess_env
from .template_repo import UpdateResult, commit_all, run_update

MAINTAINER = '<maintainer email="grace@example.com">Grace Hopper</maintainer>'


def _text(text: str) -> str:
    return textwrap.dedent(text).lstrip("\n")


def binary_stl(triangles: int, seed: int = 1) -> bytes:
    """A binary STL mesh: an 80-byte header, the count, then 50 bytes per triangle (normal,
    three vertices, attributes); vertices on a deterministic spiral."""
    header = b"binary STL written by the tests of rna-template".ljust(80, b"\0")
    body = []
    for index in range(triangles):
        angle = (index * seed) % 360 / 57.29578
        corner = (0.1 * index % 7, 0.05 * angle, 0.02 * (index % 11))
        vertices = [corner, (corner[0] + 0.01, corner[1], corner[2]), (corner[0], corner[1] + 0.01, corner[2])]
        body.append(struct.pack("<12fH", 0.0, 0.0, 1.0, *(value for vertex in vertices for value in vertex), 0))
    return header + struct.pack("<I", triangles) + b"".join(body)


def png(width: int, height: int) -> bytes:
    """A grey PNG image (8-bit greyscale), as small as zlib makes it."""
    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    rows = b"".join(b"\0" + bytes((x * 255 // max(1, width - 1)) for x in range(width)) for _ in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


@dataclass(frozen=True)
class RealPackage:
    """A package of one kind: its files, and the node a test adds and then grows."""

    name: str
    ros: int
    files: dict[str, str | bytes]
    node: dict  # the added node's answers (`copier copy` into the package)
    grown: dict  # the same node grown by `copier update` (its `nodes` entry)
    executables: tuple[str, ...] = ()  # files to mark executable
    links: dict[str, str] = field(default_factory=dict)  # link -> its target, as the link names it


# ─── A ROS 2 C++ package: components in one library and executables ──────────

VISIBILITY = _text("""
    #ifndef CAMERA_PIPELINE__VISIBILITY_CONTROL_H_
    #define CAMERA_PIPELINE__VISIBILITY_CONTROL_H_

    // Symbols of the component library, exported on every platform the pipeline builds on.
    #if defined _WIN32 || defined __CYGWIN__
      #define CAMERA_PIPELINE_EXPORT __declspec(dllexport)
      #define CAMERA_PIPELINE_IMPORT __declspec(dllimport)
      #ifdef CAMERA_PIPELINE_BUILDING_DLL
        #define CAMERA_PIPELINE_PUBLIC CAMERA_PIPELINE_EXPORT
      #else
        #define CAMERA_PIPELINE_PUBLIC CAMERA_PIPELINE_IMPORT
      #endif
    #else
      #define CAMERA_PIPELINE_PUBLIC __attribute__ ((visibility("default")))
    #endif

    #endif  // CAMERA_PIPELINE__VISIBILITY_CONTROL_H_
    """)


def _component_header(name: str, guard: str, members: str) -> str:
    return _text(f"""
        #ifndef CAMERA_PIPELINE__{guard}_HPP_
        #define CAMERA_PIPELINE__{guard}_HPP_

        #include "camera_pipeline/visibility_control.h"
        #include "rclcpp/rclcpp.hpp"
        #include "sensor_msgs/msg/image.hpp"

        namespace camera_pipeline
        {{

        class {name} : public rclcpp::Node
        {{
        public:
          CAMERA_PIPELINE_PUBLIC
          explicit {name}(const rclcpp::NodeOptions & options);

        private:
        {members}
        }};

        }}  // namespace camera_pipeline

        #endif  // CAMERA_PIPELINE__{guard}_HPP_
        """)


CAMERA_PIPELINE = RealPackage(
    name="camera_pipeline", ros=2,
    files={
        "package.xml": _text(f"""
            <?xml version="1.0"?>
            <?xml-model href="http://download.ros.org/schema/package_format3.xsd" schematypens="http://www.w3.org/2001/XMLSchema"?>
            <package format="3">
              <name>camera_pipeline</name>
              <version>0.4.2</version>
              <description>
                Grabs images from the lab camera and filters them, as components that run
                in one process or as executables of their own.
              </description>
              {MAINTAINER}
              <license>Apache-2.0</license>

              <buildtool_depend>ament_cmake</buildtool_depend>

              <depend>rclcpp</depend>
              <depend>rclcpp_components</depend>
              <depend>sensor_msgs</depend>

              <exec_depend>launch_ros</exec_depend>

              <test_depend>ament_lint_auto</test_depend>
              <test_depend>ament_lint_common</test_depend>

              <export>
                <build_type>ament_cmake</build_type>
              </export>
            </package>
            """),
        "CMakeLists.txt": _text("""
            cmake_minimum_required(VERSION 3.8)
            project(camera_pipeline)

            if(CMAKE_COMPILER_IS_GNUCXX OR CMAKE_CXX_COMPILER_ID MATCHES "Clang")
              add_compile_options(-Wall -Wextra -Wpedantic)
            endif()

            find_package(ament_cmake REQUIRED)
            find_package(rclcpp REQUIRED)
            find_package(rclcpp_components REQUIRED)
            find_package(sensor_msgs REQUIRED)

            # The components, in one library: loaded into a container, or run alone below.
            add_library(pipeline_components SHARED
              src/image_source.cpp
              src/image_filter.cpp)
            target_include_directories(pipeline_components PUBLIC
              $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
              $<INSTALL_INTERFACE:include/${PROJECT_NAME}>)
            target_compile_definitions(pipeline_components PRIVATE "CAMERA_PIPELINE_BUILDING_DLL")
            target_link_libraries(pipeline_components PUBLIC
              rclcpp::rclcpp
              rclcpp_components::component
              ${sensor_msgs_TARGETS})
            rclcpp_components_register_node(pipeline_components
              PLUGIN "camera_pipeline::ImageSource"
              EXECUTABLE image_source)
            rclcpp_components_register_node(pipeline_components
              PLUGIN "camera_pipeline::ImageFilter"
              EXECUTABLE image_filter)

            # Both components in one process, wired by hand.
            add_executable(pipeline src/pipeline.cpp)
            target_link_libraries(pipeline pipeline_components)

            add_executable(calibrate_camera src/calibrate_camera.cpp)
            target_link_libraries(calibrate_camera rclcpp::rclcpp ${sensor_msgs_TARGETS})

            install(TARGETS pipeline_components
              ARCHIVE DESTINATION lib
              LIBRARY DESTINATION lib
              RUNTIME DESTINATION bin)
            install(TARGETS pipeline calibrate_camera
              DESTINATION lib/${PROJECT_NAME})
            install(DIRECTORY include/
              DESTINATION include/${PROJECT_NAME})
            install(DIRECTORY launch config
              DESTINATION share/${PROJECT_NAME})

            if(BUILD_TESTING)
              find_package(ament_lint_auto REQUIRED)
              ament_lint_auto_find_test_dependencies()
            endif()

            ament_export_include_directories(include/${PROJECT_NAME})
            ament_export_libraries(pipeline_components)
            ament_export_dependencies(rclcpp rclcpp_components sensor_msgs)
            ament_package()
            """),
        "include/camera_pipeline/visibility_control.h": VISIBILITY,
        "include/camera_pipeline/image_source.hpp": _component_header(
            "ImageSource", "IMAGE_SOURCE",
            "  void capture();\n\n  rclcpp::Publisher<sensor_msgs::msg::Image>::SharedPtr publisher_;\n"
            "  rclcpp::TimerBase::SharedPtr timer_;\n  std::size_t frame_ = 0;"),
        "include/camera_pipeline/image_filter.hpp": _component_header(
            "ImageFilter", "IMAGE_FILTER",
            "  void filter(sensor_msgs::msg::Image::ConstSharedPtr image);\n\n"
            "  rclcpp::Subscription<sensor_msgs::msg::Image>::SharedPtr subscription_;\n"
            "  rclcpp::Publisher<sensor_msgs::msg::Image>::SharedPtr publisher_;"),
        "src/image_source.cpp": _text("""
            #include "camera_pipeline/image_source.hpp"

            #include <chrono>
            #include <memory>

            #include "rclcpp_components/register_node_macro.hpp"

            namespace camera_pipeline
            {

            ImageSource::ImageSource(const rclcpp::NodeOptions & options)
            : Node("image_source", options)
            {
              const double rate = declare_parameter("rate", 15.0);
              publisher_ = create_publisher<sensor_msgs::msg::Image>("image", rclcpp::SensorDataQoS());
              timer_ = create_wall_timer(
                std::chrono::duration<double>(1.0 / rate), [this]() {capture();});
            }

            void ImageSource::capture()
            {
              auto image = std::make_unique<sensor_msgs::msg::Image>();
              image->header.stamp = now();
              image->header.frame_id = "camera";
              image->height = 4;
              image->width = 4;
              image->encoding = "mono8";
              image->step = 4;
              image->data.assign(16, static_cast<uint8_t>(frame_++ % 256));
              publisher_->publish(std::move(image));
            }

            }  // namespace camera_pipeline

            RCLCPP_COMPONENTS_REGISTER_NODE(camera_pipeline::ImageSource)
            """),
        "src/image_filter.cpp": _text("""
            #include "camera_pipeline/image_filter.hpp"

            #include <algorithm>
            #include <memory>

            #include "rclcpp_components/register_node_macro.hpp"

            namespace camera_pipeline
            {

            ImageFilter::ImageFilter(const rclcpp::NodeOptions & options)
            : Node("image_filter", options)
            {
              publisher_ = create_publisher<sensor_msgs::msg::Image>("image_filtered", rclcpp::SensorDataQoS());
              subscription_ = create_subscription<sensor_msgs::msg::Image>(
                "image", rclcpp::SensorDataQoS(),
                [this](sensor_msgs::msg::Image::ConstSharedPtr image) {filter(image);});
            }

            void ImageFilter::filter(sensor_msgs::msg::Image::ConstSharedPtr image)
            {
              auto filtered = std::make_unique<sensor_msgs::msg::Image>(*image);
              std::transform(
                filtered->data.begin(), filtered->data.end(), filtered->data.begin(),
                [](uint8_t value) {return static_cast<uint8_t>(255 - value);});
              publisher_->publish(std::move(filtered));
            }

            }  // namespace camera_pipeline

            RCLCPP_COMPONENTS_REGISTER_NODE(camera_pipeline::ImageFilter)
            """),
        "src/pipeline.cpp": _text("""
            #include <memory>

            #include "camera_pipeline/image_filter.hpp"
            #include "camera_pipeline/image_source.hpp"
            #include "rclcpp/rclcpp.hpp"

            int main(int argc, char * argv[])
            {
              rclcpp::init(argc, argv);
              rclcpp::executors::SingleThreadedExecutor executor;
              rclcpp::NodeOptions options;
              options.use_intra_process_comms(true);
              auto source = std::make_shared<camera_pipeline::ImageSource>(options);
              auto filter = std::make_shared<camera_pipeline::ImageFilter>(options);
              executor.add_node(source);
              executor.add_node(filter);
              executor.spin();
              rclcpp::shutdown();
              return 0;
            }
            """),
        "src/calibrate_camera.cpp": _text("""
            #include <memory>

            #include "rclcpp/rclcpp.hpp"
            #include "sensor_msgs/msg/camera_info.hpp"

            int main(int argc, char * argv[])
            {
              rclcpp::init(argc, argv);
              auto node = rclcpp::Node::make_shared("calibrate_camera");
              RCLCPP_INFO(node->get_logger(), "Point the camera at the checkerboard");
              rclcpp::spin(node);
              rclcpp::shutdown();
              return 0;
            }
            """),
        "launch/pipeline.launch.py": _text("""
            from launch import LaunchDescription
            from launch_ros.actions import ComposableNodeContainer
            from launch_ros.descriptions import ComposableNode


            def generate_launch_description():
                container = ComposableNodeContainer(
                    name='pipeline_container',
                    namespace='',
                    package='rclcpp_components',
                    executable='component_container',
                    composable_node_descriptions=[
                        ComposableNode(package='camera_pipeline', plugin='camera_pipeline::ImageSource',
                                       name='image_source'),
                        ComposableNode(package='camera_pipeline', plugin='camera_pipeline::ImageFilter',
                                       name='image_filter'),
                    ],
                    output='screen',
                )
                return LaunchDescription([container])
            """),
        "config/image_source.yaml": "image_source:\n  ros__parameters:\n    rate: 30.0\n",
        "README.md": _text("""
            # camera_pipeline

            Grab and filter images: `ros2 launch camera_pipeline pipeline.launch.py`.

            | Executable | What |
            | --- | --- |
            | image_source | the camera, alone |
            | image_filter | the filter, alone |
            | pipeline | both, in one process |
            """),
        # Saved on Windows: CRLF line ends, no final newline.
        "doc/calibration.md": "# Calibration\r\n\r\nUse the 8x6 checkerboard.\r\nHold it still.",
        "doc/pipeline.png": png(32, 8),
    },
    node={"node_name": "exposure_monitor", "node_language": "cpp",
          "node_subscribers": "image:sensor_msgs/msg/Image:sensor_data",
          "node_parameters": "target_brightness:double=0.5"},
    grown={"name": "exposure_monitor", "language": "cpp", "subscribers": ["image:sensor_msgs/msg/Image:sensor_data"],
           "publishers": ["exposure:std_msgs/msg/Float64"], "timers": ["1.0"],
           "parameters": ["target_brightness:double=0.5", "gain:double=0.1"]},
)


# ─── An ament_python package: several entry points, data files ───────────────

TALKER_PY = _text('''
    """Says hello on chatter, twice a second."""

    import rclpy
    from rclpy.executors import ExternalShutdownException
    from rclpy.node import Node
    from std_msgs.msg import String


    class Talker(Node):

        def __init__(self):
            super().__init__('talker')
            self.count = 0
            self.publisher = self.create_publisher(String, 'chatter', 10)
            self.timer = self.create_timer(0.2, self.on_timer)

        def on_timer(self):
            self.publisher.publish(String(data=f'Hello from demo_tools: {self.count}'))
            self.count += 1


    def main(args=None):
        rclpy.init(args=args)
        node = Talker()
        try:
            rclpy.spin(node)
        except (KeyboardInterrupt, ExternalShutdownException):
            pass
        finally:
            node.destroy_node()
            rclpy.try_shutdown()
    ''')

DEMO_TOOLS = RealPackage(
    name="demo_tools", ros=2,
    files={
        "package.xml": _text(f"""
            <?xml version="1.0"?>
            <?xml-model href="http://download.ros.org/schema/package_format3.xsd" schematypens="http://www.w3.org/2001/XMLSchema"?>
            <package format="3">
              <name>demo_tools</name>
              <version>1.2.0</version>
              <description>Small tools for demos: a talker, a listener and a switch service</description>
              {MAINTAINER}
              <license>Apache-2.0</license>

              <exec_depend>rclpy</exec_depend>
              <exec_depend>std_msgs</exec_depend>
              <exec_depend>std_srvs</exec_depend>

              <test_depend>ament_copyright</test_depend>
              <test_depend>ament_flake8</test_depend>
              <test_depend>ament_pep257</test_depend>
              <test_depend>python3-pytest</test_depend>

              <export>
                <build_type>ament_python</build_type>
              </export>
            </package>
            """),
        # Written on Windows: CRLF line ends.
        "setup.py": _text("""
            import os
            from glob import glob

            from setuptools import find_packages, setup

            package_name = 'demo_tools'

            setup(
                name=package_name,
                version='1.2.0',
                packages=find_packages(exclude=['test']),
                data_files=[
                    ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
                    ('share/' + package_name, ['package.xml']),
                    (os.path.join('share', package_name, 'launch'), glob('launch/*.launch.py')),
                    (os.path.join('share', package_name, 'config'), glob('config/*.yaml')),
                ],
                install_requires=['setuptools'],
                zip_safe=True,
                maintainer='Grace Hopper',
                maintainer_email='grace@example.com',
                description='Small tools for demos',
                license='Apache-2.0',
                tests_require=['pytest'],
                entry_points={
                    'console_scripts': [
                        'talker = demo_tools.talker:main',
                        'listener = demo_tools.listener:main',
                        'switch_server = demo_tools.switch_server:main',
                    ],
                },
            )
            """).replace("\n", "\r\n"),
        "setup.cfg": "[develop]\nscript_dir=$base/lib/demo_tools\n[install]\ninstall_scripts=$base/lib/demo_tools\n",
        "resource/demo_tools": "",
        "demo_tools/__init__.py": "",
        "demo_tools/talker.py": TALKER_PY,
        "demo_tools/listener.py": _text('''
            """Prints what it hears on chatter."""

            import rclpy
            from rclpy.executors import ExternalShutdownException
            from rclpy.node import Node
            from std_msgs.msg import String


            class Listener(Node):

                def __init__(self):
                    super().__init__('listener')
                    self.subscription = self.create_subscription(String, 'chatter', self.on_chatter, 10)

                def on_chatter(self, msg):
                    self.get_logger().info(msg.data)


            def main(args=None):
                rclpy.init(args=args)
                node = Listener()
                try:
                    rclpy.spin(node)
                except (KeyboardInterrupt, ExternalShutdownException):
                    pass
                finally:
                    node.destroy_node()
                    rclpy.try_shutdown()
            '''),
        "demo_tools/switch_server.py": _text('''
            """Switches the demo on and off."""

            import rclpy
            from rclpy.node import Node
            from std_srvs.srv import SetBool


            class SwitchServer(Node):

                def __init__(self):
                    super().__init__('switch_server')
                    self.service = self.create_service(SetBool, 'switch', self.on_switch)

                def on_switch(self, request, response):
                    response.success = True
                    response.message = 'on' if request.data else 'off'
                    return response


            def main(args=None):
                rclpy.init(args=args)
                rclpy.spin(SwitchServer())
            '''),
        "launch/demo.launch.py": _text("""
            from launch import LaunchDescription
            from launch_ros.actions import Node


            def generate_launch_description():
                return LaunchDescription([
                    Node(package='demo_tools', executable='talker'),
                    Node(package='demo_tools', executable='listener'),
                ])
            """),
        "config/talker.yaml": "talker:\n  ros__parameters:\n    use_sim_time: false\n",
        "test/test_flake8.py": _text("""
            from ament_flake8.main import main_with_errors
            import pytest


            @pytest.mark.flake8
            @pytest.mark.linter
            def test_flake8():
                rc, errors = main_with_errors(argv=[])
                assert rc == 0, 'Found %d code style errors / warnings:\\n' % len(errors) + '\\n'.join(errors)
            """),
        # A note kept in Latin-1 by an older editor.
        "NOTES.txt": "Démo pour la journée portes ouvertes.\n".encode("latin-1"),
    },
    node={"node_name": "chatter_monitor", "node_subscribers": "chatter:std_msgs/msg/String"},
    grown={"name": "chatter_monitor", "language": "python", "subscribers": ["chatter:std_msgs/msg/String"],
           "publishers": ["chatter_count:std_msgs/msg/Int32"], "parameters": ["window:int=10"]},
)


# ─── A catkin package of rospy scripts (no setup.py) ─────────────────────────

ROSPY_TALKER = _text('''
    #!/usr/bin/env python3
    """Says hello on chatter."""

    import rospy
    from std_msgs.msg import String


    def talker():
        publisher = rospy.Publisher('chatter', String, queue_size=10)
        rospy.init_node('talker')
        rate = rospy.Rate(5)
        while not rospy.is_shutdown():
            publisher.publish(String(data='hello from rospy_tools'))
            rate.sleep()


    if __name__ == '__main__':
        try:
            talker()
        except rospy.ROSInterruptException:
            pass
    ''')

ROSPY_TOOLS = RealPackage(
    name="rospy_tools", ros=1,
    files={
        "package.xml": _text(f"""
            <?xml version="1.0"?>
            <package format="2">
              <name>rospy_tools</name>
              <version>0.1.7</version>
              <description>Talker and listener scripts for the lab's first steps with rospy</description>
              {MAINTAINER}
              <license>BSD</license>

              <buildtool_depend>catkin</buildtool_depend>
              <exec_depend>rospy</exec_depend>
              <exec_depend>std_msgs</exec_depend>
            </package>
            """),
        "CMakeLists.txt": _text("""
            cmake_minimum_required(VERSION 3.0.2)
            project(rospy_tools)

            find_package(catkin REQUIRED COMPONENTS rospy std_msgs)

            catkin_package()

            catkin_install_python(PROGRAMS
              scripts/talker.py
              scripts/listener.py
              DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION}
            )

            install(FILES launch/talker_listener.launch
              DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/launch
            )
            """),
        "scripts/talker.py": ROSPY_TALKER,
        "scripts/listener.py": _text('''
            #!/usr/bin/env python3
            """Prints what it hears on chatter."""

            import rospy
            from std_msgs.msg import String


            def on_chatter(msg):
                rospy.loginfo('heard %s', msg.data)


            if __name__ == '__main__':
                rospy.init_node('listener')
                rospy.Subscriber('chatter', String, on_chatter)
                rospy.spin()
            '''),
        "launch/talker_listener.launch": _text("""
            <launch>
              <node name="talker" pkg="rospy_tools" type="talker.py" output="screen"/>
              <node name="listener" pkg="rospy_tools" type="listener.py" output="screen"/>
            </launch>
            """),
        "README.md": "# rospy_tools\n\n`rosrun rospy_tools talker.py`, then `rosrun rospy_tools listener.py`.\n",
    },
    node={"node_name": "chatter_monitor", "node_language": "python",
          "node_subscribers": "chatter:std_msgs/msg/String"},
    grown={"name": "chatter_monitor", "language": "python", "subscribers": ["chatter:std_msgs/msg/String"],
           "publishers": ["chatter_count:std_msgs/msg/Int32"], "parameters": ["window:int=10"]},
    executables=("scripts/talker.py", "scripts/listener.py"),
)


# ─── A roscpp catkin package, as catkin_create_pkg lays it out ───────────────

ROSCPP_BRINGUP = RealPackage(
    name="roscpp_bringup", ros=1,
    files={
        "package.xml": _text(f"""
            <?xml version="1.0"?>
            <package format="2">
              <name>roscpp_bringup</name>
              <version>0.0.3</version>
              <description>The roscpp_bringup package: the lab rover's talker and odometry relay</description>

              <!-- One maintainer tag required, multiple allowed, one person per tag -->
              {MAINTAINER}

              <!-- One license tag required, multiple allowed, one license per tag -->
              <license>BSD</license>

              <!-- The *depend tags are used to specify dependencies -->
              <buildtool_depend>catkin</buildtool_depend>
              <build_depend>roscpp</build_depend>
              <build_depend>std_msgs</build_depend>
              <build_depend>nav_msgs</build_depend>
              <build_export_depend>roscpp</build_export_depend>
              <build_export_depend>std_msgs</build_export_depend>
              <exec_depend>roscpp</exec_depend>
              <exec_depend>std_msgs</exec_depend>
              <exec_depend>nav_msgs</exec_depend>

              <!-- The export tag contains other, unspecified, tags -->
              <export>
                <!-- Other tools can request additional information be placed here -->

              </export>
            </package>
            """),
        # Kept in Latin-1 since the package was started, like the sources.
        "CMakeLists.txt": _text("""
            cmake_minimum_required(VERSION 3.0.2)
            project(roscpp_bringup)

            ## Compile as C++11, supported in ROS Kinetic and newer
            # add_compile_options(-std=c++11)

            ## Find catkin macros and libraries
            ## if COMPONENTS list like find_package(catkin REQUIRED COMPONENTS xyz)
            ## is used, also find other catkin packages
            find_package(catkin REQUIRED COMPONENTS
              nav_msgs
              roscpp
              std_msgs
            )

            ## Uncomment this if the package has a setup.py. This macro ensures
            ## modules and global scripts declared therein get installed
            # catkin_python_setup()

            ###################################
            ## catkin specific configuration ##
            ###################################
            ## Betreuer: Jürgen Müller (Institut für Robotik)
            catkin_package(
            #  INCLUDE_DIRS include
            #  LIBRARIES roscpp_bringup
              CATKIN_DEPENDS nav_msgs roscpp std_msgs
            #  DEPENDS system_lib
            )

            ###########
            ## Build ##
            ###########

            ## Specify additional locations of header files
            include_directories(
              ${catkin_INCLUDE_DIRS}
            )

            add_executable(talker src/talker.cpp)
            target_link_libraries(talker ${catkin_LIBRARIES})

            add_executable(odom_relay src/odom_relay.cpp)
            target_link_libraries(odom_relay ${catkin_LIBRARIES})

            #############
            ## Install ##
            #############

            install(TARGETS talker odom_relay
              RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION}
            )

            ## Mark other files for installation (e.g. launch and bag files, etc.)
            # install(FILES
            #   # myfile1
            #   DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}
            # )
            """).encode("latin-1"),
        "src/talker.cpp": _text("""
            // Der Sprecher: sagt hallo auf chatter.  (Autor: Jürgen Müller)
            #include "ros/ros.h"
            #include "std_msgs/String.h"

            int main(int argc, char ** argv)
            {
              ros::init(argc, argv, "talker");
              ros::NodeHandle node_handle;
              ros::Publisher publisher = node_handle.advertise<std_msgs::String>("chatter", 10);
              ros::Rate rate(5.0);
              while (ros::ok()) {
                std_msgs::String message;
                message.data = "hello from roscpp_bringup";
                publisher.publish(message);
                ros::spinOnce();
                rate.sleep();
              }
              return 0;
            }
            """).encode("latin-1"),
        "src/odom_relay.cpp": _text("""
            #include "nav_msgs/Odometry.h"
            #include "ros/ros.h"

            ros::Publisher relayed;

            void on_odom(const nav_msgs::Odometry::ConstPtr & odom)
            {
              relayed.publish(*odom);
            }

            int main(int argc, char ** argv)
            {
              ros::init(argc, argv, "odom_relay");
              ros::NodeHandle node_handle;
              relayed = node_handle.advertise<nav_msgs::Odometry>("odom_relayed", 10);
              ros::Subscriber subscriber = node_handle.subscribe("odom", 10, on_odom);
              ros::spin();
              return 0;
            }
            """),
        "launch/bringup.launch": _text("""
            <launch>
              <node name="talker" pkg="roscpp_bringup" type="talker"/>
              <node name="odom_relay" pkg="roscpp_bringup" type="odom_relay"/>
            </launch>
            """),
    },
    node={"node_name": "chatter_monitor", "node_language": "cpp",
          "node_subscribers": "chatter:std_msgs/msg/String"},
    grown={"name": "chatter_monitor", "language": "cpp", "subscribers": ["chatter:std_msgs/msg/String"],
           "publishers": ["chatter_count:std_msgs/msg/Int32"], "parameters": ["window:int=10"]},
)


# ─── A robot description package: URDF, meshes, images, RViz ─────────────────

ROVER_DESCRIPTION = RealPackage(
    name="rover_description", ros=2,
    files={
        "package.xml": _text(f"""
            <?xml version="1.0"?>
            <?xml-model href="http://download.ros.org/schema/package_format3.xsd" schematypens="http://www.w3.org/2001/XMLSchema"?>
            <package format="3">
              <name>rover_description</name>
              <version>2.0.1</version>
              <description>URDF, meshes and RViz configuration of the lab rover</description>
              {MAINTAINER}
              <license>BSD-3-Clause</license>

              <buildtool_depend>ament_cmake</buildtool_depend>

              <exec_depend>joint_state_publisher</exec_depend>
              <exec_depend>robot_state_publisher</exec_depend>
              <exec_depend>rviz2</exec_depend>
              <exec_depend>xacro</exec_depend>

              <export>
                <build_type>ament_cmake</build_type>
              </export>
            </package>
            """),
        "CMakeLists.txt": _text("""
            cmake_minimum_required(VERSION 3.8)
            project(rover_description)

            find_package(ament_cmake REQUIRED)

            install(DIRECTORY launch meshes rviz urdf
              DESTINATION share/${PROJECT_NAME})

            ament_package()
            """),
        "urdf/rover.urdf.xacro": _text("""
            <?xml version="1.0"?>
            <robot name="rover" xmlns:xacro="http://www.ros.org/wiki/xacro">
              <xacro:property name="wheel_radius" value="0.08"/>

              <link name="base_link">
                <visual>
                  <geometry>
                    <mesh filename="package://rover_description/meshes/visual/base.stl"/>
                  </geometry>
                </visual>
                <collision>
                  <geometry>
                    <mesh filename="package://rover_description/meshes/collision/base.stl"/>
                  </geometry>
                </collision>
              </link>

              <xacro:macro name="wheel" params="side y">
                <link name="${side}_wheel">
                  <visual>
                    <geometry>
                      <mesh filename="package://rover_description/meshes/visual/wheel.stl"/>
                    </geometry>
                  </visual>
                </link>
                <joint name="${side}_wheel_joint" type="continuous">
                  <parent link="base_link"/>
                  <child link="${side}_wheel"/>
                  <origin xyz="0 ${y} ${wheel_radius}"/>
                  <axis xyz="0 1 0"/>
                </joint>
              </xacro:macro>

              <xacro:wheel side="left" y="0.2"/>
              <xacro:wheel side="right" y="-0.2"/>
            </robot>
            """),
        # Over the 1 MiB the update reads of a file that is not the template's.
        "meshes/visual/base.stl": binary_stl(21000),
        "meshes/visual/wheel.stl": binary_stl(300, seed=7),
        "launch/display.launch.py": _text("""
            import os

            from ament_index_python.packages import get_package_share_directory
            from launch import LaunchDescription
            from launch_ros.actions import Node
            import xacro


            def generate_launch_description():
                share = get_package_share_directory('rover_description')
                robot = xacro.process_file(os.path.join(share, 'urdf', 'rover.urdf.xacro')).toxml()
                return LaunchDescription([
                    Node(package='robot_state_publisher', executable='robot_state_publisher',
                         parameters=[{'robot_description': robot}]),
                    Node(package='joint_state_publisher', executable='joint_state_publisher'),
                    Node(package='rviz2', executable='rviz2',
                         arguments=['-d', os.path.join(share, 'rviz', 'rover.rviz')]),
                ])
            """),
        # Saved by RViz on Windows.
        "rviz/rover.rviz": _text("""
            Panels:
              - Class: rviz_common/Displays
                Name: Displays
            Visualization Manager:
              Displays:
                - Class: rviz_default_plugins/RobotModel
                  Description Topic:
                    Value: /robot_description
                  Enabled: true
                  Name: RobotModel
              Global Options:
                Fixed Frame: base_link
            """).replace("\n", "\r\n"),
        "doc/rover.png": png(64, 48),
        "README.md": ("# rover_description\n\n![The rover](doc/rover.png)\n\n"
                      "`ros2 launch rover_description display.launch.py`\n"),
    },
    node={"node_name": "wheel_odometry", "node_language": "python",
          "node_subscribers": "joint_states:sensor_msgs/msg/JointState",
          "node_publishers": "odom:nav_msgs/msg/Odometry", "node_timers": "0.1"},
    grown={"name": "wheel_odometry", "language": "python", "subscribers": ["joint_states:sensor_msgs/msg/JointState"],
           "publishers": ["odom:nav_msgs/msg/Odometry"], "timers": ["0.1"],
           "parameters": ["wheel_radius:double=0.08", "wheel_separation:double=0.4"]},
    # The collision mesh is the visual one (a link, as in many description packages).
    links={"meshes/collision": "visual"},
)

PACKAGES = {package.name: package for package in
            (CAMERA_PIPELINE, DEMO_TOOLS, ROSPY_TOOLS, ROSCPP_BRINGUP, ROVER_DESCRIPTION)}


def write(name: str, folder: Path) -> Path:
    """Write the package `name` into `folder` (created); returns `folder`."""
    package = PACKAGES[name]
    for path, content in package.files.items():
        target = folder / path
        target.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, bytes):
            target.write_bytes(content)
        else:
            target.write_bytes(content.encode())
    for path in package.executables:
        (folder / path).chmod(0o755)
    for link, target in package.links.items():
        os.symlink(target, folder / link)
    return folder


def snapshot(folder: Path) -> dict[str, files.Content]:
    """Every file of a package as it is (links as links, never followed), `.git` left out."""
    found = {}
    for current, folders, names in os.walk(folder):
        folders[:] = [name for name in folders if name != ".git"]
        for name in names + [name for name in folders if Path(current, name).is_symlink()]:
            relative = str(Path(current, name).relative_to(folder))
            found[relative] = files.read(folder, relative, owned=True)
    return found


BLOCK_BEGIN, BLOCK_END = "BEGIN rna-template", "END rna-template"


def _in_blocks(lines: list[str]) -> set[int]:
    """The indexes of the lines inside managed blocks, their markers included, and of a blank
    line beside a block (a block is a paragraph of its file: the blank line a new one brings
    is taken for the one before it or after it alike)."""
    inside, depth = set(), 0
    for index, line in enumerate(lines):
        if BLOCK_BEGIN in line:
            depth += 1
            if index and not lines[index - 1].strip():
                inside.add(index - 1)
        if depth:
            inside.add(index)
        if BLOCK_END in line:
            depth = max(0, depth - 1)
            if not depth and index + 1 < len(lines) and not lines[index + 1].strip():
                inside.add(index + 1)
    return inside


def _words_appended(old: str, new: str) -> bool:
    """Whether `new` is `old` with only words and spaces put in (a component added to a call)."""
    matcher = difflib.SequenceMatcher(None, old, new, autojunk=False)
    return all(tag == "equal" or (tag == "insert" and re.fullmatch(r"[\w\s]+", new[j1:j2]))
               for tag, _, _, j1, j2 in matcher.get_opcodes())


def changes_outside_blocks(before: dict[str, files.Content], after: dict[str, files.Content]) -> list[str]:
    """What changed in the files of `before` other than lines added inside managed blocks (and
    words added to a line, as a component to find_package): every other line must be there
    byte for byte (its line end included), every binary file and link unchanged."""
    problems = []
    for path, was in before.items():
        now = after.get(path)
        if now is None:
            problems.append(f"{path}: gone")
        elif (now.kind, now.data) == (was.kind, was.data):
            continue
        elif was.kind != "text" or now.kind != "text":
            problems.append(f"{path}: a {was.kind} file, changed into {now.kind} ({was.size} -> {now.size} bytes)")
        else:
            old_lines = was.data.splitlines(keepends=True)
            new_lines = now.data.splitlines(keepends=True)
            managed = _in_blocks(now.data.decode("latin-1").splitlines())
            matcher = difflib.SequenceMatcher(None, old_lines, new_lines, autojunk=False)
            for tag, i1, i2, j1, j2 in matcher.get_opcodes():
                if tag == "equal" or (tag == "insert" and set(range(j1, j2)) <= managed):
                    continue
                if tag == "replace" and _words_appended(b"".join(old_lines[i1:i2]).decode("latin-1"),
                                                        b"".join(new_lines[j1:j2]).decode("latin-1")):
                    continue
                problems.append(f"{path}: lines {i1 + 1}-{i2} {tag}d outside the managed blocks: "
                                f"{old_lines[i1:i2]!r} -> {new_lines[j1:j2]!r}")
    return problems


# ─── A user's steps ───────────────────────────────────────────────────────────


def add_node(template: Path, folder: Path, answers: dict) -> subprocess.CompletedProcess:
    """`copier copy` of one node into the package, as a user types it (the copier command line)."""
    data = [f"--data={key}={value}" for key, value in {"copyright_year": 2026, **answers}.items()]
    return subprocess.run([sys.executable, "-m", "copier", "copy", "--trust", "--defaults", "--vcs-ref=HEAD", *data,
                           str(template), str(folder)], cwd=folder, env=subprocess_env(), capture_output=True,
                          text=True, stdin=subprocess.DEVNULL, timeout=300)


def grown(template: Path, folder: Path, name: str) -> tuple[dict[str, files.Content], UpdateResult]:
    """The package `name` written and committed, its node added and committed, then grown by
    `copier update`: (its files before the node came, the update's result). AssertionError when
    adding the node fails or changes a byte of the package outside the blocks."""
    package = PACKAGES[name]
    write(name, folder)
    git("init", "-q", "-b", "main", cwd=folder)
    commit_all(folder, name)
    original = snapshot(folder)
    added = add_node(template, folder, package.node)
    if added.returncode != 0:
        raise AssertionError(f"adding the node to {name} failed:\n{added.stdout}{added.stderr}")
    problems = changes_outside_blocks(original, snapshot(folder))
    if problems:
        raise AssertionError(f"adding the node changed {name}:\n" + "\n".join(problems))
    commit_all(folder, "the node, added")
    answers_file = f".copier-answers.rna-{package.node['node_name']}.yml"
    return original, run_update(folder, {"nodes": [package.grown]}, extra_args=("--answers-file", answers_file))
