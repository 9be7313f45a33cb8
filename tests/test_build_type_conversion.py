"""ros tier: a package whose build type `copier update` switches (ament_python <-> ament_cmake) builds.

The user's package has their code in a node, a module of their own the node imports, a
tuned value and a line of their own in the build file. The update converts the package,
keeps the old build file (edited, so named in the summary, exit 1: its lines are the
user's to port) and the converted package builds with colcon from the Kilted wheels, the
user's node and module installed.
"""

from __future__ import annotations

import sys

import pytest

if "support.template_repo" not in sys.modules:  # its asserts explain themselves too
    pytest.register_assert_rewrite("support.template_repo")
from support import ros2 as ros2_support  # noqa: E402
from support.template_repo import (  # noqa: E402
    append_after, commit_all, generate_project, kept_of, missing_block, replace_text, run_update, write_new_file,
)

pytestmark = pytest.mark.ros

NODES = [{"name": "driver", "language": "python", "publishers": ["cmd:std_msgs/msg/String"],
          "subscribers": ["chatter:std_msgs/msg/String"], "parameters": ["gain:double=1.0"]},
         {"name": "monitor", "language": "python", "subscribers": ["cmd:std_msgs/msg/String"]}]

# (build type before, after, the old build file, an anchor in it, the user's line)
CONVERSIONS = {
    "ament_python-to-ament_cmake": ("ament_python", "ament_cmake", "setup.py",
                                    "# END rna-template: add your own executables below",
                                    "            'calibrate = robot.helpers:main',"),
    "ament_cmake-to-ament_python": ("ament_cmake", "ament_python", "CMakeLists.txt",
                                    "# END rna-template: add your own find_package() calls below",
                                    "# mine: the calibration tools come later"),
}


@pytest.mark.parametrize("case", CONVERSIONS)
def test_a_package_converted_between_build_types_keeps_the_users_code_and_builds(ros2, template_dir, tmp_path, case):
    before, after, build_file, anchor, line = CONVERSIONS[case]
    workspace = tmp_path / "ws"
    project = generate_project(template_dir, workspace / "src" / "robot_project",
                               {"package_name": "robot", "build_type": before, "nodes": NODES})
    package = project / "robot"
    lines = [
        ("robot/robot/driver.py", append_after(package / "robot" / "driver.py", "self.count += 1",
                                               "        self.last = clamp(len(msg.data))  # mine", occurrence=0)),
        ("robot/robot/driver.py", append_after(package / "robot" / "driver.py", "from robot.driver_base import",
                                               "from robot.helpers import clamp", occurrence=0)),
        ("robot/robot/helpers.py", write_new_file(package / "robot" / "helpers.py",
                                                  '"""Helpers (mine)."""\n\n\ndef clamp(value):\n'
                                                  '    return min(value, 10)\n\n\ndef main():\n    print(clamp(3))\n')),
        ("robot/config/driver.yaml", replace_text(package / "config" / "driver.yaml", "gain: 1.0", "gain: 1.8")),
        (f"robot/{build_file}", append_after(package / build_file, anchor, line)),
    ]
    commit_all(project, "my code")

    result = run_update(project, {"build_type": after, "nodes": NODES}, vcs_ref="HEAD")

    assert result.returncode == 1, f"the old build file is the user's to port: the update must say so\n{result}"
    assert f"robot/{build_file}" in kept_of(result.output), result
    for path, written in lines:
        assert missing_block(project / path, written) is None, f"{path}\n{result}"
    env = ros2.env(ros2_support.pick_domain_id())
    ros2.colcon_build(workspace, env, "--cmake-args", "-DBUILD_TESTING=OFF")
    install = workspace / "install" / "robot"
    assert (install / "lib" / "robot" / "driver").exists(), sorted(str(p) for p in install.rglob("*"))
    assert list(install.rglob("helpers.py")), "the user's module is not installed"
    assert (install / "share" / "robot" / "config" / "driver.yaml").read_text().count("gain: 1.8") == 1
