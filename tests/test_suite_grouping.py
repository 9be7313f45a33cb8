"""Tests that share a large build run on one pytest-xdist worker, so it is built once.

tests/conftest.py marks them with an xdist group; `--dist loadgroup` (the README's and
.ci/run's command) must honour the marks. Both broke silently before: the marks came after
pytest-xdist had read them, and pytest 9.2 ignores how pytest-xdist 3.8 records a group.
"""

from __future__ import annotations

import re
import subprocess
import sys
import textwrap
from pathlib import Path
from types import SimpleNamespace

import conftest

PROBE = textwrap.dedent("""
    import importlib.util, os
    import pytest

    spec = importlib.util.spec_from_file_location("suite_conftest", {conftest!r})
    suite = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(suite)
    pytest_collection_modifyitems = suite.pytest_collection_modifyitems


    @pytest.fixture(scope="session")
    def catkin_ws():
        return os.getpid()


    @pytest.mark.parametrize("index", range(4))
    def test_shared(catkin_ws, index, tmp_path_factory):
        (tmp_path_factory.getbasetemp().parent / f"pid-{{index}}").write_text(str(catkin_ws))


    @pytest.mark.parametrize("index", range(4))
    def test_alone(index):
        pass
""")


def test_the_tests_of_a_shared_build_run_on_one_worker(tmp_path):
    (tmp_path / "probe").mkdir()
    (tmp_path / "probe" / "conftest.py").write_text(PROBE.format(conftest=conftest.__file__))
    (tmp_path / "probe" / "test_probe.py").write_text("from conftest import *  # noqa: F403\n")
    result = subprocess.run([sys.executable, "-m", "pytest", "-n", "2", "--dist", "loadgroup", "-v",
                             "-p", "no:cacheprovider", "--basetemp", str(tmp_path / "base"), "probe"],
                            cwd=tmp_path, capture_output=True, text=True, timeout=120, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    grouped = re.findall(r"PASSED probe/test_probe.py::test_shared\[\d\]@test_probe:catkin_ws", result.stdout)
    assert len(grouped) == 4, result.stdout
    pids = {path.read_text() for path in (tmp_path / "base").glob("pid-*")}
    assert len(pids) == 1 and len(list((tmp_path / "base").glob("pid-*"))) == 4


def test_each_distros_workspace_is_a_group_of_its_own():
    def item(fixtures, **params):
        return SimpleNamespace(fixturenames=fixtures, path=Path("tests/test_ros2.py"),
                               callspec=SimpleNamespace(params=params))

    assert conftest.build_group(item(["workspace", "workspaces"], workspace="jazzy")) == "test_ros2:workspaces:jazzy"
    assert conftest.build_group(item(["workspace", "workspaces"])) == "test_ros2:workspaces:kilted"
    assert conftest.build_group(item(["catkin_ws"])) == "test_ros2:catkin_ws"
    # the port's examples, built for ROS 1 and ported for ROS 2, once (tests/test_port_ros.py)
    assert conftest.build_group(item(["ros1", "ros2", "ported_examples"])) == "test_ros2:ported_examples"
    assert conftest.build_group(item(["tmp_path"])) is None
