"""A new user's first steps: the README's demo command, then growing the demo with `copier update`.

The update-tier tests start where a user starts: a fresh `git clone` of this repository,
which has no tags (they do not travel with it). They run the README's first command as
written there, commit the demo as the after-copy message and
docs/pages/explanation/update-model.md say, and grow it. The fast tests check the pieces:
the recorded template path and the message.
"""

from __future__ import annotations

import hashlib
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

import rna.names
from copier_glue import absolute_source
from rna.update.resolve import answers_yaml
from support.generation import FIXED_ANSWERS, GIT_IDENTITY, ROOT, answers_of, copier_installed_by_pipx, git
from support.releases import versions

COPIER = str(Path(sys.executable).with_name("copier"))
NEW_NODE = {"name": "odometry", "subscribers": ["odom:nav_msgs/msg/Odometry"], "parameters": ["frame_id:string=odom"]}


def readme_commands() -> list[str]:
    """The commands of the README's first code block, the set-up commands."""
    block = re.search(r"```sh\n(.*?)```", (ROOT / "README.md").read_text(), re.DOTALL)
    return [line for line in block.group(1).splitlines() if line.strip()]


# ─── Fast: the pieces ─────────────────────────────────────────────────────────


def test_readme_starts_with_the_demo_and_the_test_suite_that_ci_runs():
    demo, suite = readme_commands()
    assert demo.split()[:4] == ["tests/env", "copier", "copy", "--trust"] and "~/rna_demo" in demo
    assert suite.split()[:2] == ["tests/env", "pytest"]
    (ci_command,) = [line for line in (ROOT / ".ci" / "run").read_text().splitlines() if line.startswith("exec ")]
    assert ci_command.split()[1:] == [*suite.split("#")[0].split(), '"$@"']


@pytest.mark.parametrize("source", ["gh:lab/rna-template", "gl:lab/rna-template", "https://example.com/lab/rna.git",
                                    "git@example.com:lab/rna.git", "git+ssh://example.com/rna", "~/src/rna-template",
                                    "/srv/rna-template"])
def test_remote_absolute_and_home_sources_are_recorded_as_given(source, tmp_path):
    answers = {"_commit": "v0.2.0", "_src_path": source, "nodes": []}
    assert absolute_source(answers, str(tmp_path)) == answers


@pytest.mark.parametrize("source", [".", "rna-template", "./rna-template/", "work/../rna-template"])
def test_a_relative_local_source_is_recorded_absolute(source, tmp_path):
    (tmp_path / "rna-template").mkdir()
    (tmp_path / "work").mkdir()
    cwd = tmp_path if source != "." else tmp_path / "rna-template"
    recorded = absolute_source({"_commit": "v0.2.0", "_src_path": source}, str(cwd))
    assert recorded == {"_commit": "v0.2.0", "_src_path": str(tmp_path / "rna-template")}


def test_a_relative_path_that_is_not_there_is_left_alone(tmp_path):
    assert absolute_source({"_src_path": "elsewhere"}, str(tmp_path)) == {"_src_path": "elsewhere"}


def copy_relative(template_dir: Path, destination: Path) -> subprocess.CompletedProcess:
    """`copier copy <template> <destination>` run from the template's parent, the template named relatively."""
    data = [f"--data={key}={value}" for key, value in FIXED_ANSWERS.items()]
    return subprocess.run([COPIER, "copy", "--trust", "--defaults", "--vcs-ref=HEAD", *data, template_dir.name,
                           str(destination)], cwd=template_dir.parent, capture_output=True, text=True,
                          stdin=subprocess.DEVNULL, timeout=120, env={**copier_installed_by_pipx(), "NO_COLOR": "1"})


def test_a_copy_from_a_relative_path_records_it_absolute_and_says_how_to_commit(template_dir, tmp_path):
    assert subprocess.run(["git", "-C", str(tmp_path), "rev-parse"], capture_output=True).returncode != 0
    result = copy_relative(template_dir, tmp_path / "demo")
    assert result.returncode == 0, result.stderr
    assert answers_of(tmp_path / "demo")["_src_path"] == str(template_dir)
    assert "  colcon build --packages-up-to demo\n" in result.stderr
    assert (f"  cd {tmp_path / 'demo'}\n  git init\n  git add -A .\n  git commit -m \"demo from rna-template\"\n"
            "  copier update --trust\n") in result.stderr
    assert "--packages-select" not in result.stderr
    # The README is in the destination, beside the ROS package.
    assert (f"The package demo is made, in\n  {tmp_path / 'demo'}\nREADME.md there lists what was made and where "
            "your code goes; the ROS\npackage is the demo folder beside it.\n") in result.stderr
    assert (tmp_path / "demo" / "README.md").is_file() and (tmp_path / "demo" / "demo" / "package.xml").is_file()


