"""A lab's fork: it customises only extensions/lab.yml and takes upstream releases with plain git.

The fixture is what a lab does: clone the template, write its choices into
extensions/lab.yml, make packages; upstream then releases a new version with a new
question, a changed default, a changed template file and a migration; the fork pulls it
(no conflict), its own generation and update tests pass, and a package made from the fork
before the release updates across it.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from support.generation import ROOT, answers_of, git, subprocess_env

if "support.template_repo" not in sys.modules:  # its asserts explain themselves too
    pytest.register_assert_rewrite("support.template_repo")
from support.template_repo import commit_all, run_update  # noqa: E402

pytestmark = pytest.mark.update

LAB = {
    "maintainer": "Grace Hopper",
    "maintainer_email": "grace@lab.example.org",
    "copyright_holder": "The Robotics Lab",
    "license": "BSD-3-Clause",
    "ros_distro": "humble",
    "dependencies": {"exec_depend": ["lab_bringup"]},
    "header": "Part of the Robotics Lab's robot software.\n",
    "files": {"CODEOWNERS": "* @robotics-lab/maintainers\n"},
    "docs_url": "https://robotics-lab.github.io/rna-template/",
}


def working_tree(destination: Path) -> Path:
    """This repository's files as they are now (tracked and new, not ignored), in a new repository."""
    listed = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=ROOT, check=True,
                            capture_output=True, text=True).stdout.split("\0")
    for name in filter(None, listed):
        source = ROOT / name
        if source.is_file():
            (destination / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, destination / name)
    git("init", "-q", "-b", "main", cwd=destination)
    commit_all(destination, "upstream 1.0.0")
    git("tag", "v1.0.0", cwd=destination)
    return destination


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, f"{old!r} not in {path}"
    path.write_text(text.replace(old, new, 1))


def release_upstream(upstream: Path) -> None:
    """Upstream 1.1.0: a new question, a changed default, a changed template file, a migration."""
    copier_yml = upstream / "copier.yml"
    edit(copier_yml, "# ─── Last words", "team:\n  type: str\n  help: Your team (README)\n  default: \"\"\n\n"
                                        "# ─── Last words")
    edit(copier_yml, "lab().ros_distro or 'jazzy'", "lab().ros_distro or 'kilted'")
    edit(copier_yml, "_migrations:\n", "_migrations:\n"
         "  - version: v1.1.0\n"
         "    command: [\"{{ _copier_python }}\", \"-c\", \"open('MIGRATED-1.1.0', 'w').close()\"]\n"
         "    when: \"{{ _stage == 'after' }}\"\n")
    readme = upstream / "template" / "README.md.jinja"
    readme.write_text(readme.read_text() + "\n{% if team %}Made by {{ team }}.{% endif %}\n")
    commit_all(upstream, "upstream 1.1.0")
    git("tag", "v1.1.0", cwd=upstream)


@pytest.fixture(scope="module")
def upstream(tmp_path_factory) -> Path:
    upstream = working_tree(tmp_path_factory.mktemp("upstream"))
    lab_file = upstream / "extensions" / "lab.yml"
    assert yaml.safe_load(lab_file.read_text()) is None, "upstream ships extensions/lab.yml with comments only"
    return upstream


@pytest.fixture(scope="module")
def fork(upstream, tmp_path_factory) -> Path:
    fork = tmp_path_factory.mktemp("fork") / "rna-template"
    git("clone", "-q", str(upstream), str(fork), cwd=fork.parent)
    (fork / "extensions" / "lab.yml").write_text(yaml.safe_dump(LAB, sort_keys=False))
    commit_all(fork, "our lab's choices")
    return fork


def copy_from(template: Path, destination: Path, **answers) -> Path:
    import copier

    copier.run_copy(str(template), str(destination), data={"copyright_year": 2026, **answers}, defaults=True,
                    unsafe=True, quiet=True, vcs_ref="HEAD")
    return destination


def test_the_fork_takes_an_upstream_release_without_conflict_and_keeps_its_choices(upstream, fork, tmp_path):
    # A package made from the fork before upstream's release, then edited by its user.
    package = copy_from(fork, tmp_path / "arm_driver",
                        nodes=[{"name": "arm", "publishers": ["joints:sensor_msgs/msg/JointState"], "timers": [0.1]}])
    git("init", "-q", "-b", "main", cwd=package)
    readme = package / "README.md"
    title, rest = readme.read_text().split("\n", 1)
    readme.write_text(f"{title}\n\nOur notes on the arm.\n{rest}")
    commit_all(package, "generated, then our notes")
    answers = answers_of(package)
    assert (answers["license"], answers["ros_distro"], answers["maintainer"]) == ("BSD-3-Clause", "humble",
                                                                                   "Grace Hopper")

    release_upstream(upstream)
    git("remote", "add", "upstream", str(upstream), cwd=fork)
    git("fetch", "-q", "--tags", "upstream", cwd=fork)
    pulled = git("merge", "--no-edit", "upstream/main", cwd=fork, check=False)
    assert pulled.returncode == 0, pulled.stdout + pulled.stderr  # plain git, no conflict
    assert yaml.safe_load((fork / "extensions" / "lab.yml").read_text()) == LAB

    # A new package from the fork: upstream's new question and file change, the lab's choices.
    fresh = copy_from(fork, tmp_path / "gripper", team="Manipulation")
    assert answers_of(fresh)["ros_distro"] == "humble"  # the lab's default beats upstream's new one
    assert "Made by Manipulation." in (fresh / "README.md").read_text()
    assert (fresh / "gripper" / "CODEOWNERS").read_text() == LAB["files"]["CODEOWNERS"]
    assert "lab_bringup" in (fresh / "gripper" / "package.xml").read_text()

    # The package made before the release updates across it: migration run, notes kept.
    result = run_update(package, vcs_ref="HEAD")
    assert result.returncode == 0, str(result)
    assert (package / "MIGRATED-1.1.0").exists()
    assert "Our notes on the arm." in readme.read_text()
    assert answers_of(package)["license"] == "BSD-3-Clause"
    user_file = package / "arm_driver" / "arm_driver" / "arm.py"
    assert "# Part of the Robotics Lab's robot software." in user_file.read_text()


def test_the_forks_own_generation_and_update_tests_pass(fork):
    """The fork runs the template's tests on its own template (its lab.yml included)."""
    env = {**os.environ, **subprocess_env(), "PYTHONDONTWRITEBYTECODE": "1"}
    result = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-x",
         "tests/test_examples.py", "tests/test_lab.py", "tests/test_update.py::test_add_nodes"],
        cwd=fork, env=env, capture_output=True, text=True, timeout=1200, check=False)
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-2000:]
