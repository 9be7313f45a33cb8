"""How fast rna-template generates and updates packages, against Copier's floor and a peer (issue 12).

    tests/env python tests/tools/benchmark.py [--runs N] [--warmup N] [--quick] [--only NAME ...]
                                              [--json out.json] [--template DIR] [--profile]
                                              [--instructions]

Every case is a whole `copier` process (wall time from outside, CPU time and peak RSS of
the process tree from os.wait4), run from a local git repository of the template tagged
with the current version, into a fresh folder, with machine-independent answers from a
--data-file. The cases are run round after round, each round in a rotated order, after
--warmup rounds that are not counted; the tables show medians and the spread (min..max).

The template is the whole working tree of --template (default: this repository; files
git ignores left out), committed into a temporary repository with packed objects, as a
user's clone would be, and tagged with the current version: uncommitted changes count.

Groups of cases (--only takes a group or a case name; --quick = the `default` group, one
run, no warm-up):

  default   the default package vs a one-file Copier template (the floor), and the same
            package with no compiled code kept from earlier runs (a first run); the floor
            again in a repository of this one's files (what Copier's checkout of a
            repository this size costs, whatever the template renders)
  node      one C++ node with every feature vs ros2-pkg-create 1.3.0 (own venv, cached;
            its older Copier's floor is measured too)
  scale     packages with 1, 10, 50 and 100 nodes
  update    `copier update` adding a node to a 20-node ament_cmake package vs copying it,
            and Copier's own update and copy of a one-file template (the update's floor)
  catkin    the same for a 20-node catkin (noetic) package
  large     the ament_cmake update again, the package holding a 200 MB bag of the user's
            (random bytes, committed): a file the update must not read nor slow down on

The template keeps compiled code between runs (extensions/patches/code_cache.py): here in the
scratch folder, filled by one copy before the rounds; `default_cold` runs with it off.

--profile adds where the time goes for the default package, 1 and 50 nodes and the updates
(tests/tools/profiling.py). --instructions also runs each case once under valgrind's
callgrind and counts the instructions of its whole process tree (git included): a
figure that does not move with the machine's load or speed, as wall time does here, but
that leaves out the kernel's work (the disk) and what waits. No test asserts on these figures.
"""

from __future__ import annotations

import argparse
import contextlib
import datetime
import fcntl
import importlib.metadata
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import yaml

TESTS = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(TESTS))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from support.generation import FIXED_ANSWERS, GIT_IDENTITY, ROOT  # noqa: E402
from support.ros2 import default_cache_root  # noqa: E402
from support.template_repo import NEW_VERSION, generate_project, git  # noqa: E402

PEER = "ros2-pkg-create==1.3.0"
PEER_VENV = "bench-ros2-pkg-create"

# ─── The answers of each case ─────────────────────────────────────────────────


def scaled_node(index: int) -> dict:
    """The n-th node of the scaled packages: C++ and Python in turn, a little of everything common."""
    name = f"node_{index:03d}"
    return {"name": name, "language": "cpp" if index % 2 else "python",
            "publishers": [f"{name}_out:std_msgs/msg/String"], "subscribers": [f"{name}_in:std_msgs/msg/String"],
            "timers": [0.5], "parameters": ["rate:double=10.0"]}


def scaled_package(nodes: int, ros1: bool = False) -> dict:
    target = {"ros_distro": "noetic"} if ros1 else {"build_type": "ament_cmake"}
    return {"package_name": "robot", **target, "nodes": [scaled_node(i) for i in range(1, nodes + 1)]}