@pytest.mark.parametrize(("environ", "command"), [
    ({}, "copier"),  # pipx links the same Copier onto PATH
    ({"RNA_TEMPLATE_ENV": "/src/rna/tests/env", "VIRTUAL_ENV": "/src/rna/.venv"}, "/src/rna/tests/env copier"),
])
def test_the_commands_printed_run_copier_as_it_was_installed(tmp_path, environ, command):
    from rna.terminal import copier_command

    venv = tmp_path / "src" / "rna" / ".venv" if environ else tmp_path / "pipx" / "venvs" / "copier"
    (venv / "bin").mkdir(parents=True)
    (venv / "bin" / "copier").write_text("")
    (tmp_path / "bin").mkdir()
    (tmp_path / "bin" / "copier").symlink_to(venv / "bin" / "copier")
    environ = {key: value.replace("/src", str(tmp_path / "src")) for key, value in environ.items()}
    found = copier_command(environ, str(venv / "bin" / "python"), lambda name: str(tmp_path / "bin" / name))
    assert found == command.replace("/src", str(tmp_path / "src"))
    # A Copier run from an environment that is not on PATH is named by its path.
    elsewhere = tmp_path / "elsewhere" / "bin"
    elsewhere.mkdir(parents=True)
    (elsewhere / "copier").write_text("")
    assert copier_command({}, str(elsewhere / "python"), lambda name: str(tmp_path / "bin" / name)) == str(
        elsewhere / "copier")
    assert copier_command({}, str(elsewhere / "python"), lambda name: None) == str(elsewhere / "copier")


def test_the_message_keeps_to_80_columns_with_the_longest_names(template_dir, tmp_path):
    """Only a line that holds a path the user chose, or one command, may be longer."""
    destination = tmp_path / ("p" * rna.names.PACKAGE_NAME_MAX)
    result = copy_relative(template_dir, destination)
    assert result.returncode == 0, result.stderr
    message = result.stderr[result.stderr.index("The package "):].splitlines()
    assert len(message) >= 9
    long = [line for line in message if len(line) > 79 and str(tmp_path) not in line]
    assert not long, long


def test_inside_a_repository_the_message_only_says_commit(template_dir, tmp_path):
    workspace = tmp_path / "ws"
    workspace.mkdir()
    git("init", "-q", cwd=workspace)
    result = copy_relative(template_dir, workspace / "src" / "demo")
    assert result.returncode == 0, result.stderr
    assert '\n  git add -A .\n  git commit -m "demo from rna-template"\n' in result.stderr
    assert "git init" not in result.stderr


def test_the_settings_file_trusts_the_template_and_gives_defaults(template_dir, tmp_path):
    """docs/pages/how-to/trust-and-settings.md: a trusted template needs no --trust; `defaults` answer for the user."""
    settings = tmp_path / "settings.yml"
    settings.write_text(yaml.safe_dump({"trust": [str(template_dir)],
                                        "defaults": {"maintainer": "Grace Hopper", "license": "MIT"}}))
    result = subprocess.run([COPIER, "copy", "--defaults", "--vcs-ref=HEAD", "--data=copyright_year=2026",
                             str(template_dir), str(tmp_path / "demo")], capture_output=True, text=True,
                            stdin=subprocess.DEVNULL, timeout=120,
                            env={**os.environ, "COPIER_SETTINGS_PATH": str(settings), "NO_COLOR": "1"})
    assert result.returncode == 0, result.stderr
    answers = answers_of(tmp_path / "demo")
    assert (answers["maintainer"], answers["license"]) == ("Grace Hopper", "MIT")


# ─── Update tier: from a fresh clone, as the README says ──────────────────────


@pytest.fixture(scope="module")
def fresh_clone(tmp_path_factory) -> Path:
    """A `git clone` of this repository's committed HEAD: no tags, like every clone of it."""
    clone = tmp_path_factory.mktemp("clone") / "rna-template"
    subprocess.run(["git", "clone", "-q", "--no-tags", str(ROOT), str(clone)], check=True)
    git("fetch", "-q", "--no-tags", str(ROOT), "HEAD", cwd=clone)  # HEAD may be on no branch
    git("checkout", "-q", "--detach", "FETCH_HEAD", cwd=clone)
    assert git("tag", "-l", cwd=clone).stdout == ""
    return clone


