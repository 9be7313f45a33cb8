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

import subprocess
import sys

import pytest

if "support.template_repo" not in sys.modules:  # its asserts explain themselves too
    pytest.register_assert_rewrite("support.template_repo")
from support import real_packages  # noqa: E402
from support.generation import git, subprocess_env  # noqa: E402
from support.real_packages import PACKAGES, changes_outside_blocks, snapshot  # noqa: E402
from support.template_repo import commit_all, conflicted_files, run_update, summary_of  # noqa: E402

pytest_plugins = ("support.template_repo",)
pytestmark = pytest.mark.update


def add_node(template_dir, folder, answers: dict) -> subprocess.CompletedProcess:
    """`copier copy` of one node into the package, as a user types it."""
    data = [f"--data={key}={value}" for key, value in {"copyright_year": 2026, **answers}.items()]
    return subprocess.run([sys.executable, "-m", "copier", "copy", "--trust", "--defaults", "--vcs-ref=HEAD", *data,
                           str(template_dir), str(folder)], cwd=folder, env=subprocess_env(), capture_output=True,
                          text=True, stdin=subprocess.DEVNULL, timeout=300)


def grown_package(template_dir, folder, name: str):
    """The package `name` written, committed, its node added and committed, then grown by an update:
    (its files before the node, the update's result)."""
    package = PACKAGES[name]
    real_packages.write(name, folder)
    git("init", "-q", "-b", "main", cwd=folder)
    commit_all(folder, name)
    original = snapshot(folder)
    added = add_node(template_dir, folder, package.node)
    assert added.returncode == 0, added.stdout + added.stderr
    problems = changes_outside_blocks(original, snapshot(folder))
    assert not problems, "adding the node changed the package:\n" + "\n".join(problems)
    commit_all(folder, "the node, added")
    answers_file = f".copier-answers.rna-{package.node['node_name']}.yml"
    result = run_update(folder, {"nodes": [package.grown]}, extra_args=("--answers-file", answers_file))
    return original, result


@pytest.mark.parametrize("name", PACKAGES)
def test_a_node_added_to_a_real_package_and_grown_leaves_every_byte_of_it(template_dir, tmp_path, figure, name):
    folder = tmp_path / name
    original, result = grown_package(template_dir, folder, name)
    problems = changes_outside_blocks(original, snapshot(folder))
    figure(result, folder, lost=len(problems))
    assert result.returncode == 0, result
    assert not conflicted_files(folder), result
    assert not problems, "the update changed the package:\n" + "\n".join(problems)
    node = PACKAGES[name].grown["name"]
    assert any(node in path for path in summary_of(result.output).get("updated", [])), result
    assert result.stdout.rstrip().endswith("Done. Review with `git diff HEAD`, then commit."), result
