"""`copier update` end to end: grow a generated package, shrink it, and upgrade the template.

Every test runs the real `copier` command line in a private copy of a base project that
was generated once per session (tests/support/template_repo.py), on the three flavours:
ament_python, ament_cmake (a C++ and a Python node) and catkin (ROS 1). Each checks the
exit code, that no conflict marker or .rej file is left, and that what was added or
removed shows in package.xml (catkin_pkg), the launch file (ElementTree), the build file
(setup.py entry points, CMake targets) and the node files.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml
from catkin_pkg.package import parse_package

if "support.template_repo" not in sys.modules:  # its asserts explain themselves too
    pytest.register_assert_rewrite("support.template_repo")
from support.generation import ROOT, subprocess_env  # noqa: E402
from support.packages import dependency_names, rna  # noqa: E402
from support.real_packages import png  # noqa: E402
from support.template_repo import (  # noqa: E402
    FLAVORS, NEW_VERSION, OLD_VERSION, PACKAGE, RELEASES, Flavor, answers_of, append_after, commit_all,
    conflict_excerpts, conflicted_files, find_node, generate_project, git, kept_of, managed_lines, missing_block,
    replace_text, run_update, summary_of, to_port_of, tree_differences, unmanaged_lines, user_answers,
)

pytest_plugins = ("support.template_repo",)
pytestmark = pytest.mark.update


# ─── Reading a generated package ──────────────────────────────────────────────


def assert_clean_update(result, project: Path) -> None:
    assert result.returncode == 0, f"copier update failed\n{result}"
    conflicts = conflicted_files(project)
    assert not conflicts, f"conflicts left in {conflicts}\n{conflict_excerpts(project)}\n{result}"


def launched(project: Path, flavor: Flavor) -> dict[str, tuple[str, str]]:
    """node name -> (executable, the config file it loads), from the launch file."""
    root = ET.parse(project / flavor.launch_file).getroot()
    nodes = {}
    for node in root.iter("node"):
        if node.get("pkg") != "robot":
            continue
        if flavor.ros1:
            nodes[node.get("name")] = (node.get("type"), node.find("rosparam").get("file"))
        else:
            nodes[node.get("name")] = (node.get("exec"), node.find("param").get("from"))
    return nodes


def expected_launch_entry(flavor: Flavor, node: str, language: str) -> tuple[str, str]:
    if flavor.ros1:
        return (f"{node}.py" if language == "python" else node, f"$(find robot)/config/{node}.yaml")
    return (node, f"$(find-pkg-share robot)/config/{node}.yaml")


def build_entries(project: Path, flavor: Flavor, managed_only: bool = False) -> set[str]:
    """What the build file installs, as `python:<node>` / `cpp:<node>`, read from its text
    (with `managed_only`, from the lines inside its managed blocks alone)."""
    text = (project / flavor.build_file).read_text()
    if managed_only:
        text = "\n".join(managed_lines(text)) + "\n"
    entries = set()
    if flavor.name == "ament_python":
        entries |= {f"python:{name}" for name, module in re.findall(r"'(\w+) = robot\.(\w+):main'", text)
                    if name == module}
    else:
        # a node's target is named after it (or `${PROJECT_NAME}_<node>`); its source is src/<node>.cpp
        entries |= {f"cpp:{name}" for name in re.findall(r"add_executable\([^\s)]+ src/(\w+)\.cpp\)", text)}
        if flavor.ros1:
            entries |= {f"python:{name}" for name in re.findall(r"^  scripts/(\w+)\.py$", text, re.M)}
        else:
            entries |= {f"python:{name}" for name in re.findall(r"RENAME (\w+)\)", text)}
    return entries


def config_values(project: Path, flavor: Flavor, node: str) -> dict:
    data = yaml.safe_load((project / flavor.config_file(node)).read_text())
    return data if flavor.ros1 else data["/**"]["ros__parameters"]


def fresh_copy_differences(project: Path, template, tmp_path: Path, version: str = NEW_VERSION) -> list[str]:
    """How `project` differs from a fresh copy made with its answers (`.git`, `_commit` aside)."""
    fresh = generate_project(template, tmp_path / "fresh", user_answers(project), vcs_ref=version)
    return tree_differences(project, fresh)


def edit_user_file(project: Path, flavor: Flavor, node: str) -> list[str]:
    """A line of the user's own at the end of the node's class (just before main())."""
    path = project / flavor.user_file(node)
    if flavor.language(node) == "cpp":
        return append_after(path, "public:", ["  // my notes: tuned on the real robot"])
    return replace_text(path, "\n\n\ndef main(", "\n\n    # my notes: tuned on the real robot\n\n\ndef main(")


def node_answers(flavor: Flavor, name: str, language: str, **endpoints) -> dict:
    node = {"name": name, **endpoints}
    if flavor.name != "ament_python":
        node["language"] = language
    return node


# ─── Adding nodes ─────────────────────────────────────────────────────────────

PLANNER = {"subscribers": ["scan:sensor_msgs/msg/LaserScan:sensor_data"], "publishers": ["path:nav_msgs/msg/Path"],
           "timers": ["0.2"], "parameters": ["horizon:double=2.0"]}
RELAY = {"subscribers": ["chatter:std_msgs/msg/String"], "publishers": ["chatter_out:std_msgs/msg/String"]}

NEW_NODES = {  # flavour -> (name, language, endpoints) of the nodes an update adds
    "ament_python": [("planner", "python", PLANNER)],
    "ament_cmake": [("planner", "cpp", PLANNER), ("relay", "python", RELAY)],
    "catkin": [("planner", "cpp", PLANNER), ("relay", "python", RELAY)],
}


@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_add_nodes(project, current_template, tmp_path, flavor_name):
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    nodes = flavor.answers["nodes"] + [node_answers(flavor, name, language, **endpoints)
                                       for name, language, endpoints in NEW_NODES[flavor_name]]

    result = run_update(destination, {"nodes": nodes})
    assert_clean_update(result, destination)

    assert answers_of(destination)["nodes"][-1]["name"] == NEW_NODES[flavor_name][-1][0]
    launch = launched(destination, flavor)
    entries = build_entries(destination, flavor, managed_only=True)
    for name, language, _ in NEW_NODES[flavor_name]:
        class_name = name.capitalize()
        user = (destination / flavor.user_file(name, language)).read_text()
        base = (destination / flavor.base_file(name, language)).read_text()
        assert (f"class {class_name}(" in user) or (f"class {class_name} : public {class_name}Base" in user)
        assert f"{class_name}Base" in base
        assert launch[name] == expected_launch_entry(flavor, name, language)
        assert f"{language}:{name}" in entries, f"{name} is not built or installed by {flavor.build_file}"
        if flavor.ros1 and language == "python":
            assert os.access(destination / flavor.user_file(name, language), os.X_OK)
    assert config_values(destination, flavor, "planner") == {"horizon": 2.0}
    # the nodes that were there stay launched
    assert {"driver", "monitor", "logger"} <= set(launch)

    dependencies = dependency_names(destination / flavor.package_xml)
    assert {"sensor_msgs", "nav_msgs"} <= dependencies
    if flavor_name != "ament_python":
        assert "std_msgs" in dependencies
    if flavor_name == "ament_cmake":
        assert "find_package(sensor_msgs REQUIRED)" in managed_lines((destination / flavor.build_file).read_text())
    if flavor.ros1:
        assert "  sensor_msgs" in managed_lines((destination / flavor.build_file).read_text())
    assert "| `planner` |" in (destination / "README.md").read_text()

    # An untouched package that grew equals a fresh copy made with the grown answers.
    assert fresh_copy_differences(destination, current_template, tmp_path) == []


def test_a_package_inside_a_larger_repository_updates_like_one_on_its_own(base_project, tmp_path):
    """A package in a workspace's repository (src/robot): the after-update step reads the
    committed files by their path from the package, and keeps the user's line."""
    flavor = Flavor("ament_cmake")
    workspace = tmp_path / "ws"
    destination = workspace / "src" / "robot"
    shutil.copytree(base_project("ament_cmake"), destination, ignore=shutil.ignore_patterns(".git"))
    git("init", "-q", "-b", "main", cwd=workspace)
    commit_all(workspace, "a workspace")
    mine = edit_user_file(destination, flavor, "driver")
    commit_all(workspace)
    nodes = flavor.answers["nodes"] + [node_answers(flavor, "planner", "cpp", **PLANNER)]

    result = run_update(destination, {"nodes": nodes})
    assert_clean_update(result, destination)

    assert set(mine) <= set((destination / flavor.user_file("driver")).read_text().splitlines())
    assert flavor.user_file("planner", "cpp") in summary_of(result.output)["added"], result


