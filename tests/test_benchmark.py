"""tests/tools/benchmark.py runs end to end in its quickest mode (no timing is asserted)."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

TOOLS = Path(__file__).resolve().parent / "tools"


def test_a_case_named_alone_brings_the_case_it_is_compared_with():
    # Imported here, not at collection: it imports support.template_repo, which the
    # update tests load as a pytest plugin first (so that pytest rewrites its asserts).
    sys.path.insert(0, str(TOOLS))
    import benchmark

    assert benchmark.selected(["nodes_50"]) == {"nodes_50", "nodes_1"}
    assert benchmark.selected(["update_20_catkin"]) == {"update_20_catkin", "copy_20_catkin"}
    assert benchmark.selected(["default"]) == {"default", "default_cold", "floor", "floor_in_repository"}
    assert benchmark.selected(None) == {name for names in benchmark.CASE_GROUPS.values() for name in names}


@pytest.mark.skipif(shutil.which("valgrind") is None, reason="valgrind is not installed")
def test_instructions_are_counted_in_every_process_of_the_tree(tmp_path):
    sys.path.insert(0, str(TOOLS))
    import benchmark

    alone = benchmark.count_instructions(["/bin/true"], tmp_path, {}, tmp_path / "one")
    with_child = benchmark.count_instructions(["/bin/sh", "-c", "/bin/true; /bin/true"], tmp_path, {},
                                              tmp_path / "tree")
    assert alone > 0
    assert with_child > 2 * alone  # the shell's own and both children's
    assert list(tmp_path.iterdir()) == []  # callgrind's files are gone


def test_quick_mode_measures_the_default_package_against_the_floor(tmp_path):
    output = tmp_path / "figures.json"
    result = subprocess.run([sys.executable, str(TOOLS / "benchmark.py"), "--quick", "--json", str(output)],
                            capture_output=True, text=True, timeout=120, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    figures = json.loads(output.read_text())
    assert set(figures["cases"]) == {"floor", "floor_in_repository", "default", "default_cold"}
    for case in figures["cases"].values():
        (sample,) = case["samples"]
        assert sample["wall"] > 0 and sample["cpu"] > 0
    row, cold, checkout, own = figures["comparisons"]
    assert (row["case"], row["reference"], row["goal"]) == ("default", "floor", 1.15)
    assert (cold["case"], cold["reference"], cold["goal"]) == ("default_cold", "floor", None)
    assert (checkout["case"], checkout["reference"]) == ("floor_in_repository", "floor")
    assert (own["case"], own["reference"]) == ("default", "floor_in_repository")
    assert row["met"] is (row["ratio"] <= 1.15)
    assert "default package / one-file template (floor)" in result.stdout


def test_a_staged_copy_stops_where_its_stage_ends(template_dir, tmp_path):
    """instruction_stages.py's copy: stopped before the questions, a bad answer goes unseen;
    stopped after them, it was refused there; either way nothing was written."""
    sys.path.insert(0, str(TOOLS))
    import instruction_stages

    def staged_copy(stage: str, answers: dict) -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, "-c", instruction_stages.STAGED_COPY, stage, str(template_dir),
                               str(tmp_path / stage), json.dumps({"copyright_year": 2026, **answers})],
                              capture_output=True, text=True, timeout=120, check=False)

    assert staged_copy("environment", {"ros_distro": "foxy"}).returncode == 0
    asked = staged_copy("questions", {"ros_distro": "foxy"})
    assert asked.returncode != 0 and "invalid answer to 'ros_distro'" in asked.stderr, asked.stderr[-2000:]
    assert staged_copy("questions", {"ros_distro": "jazzy"}).returncode == 0
    assert list(tmp_path.iterdir()) == []


def test_each_speed_up_is_counted_off_alone_against_all_on(monkeypatch):
    """tests/tools/speedup_savings.py: the bookkeeping of its counts, callgrind left out."""
    sys.path.insert(0, str(TOOLS))
    import benchmark
    import speedup_savings

    cases = [benchmark.Case(name, "scale", name, lambda folder: ([], folder), "x") for name in ("default", "nodes_50")]
    extra = {"": 0, "strings": 5_000_000, "all": 90_000_000}

    def counted(run, bench, folder):
        return 1_000_000_000 + extra[run.env[speedup_savings.patches.SWITCH]]

    monkeypatch.setattr(speedup_savings, "_count_one", counted)
    counts = speedup_savings.count(None, cases, ("", "strings", "all"))
    assert counts == {setting: {"default": 1_000_000_000 + more, "nodes_50": 1_000_000_000 + more}
                      for setting, more in extra.items()}
    table = speedup_savings.table(counts, ("default", "nodes_50"))
    assert "| strings             |" in table and "+5 M ( +0.5%)" in table and "+90 M ( +9.0%)" in table
