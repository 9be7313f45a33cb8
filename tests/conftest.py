"""Fixtures shared by the tiers: a committed snapshot of the template, and a package maker.

Tiers (pytest -m):
  (no mark)  fast: extension functions, questions, generated files checked statically
  ros        ROS 2 Kilted and Jazzy from PyPI wheels: colcon builds, nodes run in separate processes
  ros1       ROS 1 from Debian packages: catkin builds, node pairs run against a master
  update     copier update flows and merge-safety scenarios (copier and git only)
  browser    the documentation site in headless Chromium from Debian's packages
  compat     the patches on and off, the newest Copier, copier-template-extensions, Jinja,
             questionary and prompt_toolkit, Python 3.12 and 3.13 (each in an environment of
             its own; tests/test_compat.py)

Outside CI a ROS or compat tier that cannot set itself up is skipped with the reason; with
CI=true it fails instead, so a green CI run always means every tier ran. Helpers live
in tests/support/; test modules import only from there.
"""

from __future__ import annotations

import functools
import os
import shutil
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, Phase, settings

sys.path.insert(0, str(Path(__file__).resolve().parent))

from support import ros1 as ros1_support  # noqa: E402
from support import ros2 as ros2_support  # noqa: E402
from support import scratch  # noqa: E402
from support.generation import ROOT, copy_template, generate, snapshot_template  # noqa: E402
from support.tiers import unavailable  # noqa: E402

sys.path.insert(0, str(ROOT / "extensions"))

# Set before pytest makes its base folder and pytest-xdist starts its workers, which
# inherit it (as do the pytest sessions tests start).
scratch.use_memory_for_scratch()


# Hypothesis (test_generative.py): the fast tier draws a few answer sets, the same ones on
# every run, and reports a failure as drawn (shrinking would re-render packages for
# minutes); CI draws more of them the same way; HYPOTHESIS_PROFILE=thorough draws many,
# different each run, and shrinks.
settings.register_profile(
    "fast", max_examples=15, deadline=None, derandomize=True, database=None, print_blob=True,
    phases=(Phase.explicit, Phase.reuse, Phase.generate),
    suppress_health_check=(HealthCheck.too_slow, HealthCheck.filter_too_much, HealthCheck.data_too_large),
)
settings.register_profile(
    "thorough", max_examples=500, deadline=None, print_blob=True,
    suppress_health_check=(HealthCheck.too_slow, HealthCheck.filter_too_much, HealthCheck.data_too_large),
)
# CI draws more sets than the fast tier, still the same ones on every run, within its budget.
settings.register_profile("ci", parent=settings.get_profile("fast"), max_examples=60)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI") == "true" else "fast"))


# Fixtures that build something large once: with pytest-xdist each worker would build its
# own, so the tests that use one are kept on one worker (`--dist loadgroup`, as .ci/run
# runs; other tests go wherever a worker is free). `workspaces` builds one per ROS 2
# distro: a distro's tests are a group, so two distros can build at once.
SHARED_BUILDS = ("workspaces", "catkin_ws", "example_packages", "colcon_tested", "catkin_tested",
                 "ported_examples")


def build_group(item) -> str | None:
    """The xdist group of a test that uses a shared build, or None."""
    used = [name for name in SHARED_BUILDS if name in getattr(item, "fixturenames", ())]
    if not used:
        return None
    group = f"{item.path.stem}:{used[0]}"
    if used[0] == "workspaces":
        params = getattr(getattr(item, "callspec", None), "params", {})
        group += f":{params.get('workspace', ros2_support.DEFAULT_DISTRO)}"
    return group


@pytest.hookimpl(tryfirst=True)  # pytest-xdist reads the marks in its own hook
def pytest_collection_modifyitems(config, items):
    for item in items:
        group = build_group(item)
        if group is not None:
            item.add_marker(pytest.mark.xdist_group(group))


