"""Work the glue spares Copier (extensions/copier_glue.py), counted in a Copier process of its own.

Copier renders the answers file's name (`_answers_file`, a template here) for every file it
renders and for every read of `_copier_conf.answers_file` in a context hook: about ten
renders per file. Once the questions are answered the name cannot change, so the glue
renders it once per render of a package, however many files the package has.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from support.generation import FIXED_ANSWERS, copy_counted, snapshot_template

# How many times a Copier run really rendered the answers file's name.
COUNTING = """
    from copier._main import Worker
    counted = 0
    render_name = Worker.answers_relpath.fget
    def counting(self):
        global counted
        counted += 1
        return render_name(self)
    Worker.answers_relpath = property(counting)
"""


def package_answers(nodes: int) -> dict:
    return {**FIXED_ANSWERS, "package_name": "robot", "build_type": "ament_cmake",
            "nodes": [{"name": f"node_{number}", "language": "cpp", "publishers": ["status:std_msgs/msg/String"]}
                      for number in range(1, nodes + 1)]}


def renders_of_the_answers_file_name(template: Path, run: Path, nodes: int) -> tuple[int, int]:
    """(renders of the answers file's name, files written) in a copy of a package with `nodes` nodes."""
    run.mkdir()
    destination = run / "robot"
    renders = copy_counted(COUNTING, template, destination, package_answers(nodes))
    return renders, sum(1 for path in destination.rglob("*") if path.is_file())


@pytest.fixture(scope="module")
def template(tmp_path_factory) -> Path:
    return snapshot_template(tmp_path_factory.mktemp("template"))


def test_the_answers_file_name_is_rendered_once_per_package_not_per_file(template, tmp_path):
    small, small_files = renders_of_the_answers_file_name(template, tmp_path / "one", 1)
    large, large_files = renders_of_the_answers_file_name(template, tmp_path / "six", 6)
    assert large_files >= small_files + 15  # a config, a header, a source and a test per node
    assert large == small, f"{small} renders for {small_files} files, {large} for {large_files}"
