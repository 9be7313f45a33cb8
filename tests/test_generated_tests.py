"""The tests a generated package brings run and pass, and fail when a node lacks what its answers give it.

ros tier: `colcon test` and `colcon test-result --verbose` on generated ament_python and
ament_cmake packages built with BUILD_TESTING on: each Python node's unit test, and the
package's flake8 and pep257 tests. What has no wheel here is named in
docs/pages/reference/testing.md: ament_copyright (its test is left out), launch_testing (the
launch test is left out of pytest's collection, and ament_cmake's add_launch_test() is a
stand-in), ament_lint_auto (a stand-in: the tier runs the ament linters itself) and rclcpp
(the C++ nodes' gtests).
"""

from __future__ import annotations

import re
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest
from support import ros2 as ros2_support
from support.generation import example, generate

STAND_INS = Path(__file__).parent / "support" / "stand_ins"

# Every kind of Python node (lifecycle too) in an ament_python package, Python nodes of an
# ament_cmake package (ament_cmake_pytest), and parameters of every form.
PACKAGES = {
    "stoppable": example("every_python_node"),
    "robot_beacons": example("cmake_python_nodes"),
    "robot_services": example("services_and_actions"),
}
# The first of them again, its talker then made to publish on another topic than its
# answers say and to declare another default: its tests must fail.
MUTATED = "mutated_robot"

# No wheels: ament_copyright's test, and launch tests (launch_testing's pytest plugin).
PYTEST_ARGS = ("--ignore-glob=*/test_copyright.py", "--ignore-glob=*_launch.py")

SUMMARY = re.compile(r"Summary: (\d+) tests, (\d+) errors, (\d+) failures, (\d+) skipped")


@dataclass
class Results:
    tests: int
    errors: int
    failures: int
    skipped: int
    output: str


def mutate(package: Path) -> None:
    """Break the talker's ROS interface the way a wrong edit of its base class would."""
    base = package / MUTATED / "talker_base.py"
    text = base.read_text()
    assert "'chatter'" in text and "'rate', 20.0" in text, text
    base.write_text(text.replace("'chatter'", "'chatter_elsewhere'").replace("'rate', 20.0", "'rate', 10.0"))


@pytest.fixture(scope="module")
def colcon_tested(ros2, template_dir, tmp_path_factory) -> dict[str, Results]:
    """The packages generated, built with their tests, tested; each package's results."""
    path = tmp_path_factory.mktemp("ros2_tested_ws")
    for name, answers in PACKAGES.items():
        generate(template_dir, path / "src" / name, answers)
    generate(template_dir, path / "src" / MUTATED, example("every_python_node", package_name=MUTATED))
    mutate(path / "src" / MUTATED / MUTATED)
    for stand_in in STAND_INS.iterdir():
        shutil.copytree(stand_in, path / "src" / stand_in.name)
    env = ros2.env(ros2_support.pick_domain_id())
    ros2.colcon_build(path, env, "--cmake-args", "-DBUILD_TESTING=ON")
    colcon = str(ros2.venv / "bin" / "colcon")
    tested = subprocess.run([colcon, "test", "--base-paths", "src", "--event-handlers", "console_cohesion+",
                             "desktop_notification-", "--pytest-args", *PYTEST_ARGS],
                            cwd=path, env=env, capture_output=True, text=True, timeout=900, check=False)
    results = {}
    for name in [*PACKAGES, MUTATED]:
        shown = subprocess.run([colcon, "test-result", "--verbose", "--test-result-base", f"build/{name}"],
                               cwd=path, env=env, capture_output=True, text=True, timeout=120, check=False)
        found = SUMMARY.search(shown.stdout)
        assert found, f"{name}: no summary\n{shown.stdout}{shown.stderr}\n{tested.stdout[-4000:]}"
        results[name] = Results(*map(int, found.groups()), shown.stdout + tested.stdout)
    return results


@pytest.mark.ros
@pytest.mark.parametrize("package", list(PACKAGES))
def test_generated_tests_pass_under_colcon_test(colcon_tested, package):
    results = colcon_tested[package]
    assert (results.errors, results.failures) == (0, 0), results.output[-6000:]
    # Each node's unit test ran (at least its name check), and the linters.
    nodes = PACKAGES[package]["nodes"]
    assert results.tests >= len(nodes) + (2 if PACKAGES[package].get("build_type") != "ament_cmake" else 0)
    assert results.skipped == 0, results.output[-6000:]


@pytest.mark.ros
def test_generated_tests_fail_when_a_node_lacks_its_endpoint(colcon_tested):
    results = colcon_tested[MUTATED]
    assert results.failures == 2, results.output[-6000:]
    assert "test_publishers" in results.output and "/chatter" in results.output
    assert "test_parameters" in results.output and "parameter rate" in results.output