def user_env(clone: Path, home: Path) -> dict[str, str]:
    """A user's environment: their own home (no Copier settings), a git identity, this test run's Python env."""
    env = {key: value for key, value in os.environ.items()
           if key not in ("XDG_CONFIG_HOME", "COPIER_SETTINGS_PATH", "RNA_TEMPLATE_VENV")}
    env.update(GIT_IDENTITY, HOME=str(home), NO_COLOR="1", GIT_CONFIG_NOSYSTEM="1")
    # tests/env would build the clone its own .venv; the one running this test has the same pins.
    stamp = Path(sys.prefix, ".requirements-sha256")
    wanted = hashlib.sha256((clone / "tests" / "requirements.txt").read_bytes()).hexdigest()
    if stamp.is_file() and stamp.read_text().strip() == wanted:
        env["RNA_TEMPLATE_VENV"] = sys.prefix
    return env


def shell(command: str | list[str], cwd: Path, env: dict[str, str]) -> subprocess.CompletedProcess:
    result = subprocess.run(command if isinstance(command, list) else ["bash", "-c", command], cwd=cwd, env=env,
                            stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, f"$ {command}\nexit {result.returncode}\n{result.stdout}{result.stderr}"
    return result


def commit_as_documented(project: Path, env: dict[str, str]) -> None:
    """What the after-copy message and docs/pages/explanation/update-model.md say for a folder not yet in git."""
    shell('git init && git add -A . && git commit -m "rna_demo from rna-template"', project, env)


@pytest.mark.update
def test_the_readme_demo_is_a_release_and_grows_with_copier_update(fresh_clone, tmp_path):
    home = tmp_path / "home"
    home.mkdir()
    env = user_env(fresh_clone, home)
    newest = versions(fresh_clone)[0]

    copied = shell(readme_commands()[0], fresh_clone, env)
    demo = home / "rna_demo"
    assert f"Copying from template version {newest}" in copied.stderr
    assert "No git tags found" not in copied.stderr
    assert answers_of(demo)["_commit"] == f"v{newest}"
    assert answers_of(demo)["_src_path"] == str(fresh_clone)
    assert f"v{newest}" in git("tag", "-l", cwd=fresh_clone).stdout.split()

    commit_as_documented(demo, env)
    nodes = yaml.safe_dump([*answers_of(demo)["nodes"], NEW_NODE], default_flow_style=True, width=10_000).strip()
    updated = shell([str(fresh_clone / "tests" / "env"), "copier", "update", "--trust", "--defaults",
                     "--data", f"nodes={nodes}"], demo, env)
    assert f"Keeping template version {newest}" in updated.stderr
    for path in ("rna_demo/odometry.py", "rna_demo/odometry_base.py", "config/odometry.yaml"):
        assert (demo / "rna_demo" / path).is_file(), f"{path} is missing after the update:\n{updated.stderr}"
    assert "odometry" in (demo / "rna_demo" / "launch" / "rna_demo.launch.xml").read_text()
    assert [node["name"] for node in answers_of(demo)["nodes"]] == ["talker", "listener", "odometry"]


@pytest.mark.update
def test_releases_are_selected_with_vcs_ref_in_a_fresh_clone(fresh_clone, tmp_path):
    home = tmp_path / "home"
    home.mkdir()
    env = user_env(fresh_clone, home)
    oldest, newest = versions(fresh_clone)[-1], versions(fresh_clone)[0]
    assert oldest != newest

    copied = shell(f'tests/env copier copy --trust --defaults --vcs-ref v{oldest} "$PWD" ~/rna_demo', fresh_clone,
                   env)
    demo = home / "rna_demo"
    assert f"Copying from template version {oldest}" in copied.stderr
    assert answers_of(demo)["_commit"] == f"v{oldest}"

    commit_as_documented(demo, env)
    updated = shell([str(fresh_clone / "tests" / "env"), "copier", "update", "--trust", "--defaults",
                     "--vcs-ref", f"v{newest}"], demo, env)
    assert f"Updating to template version {newest}" in updated.stderr
    assert answers_of(demo)["_commit"] == f"v{newest}"
    assert git("status", "--porcelain", cwd=demo).stdout.strip(), "the update changed nothing"


@pytest.mark.parametrize("text", ["plain", "café ✓", "a\x85b", "line\nbreak", "\u2028", "tab\there"])
def test_the_answers_file_reads_back_as_written(text):
    """PyYAML writes NEL raw in a quoted string and reads it back as a space: such answers get escapes."""
    answers = {"nodes": [{"name": "a", "parameters": [{"name": "g", "type": "string", "default": text}]}]}
    written = answers_yaml(answers)
    assert yaml.safe_load(written) == answers
    if text.isascii() or text == "café ✓":
        assert written == yaml.dump(answers, indent=4, allow_unicode=True, default_flow_style=False)