# ─── What an update says ──────────────────────────────────────────────────────


def test_an_update_ends_with_a_summary_instead_of_internal_command_lines(project):
    flavor = Flavor("ament_python")
    destination = project("ament_python")
    edit_user_file(destination, flavor, "driver")
    replace_text(destination / flavor.config_file("driver"), "max_speed: 0.5", "max_speed: 0.8")
    commit_all(destination)
    nodes = flavor.answers["nodes"] + [node_answers(flavor, "planner", "python", **PLANNER)]
    find_node(nodes, "driver")["parameters"][0]["default"] = 2.5  # merged with the tuned max_speed
    find_node(nodes, "monitor")["parameters"] = ["limit:int=7"]  # a file the user never edited

    result = run_update(destination, {"nodes": nodes})
    assert_clean_update(result, destination)

    summary = summary_of(result.output)
    added = {flavor.config_file("planner"), flavor.user_file("planner", "python"),
             flavor.base_file("planner", "python")}
    assert added <= set(summary["added"]), result
    assert flavor.config_file("monitor") in summary["updated"], result
    assert flavor.config_file("driver") in summary["merged"], result
    assert flavor.user_file("driver") not in str(summary), "an edited file that did not change is not listed"
    # Copier names the migration it runs: a plain shell line, not a Python list of temporary paths.
    task_lines = [line for line in result.stderr.splitlines() if "Running task" in line]
    assert all("['" not in line and "after_update.py" in line for line in task_lines), result


def test_the_last_line_says_done_or_done_with_items_and_the_exit_status_follows(project):
    flavor = Flavor("ament_python")
    destination = project("ament_python")
    edit_user_file(destination, flavor, "logger")
    commit_all(destination)
    nodes = [node for node in flavor.answers["nodes"] if node["name"] != "logger"]
    result = run_update(destination, {"nodes": nodes})
    assert result.returncode == 1, result
    last = result.stdout[result.stdout.rindex("Done, with"):].splitlines()
    assert " ".join(last) == ("Done, with 1 item for you (above): review with `git diff HEAD`, and commit once it is "
                              "done. copier exits with status 1 to say so; its line \"Task ... returned non-zero "
                              "exit status 1\" below means that, not a failure."), result
    assert all(len(line) <= 80 for line in last), last
    assert "returned non-zero exit status 1." in result.stderr.rstrip().splitlines()[-1], result
    assert git("status", "--porcelain", cwd=destination).stdout, "the update is done: the package changed"


def exit_status_script() -> str:
    """The script of the grow-a-package page that tells the outcomes of an update apart."""
    page = (ROOT / "docs" / "pages" / "how-to" / "grow-a-package.md").read_text()
    return re.search(r"```sh\n(.*?)```", page.split("## What the exit status says")[1], re.S).group(1)


@pytest.mark.parametrize("outcome", ["done", "done with items", "failed", "dirty"])
def test_the_script_of_the_docs_tells_an_updates_outcomes_apart(project, outcome):
    flavor = Flavor("ament_python")
    destination = project("ament_python")
    nodes = flavor.answers["nodes"]
    data = {"nodes": nodes + [{"name": "planner", "subscribers": ["scan:sensor_msgs/msg/LaserScan"]}]}
    if outcome == "done with items":
        edit_user_file(destination, flavor, "logger")
        commit_all(destination)
        data = {"nodes": [node for node in nodes if node["name"] != "logger"]}
    elif outcome == "failed":
        data = {"build_type": "catkin"}
    elif outcome == "dirty":
        (destination / "notes.txt").write_text("not committed\n")
    (destination.parent / "changes.yml").write_text(yaml.safe_dump(data))
    result = subprocess.run(["bash", "-c", exit_status_script()], cwd=destination, capture_output=True, text=True,
                            env={**subprocess_env(), "PATH": f"{Path(sys.executable).parent}:{os.environ['PATH']}"},
                            stdin=subprocess.DEVNULL, timeout=300)
    said = {"done": "updated: review and commit", "done with items": "updated, with items for you: see the summary",
            "failed": "the update failed; nothing changed", "dirty": "commit or stash first"}[outcome]
    assert result.stdout.splitlines()[-1:] == [said], result.stdout + result.stderr
    assert result.returncode == (0 if outcome.startswith("done") else 1), result.stdout + result.stderr


