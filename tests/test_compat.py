"""The compat tier: the patches (extensions/patches/) never change what users get, with the
pinned libraries, with the newest releases of the libraries they patch, and under the
Pythons users run Copier with (Ubuntu 24.04's 3.12, Debian 13's 3.13).

- Every example answers file renders byte for byte the same with the patches on (a first
  run, then a run that finds the compiled code kept) and off (RNA_TEMPLATE_PATCHES_OFF=all),
  and six updates of this file's, exit codes and messages included; so does every update of
  a sample of the update tier's tests (each test, every change of its core scenario), each
  run off and then on in the project's own folder, before the test checks what it checks.
- Python 3.12 and 3.13 (tests/support/compat.py finds or installs them, each in an
  environment of the pins) run the whole fast tier, and render every example byte for
  byte as 3.11 does, sharing one code cache folder with it (each Python keeps its own code).
- The newest Copier, copier-template-extensions, Jinja, questionary and prompt_toolkit the
  registries offer run the whole fast tier, this file's on/off comparisons and a sample of
  the update tier (each update compared off and on too), with every patch on: a release
  that changes what a patch relies on fails here (its guard turned it off, or the output or
  the screen differs), before a user meets it.

Outside CI a part that cannot set itself up is skipped with the reason; in CI it fails.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from support import compat
from support.generation import FIXED_ANSWERS, ROOT, differences, example, examples, subprocess_env, tree
from support.template_repo import (
    COMPARE_PATCHES, RELEASES, Flavor, commit_all, find_node, generate_project, git, release_history_repo,
    replace_text,
)
from support.tiers import unavailable

# One worker runs the tier, one part after the other: each part runs a test session or renders
# every example in a process of its own, and the suite's other worker goes on with the rest.
pytestmark = [pytest.mark.compat, pytest.mark.xdist_group("compat")]

OFF = {"RNA_TEMPLATE_PATCHES_OFF": "all"}
EXTENSIONS = ROOT / "extensions"

# What the newest libraries run besides the whole fast tier (the patches' own tests among it, and
# a newcomer's replay at a terminal): the update tier's flows that exercise an update's every
# step (scratch renders kept, a release's glue beside this one's, renames, removals), and this
# file's on/off comparisons.
UPDATE_SAMPLE = ["tests/test_update.py::test_add_nodes", "tests/test_update.py::test_remove_nodes",
                 "tests/test_update.py::test_an_update_ends_with_a_summary_instead_of_internal_command_lines",
                 "tests/test_merge_safety.py::test_a_renamed_node_carries_the_users_file_values_launch_entry_and_build_lines",
                 "tests/test_merge_safety.py::test_a_rename_naming_no_node_of_the_package_is_refused"]
COMPARISONS = ["tests/test_compat.py::test_every_example_renders_byte_identical_with_the_patches_on_and_off",
               "tests/test_compat.py::test_an_update_does_and_says_the_same_with_the_patches_on_and_off"]


# ─── Rendering every example in a process of its own ──────────────────────────

RENDER_EXAMPLES = """
import json, sys
from pathlib import Path
import copier
template, out, answers = sys.argv[1], Path(sys.argv[2]), json.loads(sys.argv[3])
for name, data in answers.items():
    copier.run_copy(template, str(out / name), data=data, defaults=True, unsafe=True, quiet=True, vcs_ref="HEAD")