# ros2-pkg-create's C++ package with every feature: a node with a publisher and a
# subscriber (geometry_msgs/PointStamped), a std_srvs/SetBool service, a Fibonacci action
# defined in a <package>_interfaces package beside it, a timer, a parameter and a launch
# file. The same here (a launch file and a config file come with every package).
ALL_FEATURES = {
    "package_name": "robot", "build_type": "ament_cmake",
    "interfaces": {"actions": [{"name": "Fibonacci", "goal": ["int32 order"], "result": ["int32[] sequence"],
                                "feedback": ["int32[] partial_sequence"]}]},
    "interfaces_location": "separate",
    "nodes": [{"name": "driver", "language": "cpp",
               "publishers": ["output:geometry_msgs/msg/PointStamped"],
               "subscribers": ["input:geometry_msgs/msg/PointStamped"],
               "service_servers": ["set_enabled:std_srvs/srv/SetBool"],
               "action_servers": ["fibonacci:Fibonacci"],
               "timers": [0.1], "parameters": ["param:double=1.0"]}],
}
PEER_ARGS = ["--defaults", "--use-local-templates", "--template", "ros2_cpp_pkg", "--package-name", "robot",
             "--description", "A robot", "--maintainer", FIXED_ANSWERS["maintainer"],
             "--maintainer-email", FIXED_ANSWERS["maintainer_email"], "--author", FIXED_ANSWERS["maintainer"],
             "--author-email", FIXED_ANSWERS["maintainer_email"], "--license", "Apache-2.0", "--node-name", "driver",
             "--has-launch-file", "--launch-file-type", "xml", "--has-params", "--has-subscriber", "--has-publisher",
             "--has-service-server", "--has-action-server", "--has-timer"]

FLOOR_FILES = {"copier.yml": "_subdirectory: template\nname:\n  type: str\n  default: demo\n",
               "template/README.md.jinja": "# {{ name }}\n"}
# The floor again, in a repository with every file of this one beside it (docs, tests, the
# template's own files under template/, none of them rendered): Copier checks out a
# template's whole repository, so this is the floor a template of this repository's size
# starts from, whatever it renders.
FLOOR_IN_REPOSITORY_FILES = {"copier.yml": "_subdirectory: floor\nname:\n  type: str\n  default: demo\n",
                             "floor/README.md.jinja": "# {{ name }}\n"}
# The floor of an update: the same, recording its answers (Copier updates only such a project).
FLOOR_UPDATE_FILES = {**FLOOR_FILES,
                      "template/{{ _copier_conf.answers_file }}.jinja": "{{ _copier_answers|to_nice_yaml }}\n"}
UPDATE_NODES = 20
LARGE_FILE = 200 * 10**6  # bytes: a bag or map of the user's, committed in the package

# ─── Measuring one process ────────────────────────────────────────────────────


@dataclass
class Sample:
    wall: float  # seconds
    cpu: float  # user + system seconds of the process and the processes it waited for
    rss: float | None  # MiB: the peak resident set of the largest process of the tree


# GNU time reports the peak RSS of a process it forked itself. os.wait4 on a child of this
# (larger) process would report at least this process's size: Python starts children with
# vfork, and Linux keeps the parent's high-water mark across the exec.
GNU_TIME = shutil.which("time", path="/usr/bin:/bin")


