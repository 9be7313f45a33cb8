"""A node added to packages shaped like real ones, then grown by `copier update`: nothing of theirs changes.

The packages (tests/support/real_packages.py) hold what real ones hold: C++ components
and executables, entry points and data files, rospy scripts without a setup.py, a
catkin_create_pkg CMakeLists.txt, meshes and images, a file in Latin-1, CRLF line ends, a
mesh over the update's reading limit, a link. After the node is added, and again after an
update grows it, every file of the package is there byte for byte, but for lines added
inside managed blocks (and components added to a catkin find_package() call); the tally
goes into the update tier's merge-safety figure. The ros and ros1 tiers build these
packages with the grown node and run it (test_ros2.py, test_ros1.py).
"""

from __future__ import annotations

import sys

import pytest

if "support.template_repo" not in sys.modules:  # its asserts explain themselves too
    pytest.register_assert_rewrite("support.template_repo")
from support import real_packages  # noqa: E402
from support.real_packages import PACKAGES, changes_outside_blocks, snapshot  # noqa: E402
from support.template_repo import conflicted_files, summary_of  # noqa: E402

pytest_plugins = ("support.template_repo",)
pytestmark = pytest.mark.update


@pytest.mark.parametrize("name", PACKAGES)
def test_a_node_added_to_a_real_package_and_grown_leaves_every_byte_of_it(template_dir, tmp_path, figure, name):
    folder = tmp_path / name
    original, result = real_packages.grown(template_dir, folder, name)
    problems = changes_outside_blocks(original, snapshot(folder))
    figure(result, folder, lost=len(problems))
    assert result.returncode == 0, result
    assert not conflicted_files(folder), result
    assert not problems, "the update changed the package:\n" + "\n".join(problems)
    node = PACKAGES[name].grown["name"]
    assert any(node in path for path in summary_of(result.output).get("updated", [])), result
    assert result.stdout.rstrip().endswith("Done. Review with `git diff HEAD`, then commit."), result