def pytest_configure(config):
    config.addinivalue_line("markers", "ros: builds and runs generated ROS 2 packages (PyPI wheels)")
    config.addinivalue_line("markers", "ros1: builds and runs generated ROS 1 packages (Debian)")
    config.addinivalue_line("markers", "update: copier update flows and merge-safety scenarios")
    config.addinivalue_line("markers", "browser: the documentation site in headless Chromium (Debian)")
    config.addinivalue_line("markers", "compat: patches on and off, the newest libraries, Python 3.12 and 3.13")


def pytest_sessionfinish(session, exitstatus):
    """A passing run's scratch files leave memory (pytest would keep them, as it keeps its last three runs')."""
    if exitstatus != 0 or hasattr(session.config, "workerinput"):
        return
    basetemp = session.config._tmp_path_factory.getbasetemp()  # the tmp_path_factory fixture's
    if basetemp.is_relative_to(scratch.folder_in_memory()):
        shutil.rmtree(basetemp, ignore_errors=True)


def pytest_terminal_summary(terminalreporter):
    """The merge-safety figure (tests/test_merge_safety.py records one tally per update)."""
    tallies = [value for reports in terminalreporter.stats.values() for report in reports
               if getattr(report, "when", None) == "call"
               for key, value in getattr(report, "user_properties", ()) if key == "merge_safety"]
    if tallies:
        terminalreporter.write_sep("-", "merge safety")
        terminalreporter.write_line(
            f"{len(tallies)} updates: {sum(t['lost'] for t in tallies)} user lines lost through copier update; "
            f"{sum(t['broken'] for t in tallies)} updates exited 0 with a package that does not parse or build")


@pytest.fixture(scope="session")
def template_dir(tmp_path_factory) -> Path:
    """The template as it is in this working tree, committed in a private repo."""
    return snapshot_template(tmp_path_factory.mktemp("template"))


@pytest.fixture(scope="session")
def template_folder(tmp_path_factory) -> Path:
    """The same template as a plain folder: Copier renders it in place instead of cloning a
    repository for every package (for tests of the generated files, not of versions)."""
    return copy_template(tmp_path_factory.mktemp("plain_template"))


@pytest.fixture
def make_package(template_folder, tmp_path):
    """Generate a package from answers; returns the destination folder.

    `name` names the destination folder, for the answers whose defaults come from it.
    """
    made = []

    def make(answers: dict | None = None, name: str | None = None) -> Path:
        destination = tmp_path / (name or f"project{len(made)}")
        generate(template_folder, destination, answers)
        made.append(destination)
        return destination

    return make


@functools.cache
def _ros2_environment(distro: str) -> ros2_support.Ros2Environment | Exception:
    """Each distro's environment set up once per run; a failure too, not retried by every test."""
    try:
        return ros2_support.ensure_environment(distro)
    except Exception as error:  # noqa: BLE001 - any failure means the tier cannot run
        return error


@pytest.fixture(scope="session")
def ros2_of():
    """ROS 2 of a distro with wheels (tests/support/ros2.py DISTROS), set up on first use."""
    def of(distro: str) -> ros2_support.Ros2Environment:
        environment = _ros2_environment(distro)
        if isinstance(environment, Exception):
            unavailable(f"ROS 2 {distro.capitalize()} from PyPI wheels could not be set up: {environment}")
        return environment
    return of


@pytest.fixture(scope="session")
def ros2(ros2_of):
    """ROS 2 Kilted from PyPI wheels: the ros tier, and the linters the ros1 tier borrows."""
    return ros2_of(ros2_support.DEFAULT_DISTRO)


@pytest.fixture(scope="session")
def ros1():
    """ROS 1 Noetic from Debian's packages (installed when running as root), set up once."""
    try:
        return ros1_support.ensure_environment(install=os.geteuid() == 0)
    except ros1_support.Ros1Unavailable as error:
        unavailable(f"ROS 1 from Debian's packages is not available: {error}")