def measure(argv: list[str], cwd: Path, env: dict[str, str]) -> Sample:
    """Run `argv` to the end: its wall time, CPU time (os.wait4) and peak RSS (GNU time)."""
    with tempfile.TemporaryFile() as output, tempfile.NamedTemporaryFile("r") as peak:
        command = [GNU_TIME, "--quiet", "-f", "%M", "-o", peak.name, *argv] if GNU_TIME else argv
        start = time.perf_counter()
        process = subprocess.Popen(command, cwd=cwd, env=env, stdin=subprocess.DEVNULL, stdout=output,
                                   stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.perf_counter() - start
        process.returncode = os.waitstatus_to_exitcode(status)
        if process.returncode != 0:
            output.seek(0)
            raise RuntimeError(f"exit code {process.returncode}: {' '.join(argv)}\n"
                               f"{output.read().decode(errors='replace')[-4000:]}")
        rss = int(peak.read().split()[-1]) / 1024 if GNU_TIME else None
    return Sample(wall, usage.ru_utime + usage.ru_stime, rss)


VALGRIND = shutil.which("valgrind")


def count_instructions(argv: list[str], cwd: Path, env: dict[str, str], scratch: Path) -> int:
    """Run `argv` under callgrind: the instructions its process and every child executed."""
    scratch.mkdir(parents=True, exist_ok=True)
    command = [VALGRIND, "--tool=callgrind", "--trace-children=yes", "-q",
               f"--callgrind-out-file={scratch}/callgrind.%p", *argv]
    # A fixed hash seed: Python's sets and dicts of strings then do the same work every run.
    result = subprocess.run(command, cwd=cwd, env={**env, "PYTHONHASHSEED": "0"}, stdin=subprocess.DEVNULL,
                            capture_output=True, text=True, check=False, timeout=1800)
    if result.returncode != 0:
        raise RuntimeError(f"exit code {result.returncode} under callgrind: {' '.join(argv)}\n"
                           f"{(result.stdout + result.stderr)[-4000:]}")
    total = callgrind_total([path.read_text() for path in scratch.glob("callgrind.*")])
    shutil.rmtree(scratch)
    return total


def callgrind_total(outputs: list[str]) -> int:
    """The instructions counted in callgrind's output files (one per process), summed."""
    return sum(int(line.split()[1]) for output in outputs for line in output.splitlines()
               if line.startswith("summary:"))


# ─── Cases ────────────────────────────────────────────────────────────────────


@dataclass
class Case:
    name: str
    group: str
    label: str
    prepare: Callable[[Path], tuple[list[str], Path]]  # a fresh folder -> (command, working dir)
    produces: str  # a path (relative to the fresh folder) that must exist afterwards
    samples: list[Sample] = field(default_factory=list)
    env: dict[str, str] = field(default_factory=dict)  # over the bench's environment
    instructions: int | None = None  # counted by callgrind, once

    def run(self, folder: Path, env: dict[str, str]) -> Sample:
        return self._run_with(measure, folder, env)

    def count(self, folder: Path, env: dict[str, str]) -> None:
        self.instructions = self._run_with(
            lambda argv, cwd, env: count_instructions(argv, cwd, env, folder.with_name(f"{folder.name}-callgrind")),
            folder, env)

    def _run_with(self, run: Callable, folder: Path, env: dict[str, str]):
        folder.mkdir(parents=True)
        argv, cwd = self.prepare(folder)
        result = run(argv, cwd, {**env, **self.env})
        if not (folder / self.produces).exists():
            raise RuntimeError(f"{self.name}: {self.produces} is missing after {' '.join(argv)}")
        return result

    def median(self, attribute: str) -> float | None:
        """The median of a measure of the samples; "instructions", the one count."""
        if attribute == "instructions":
            return self.instructions
        values = [getattr(s, attribute) for s in self.samples]
        return None if not values or None in values else statistics.median(values)

    def spread(self) -> tuple[float, float]:
        walls = [s.wall for s in self.samples]
        return min(walls), max(walls)


@dataclass(frozen=True)
class Comparison:
    label: str
    case: str
    reference: str
    goal: float | None = None  # the largest ratio that meets the goal
    floors: tuple[str, str] | None = None  # divide each side by its own floor first


COMPARISONS = (
    Comparison("default package / one-file template (floor)", "default", "floor", 1.15),
    Comparison("the same, a first run (no compiled code kept) / floor", "default_cold", "floor"),
    Comparison("the floor in a repository of this one's files / floor", "floor_in_repository", "floor"),
    Comparison("default package / the floor in a repository of this one's files", "default", "floor_in_repository"),
    Comparison("all-features C++ node / ros2-pkg-create 1.3.0", "node_all", "ros2_pkg_create", 1.0),
    Comparison("ros2-pkg-create / its Copier's floor (same kind of source: a folder)", "ros2_pkg_create",
               "floor_peer_dir"),
    Comparison("all-features C++ node / floor", "node_all", "floor"),
    Comparison("the same, each over its own Copier's floor (git / folder)", "node_all", "ros2_pkg_create",
               floors=("floor", "floor_peer_dir")),
    Comparison("peer Copier's floor (git) / this Copier's floor", "floor_peer_git", "floor"),
    Comparison("10 nodes / 1 node", "nodes_10", "nodes_1"),
    Comparison("50 nodes / 1 node", "nodes_50", "nodes_1", 1.5),
    Comparison("100 nodes / 1 node", "nodes_100", "nodes_1"),
    Comparison("update +1 node / copy, 20-node ament_cmake", "update_20", "copy_20", 3.0),
    Comparison("update +1 node / copy, 20-node catkin", "update_20_catkin", "copy_20_catkin", 3.0),
    Comparison("Copier's own: update / copy, one-file template (its floor)", "floor_update", "floor_copy"),
    Comparison("update +1 node, 20-node ament_cmake / Copier's own update", "update_20", "floor_update"),
    Comparison("update +1 node, the package holding a 200 MB bag / without", "update_20_large", "update_20", 1.1),
)
GROUPS = ("default", "node", "scale", "update", "catkin", "large")  # CASE_GROUPS names their cases


class Bench:
    """The template repositories, answers and base projects the cases run from, in `work`."""

    def __init__(self, work: Path, template_source: Path, groups: set[str]):
        self.work = work
        self.env = {**os.environ, **GIT_IDENTITY, "NO_COLOR": "1", "GIT_CONFIG_NOSYSTEM": "1",
                    "COPIER_SETTINGS_PATH": str(work / "copier-settings.yml"),
                    "RNA_TEMPLATE_CACHE_DIR": str(work / "code-cache")}
        self.env.pop("RNA_BENCH_PROFILE_DIR", None)
        (work / "copier-settings.yml").write_text("{}\n")
        self.copier = str(Path(sys.executable).with_name("copier"))
        self.template = self._template_repo(template_source)
        self.floor = self._floor_repo("floor", FLOOR_FILES)
        self.floor_in_repository = self._template_repo(template_source, "floor-in-repository",
                                                       FLOOR_IN_REPOSITORY_FILES)
        self.data = work / "data"
        self.data.mkdir()
        self.peer: Path | None = None
        self.peer_error = ""
        if "node" in groups:
            try:
                self.peer = peer_venv()
            except (OSError, subprocess.CalledProcessError) as error:
                self.peer_error = f"{PEER} could not be installed: {error}"
        self.bases = {}
        for group, ros1 in (("update", False), ("catkin", True)):
            if group in groups:
                destination = work / f"base-{group}" / "project"
                self.bases[group] = generate_project(self.template, destination, scaled_package(UPDATE_NODES, ros1),
                                                     vcs_ref=NEW_VERSION)
        if "large" in groups:
            self.bases["large"] = self._with_large_file(self.bases["update"], work / "base-large" / "project")
        if "update" in groups:
            self.floor_for_update = self._floor_repo("floor-update", FLOOR_UPDATE_FILES)
            self.bases["floor"] = generate_project(self.floor_for_update, work / "base-floor" / "project",
                                                   {"name": "demo"}, vcs_ref="v1.0.0")

    def fill_code_cache(self) -> None:
        """One copy not measured, so that the cases find the template's compiled code kept, as
        every run after a user's first does (without it, the first round would compile)."""
        folder = self.work / "fill-code-cache"
        folder.mkdir()
        argv, cwd = self.copy(self.template, self.data_file("default", {}))(folder)
        measure(argv, cwd, self.env)
        shutil.rmtree(folder)

    def _template_repo(self, source: Path, name: str = "template", replaced: dict[str, str] | None = None) -> Path:
        """The whole repository as a user's clone has it (docs and tests too), working tree
        included; `replaced` files (path: text) written over it."""
        destination = self.work / name
        listed = git("ls-files", "-z", "--cached", "--others", "--exclude-standard", cwd=source).stdout
        for path in filter(None, listed.split("\0")):
            if (source / path).is_file():
                (destination / path).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(source / path, destination / path)
        for path, text in (replaced or {}).items():
            (destination / path).parent.mkdir(parents=True, exist_ok=True)
            (destination / path).write_text(text)
        commit_repository(destination, f"rna-template {NEW_VERSION} (benchmark snapshot)", NEW_VERSION)
        return destination

    @staticmethod
    def _with_large_file(base: Path, destination: Path) -> Path:
        """`base` with a bag of LARGE_FILE random bytes (no compression spares git anything) committed."""
        project = shutil.copytree(base, destination, symlinks=True)
        bag = project / "robot" / "bags" / "drive.bag"
        bag.parent.mkdir()
        with bag.open("wb") as out:
            for _ in range(LARGE_FILE // 10**6):
                out.write(os.urandom(10**6))
        git("add", "-A", cwd=project)
        git("commit", "-q", "-m", "a drive recorded", cwd=project)
        return project

    def _floor_repo(self, name: str, files: dict[str, str]) -> Path:
        destination = self.work / name
        for path, text in files.items():
            (destination / path).parent.mkdir(parents=True, exist_ok=True)
            (destination / path).write_text(text)
        shutil.copytree(destination, self.work / f"{name}-folder")  # the same, without git
        commit_repository(destination, "one-file template", "v1.0.0")
        return destination

    def data_file(self, name: str, answers: dict, fixed: bool = True) -> Path:
        path = self.data / f"{name}.yml"
        path.write_text(yaml.safe_dump({**(FIXED_ANSWERS if fixed else {}), **answers}, sort_keys=False))
        return path

    def copy(self, template: Path, data: Path, copier: str | None = None):
        def prepare(folder: Path) -> tuple[list[str], Path]:
            return ([copier or self.copier, "copy", "--trust", "--defaults", "--quiet", "--data-file", str(data),
                     str(template), str(folder / "project")], folder)
        return prepare

    def update(self, group: str, data: Path):
        def prepare(folder: Path) -> tuple[list[str], Path]:
            project = shutil.copytree(self.bases[group], folder / "project", symlinks=True)
            return [self.copier, "update", "--trust", "--defaults", "--quiet", "--data-file", str(data)], project
        return prepare

    def cases(self) -> list[Case]:
        floor_data = self.data / "floor.yml"
        floor_data.write_text("name: demo\n")
        cases = [
            Case("floor", "default", f"one-file template (the floor), Copier {copier_version()}",
                 self.copy(self.floor, floor_data), "project/README.md"),
            Case("floor_in_repository", "default", "the floor in a repository of this one's files",
                 self.copy(self.floor_in_repository, floor_data), "project/README.md"),
            Case("default", "default", "default package (talker + listener)",
                 self.copy(self.template, self.data_file("default", {})), "project/project/package.xml"),
            Case("default_cold", "default", "the same, a first run: no compiled code kept",
                 self.copy(self.template, self.data_file("default", {})), "project/project/package.xml",
                 env={"RNA_TEMPLATE_CACHE_DIR": ""}),
            Case("node_all", "node", "all-features C++ node + interfaces package",
                 self.copy(self.template, self.data_file("node_all", ALL_FEATURES)),
                 "project/robot_interfaces/action/Fibonacci.action"),
        ]
        if self.peer is not None:
            peer_copier = str(self.peer / "bin" / "copier")
            cases += [
                Case("ros2_pkg_create", "node", f"ros2-pkg-create {PEER.split('==')[1]}, same features",
                     lambda folder: ([str(self.peer / "bin" / "ros2-pkg-create"), *PEER_ARGS, str(folder / "project")],
                                     folder), "project/robot_interfaces/action/Fibonacci.action"),
                Case("floor_peer_git", "node", f"floor with ros2-pkg-create's Copier {peer_copier_version(self.peer)}",
                     self.copy(self.floor, floor_data, peer_copier), "project/README.md"),
                Case("floor_peer_dir", "node", "the same, from a folder (as ros2-pkg-create runs)",
                     self.copy(self.work / "floor-folder", floor_data, peer_copier), "project/README.md"),
            ]
        if "floor" in self.bases:
            cases += [
                Case("floor_copy", "update", "copy: one-file template recording its answers",
                     self.copy(self.floor_for_update, floor_data), "project/.copier-answers.yml"),
                Case("floor_update", "update", "update: the same, one answer changed",
                     self.update("floor", self.data_file("floor_update", {"name": "changed"}, fixed=False)),
                     "project/README.md"),
            ]
        for count in (1, 10, 50, 100):
            cases.append(Case(f"nodes_{count}", "scale", f"ament_cmake package, {count} node(s)",
                              self.copy(self.template, self.data_file(f"nodes_{count}", scaled_package(count))),
                              f"project/robot/config/node_{count:03d}.yaml"))
        added = f"node_{UPDATE_NODES + 1:03d}"
        for group, ros1, suffix, kind in (("update", False, "", "ament_cmake"), ("catkin", True, "_catkin", "catkin")):
            answers = scaled_package(UPDATE_NODES, ros1)
            cases.append(Case(f"copy_20{suffix}", group, f"copy: {kind} package, 20 nodes",
                              self.copy(self.template, self.data_file(f"copy_20{suffix}", answers)),
                              f"project/robot/config/node_{UPDATE_NODES:03d}.yaml"))
            grown = scaled_package(UPDATE_NODES + 1, ros1)
            cases.append(Case(f"update_20{suffix}", group, f"update: add a node to the {kind} package",
                              self.update(group, self.data_file(f"update_20{suffix}", {"nodes": grown["nodes"]})),
                              f"project/robot/config/{added}.yaml"))
        if "large" in self.bases:
            cases.append(Case("update_20_large", "large", "update: the same, the package holding a 200 MB bag",
                              self.update("large", self.data_file("update_20", {"nodes": scaled_package(
                                  UPDATE_NODES + 1)["nodes"]})), f"project/robot/config/{added}.yaml"))
        return cases


def commit_repository(folder: Path, message: str, tag: str) -> None:
    """Commit `folder` in a new repository, tagged, its objects packed as in a clone."""
    git("init", "-q", "-b", "main", cwd=folder)
    git("add", "-A", cwd=folder)
    git("commit", "-q", "-m", message, cwd=folder)
    git("tag", "-a", tag, "-m", message, cwd=folder)
    git("repack", "-a", "-d", "-q", cwd=folder)
    git("prune-packed", cwd=folder)


# ─── The peer, in a virtual environment of its own ────────────────────────────


def peer_venv() -> Path:
    """ros2-pkg-create in its own venv (it pins an older Copier), made once and cached."""
    root = default_cache_root()
    root.mkdir(parents=True, exist_ok=True)
    venv = root / PEER_VENV
    stamp = venv / ".rna-bench-installed"
    with (root / f"{PEER_VENV}.lock").open("a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if stamp.is_file() and stamp.read_text() == PEER:
            return venv
        print(f"benchmark: installing {PEER} in {venv}", file=sys.stderr)
        subprocess.run([sys.executable, "-m", "venv", "--clear", str(venv)], check=True)
        subprocess.run([str(venv / "bin" / "python"), "-m", "pip", "install", "--quiet", "--disable-pip-version-check",
                        PEER], check=True, stdout=subprocess.DEVNULL)
        stamp.write_text(PEER)
    return venv


def copier_version() -> str:
    return importlib.metadata.version("copier")


def peer_copier_version(venv: Path) -> str:
    return subprocess.run([str(venv / "bin" / "python"), "-c",
                           "import importlib.metadata as m; print(m.version('copier'))"],
                          capture_output=True, text=True, check=True).stdout.strip()


# ─── Running and reporting ────────────────────────────────────────────────────


def run_rounds(cases: list[Case], bench: Bench, runs: int, warmup: int) -> None:
    """Every case once per round, each round in a rotated order; the warm-up rounds are dropped."""
    scratch = bench.work / "runs"
    for round_index in range(warmup + runs):
        shift = round_index % len(cases)
        order = cases[shift:] + cases[:shift]
        counted = round_index >= warmup
        print(f"benchmark: round {round_index + 1}/{warmup + runs}{'' if counted else ' (warm-up)'}",
              file=sys.stderr, flush=True)
        for case in order:
            folder = scratch / case.name
            sample = case.run(folder, bench.env)
            shutil.rmtree(folder)
            if counted:
                case.samples.append(sample)


def machine() -> dict:
    model = next((line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                  if line.startswith("model name")), platform.processor())
    git_version = subprocess.run(["git", "--version"], capture_output=True, text=True).stdout.strip()
    return {"cpu": model, "cores": os.cpu_count(), "python": platform.python_version(),
            "system": f"{platform.system()} {platform.release()}", "git": git_version,
            "copier": copier_version(),
            "copier-template-extensions": importlib.metadata.version("copier-template-extensions"),
            "jinja2": importlib.metadata.version("jinja2")}


def ratio(comparison: Comparison, cases: dict[str, Case], measure: str) -> float:
    """The ratio of the two cases' medians of `measure` ("wall", "cpu", or the "instructions" counted),
    each over its floor if asked."""
    value = cases[comparison.case].median(measure) / cases[comparison.reference].median(measure)
    if comparison.floors:
        value /= cases[comparison.floors[0]].median(measure) / cases[comparison.floors[1]].median(measure)
    return value


def comparisons(cases: dict[str, Case]) -> list[dict]:
    rows = []
    for comparison in COMPARISONS:
        needed = [comparison.case, comparison.reference, *(comparison.floors or ())]
        if not all(name in cases and cases[name].samples for name in needed):
            continue
        wall = ratio(comparison, cases, "wall")
        rows.append({"label": comparison.label, "case": comparison.case, "reference": comparison.reference,
                     "case_wall": cases[comparison.case].median("wall"),
                     "reference_wall": cases[comparison.reference].median("wall"),
                     "ratio": wall, "cpu_ratio": ratio(comparison, cases, "cpu"), "goal": comparison.goal,
                     "met": None if comparison.goal is None else wall <= comparison.goal})
    return rows


def instruction_comparisons(cases: dict[str, Case]) -> list[dict]:
    """The comparisons again, in instructions counted (the goals are the wall time's)."""
    return [{"label": comparison.label, "case": comparison.case, "reference": comparison.reference,
             "ratio": ratio(comparison, cases, "instructions"), "goal": comparison.goal}
            for comparison in COMPARISONS
            if all(name in cases and cases[name].instructions
                   for name in (comparison.case, comparison.reference, *(comparison.floors or ())))]


def count_cases(cases: list[Case], bench: Bench) -> None:
    """Each case once under callgrind, two at a time (the counts do not depend on the load).

    Each case first runs once uncounted: the template's compiled code is kept per template
    file, so a case that is the first of its kind (a catkin package, a C++ node) would
    otherwise count the compiling, and which case comes first would change the counts.
    """
    from concurrent.futures import ThreadPoolExecutor

    scratch = bench.work / "counted"
    for case in cases:
        case.run(scratch / f"{case.name}-warm-up", bench.env)
        shutil.rmtree(scratch / f"{case.name}-warm-up")
    print(f"benchmark: counting instructions under callgrind, {len(cases)} case(s), each 40 to 60 times "
          "slower than its run", file=sys.stderr, flush=True)
    with ThreadPoolExecutor(max_workers=min(2, os.cpu_count() or 1)) as pool:
        for future in [pool.submit(case.count, scratch / case.name, bench.env) for case in cases]:
            future.result()


def print_instruction_tables(cases: list[Case], rows: list[dict]) -> None:
    print("\ninstructions counted by callgrind, one run each, whole process tree (git included; "
          "the kernel's work is not counted)\n")
    print(f"| {'case':<66} | instructions (millions) |")
    print(f"| {'-' * 66} | ----------------------: |")
    for case in cases:
        if case.instructions:
            print(f"| {case.name + ': ' + case.label:<66} | {case.instructions / 1e6:23,.0f} |")
    if rows:
        print(f"\n| {'ratio of instructions':<68} | ratio  | goal (wall time's) |")
        print(f"| {'-' * 68} | -----: | ------------------ |")
        for row in rows:
            goal = f"<= {row['goal']:.2f}" if row["goal"] is not None else ""
            print(f"| {row['label']:<68} | {row['ratio']:5.2f}x | {goal:<18} |")


def rss(megabytes: float | None) -> str:
    return "n/a (no GNU time)" if megabytes is None else f"{megabytes:.0f}"


def print_tables(cases: list[Case], rows: list[dict], runs: int, warmup: int) -> None:
    print(f"\nrna-template benchmark: medians of {runs} interleaved run(s) after {warmup} warm-up round(s); "
          f"load average now {os.getloadavg()[0]:.2f}\n")
    print(f"| {'case':<66} | wall s | spread (min..max) | CPU s | peak RSS MiB |")
    print(f"| {'-' * 66} | -----: | ----------------- | ----: | -----------: |")
    for case in cases:
        if case.samples:
            low, high = case.spread()
            print(f"| {case.name + ': ' + case.label:<66} | {case.median('wall'):6.3f} | "
                  f"{low:7.3f}..{high:<8.3f} | {case.median('cpu'):5.2f} | {rss(case.median('rss')):>12} |")
    if rows:
        print(f"\n| {'ratio of medians (wall time; CPU time beside it)':<68} | case s | reference s | ratio  | "
              "CPU ratio | goal    | met |")
        print(f"| {'-' * 68} | -----: | ----------: | -----: | --------: | ------- | --- |")
        for row in rows:
            goal = f"<= {row['goal']:.2f}" if row["goal"] is not None else ""
            met = "" if row["met"] is None else ("yes" if row["met"] else "no")
            print(f"| {row['label']:<68} | {row['case_wall']:6.3f} | {row['reference_wall']:11.3f} | "
                  f"{row['ratio']:5.2f}x | {row['cpu_ratio']:8.2f}x | {goal:<7} | {met:<3} |")


def parse_arguments(argv: list[str] | None = None) -> argparse.Namespace:
    names = [*GROUPS, *(name for members in CASE_GROUPS.values() for name in members if name not in GROUPS)]
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=5, help="counted rounds (default 5)")
    parser.add_argument("--warmup", type=int, default=1, help="rounds run first and not counted (default 1)")
    parser.add_argument("--quick", action="store_true", help="the default group only, one run, no warm-up")
    parser.add_argument("--only", action="append", choices=names, metavar="NAME",
                        help=f"a group or case to run (repeatable): {', '.join(names)}")
    parser.add_argument("--json", type=Path, help="also write the figures to this JSON file")
    parser.add_argument("--template", type=Path, default=ROOT, help="the template's working tree (default: here)")
    parser.add_argument("--instructions", action="store_true",
                        help="then count each case's instructions once under valgrind's callgrind")
    parser.add_argument("--profile", action="store_true",
                        help="then profile the default package, 1 and 50 nodes and the updates "
                             "(tests/tools/profiling.py)")
    arguments = parser.parse_args(argv)
    if arguments.quick:
        arguments.runs, arguments.warmup, arguments.only = 1, 0, arguments.only or ["default"]
    return arguments


def selected(only: list[str] | None) -> set[str]:
    """The cases to run: the named ones and the groups' ones, each with the case it is compared with."""
    names = set()
    for name in only or GROUPS:
        names.update(CASE_GROUPS.get(name, (name,)))
    return names | {c.reference for c in COMPARISONS if c.case in names and not c.floors}


def main(argv: list[str] | None = None) -> int:
    arguments = parse_arguments(argv)
    names = selected(arguments.only)
    groups = {group for group, members in CASE_GROUPS.items() if not names.isdisjoint(members)}
    started = datetime.datetime.now().astimezone()
    load_before = os.getloadavg()
    if load_before[0] > (os.cpu_count() or 1) / 2:
        print(f"benchmark: load average {load_before[0]:.1f} on {os.cpu_count()} cores: other work competes, "
              "so the figures will spread; the ratios of medians suffer least", file=sys.stderr)
    with tempfile.TemporaryDirectory(prefix="rna-bench-") as scratch:
        bench = Bench(Path(scratch), arguments.template.resolve(), groups)
        if bench.peer_error:
            print(f"benchmark: {bench.peer_error}; the peer's cases are left out", file=sys.stderr)
        cases = [case for case in bench.cases() if case.name in names]
        bench.fill_code_cache()
        run_rounds(cases, bench, arguments.runs, arguments.warmup)
        rows = comparisons({case.name: case for case in cases})
        if arguments.runs:
            print_tables(cases, rows, arguments.runs, arguments.warmup)
        counted_rows = []
        if arguments.instructions:
            if VALGRIND is None:
                print("benchmark: valgrind is not installed (apt-get install valgrind): no instructions counted",
                      file=sys.stderr)
            else:
                count_cases(cases, bench)
                counted_rows = instruction_comparisons({case.name: case for case in cases})
                print_instruction_tables(cases, counted_rows)
        profile = None
        if arguments.profile:
            import profiling

            profile = profiling.profile_cases([case for case in cases if case.name in profiling.PROFILED], bench.env)
        peer = {"package": PEER, "copier": peer_copier_version(bench.peer)} if bench.peer else None
    if arguments.json:
        result = {
            "date": started.isoformat(timespec="seconds"), "machine": machine(), "peer": peer,
            "runs": arguments.runs, "warmup": arguments.warmup,
            "load_average": {"before": load_before, "after": os.getloadavg()},
            "cases": {case.name: {"label": case.label, "group": case.group,
                                  "median": {key: case.median(key) for key in ("wall", "cpu", "rss")},
                                  "samples": [vars(sample) for sample in case.samples],
                                  "instructions": case.instructions}
                      for case in cases if case.samples or case.instructions},
            "comparisons": rows, "instruction_comparisons": counted_rows, "profile": profile,
        }
        arguments.json.write_text(json.dumps(result, indent=2) + "\n")
    return 0


CASE_GROUPS = {
    "default": ("floor", "floor_in_repository", "default", "default_cold"),
    "node": ("node_all", "ros2_pkg_create", "floor_peer_git", "floor_peer_dir"),
    "scale": ("nodes_1", "nodes_10", "nodes_50", "nodes_100"),
    "update": ("copy_20", "update_20", "floor_copy", "floor_update"),
    "catkin": ("copy_20_catkin", "update_20_catkin"),
    "large": ("update_20_large",),
}

if __name__ == "__main__":
    with contextlib.suppress(KeyboardInterrupt):
        sys.exit(main())