BROKEN_STEP = """
import sys
sys.path.insert(0, sys.argv[1])
import after_update


def broken(*args, **kwargs):
    raise RuntimeError("a step broke")


after_update.blocks.dropped_but_used = broken
sys.exit(after_update.main(".copier-answers.yml", after_update.Path(sys.argv[2]), after_update.Path(sys.argv[3])))
"""


def test_an_after_update_step_that_fails_undoes_the_update_and_says_so(project, current_template):
    """Whatever breaks in the step after Copier's merge, the package comes back as committed (Copier
    updates a clean one only), and one line says so: a failed update never leaves it half done.
    (The step runs in a process of its own, as Copier runs it, with one of its steps broken.)"""
    destination = project("ament_cmake")
    (destination / "README.md").write_text("what Copier had written\n")  # Copier's part of the update
    (destination / "robot" / "src" / "planner.cpp").write_text("// a node Copier added\n")
    result = subprocess.run([sys.executable, "-c", BROKEN_STEP, str(current_template.path / "extensions"),
                             str(destination), str(current_template.path)], cwd=destination, env=subprocess_env(),
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 1, result.stdout + result.stderr
    error = result.stderr.strip()
    assert error.startswith("rna-template: the update failed while finishing (RuntimeError: a step broke, at "
                            "<string>:"), error
    assert error.endswith("so it was undone: the package is as you committed it. Please report this, with the "
                          "command you ran."), error
    assert "\n" not in error
    assert git("status", "--porcelain", cwd=destination).stdout == ""


# ─── Answers stored resolved ──────────────────────────────────────────────────
# A node's language defaults from the build type; the answers file records it, so that
# changing the build type (or the distro) never turns a Python node into a C++ one.


def node_files(destination: Path) -> set[str]:
    return {str(p.relative_to(destination)) for p in destination.rglob("*")
            if p.suffix in (".py", ".cpp", ".hpp") and p.name != "setup.py" and not {".git", "test"} & set(p.parts)}


@pytest.mark.parametrize("version", [NEW_VERSION, OLD_VERSION], ids=["resolved-answers", "answers-of-0.1.0"])
def test_changing_the_build_type_keeps_each_nodes_language(project, version):
    flavor = Flavor("ament_python")
    destination = project("ament_python", version)
    recorded = answers_of(destination)["nodes"]
    if version == NEW_VERSION:
        assert all(node.get("language") == "python" for node in recorded), recorded
    kept = edit_user_file(destination, flavor, "driver")
    commit_all(destination)
    python_files = node_files(destination)

    result = run_update(destination, {"build_type": "ament_cmake"}, vcs_ref=NEW_VERSION)
    assert_clean_update(result, destination)

    assert [node["language"] for node in answers_of(destination)["nodes"]] == ["python"] * 3
    assert node_files(destination) == python_files, "a node changed language"
    assert missing_block(destination / flavor.user_file("driver"), kept) is None
    assert build_entries(Path(destination), Flavor("ament_cmake"), managed_only=True) == {
        "python:driver", "python:monitor", "python:logger"}


@pytest.mark.parametrize("edited", [False, True], ids=["untouched", "edited"])
def test_changing_the_launch_format(project, edited):
    """The launch file of the old format goes when it is the template's own; the user's edited one stays, named."""
    flavor = Flavor("ament_cmake")
    destination = project("ament_cmake")
    old = flavor.launch_file
    new = f"{PACKAGE}/launch/{PACKAGE}.launch.py"
    if edited:
        mine = append_after(destination / old, "<!-- END rna-template: add your own actions below -->",
                            '  <set_parameter name="use_sim_time" value="true"/>')
        commit_all(destination)

    result = run_update(destination, {"launch_format": "python"})

    assert not conflicted_files(destination), conflict_excerpts(destination)
    assert answers_of(destination)["launch_format"] == "python"
    launch = (destination / new).read_text()
    assert all(f"executable='{node['name']}'" in launch for node in flavor.answers["nodes"])
    package_xml = (destination / flavor.package_xml).read_text()
    assert "<exec_depend>launch_ros</exec_depend>" in package_xml
    assert f"ros2 launch {PACKAGE} {PACKAGE}.launch.py" in (destination / "README.md").read_text()
    if edited:
        assert result.returncode == 1, result
        assert missing_block(destination / old, mine) is None
        assert kept_of(result.output)[old] == f"the launch file is Python now: move what you added into {new}"
    else:
        assert_clean_update(result, destination)
        assert not (destination / old).exists()


def test_nodes_given_without_a_language_keep_theirs(project):
    """`--data nodes=...` written as the docs do, without `language`, changes no node's language."""
    flavor = Flavor("ament_python")
    destination = project("ament_python")
    nodes = flavor.answers["nodes"] + [{"name": "planner", **PLANNER}]
    result = run_update(destination, {"build_type": "ament_cmake", "nodes": nodes})
    assert_clean_update(result, destination)
    languages = {node["name"]: node["language"] for node in answers_of(destination)["nodes"]}
    assert languages == {"driver": "python", "monitor": "python", "logger": "python", "planner": "cpp"}
    assert (destination / "robot/src/planner.cpp").is_file() and (destination / "robot/robot/driver.py").is_file()


def test_a_new_node_does_not_take_over_a_file_of_the_users_with_its_name(project):
    """The user's own planner.py (not built on PlannerBase) stops an update adding a node planner."""
    destination = project("ament_python")
    mine = destination / "robot" / "robot" / "planner.py"
    mine.write_text('"""My own path planner, not a generated node."""\n\n\ndef plan():\n    return []\n')
    commit_all(destination, "my planner module")
    nodes = Flavor("ament_python").answers["nodes"] + [{"name": "planner", "language": "python", **PLANNER}]
    result = run_update(destination, {"nodes": nodes})
    assert result.returncode != 0
    assert ("invalid answer to 'nodes': node 'planner': robot/robot/planner.py is already in the package and does not "
            "build on PlannerBase") in result.stderr
    assert "Traceback" not in result.stderr
    assert git("status", "--porcelain", cwd=destination).stdout == ""
    assert mine.read_text().startswith('"""My own path planner')
    # Under another name the node is added, and the user's module stays as it was.
    nodes[-1]["name"] = "path_planner"
    assert_clean_update(run_update(destination, {"nodes": nodes}), destination)
    assert (destination / "robot" / "robot" / "path_planner_base.py").is_file()
    assert mine.read_text().startswith('"""My own path planner')


def test_a_language_changed_on_purpose_keeps_the_edited_file(project):
    flavor = Flavor("ament_cmake")
    destination = project("ament_cmake")
    kept = edit_user_file(destination, flavor, "monitor")
    commit_all(destination)
    nodes = flavor.answers["nodes"]
    find_node(nodes, "monitor")["language"] = "cpp"
    result = run_update(destination, {"nodes": nodes})
    assert result.returncode == 1, result
    assert missing_block(destination / flavor.user_file("monitor", "python"), kept) is None
    assert "cpp now" in kept_of(result.output)[flavor.user_file("monitor", "python")]
    assert (destination / flavor.user_file("monitor", "cpp")).is_file()


def test_the_one_node_questions_are_the_first_copys_and_an_update_given_one_refuses_it(release_template, tmp_path):
    """`node_publishers` and the other one-node questions fill in `nodes` on a first copy. The
    answers file records `nodes` alone (0.3.1 recorded both, and an update given one changed
    nothing while recording it); an update given one says, in one line, that nodes change in
    `nodes`, and writes nothing."""
    answers = {"package_name": PACKAGE, "node_setup": "one", "node_name": "driver",
               "node_publishers": "cmd_vel:geometry_msgs/msg/Twist"}
    fresh = answers_of(generate_project(release_template, tmp_path / "fresh", answers, vcs_ref=NEW_VERSION))
    assert not set(rna.answers.FIRST_COPY) & set(fresh), fresh
    old = generate_project(release_template, tmp_path / "old", answers, vcs_ref=RELEASES[-1])
    assert "node_publishers" in answers_of(old)
    assert_clean_update(run_update(old, vcs_ref=NEW_VERSION), old)
    recorded = answers_of(old)
    assert not set(rna.answers.FIRST_COPY) & set(recorded), recorded
    assert recorded["nodes"] == fresh["nodes"] == [
        {"language": "python", "name": "driver", "publishers": ["cmd_vel:geometry_msgs/msg/Twist"]}]
    commit_all(old, "updated")

    refused = run_update(old, {"node_publishers": "odom:nav_msgs/msg/Odometry"})
    assert refused.returncode == 1, refused
    assert ("rna-template: invalid answer to 'node_publishers': node_publishers is a question of the first copy, "
            "which it helps fill in 'nodes'; this package records its nodes in 'nodes'") in refused.stderr, refused
    assert "Traceback" not in refused.stderr and git("status", "--porcelain", cwd=old).stdout == "", refused


INVALID_CHOICES = {  # id -> (flavour, what the update is given, the error)
    "ament_python-catkin": (
        "ament_python", {"build_type": "catkin"},
        "invalid answer to 'build_type': 'catkin' is not one of ament_cmake, ament_python for ROS 2"),
    "ament_python-interfaces-in-the-package": (
        "ament_python", {"interfaces_location": "package"},
        "invalid answer to 'interfaces_location': an ament_python package cannot build interfaces"),
    "catkin-ament_cmake": ("catkin", {"build_type": "ament_cmake"},
                           "invalid answer to 'build_type': 'ament_cmake' is not one of catkin for ROS 1"),
}


@pytest.mark.parametrize("case", INVALID_CHOICES)
def test_a_choice_the_packages_answers_rule_out_gives_one_line_and_writes_nothing(project, case):
    """Copier checks a choice given with --data-file against the choices the other answers
    leave (the package's, from its answers file) and ends in a traceback; the template says
    which rule in one line first."""
    flavor_name, data, message = INVALID_CHOICES[case]
    destination = project(flavor_name)
    result = run_update(destination, data)
    assert result.returncode == 1, result
    assert f"rna-template: {message}" in result.stderr and "Traceback" not in result.stderr, result
    assert git("status", "--porcelain", cwd=destination).stdout == "", result


@pytest.mark.parametrize("command", ["recopy", "copy"])
def test_recopy_over_a_lived_in_package_is_refused_in_one_line(project, current_template, command):
    """Copier suggests `copier recopy` when an update goes wrong; it renders the package afresh
    over the user's files (with --overwrite, without asking), so the user's lines in
    package.xml, the build files, config and README would go, with exit 0. Refused instead."""
    flavor = Flavor("ament_python")
    destination = project("ament_python")
    lived_in_edits(destination, flavor)
    where = [] if command == "recopy" else [str(current_template.path), "."]
    result = subprocess.run([sys.executable, "-m", "copier", command, "--trust", "--defaults", "--overwrite", *where],
                            cwd=destination, env=subprocess_env(), capture_output=True, text=True,
                            stdin=subprocess.DEVNULL, timeout=300)
    assert result.returncode == 1, result.stdout + result.stderr
    assert ("rna-template: this folder holds a package the template made (.copier-answers.yml): copier recopy and "
            "copier copy render it afresh") in result.stderr and "Traceback" not in result.stderr, result.stderr
    assert git("status", "--porcelain", cwd=destination).stdout == ""


def test_a_file_name_that_is_not_utf_8_stops_the_update_before_copier_fails_half_way(project):
    """Copier 9.19 reads the names in git's diff as UTF-8 and fails after it has written the new
    version; the template refuses first, naming the file."""
    destination = project("ament_python")
    (destination / "robot" / os.fsdecode(b"caf\xe9 notes.txt")).write_bytes(b"\xe9t\xe9\n")
    commit_all(destination, "a note from an old machine")
    result = run_update(destination, {"nodes": Flavor("ament_python").answers["nodes"][:2]})
    assert result.returncode == 1, result
    assert ("rna-template: the file robot/caf\\xe9 notes.txt has a name that is not UTF-8, on which copier update "
            "fails half-way (nothing was written)") in result.stderr and "Traceback" not in result.stderr, result
    assert git("status", "--porcelain", cwd=destination).stdout == ""


@pytest.mark.parametrize("how", ["gitattributes", "autocrlf"])
def test_a_checkout_with_crlf_line_ends_keeps_them_through_an_update(project, tmp_path, figure, how):
    """A .gitattributes asking for CRLF line ends (`* text eol=crlf`), or Windows' git
    (core.autocrlf=true), has git write text files with CRLF line ends and hold them with LF;
    Copier writes what it renders or merges with LF. The update leaves every text file it wrote
    as git would have checked it out, binary ones as they were, and lists only the files whose
    content changed (not those whose line ends Copier alone turned)."""
    flavor = Flavor("ament_cmake")
    committed = project("ament_cmake")
    image = png(8, 8)
    (committed / PACKAGE / "doc").mkdir()
    (committed / PACKAGE / "doc" / "logo.png").write_bytes(image)
    if how == "gitattributes":
        (committed / ".gitattributes").write_text("* text=auto eol=crlf\n*.png binary\n")
    commit_all(committed, "line ends as the lab wants them")
    destination = tmp_path / "checkout"
    git("clone", "-q", *(["-c", "core.autocrlf=true"] if how == "autocrlf" else []), str(committed), str(destination),
        cwd=tmp_path)
    nodes = flavor.answers["nodes"] + [{"name": "planner", "language": "python",
                                        "subscribers": ["scan:sensor_msgs/msg/LaserScan"]}]

    result = run_update(destination, {"nodes": nodes})

    figure(result, destination, lost=int((destination / PACKAGE / "doc" / "logo.png").read_bytes() != image))
    assert_clean_update(result, destination)
    assert (destination / PACKAGE / "doc" / "logo.png").read_bytes() == image
    lf_only = [path for path in git("ls-files", "--cached", "--others", "--exclude-standard", cwd=destination
                                    ).stdout.split() if path != "robot/doc/logo.png"
               and re.search(rb"(?<!\r)\n", (destination / path).read_bytes())]
    assert not lf_only, f"files with LF line ends in a CRLF checkout: {lf_only}\n{result}"
    summary = summary_of(result.output)
    listed = {path for label in ("added", "updated", "merged") for path in summary.get(label, [])}
    changed = set(git("diff", "HEAD", "--name-only", cwd=destination).stdout.split()) | set(
        git("ls-files", "--others", "--exclude-standard", cwd=destination).stdout.split())
    assert listed == changed - {".copier-answers.yml"}, result
    assert git("status", "--porcelain", "--untracked-files=no", cwd=destination).stdout.count("\n") == len(
        set(git("diff", "HEAD", "--name-only", cwd=destination).stdout.split())), "files whose line ends alone changed"


# ─── Adding endpoints to existing nodes ───────────────────────────────────────


def endpoints_for(flavor: Flavor) -> dict:
    action = "actionlib/action/Test" if flavor.ros1 else "test_msgs/action/Fibonacci"
    return {
        "publishers": ["status:std_msgs/msg/String"],
        "subscribers": ["scan:sensor_msgs/msg/LaserScan"],
        "service_servers": ["calibrate:std_srvs/srv/Trigger"],
        "action_servers": [f"dock:{action}"],
        "timers": ["watchdog:1.0"],
    }


# What each endpoint kind puts in the base class (both languages use these names).
ENDPOINT_CODE = {
    "publishers": "status_publisher",
    "subscribers": "on_scan(",
    "service_servers": "on_calibrate_request(",
    "action_servers": "execute_dock(",
    "timers": "on_watchdog(",
}
# What an untouched user file gains: the starter overrides (the timer callback only where
# the new timer is the node's first, i.e. monitor's).
USER_OVERRIDES = {
    "subscribers": "on_scan(",
    "service_servers": "on_calibrate_request(",
    "action_servers": "execute_dock(",
}
GROWN = ("driver", "monitor")  # driver: C++ in ament_cmake and catkin; monitor: Python everywhere


def grow(nodes: list[dict], flavor: Flavor, names=GROWN) -> list[dict]:
    for name in names:
        node = find_node(nodes, name)
        for kind, values in endpoints_for(flavor).items():
            node[kind] = node.get(kind, []) + values
    return nodes


@pytest.mark.parametrize("edited", [True, False], ids=["edited-user-files", "untouched-user-files"])
@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_add_every_endpoint_kind_to_existing_nodes(project, current_template, tmp_path, flavor_name, edited):
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    if edited:
        for name in GROWN:
            edit_user_file(destination, flavor, name)
        commit_all(destination)
    before = {name: (destination / flavor.user_file(name)).read_text() for name in GROWN}

    result = run_update(destination, {"nodes": grow(flavor.answers["nodes"], flavor)})
    assert_clean_update(result, destination)

    missing = []
    for name in GROWN:
        base = (destination / flavor.base_file(name)).read_text()
        missing += [f"{flavor.base_file(name)} lacks the {kind} code {code!r}"
                    for kind, code in ENDPOINT_CODE.items() if code not in base]
    assert not missing, "\n".join(missing)

    dependencies = dependency_names(destination / flavor.package_xml)
    expected = {"std_msgs", "sensor_msgs", "std_srvs"} | (
        {"actionlib", "actionlib_msgs"} if flavor.ros1 else {"test_msgs"})
    assert expected <= dependencies, f"package.xml lacks {expected - dependencies}"
    if flavor_name == "ament_cmake":
        cmake = "\n".join(managed_lines((destination / flavor.build_file).read_text()))
        for package in ("sensor_msgs", "std_msgs", "std_srvs", "test_msgs", "rclcpp_action"):
            assert f"find_package({package} REQUIRED)" in cmake
        assert "${sensor_msgs_TARGETS}" in cmake

    summary = summary_of(result.output)
    for name in GROWN:
        user = (destination / flavor.user_file(name)).read_text()
        if edited:
            assert user == before[name], f"copier update changed the user's {flavor.user_file(name)}"
            assert flavor.user_file(name) not in str(summary), result
        else:
            gained = {kind: code for kind, code in USER_OVERRIDES.items() if code not in user}
            assert not gained, f"untouched {flavor.user_file(name)} did not gain {gained}\n{user}"
            assert flavor.user_file(name) in summary["updated"], result
    if not edited:
        assert "on_watchdog(" in (destination / flavor.user_file("monitor")).read_text()
        assert fresh_copy_differences(destination, current_template, tmp_path) == []


# ─── Executors, callback groups, remappings ──────────────────────────────────


def threaded(flavor: Flavor) -> list[dict]:
    """The base nodes, the driver on a multi-threaded executor (ROS 2: its odometry in a callback group of its
    own) and both it and the monitor remapped by the launch file."""
    nodes = flavor.answers["nodes"]
    driver, monitor = find_node(nodes, "driver"), find_node(nodes, "monitor")
    driver.update(executor="multi_threaded", threads=2, remappings={"cmd_vel": "base/cmd_vel"})
    if not flavor.ros1:
        driver["callback_groups"] = [{"name": "sensing", "type": "reentrant", "members": ["odom"]}]
    monitor["remappings"] = {"cmd_vel": "base/cmd_vel", "reset": "/robot/reset"}
    return nodes


EXECUTOR_CODE = {"python": "MultiThreadedExecutor(num_threads=2)",
                 "cpp": "MultiThreadedExecutor executor(rclcpp::ExecutorOptions(), 2)",
                 "ros1": "ros::MultiThreadedSpinner spinner(2);"}


@pytest.mark.parametrize("edited", [True, False], ids=["edited-user-files", "untouched-user-files"])
@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_switching_the_executor_and_adding_remappings_keeps_every_user_line(project, current_template, tmp_path,
                                                                           flavor_name, edited):
    """The executor and the callback groups live in the base files, the remappings in the launch file: the
    user files stay as they are, edited or not (an untouched one equals a fresh copy's)."""
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    if edited:
        for name in ("driver", "monitor"):
            edit_user_file(destination, flavor, name)
        commit_all(destination)
    before = {name: (destination / flavor.user_file(name)).read_text() for name in ("driver", "monitor")}

    result = run_update(destination, {"nodes": threaded(flavor)})
    assert_clean_update(result, destination)

    for name in ("driver", "monitor"):
        assert (destination / flavor.user_file(name)).read_text() == before[name], flavor.user_file(name)
    language = "ros1" if flavor.ros1 else flavor.language("driver")
    base = (destination / flavor.base_file("driver")).read_text()
    assert EXECUTOR_CODE[language] in base, base
    if not flavor.ros1:
        assert "sensing_callback_group" in base, base
    launch = (destination / flavor.launch_file).read_text()
    assert launch.count('<remap from="cmd_vel" to="base/cmd_vel"/>') == 2, launch
    assert '<remap from="reset" to="/robot/reset"/>' in launch, launch
    assert not to_port_of(result.output), result
    if not edited:
        assert fresh_copy_differences(destination, current_template, tmp_path) == []


@pytest.mark.parametrize("flavor_name", ["ament_cmake", "catkin"])
def test_an_edited_cpp_main_of_an_older_release_is_told_to_spin_on_the_new_executor(project, flavor_name):
    """0.3.1's C++ main() spun the node itself (rclcpp::spin, ros::spin): it keeps working on one thread, and
    switched to a multi-threaded executor the update leaves a "to port" note and the new starter beside it."""
    flavor = Flavor(flavor_name)
    destination = project(flavor_name, RELEASES[-1])
    edit_user_file(destination, flavor, "driver")
    commit_all(destination)
    user = (destination / flavor.user_file("driver")).read_text()
    assert "Driver::spin(" not in user  # the older form: rclcpp::spin(node), ros::spin()

    result = run_update(destination, {"nodes": threaded(flavor)}, vcs_ref=NEW_VERSION)
    assert result.returncode == 1, result
    assert (destination / flavor.user_file("driver")).read_text() == user
    notes = to_port_of(result.output)
    assert list(notes) == [flavor.user_file("driver")], result
    assert "it spins on a multi-threaded executor now, which main() gets by calling Driver::spin()" in notes[
        flavor.user_file("driver")], result
    assert (destination / (flavor.user_file("driver") + ".new-starter")).is_file()


# ─── Changing a parameter's default ───────────────────────────────────────────


@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_change_parameter_defaults(project, flavor_name):
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    # The user tunes a parameter whose default does not change; it must stay tuned.
    tuned = replace_text(destination / flavor.config_file("driver"), "max_speed: 0.5", "max_speed: 0.8")
    commit_all(destination, "tune max_speed")

    nodes = flavor.answers["nodes"]
    driver, monitor = find_node(nodes, "driver"), find_node(nodes, "monitor")
    driver["parameters"][0]["default"] = 2.5
    monitor["parameters"] = ["limit:int=7"]
    result = run_update(destination, {"nodes": nodes})
    assert_clean_update(result, destination)

    assert config_values(destination, flavor, "driver") == {"gain": 2.5, "frame_id": "base_link", "max_speed": 0.8}
    assert config_values(destination, flavor, "monitor") == {"limit": 7}
    assert missing_block(destination / flavor.config_file("driver"), tuned) is None
    driver_base = (destination / flavor.base_file("driver")).read_text()
    monitor_base = (destination / flavor.base_file("monitor")).read_text()
    assert re.search(r"\"gain\",[^;]*\b2\.5\b|'gain', 2\.5", driver_base), driver_base
    assert not re.search(r"\"gain\",[^;]*\b1\.0\b|'gain', 1\.0", driver_base)
    assert re.search(r"'(~)?limit', 7\b", monitor_base), monitor_base


# ─── Removing nodes ───────────────────────────────────────────────────────────

REMOVALS = {  # id -> (flavour, the removed node whose user file was edited, the untouched one)
    "ament_python": ("ament_python", "driver", "logger"),
    "ament_cmake-cpp-edited": ("ament_cmake", "driver", "monitor"),
    "ament_cmake-python-edited": ("ament_cmake", "monitor", "driver"),
    "catkin-cpp-edited": ("catkin", "driver", "logger"),
    "catkin-python-edited": ("catkin", "logger", "driver"),
}
ONLY_USED_BY = {"driver": {"nav_msgs"}, "monitor": {"std_srvs"}, "logger": {"diagnostic_msgs"}}


@pytest.mark.parametrize("case", REMOVALS)
def test_remove_nodes(project, case):
    flavor_name, edited, untouched = REMOVALS[case]
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    languages = {name: flavor.language(name) for name in (edited, untouched)}
    kept_lines = edit_user_file(destination, flavor, edited)
    commit_all(destination)

    nodes = [node for node in flavor.answers["nodes"] if node["name"] not in (edited, untouched)]
    result = run_update(destination, {"nodes": nodes})

    # The edited user file is kept, the update fails naming it, and it still holds the user's line.
    assert result.returncode == 1, result
    assert not conflicted_files(destination), conflict_excerpts(destination)
    edited_file = flavor.user_file(edited, languages[edited])
    assert (destination / edited_file).is_file(), f"the user's edited {edited_file} was deleted\n{result}"
    assert f"node '{edited}'" in kept_of(result.output).get(edited_file, ""), result
    assert missing_block(destination / edited_file, kept_lines) is None
    # The untouched one is gone like the rest of both nodes.
    assert not (destination / flavor.user_file(untouched, languages[untouched])).exists(), result
    for name in (edited, untouched):
        assert not (destination / flavor.base_file(name, languages[name])).exists()
        assert not (destination / flavor.config_file(name)).exists()
    remaining = {node["name"] for node in nodes}
    assert set(launched(destination, flavor)) == remaining
    assert build_entries(destination, flavor) == {f"{flavor.language(n)}:{n}" for n in remaining}
    dependencies = dependency_names(destination / flavor.package_xml)
    gone = ONLY_USED_BY[edited] | ONLY_USED_BY[untouched]
    assert not gone & dependencies, f"package.xml still depends on {gone & dependencies}"
    if flavor_name == "ament_cmake":
        cmake = (destination / flavor.build_file).read_text()
        for package in gone:
            assert f"find_package({package} REQUIRED)" not in cmake
        if "monitor" in (edited, untouched):  # the only Python node
            assert "ament_python_install_package" not in cmake
            assert "rclpy" not in dependencies
    readme = (destination / "README.md").read_text()
    for name in (edited, untouched):
        assert f"| `{name}` |" not in readme


# ─── Adding an interface ──────────────────────────────────────────────────────

NEW_INTERFACES = {
    "messages": [{"name": "Target", "fields": ["float64 x", "float64 y"]}],
    "services": [{"name": "SetTarget", "request": ["Target target"], "response": ["bool accepted"]}],
}
INTERFACE_CASES = {  # id -> (flavour, interfaces_location)
    "ament_python-separate": ("ament_python", "separate"),
    "ament_cmake-separate": ("ament_cmake", "separate"),
    "ament_cmake-package": ("ament_cmake", "package"),
    "catkin-separate": ("catkin", "separate"),
    "catkin-package": ("catkin", "package"),
}


def definition_lines(path: Path) -> list[str]:
    return [line for line in path.read_text().splitlines() if line and not line.startswith("#")]


@pytest.mark.parametrize("case", INTERFACE_CASES)
def test_add_an_interface(project, current_template, tmp_path, case):
    flavor_name, location = INTERFACE_CASES[case]
    flavor = Flavor(flavor_name)
    destination = project(flavor_name)
    kept = {name: edit_user_file(destination, flavor, name) for name in ("driver", "monitor")}
    commit_all(destination)

    nodes = flavor.answers["nodes"]
    find_node(nodes, "driver")["publishers"] = [*find_node(nodes, "driver").get("publishers", []), "target:Target"]
    find_node(nodes, "monitor")["service_servers"] = ["set_target:SetTarget"]
    monitor_file = flavor.user_file("monitor")
    imports_old_type = "std_srvs" in (destination / monitor_file).read_text()
    result = run_update(destination, {"interfaces": NEW_INTERFACES, "interfaces_location": location,
                                      "nodes": nodes})
    # The user's monitor still overrides on_reset_request, whose service is gone (dead code
    # in Python): the update names the file to port and fails.
    assert result.returncode == 1, result
    assert "on_reset_request is never called" in to_port_of(result.output).get(monitor_file, ""), result
    assert not conflicted_files(destination), conflict_excerpts(destination)
    if imports_old_type:
        # It still uses the Trigger service it no longer serves, and std_srvs leaves the
        # package's dependencies: the update says that too.
        assert f"your {monitor_file} still imports it" in " ".join(result.stdout.split()), result

    home = PACKAGE if location == "package" else f"{PACKAGE}_interfaces"
    assert definition_lines(destination / home / "msg" / "Target.msg") == ["float64 x", "float64 y"]
    assert definition_lines(destination / home / "srv" / "SetTarget.srv") == ["Target target", "---", "bool accepted"]
    for name, lines in kept.items():
        assert missing_block(destination / flavor.user_file(name), lines) is None

    # The nodes use the new types, and the package depends on (or builds) them.
    driver_base = (destination / flavor.base_file("driver")).read_text()
    monitor_base = (destination / flavor.base_file("monitor")).read_text()
    if flavor.language("driver") == "cpp":
        assert f"#include \"{home}/{'Target.h' if flavor.ros1 else 'msg/target.hpp'}\"" in driver_base
    else:
        assert f"from {home}.msg import Target" in driver_base
    assert f"from {home}.srv import SetTarget" in monitor_base
    dependencies = dependency_names(destination / flavor.package_xml)
    if location == "separate":
        assert f"{PACKAGE}_interfaces" in dependencies
        interfaces_xml = destination / home / "package.xml"
        assert parse_package(str(interfaces_xml)).name == home
    else:
        package = parse_package(str(destination / flavor.package_xml))
        if flavor.ros1:
            assert {"message_generation", "message_runtime"} <= dependencies
        else:
            assert "rosidl_default_generators" in {d.name for d in package.buildtool_depends}
            assert [group.name for group in package.member_of_groups] == ["rosidl_interface_packages"]
        cmake = (destination / flavor.build_file).read_text()
        assert ("add_message_files(" if flavor.ros1 else "rosidl_generate_interfaces(") in cmake

    # Committed, the same package grows no further when updated again with the same answers.
    commit_all(destination, "interfaces added")
    again = run_update(destination, {})
    assert_clean_update(again, destination)
    assert git("status", "--porcelain", cwd=destination).stdout == "", again


# ─── Template upgrades from every release ─────────────────────────────────────


def lived_in_edits(project: Path, flavor: Flavor) -> dict[str, list[str]]:
    """A few edits of every kind of file: user code, a build line, a dependency, a tuned value."""
    kept = {}
    driver = flavor.user_file("driver")
    kept[driver] = edit_user_file(project, flavor, "driver")
    kept[flavor.package_xml] = append_after(project / flavor.package_xml,
                                            "<!-- END rna-template: add your own dependencies below -->",
                                            ["  <depend>tf2_ros</depend>"])
    if flavor.name == "ament_python":
        kept[flavor.build_file] = append_after(project / flavor.build_file,
                                               "# END rna-template: add your own executables below",
                                               ["            'calibrate = robot.calibrate:main',"])
    else:
        kept[flavor.build_file] = append_after(
            project / flavor.build_file, "# END rna-template: add your own targets below",
            ["install(PROGRAMS tools/calibrate.sh DESTINATION share/${PROJECT_NAME})"])
    kept[flavor.config_file("driver")] = replace_text(project / flavor.config_file("driver"),
                                                      "max_speed: 0.5", "max_speed: 0.8")
    commit_all(project, "lived-in edits")
    return kept


@pytest.mark.parametrize("release", RELEASES)
@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_upgrade_from_a_release_keeps_user_edits(project, flavor_name, release):
    flavor = Flavor(flavor_name)
    destination = project(flavor_name, release)
    assert answers_of(destination)["_commit"] == release
    kept = lived_in_edits(destination, flavor)
    user_file_before = (destination / flavor.user_file("driver")).read_text()

    result = run_update(destination, vcs_ref=NEW_VERSION)
    if "CtrlC" in user_file_before:
        # A Python main() of 0.3 imported the base module's CtrlC, which run() has replaced: the
        # update stops with a note to port it, the new starter beside it; everything else is done.
        assert result.returncode == 1, result
        note = to_port_of(result.output)[flavor.user_file("driver")]
        assert "no longer has CtrlC, which your code uses: main() is a call of the base module's run() now" in note
        assert (destination / (flavor.user_file("driver") + ".new-starter")).is_file()
        assert not conflicted_files(destination), conflict_excerpts(destination)
    else:
        assert_clean_update(result, destination)

    assert answers_of(destination)["_commit"] == NEW_VERSION
    assert (destination / flavor.user_file("driver")).read_text() == user_file_before
    missing = [problem for path, lines in kept.items() if (problem := missing_block(destination / path, lines))]
    assert not missing, "\n".join(missing)
    for path, lines in kept.items():  # the user's lines stay outside the managed blocks
        if path.endswith(("package.xml", "setup.py", "CMakeLists.txt")):
            assert lines[0] in unmanaged_lines((destination / path).read_text()), path


def every_endpoint(ros1: bool) -> dict:
    action = "actionlib/action/Test" if ros1 else "test_msgs/action/Fibonacci"
    return {
        "publishers": ["cmd_vel:geometry_msgs/msg/Twist", "chatter:std_msgs/msg/String"],
        "subscribers": ["odom:nav_msgs/msg/Odometry", "/camera/depth/points:sensor_msgs/msg/PointCloud2:sensor_data"],
        "service_servers": ["reset:std_srvs/srv/Trigger", "enable:std_srvs/srv/SetBool"],
        "service_clients": ["arm:std_srvs/srv/SetBool"],
        "action_servers": [f"fibonacci:{action}"],
        "action_clients": [f"compute:{action}"],
        "timers": ["control_loop:0.05", "slow:2"],
        "parameters": [
            {"name": "gain", "type": "double", "default": 2.0, "description": "Proportional gain",
             "range": [0.0, 10.0]},
            "frame_id:string=base_link", "gains:double[]=[1.0, 2.5]",
            {"name": "retries", "default": 3, "read_only": True, "range": [0, 10, 1]}, "verbose=true",
        ],
    }


# Packages that use every kind of endpoint and parameter (and lifecycle nodes and components
# in ROS 2), so that an upgrade has to carry every part of the template.
EVERYTHING = {
    "ament_python": {"package_name": "robot", "build_type": "ament_python", "nodes": [
        {"name": "brain", **every_endpoint(False)},
        {"name": "supervisor", "lifecycle": True, **every_endpoint(False)}]},
    "ament_cmake": {"package_name": "robot", "build_type": "ament_cmake", "nodes": [
        {"name": "driver", "language": "cpp", **every_endpoint(False)},
        {"name": "monitor", "language": "python", **every_endpoint(False)},
        {"name": "supervisor", "language": "cpp", "lifecycle": True, **every_endpoint(False)},
        {"name": "camera", "component": True, "publishers": ["image:sensor_msgs/msg/Image:sensor_data"],
         "timers": [0.033]}]},
    "catkin": {"package_name": "robot", "ros_distro": "noetic", "nodes": [
        {"name": "driver", "language": "cpp", **every_endpoint(True)},
        {"name": "monitor", "language": "python", **every_endpoint(True)}]},
}


@pytest.mark.parametrize("release", RELEASES)
@pytest.mark.parametrize("package", ["base", "every-endpoint"])
@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_upgrade_parity_with_a_fresh_copy(project, release_template, tmp_path, flavor_name, package, release):
    """An untouched package made by a release and updated to the working tree equals a fresh copy of it."""
    if package == "base":
        destination = project(flavor_name, release)
    else:
        destination = generate_project(release_template, tmp_path / "project", EVERYTHING[flavor_name],
                                       vcs_ref=release)

    result = run_update(destination)
    assert_clean_update(result, destination)

    assert answers_of(destination)["_commit"] == NEW_VERSION
    differences = fresh_copy_differences(destination, release_template, tmp_path, NEW_VERSION)
    assert differences == [], "\n".join(differences) + f"\n{result}"


def test_migration_to_0_2_0_renames_catkin_targets_in_user_lines(project):
    """0.2.0 names catkin C++ targets <package>_<node>; a user's own line naming the old target follows."""
    destination = project("catkin", OLD_VERSION)
    cmake = destination / Flavor("catkin").build_file
    append_after(cmake, "# END rna-template: add your own targets below",
                 ["target_compile_options(driver PRIVATE -O2)"])
    commit_all(destination)
    result = run_update(destination, vcs_ref=NEW_VERSION)
    assert_clean_update(result, destination)
    text = cmake.read_text()
    assert "target_compile_options(${PROJECT_NAME}_driver PRIVATE -O2)" in text
    assert "add_executable(${PROJECT_NAME}_driver src/driver.cpp)" in text
    assert "renamed in your lines" in result.stdout


def test_target_renaming_leaves_managed_blocks_and_other_names_alone():
    from migrate_0_2_0 import rename_targets

    text = ("# BEGIN rna-template: the nodes\nadd_executable(${PROJECT_NAME}_driver src/driver.cpp)\n"
            "# END rna-template: add your own targets below\n"
            "target_link_libraries(driver ${Boost_LIBRARIES})\ninstall(TARGETS driver_tool DESTINATION bin)\n"
            "install(TARGETS driver RUNTIME DESTINATION bin)\n")
    renamed, changes = rename_targets(text, ["driver"])
    assert "target_link_libraries(${PROJECT_NAME}_driver ${Boost_LIBRARIES})" in renamed
    assert "install(TARGETS ${PROJECT_NAME}_driver RUNTIME" in renamed
    assert "install(TARGETS driver_tool DESTINATION bin)" in renamed
    assert renamed.startswith("# BEGIN rna-template: the nodes\nadd_executable(${PROJECT_NAME}_driver")
    assert changes == ["driver -> ${PROJECT_NAME}_driver (2x)"]
    assert rename_targets(renamed, ["driver"]) == (renamed, [])