"""


def render_examples(python: Path, template: Path, out: Path, env: dict[str, str]) -> dict:
    """Every example answers file rendered by `python` into `out`: the files written (support.generation.tree)."""
    answers = {name: {**FIXED_ANSWERS, **example(name)} for name in examples()}
    result = subprocess.run([str(python), "-c", RENDER_EXAMPLES, str(template), str(out), json.dumps(answers)],
                            env={**subprocess_env(), **env}, capture_output=True, text=True, timeout=900, check=False)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    return tree(out)


@pytest.fixture(scope="module")
def reference(template_dir, tmp_path_factory):
    """Every example rendered by the suite's Python with the patches on, and the cache folder
    that render filled: what every other render must equal."""
    folder = tmp_path_factory.mktemp("reference")
    cache = folder / "cache"
    files = render_examples(Path(sys.executable), template_dir, folder / "out", {"RNA_TEMPLATE_CACHE_DIR": str(cache)})
    assert len({name.split("/")[0] for name in files}) == len(examples())
    return files, cache


def test_every_example_renders_byte_identical_with_the_patches_on_and_off(template_dir, reference, tmp_path):
    files, cache = reference
    kept = render_examples(Path(sys.executable), template_dir, tmp_path / "kept",
                           {"RNA_TEMPLATE_CACHE_DIR": str(cache)})
    off = render_examples(Path(sys.executable), template_dir, tmp_path / "off",
                          {"RNA_TEMPLATE_CACHE_DIR": str(tmp_path / "unused"), **OFF})
    assert differences(files, kept) == []
    assert differences(files, off) == []
    assert not (tmp_path / "unused").exists()  # off, nothing is kept


# ─── An update, on and off ────────────────────────────────────────────────────


def _edited_driver(project: Path, flavor: Flavor) -> None:
    if flavor.language("driver") == "cpp":
        replace_text(project / flavor.user_file("driver"), "public:", "public:\n  // my notes: tuned on the robot")
    else:
        replace_text(project / flavor.user_file("driver"), "\n\n\ndef main(", "\n\n    # my notes\n\n\ndef main(")
    commit_all(project, "my notes")


def _grown(flavor: Flavor) -> dict:
    nodes = flavor.answers["nodes"]
    nodes.append({"name": "planner", **({} if flavor.name == "ament_python" else {"language": "cpp"}),
                  "subscribers": ["scan:sensor_msgs/msg/LaserScan"], "parameters": ["horizon:double=2.0"]})
    return {"nodes": nodes}


def _shrunk(flavor: Flavor) -> dict:
    return {"nodes": [node for node in flavor.answers["nodes"] if node["name"] != "logger"]}


def _renamed(flavor: Flavor) -> dict:
    nodes = flavor.answers["nodes"]
    if flavor.name != "ament_python":
        for node in nodes:
            node.setdefault("language", flavor.language(node["name"]))
    driver = find_node(nodes, "driver")
    driver["name"], driver["renamed_from"] = "base_controller", "driver"
    return {"nodes": nodes}


def _tuned_gain_changed(flavor: Flavor) -> dict:
    nodes = flavor.answers["nodes"]
    find_node(nodes, "driver")["parameters"][0]["default"] = 2.5
    return {"nodes": nodes}


def _tuned(project: Path, flavor: Flavor) -> None:
    replace_text(project / flavor.config_file("driver"), "gain: 1.0", "gain: 1.8")
    commit_all(project, "tuned")


def _edited_answers(project: Path, flavor: Flavor) -> None:
    answers = project / ".copier-answers.yml"
    answers.write_text(answers.read_text().replace("max_speed:double=0.5", "max_speed:double=0.7", 1))
    commit_all(project, "edited the answers by hand")


# id -> (flavour, release the project was made with or None for this version, what the user did, the update's data)
UPDATES = {
    "add-a-node": ("ament_cmake", None, _edited_driver, _grown),
    "remove-a-node": ("catkin", None, _edited_driver, _shrunk),
    "rename-a-node": ("ament_python", None, _edited_driver, _renamed),
    "upgrade-a-release": ("ament_cmake", "latest", _edited_driver, None),
    "conflict": ("ament_python", None, _tuned, _tuned_gain_changed),
    "refused": ("ament_python", None, _edited_answers, _grown),
}


@pytest.fixture(scope="module")
def templates(template_dir, tmp_path_factory):
    """The releases, then this working tree, in one repository (the update tier's release template)."""
    return release_history_repo(tmp_path_factory.mktemp("history"), new_tree=template_dir)


SCRATCH = re.compile(r"(copier\._[a-z]+\.[a-z_]+\.)\w+")  # Copier's clone and scratch folders: named at random


def update_result(project: Path, data: dict | None, env: dict[str, str]) -> dict:
    """What `copier update` did: exit code, messages, files written, the commit and git's status."""
    command = [sys.executable, "-m", "copier", "update", "--trust", "--defaults"]
    if data is not None:
        data_file = project.parent / "update-data.yml"
        data_file.write_text(yaml.safe_dump(data, sort_keys=False))
        command += ["--data-file", str(data_file)]
    result = subprocess.run(command, cwd=project, env={**subprocess_env(), **env}, stdin=subprocess.DEVNULL,
                            capture_output=True, text=True, timeout=600, check=False)
    status = git("status", "--porcelain", "--untracked-files=all", cwd=project).stdout
    return {"exit": result.returncode, "stdout": SCRATCH.sub(r"\1*", result.stdout),
            "stderr": SCRATCH.sub(r"\1*", result.stderr), "files": tree(project),
            "status": status, "head": git("rev-parse", "HEAD", cwd=project).stdout}


@pytest.mark.parametrize("case", UPDATES)
def test_an_update_does_and_says_the_same_with_the_patches_on_and_off(templates, tmp_path, case):
    flavor_name, release, user, change = UPDATES[case]
    flavor = Flavor(flavor_name)
    made = tmp_path / "made" / "project"
    version = RELEASES[-1] if release == "latest" else templates.latest
    generate_project(templates, made, flavor.answers, vcs_ref=version)
    user(made, flavor)
    data = change(flavor) if change else None
    results = {}
    for name, env in (("on", {"RNA_TEMPLATE_CACHE_DIR": str(tmp_path / "cache")}), ("off", OFF)):
        project = tmp_path / "run" / "project"  # the same path each time: messages name it
        shutil.rmtree(project.parent, ignore_errors=True)
        shutil.copytree(made, project, symlinks=True)
        results[name] = update_result(project, data, env)
    on, off = results["on"], results["off"]
    assert (on["exit"] != 0) == (case in ("refused", "conflict")), on
    for key in ("exit", "stdout", "stderr", "status", "head"):
        assert on[key] == off[key], f"{key}: on\n{on[key]}\noff\n{off[key]}"
    assert differences(on["files"], off["files"]) == []


# ─── The update tier's cases, on and off ──────────────────────────────────────

# The update tier's own files (its ROS-built tests aside): each test with its first parameters,
# and the core scenario with every change the merge-safety figure counts, once each across the
# flavours (every third of its change x flavour sets).
UPDATE_TIER = ["tests/test_update.py", "tests/test_merge_safety.py", "tests/test_update_drawn.py",
               "tests/test_port.py", "tests/test_add_node.py", "tests/test_forks.py"]
EVERY_CHANGE = "tests/test_merge_safety.py::test_user_lines_survive"


def update_tier_sample() -> list[str]:
    listed = subprocess.run([sys.executable, "-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider",
                             "-m", "update and not ros and not ros1", *UPDATE_TIER], cwd=ROOT,
                            env=compat.env_of(Path(sys.prefix)), capture_output=True, text=True, check=True).stdout
    by_test: dict[str, list[str]] = {}
    for line in listed.splitlines():
        if "::" in line:
            by_test.setdefault(line.split("[")[0], []).append(line.strip())
    return [node for test, nodes in by_test.items() for node in (nodes[::3] if test == EVERY_CHANGE else nodes[:1])]


def test_the_update_tiers_cases_do_and_say_the_same_with_the_patches_on_and_off(tmp_path):
    """Every update of the sample's tests runs with the patches off, then on, in the project's
    own folder, and must leave the same files, links, modes and git state and print the same
    (tests/support/template_repo.py, COMPARE_PATCHES); each test then checks what it checks."""
    sample = update_tier_sample()
    assert len(sample) >= 50, sample
    result = compat.pytest_in(Path(sys.prefix), sample, tmp_path / "updates", timeout=1800,
                              **{COMPARE_PATCHES: "1"})
    assert result.returncode == 0, f"{result.stdout[-8000:]}\n{result.stderr[-2000:]}"


# ─── Other Pythons ────────────────────────────────────────────────────────────


def environment_of(version: str) -> Path:
    try:
        return compat.environment(compat.python(version))
    except compat.Unavailable as error:
        unavailable(f"the compat tier cannot run under Python {version}: {error}")


@pytest.mark.parametrize("version", compat.PYTHONS)
def test_the_fast_tier_passes_under_python(version, tmp_path):
    venv = environment_of(version)
    # The answer sets drawn are the fast tier's (CI's are drawn under 3.11): what differs here is Python.
    result = compat.pytest_in(venv, ["-m", compat.FAST_TIER], tmp_path / "base", timeout=1800,
                              HYPOTHESIS_PROFILE="fast")
    assert result.returncode == 0, f"Python {version}:\n{result.stdout[-6000:]}\n{result.stderr[-2000:]}"


@pytest.mark.parametrize("version", compat.PYTHONS)
def test_every_example_renders_byte_identical_under_python(version, template_dir, reference, tmp_path):
    venv = environment_of(version)
    files, reference_cache = reference
    cache = tmp_path / "cache"
    shutil.copytree(reference_cache, cache)  # 3.11's code beside it: each Python must keep to its own
    before = tree(cache)
    env = {"RNA_TEMPLATE_CACHE_DIR": str(cache)}
    first = render_examples(venv / "bin" / "python", template_dir, tmp_path / "first", env)
    kept = render_examples(venv / "bin" / "python", template_dir, tmp_path / "kept", env)
    assert differences(files, first) == [], f"Python {version} renders otherwise than {sys.version.split()[0]}"
    assert differences(files, kept) == [], f"Python {version}, its compiled code kept"
    after = tree(cache)
    assert all(after[name] == before[name] for name in before), "another Python rewrote 3.11's code"
    added = set(after) - set(before)
    assert {name.split("-")[0] for name in added} == {"jinja", "python"}, sorted(after)


# ─── The newest Copier, copier-template-extensions and Jinja ──────────────────


def test_the_newest_libraries_run_the_core_tests_with_every_patch_on(tmp_path):
    try:
        venv = compat.environment(Path(sys.executable), newest=True)
    except compat.Unavailable as error:
        unavailable(f"the newest {', '.join(compat.NEWEST)} could not be installed: {error}")
    found = compat.versions(venv)
    script = f"import json, sys; sys.path.insert(0, {str(EXTENSIONS)!r}); import patches; " \
             "print(json.dumps(patches.status()))"
    states = json.loads(subprocess.run([str(venv / "bin" / "python"), "-c", script], env=compat.env_of(venv),
                                       capture_output=True, text=True, check=True).stdout)
    off = {name: state for name, state in states.items() if state != "on"}
    assert not off, (f"with {found}, these patches' guards turned them off: {off}. Check each against this "
                     "release (tests/test_patches.py, this tier), then widen its guard in extensions/patches/")
    fast = compat.pytest_in(venv, ["-m", compat.FAST_TIER], tmp_path / "fast", timeout=1800)
    assert fast.returncode == 0, f"with {found}:\n{fast.stdout[-6000:]}\n{fast.stderr[-2000:]}"
    sample = compat.pytest_in(venv, [*UPDATE_SAMPLE, *COMPARISONS], tmp_path / "sample", timeout=1800,
                              **{COMPARE_PATCHES: "1"})
    assert sample.returncode == 0, f"with {found}:\n{sample.stdout[-6000:]}\n{sample.stderr[-2000:]}"
