"""Template repositories, generated projects and `copier update` runs for the update tests.

`copier update` needs what a real user has: a template in git with version tags, and a
project that is a clean git repository generated from one of those tags. This module
builds both in temporary folders:

* `snapshot_repo()`: the working tree's template (copier.yml, template/, extensions/)
  committed in a fresh repository and tagged as the version after the newest release
  (`NEW_VERSION`, e.g. v0.3.1 after 0.3.0);
* `release_history_repo()`: every real release of this repository (`git archive` of the
  commit the changelog names, support/releases.py), oldest first, each committed and
  tagged, with the working tree committed on top and tagged `NEW_VERSION`, so an update
  from any release users have runs over real history;
* `generate_project()`: `copier copy` from one tag with machine-independent answers, then
  `git init` and a commit;
* `run_update()`: the `copier` command line, `copier update --trust --defaults`, as a
  subprocess with stdin closed;
* `append_after()`, `insert_before()`, `replace_text()`: user edits that fail loudly when
  the text they are anchored to is missing, so a template change never turns a scenario
  into one that silently edits nothing.

It is also a pytest plugin (`pytest_plugins = ("support.template_repo",)`): session
fixtures build each template repository and each base project once, and `project()` hands
every test its own copy.
"""

from __future__ import annotations

import copy
import io
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
from dataclasses import dataclass
from pathlib import Path

import pytest
import yaml
from catkin_pkg.package import parse_package

from .generation import (
    ANSWERS_FILE, FIXED_ANSWERS, ROOT, TEMPLATE_ITEMS, answers_of, example, git, snapshot_template, subprocess_env,
)
from .packages import rna
from rna import files  # noqa: E402 - found once .packages has put extensions/ on the path
from .releases import ReleaseError, following_version, release_commit, tag_name, versions

RELEASES = tuple(tag_name(version) for version in reversed(versions(ROOT)))  # oldest first
NEW_VERSION = tag_name(following_version(versions(ROOT)[0]))  # the working tree
OLD_VERSION = "v0.1.0"  # the first release: answers without node languages, catkin targets before 0.2.0

CONFLICT_MARKERS = ("<<<<<<< before updating", ">>>>>>> after updating")
ANSI = re.compile(r"\x1b\[[0-9;]*[A-Za-z]")


# ─── Template repositories ────────────────────────────────────────────────────


@dataclass(frozen=True)
class TemplateRepo:
    path: Path
    tags: tuple[str, ...]

    @property
    def latest(self) -> str:
        return self.tags[-1]


def snapshot_repo(destination: Path, version: str = NEW_VERSION) -> TemplateRepo:
    """The working tree's template, committed in a fresh repository and tagged `version`."""
    snapshot_template(destination)
    git("tag", "-a", version, "-m", f"rna-template {version} (working tree snapshot)", cwd=destination)
    return TemplateRepo(destination, (version,))


def release_ref(tag: str, source: Path = ROOT) -> str:
    """The commit of release `tag` by the changelog's rule (support/releases.py): tags or not."""
    try:
        return release_commit(source, tag.removeprefix("v"))
    except ReleaseError as error:
        pytest.fail(f"the upgrade tests need the release {tag}: {error}", pytrace=False)


def release_history_repo(destination: Path, releases: tuple[str, ...] = RELEASES, new: str = NEW_VERSION,
                         source: Path = ROOT, new_tree: Path | None = None) -> TemplateRepo:
    """The real `releases` of this repository, oldest first, each tagged; the working tree on top tagged `new`.

    `new_tree` (default: `source`'s working tree) is where the new version's copier.yml,
    template/ and extensions/ are taken from: passing the snapshot repository of the same
    session makes both `new` versions identical even while the working tree is being edited.
    """
    destination.mkdir(parents=True, exist_ok=True)
    git("init", "-q", "-b", "main", cwd=destination)
    for release in releases:
        _replace_template_items(destination)
        archive = subprocess.run(["git", "-C", str(source), "archive", "--format=tar", release_ref(release, source),
                                  *TEMPLATE_ITEMS],
                                 capture_output=True, check=True)
        with tarfile.open(fileobj=io.BytesIO(archive.stdout)) as tar:
            tar.extractall(destination, filter="tar")
        git("add", "-A", cwd=destination)
        git("commit", "-q", "-m", f"rna-template {release} (from git archive {release})", cwd=destination)
        git("tag", "-a", release, "-m", f"rna-template {release}", cwd=destination)

    _replace_template_items(destination)
    for item in TEMPLATE_ITEMS:
        path = destination / item
        origin = (new_tree or source) / item
        if origin.is_dir():
            shutil.copytree(origin, path, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            shutil.copy2(origin, path)
    git("add", "-A", cwd=destination)
    # The working tree may equal the release (nothing changed yet): still a new version.
    git("commit", "-q", "--allow-empty", "-m", f"rna-template {new} (working tree)", cwd=destination)
    git("tag", "-a", new, "-m", f"rna-template {new}", cwd=destination)
    return TemplateRepo(destination, (*releases, new))


def _replace_template_items(destination: Path) -> None:
    """Remove the template's items, so that files a version deleted are gone from the next commit."""
    for item in TEMPLATE_ITEMS:
        path = destination / item
        if path.is_dir():
            shutil.rmtree(path)
        elif path.exists():
            path.unlink()


# ─── Projects ─────────────────────────────────────────────────────────────────


def generate_project(template: TemplateRepo | Path, destination: Path, answers: dict,
                     vcs_ref: str | None = None) -> Path:
    """`copier copy` from one tag with fixed answers, then `git init` and a first commit."""
    import copier

    repo = template.path if isinstance(template, TemplateRepo) else Path(template)
    ref = vcs_ref or (template.latest if isinstance(template, TemplateRepo) else "HEAD")
    copier.run_copy(str(repo), str(destination), data={**FIXED_ANSWERS, **answers}, defaults=True,
                    unsafe=True, quiet=True, vcs_ref=ref)
    git("init", "-q", "-b", "main", cwd=destination)
    commit_all(destination, f"generated from rna-template {ref}")
    return destination


def commit_all(project: Path, message: str = "my edits") -> None:
    """What a user does before `copier update`: commit everything (the update needs a clean tree)."""
    git("add", "-A", cwd=project)
    git("commit", "-q", "--allow-empty", "-m", message, cwd=project)


def clone_project(project: Path, destination: Path) -> Path:
    """A private copy of a generated project (its git history included) for one scenario."""
    shutil.copytree(project, destination, symlinks=True)
    return destination


def user_answers(project: Path) -> dict:
    """The recorded answers without Copier's own keys (`_commit`, `_src_path`)."""
    return {key: value for key, value in answers_of(project).items() if not key.startswith("_")}


@dataclass
class UpdateResult:
    returncode: int
    stdout: str
    stderr: str
    command: list[str]

    @property
    def output(self) -> str:
        return self.stdout + self.stderr

    def __str__(self) -> str:
        return (f"$ {' '.join(self.command)}\nexit code {self.returncode}\n"
                f"--- stdout\n{self.stdout}\n--- stderr\n{self.stderr}")


def run_update(project: Path, data: dict | None = None, vcs_ref: str | None = None,
               extra_args: tuple[str, ...] = (), timeout: float = 300) -> UpdateResult:
    """`copier update --trust --defaults [--data-file f] [--vcs-ref v]` in `project`, stdin closed.

    The data file is written beside the project, not in it: an untracked file would make
    the project dirty and Copier would refuse to update.
    """
    command = [sys.executable, "-m", "copier", "update", "--trust", "--defaults"]
    if data is not None:
        data_file = project.parent / f"{project.name}.update-data.yml"
        data_file.write_text(yaml.safe_dump(data, sort_keys=False))
        command += ["--data-file", str(data_file)]
    if vcs_ref is not None:
        command += ["--vcs-ref", vcs_ref]
    command += list(extra_args)
    if os.environ.get(COMPARE_PATCHES):
        return _compared_with_the_patches_off(project, command, timeout)
    return _update(project, command, timeout)


def _update(project: Path, command: list[str], timeout: float, **env: str) -> UpdateResult:
    result = subprocess.run(command, cwd=project, env={**subprocess_env(), **env}, stdin=subprocess.DEVNULL,
                            capture_output=True, text=True, timeout=timeout)
    return UpdateResult(result.returncode, ANSI.sub("", result.stdout), ANSI.sub("", result.stderr), command)


# Set (the compat tier sets it), every update of run_update() runs twice in the project's own
# folder, as it was: with the patches off (extensions/patches/), then on; the two must leave the
# same files, links, modes and git state and say the same (Copier's scratch folders, named at
# random, aside). The test goes on with the second.
COMPARE_PATCHES = "RNA_TEST_COMPARE_PATCHES"
SCRATCH_NAMES = re.compile(r"(copier\._[a-z]+\.[a-z_]+\.|rna-update-renders-)\w+")


def _compared_with_the_patches_off(project: Path, command: list[str], timeout: float) -> UpdateResult:
    # Held outside the project's folder and its parent: that may be in the same repository.
    held = Path(tempfile.mkdtemp(prefix="rna-before-update-")) / project.name
    shutil.copytree(project, held, symlinks=True)
    try:
        off = _update(project, command, timeout, RNA_TEMPLATE_PATCHES_OFF="all")
        off_state = project_state(project)
        shutil.rmtree(project)
        shutil.copytree(held, project, symlinks=True)
    finally:
        shutil.rmtree(held.parent, ignore_errors=True)
    on = _update(project, command, timeout)
    on_state = project_state(project)
    said = [(name, SCRATCH_NAMES.sub(r"\1*", getattr(on, name)), SCRATCH_NAMES.sub(r"\1*", getattr(off, name)))
            for name in ("stdout", "stderr")]
    differing = [f"{name}: on\n{with_patches}\noff\n{without}" for name, with_patches, without in said
                 if with_patches != without]
    differing += [f"{key} differs: on {on_state[key]!r}, off {off_state[key]!r}"
                  for key in on_state if key != "files" and on_state[key] != off_state[key]]
    differing += [f"{path}: on {on_state['files'].get(path)!r:.200}, off {off_state['files'].get(path)!r:.200}"
                  for path in sorted(on_state["files"].keys() | off_state["files"].keys())
                  if on_state["files"].get(path) != off_state["files"].get(path)]
    assert on.returncode == off.returncode and not differing, (
        f"the update did otherwise with the patches on (exit {on.returncode}) and off (exit {off.returncode}):\n"
        + "\n".join(differing))
    return on


def project_state(project: Path) -> dict:
    """What an update can change in a project: every path but .git's (a file's bytes and mode, a
    link's target, a folder), git's status, index and HEAD."""
    files: dict[str, tuple] = {}
    for path in sorted(project.rglob("*")):
        relative = path.relative_to(project)
        if relative.parts[0] == ".git":
            continue
        mode = path.lstat().st_mode
        files[str(relative)] = (("link", os.readlink(path)) if path.is_symlink()
                                else ("folder", mode & 0o777) if path.is_dir()
                                else ("file", mode & 0o777, path.read_bytes()))
    return {"files": files,
            "status": git("status", "--porcelain", "--untracked-files=all", cwd=project).stdout,
            "index": git("ls-files", "--stage", cwd=project).stdout,
            "head": git("rev-parse", "HEAD", cwd=project).stdout}


# ─── What an update left behind ───────────────────────────────────────────────


SUMMARY_HEADING = "rna-template: what this update changed"


def summary_of(output: str) -> dict[str, list[str]]:
    """The file lists of the summary an update ends with: label -> paths (`old -> new` for renames)."""
    assert SUMMARY_HEADING in output, f"the update printed no summary\n{output}"
    lines = output[output.index(SUMMARY_HEADING):].splitlines()[1:]
    found: dict[str, list[str]] = {}
    label = None
    for line in lines:
        match = re.match(r"^  (added|updated|merged|removed|renamed):\s+(.*)$", line)
        if match:
            label = match[1]
            found[label] = []
            text = match[2]
        elif label and line.startswith(" " * 12) and line.strip():
            text = line.strip()
        else:
            label = None
            continue
        found[label] += [item.strip() for item in text.split(",") if item.strip()]
    return found



def project_files(project: Path) -> list[Path]:
    return sorted(p for p in project.rglob("*") if p.is_file() and ".git" not in p.relative_to(project).parts)


def conflicted_files(project: Path) -> list[str]:
    """Files holding Copier's conflict markers, `.rej` files and paths git records as unmerged."""
    found = set()
    for path in project_files(project):
        relative = str(path.relative_to(project))
        if path.suffix == ".rej":
            found.add(relative)
            continue
        try:
            text = path.read_text()
        except UnicodeDecodeError:
            continue
        if any(line.rstrip() in CONFLICT_MARKERS for line in text.splitlines()):
            found.add(relative)
    unmerged = git("ls-files", "--unmerged", cwd=project).stdout
    found.update(line.split("\t", 1)[1] for line in unmerged.splitlines() if "\t" in line)
    return sorted(found)


def conflict_regions(text: str) -> list[tuple[list[str], list[str]]]:
    """(the project's side, the template's side) of every `<<<<<<< before updating` block."""
    regions, ours, theirs, side = [], [], [], None
    for line in text.splitlines():
        if line.startswith("<<<<<<< before updating"):
            ours, theirs, side = [], [], "ours"
        elif side and line.startswith("|||||||"):
            side = "base"
        elif side and line.startswith("======="):
            side = "theirs"
        elif side and line.startswith(">>>>>>> after updating"):
            regions.append((ours, theirs))
            side = None
        elif side == "ours":
            ours.append(line)
        elif side == "theirs":
            theirs.append(line)
    return regions


def tree_differences(left: Path, right: Path, ignore_answer_keys: tuple[str, ...] = ("_commit",)) -> list[str]:
    """`diff -r` of two generated projects, ignoring `.git` and the given keys of the answers file."""
    differences = []

    def relative_files(root: Path) -> set[str]:
        return {str(p.relative_to(root)) for p in project_files(root)}

    left_files, right_files = relative_files(left), relative_files(right)
    differences += [f"only in {left.name}: {name}" for name in sorted(left_files - right_files)]
    differences += [f"only in {right.name}: {name}" for name in sorted(right_files - left_files)]
    for name in sorted(left_files & right_files):
        a, b = (left / name).read_bytes(), (right / name).read_bytes()
        if name == ANSWERS_FILE:
            a, b = (_without_keys(x.decode(), ignore_answer_keys).encode() for x in (a, b))
        if a != b:
            diff = subprocess.run(["diff", "-u", str(left / name), str(right / name)], capture_output=True,
                                  text=True).stdout
            differences.append(f"{name} differs:\n{diff}")
        elif os.access(left / name, os.X_OK) != os.access(right / name, os.X_OK):
            differences.append(f"{name}: the executable bit differs")
    return differences


def _without_keys(text: str, keys: tuple[str, ...]) -> str:
    return "".join(line for line in text.splitlines(keepends=True)
                   if not any(line.startswith(f"{key}:") for key in keys))


def kept_of(output: str) -> dict[str, str]:
    """The summary's `kept` items: path -> why."""
    return _items(output, "  kept")


def to_port_of(output: str) -> dict[str, str]:
    """The summary's `to port` items: path -> what changed."""
    return _items(output, "  to port")


def conflicts_of(output: str) -> list[str]:
    """The files the summary lists as conflicts."""
    return list(_items(output, "  conflicts"))


def _items(output: str, heading: str) -> dict[str, str]:
    items: dict[str, str] = {}
    inside, current = False, None
    for line in output.splitlines():
        if line.startswith(heading):
            inside = True
        elif inside and line.startswith("    ") and not line.startswith("      "):
            current, _, why = line.strip().partition(": ")
            items[current] = why
        elif inside and line.startswith("      ") and current:
            items[current] += " " + line.strip()
        else:
            inside = False
    return items


IGNORE_MARKERS = ("COLCON_IGNORE", "CATKIN_IGNORE", "AMENT_IGNORE")


def broken_packages(project: Path) -> list[str]:
    """What stops colcon or catkin from reading a package of `project`, by reading its files.

    package.xml must parse with catkin_pkg (duplicate dependencies included); the build
    file its <build_type> names must exist and be sane: CMakeLists.txt with balanced
    parentheses naming sources that exist, setup.py that parses with entry points whose
    modules exist. Building for real is the ros and ros1 tiers' job.
    """
    problems = []
    for xml in sorted(project.rglob("package.xml")):
        folder = xml.parent
        if ".git" in xml.relative_to(project).parts or any((folder / m).exists() for m in IGNORE_MARKERS):
            continue
        where = str(folder.relative_to(project))
        try:
            package = parse_package(str(xml))
        except Exception as error:  # noqa: BLE001 - catkin_pkg raises several kinds
            problems.append(f"{where}/package.xml does not parse: {error}")
            continue
        build_type = package.get_build_type()
        build_file = folder / ("setup.py" if build_type == "ament_python" else "CMakeLists.txt")
        if not build_file.is_file():
            problems.append(f"{where}: {build_type} without {build_file.name}")
        elif build_file.name == "CMakeLists.txt":
            text = files.text(folder, build_file.name) or ""
            problems += [f"{where}/CMakeLists.txt: {p}" for p in _cmake_problems(text, folder)]
        else:
            text = files.text(folder, build_file.name) or ""
            problems += [f"{where}/setup.py: {p}" for p in _setup_py_problems(text, folder)]
    return problems


def _cmake_problems(text: str, folder: Path) -> list[str]:
    code = re.sub(r'"(?:\\.|[^"\\])*"|#[^\n]*', "", text)
    problems = [] if code.count("(") == code.count(")") else ["unbalanced parentheses"]
    problems += [f"names {source}, which does not exist"
                 for source in re.findall(r"\b((?:src|scripts|[a-z]\w*)/[\w/]+\.(?:cpp|py|msg|srv|action))\b", code)
                 if not (folder / source).is_file()]
    if any(marker in text for marker in CONFLICT_MARKERS):
        problems.append("conflict markers")
    return problems


def _setup_py_problems(text: str, folder: Path) -> list[str]:
    import ast

    try:
        ast.parse(text)
    except SyntaxError as error:
        return [f"does not parse: {error}"]
    return [f"entry point {name} names {module}, which does not exist"
            for name, module in re.findall(r"'(\w+) = ([\w.]+):\w+'", text)
            if not (folder / (module.replace(".", "/") + ".py")).is_file()]


# ─── The update tier's merge-safety figure ────────────────────────────────────

FIGURE = "merge_safety"


@pytest.fixture
def figure(record_property):
    """figure(result, project, user_lines, lost=0): records one update's tally (before the test's
    asserts): the user's lines (path, lines) missing after it, plus `lost` counted otherwise
    (bytes of files the update does not own, tests/test_real_packages.py), and whether it
    exited 0 with a package that does not parse or build. conftest.py sums them."""
    def count(result, project: Path, user_lines: list[tuple[str, list[str]]] = (), lost: int = 0) -> None:
        for path, lines in user_lines:  # a line of an edit may be part of a line (a value replaced)
            text = (project / path).read_text() if (project / path).is_file() else ""
            lost += sum(1 for line in lines if line.strip() and line not in text)
        broken = result.returncode == 0 and bool(broken_packages(project))
        record_property(FIGURE, {"lost": lost, "broken": int(broken)})
    return count


# ─── User edits ───────────────────────────────────────────────────────────────


def _lines_of(text: str | list[str]) -> list[str]:
    return list(text) if isinstance(text, list) else text.split("\n")


def _anchor_index(lines: list[str], path: Path, anchor: str, occurrence: int | None) -> int:
    hits = [index for index, line in enumerate(lines) if anchor in line]
    if not hits:
        raise AssertionError(f"edit anchor not found in {path}: {anchor!r}\n--- the file:\n" + "\n".join(lines))
    if occurrence is None:
        if len(hits) > 1:
            raise AssertionError(f"edit anchor {anchor!r} is on {len(hits)} lines of {path} "
                                 f"({[h + 1 for h in hits]}): pass occurrence= to choose one")
        return hits[0]
    if occurrence >= len(hits):
        raise AssertionError(f"edit anchor {anchor!r} is on {len(hits)} lines of {path}, not {occurrence + 1}")
    return hits[occurrence]


def append_after(path: Path, anchor: str, text: str | list[str], occurrence: int | None = None) -> list[str]:
    """Insert lines after the (only) line containing `anchor`; returns the inserted lines."""
    lines = path.read_text().split("\n")
    index = _anchor_index(lines, path, anchor, occurrence)
    added = _lines_of(text)
    lines[index + 1:index + 1] = added
    path.write_text("\n".join(lines))
    return added


def insert_before(path: Path, anchor: str, text: str | list[str], occurrence: int | None = None) -> list[str]:
    """Insert lines before the (only) line containing `anchor`; returns the inserted lines."""
    lines = path.read_text().split("\n")
    index = _anchor_index(lines, path, anchor, occurrence)
    added = _lines_of(text)
    lines[index:index] = added
    path.write_text("\n".join(lines))
    return added


def replace_text(path: Path, old: str, new: str, count: int = 1) -> list[str]:
    """Replace exactly `count` occurrences of `old`; returns the lines of `new`."""
    text = path.read_text()
    found = text.count(old)
    if found != count:
        raise AssertionError(f"expected {count} occurrence(s) of {old!r} in {path}, found {found}"
                             f"\n--- the file:\n{text}")
    path.write_text(text.replace(old, new))
    return new.split("\n")


def write_new_file(path: Path, text: str, executable: bool = False) -> list[str]:
    """A file the user adds to the package; returns its lines."""
    if path.exists():
        raise AssertionError(f"{path} already exists: a scenario's new file must be new")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    if executable:
        path.chmod(0o755)
    return text.split("\n")


def missing_block(path: Path, lines: list[str]) -> str | None:
    """None when `lines` are in the file, one after the other; otherwise what is missing."""
    if not path.is_file():
        return f"{path} is gone"
    text = path.read_text()
    if "\n".join(lines) in text:
        return None
    present = set(text.split("\n"))
    missing = [line for line in lines if line not in present]
    if missing:
        return f"{path}: lines missing: {missing}"
    return f"{path}: every line is there, but not in the order written: {lines}"


def _split_managed(text: str) -> tuple[list[str], list[str]]:
    """(lines inside BEGIN/END rna-template blocks, lines outside them), markers excluded."""
    inside, managed, unmanaged = False, [], []
    for line in text.splitlines():
        if "BEGIN rna-template" in line or "END rna-template" in line:
            inside = "BEGIN rna-template" in line
        else:
            (managed if inside else unmanaged).append(line)
    return managed, unmanaged


def managed_lines(text: str) -> list[str]:
    """The lines between `BEGIN rna-template` and `END rna-template` markers."""
    return _split_managed(text)[0]


def unmanaged_lines(text: str) -> list[str]:
    """The lines outside the managed blocks (the markers excluded)."""
    return _split_managed(text)[1]


# ─── The base projects the update tests grow ──────────────────────────────────
# Three flavours of one package `robot`, each with three nodes: `driver` and `monitor`
# (the nodes whose files users edit) and `logger` (the "other" node).

# The same nodes in each flavour; ament_cmake and catkin choose each node's language.
FLAVOR_TARGETS = {"ament_python": {"build_type": "ament_python"}, "ament_cmake": {"build_type": "ament_cmake"},
                  "catkin": {"ros_distro": "noetic"}}
FLAVOR_LANGUAGES = {"ament_python": {},
                    "ament_cmake": {"driver": "cpp", "monitor": "python", "logger": "cpp"},
                    "catkin": {"driver": "cpp", "monitor": "python", "logger": "python"}}


def _base_answers(flavor: str) -> dict:
    grown = example("robot_grown")
    languages = FLAVOR_LANGUAGES[flavor]
    nodes = [{"name": node["name"], **({"language": languages[node["name"]]} if languages else {}),
              **{key: value for key, value in node.items() if key != "name"}} for node in grown["nodes"]]
    return {"package_name": grown["package_name"], **FLAVOR_TARGETS[flavor], "nodes": nodes}


BASE_ANSWERS = {flavor: _base_answers(flavor) for flavor in FLAVOR_TARGETS}
FLAVORS = tuple(BASE_ANSWERS)
PACKAGE = "robot"


@dataclass(frozen=True)
class Flavor:
    """Where a flavour of the base project keeps each file (paths relative to the project)."""

    name: str

    @property
    def answers(self) -> dict:
        return copy.deepcopy(BASE_ANSWERS[self.name])

    @property
    def ros1(self) -> bool:
        return self.name == "catkin"

    def language(self, node: str, nodes: list[dict] | None = None) -> str:
        for entry in nodes or self.answers["nodes"]:
            if entry["name"] == node:
                return entry.get("language", "python" if self.name == "ament_python" else "cpp")
        raise KeyError(node)

    def _node(self, node: str, language: str | None = None):
        """The model of one of the flavour's nodes (in `language`, if given), which knows its files."""
        answers = self.answers
        answers["nodes"] = [{"name": node, "language": language or self.language(node)}]
        return rna.build_package({**FIXED_ANSWERS, "description": "x", "license": "Apache-2.0",
                                  "ros_distro": "noetic" if self.ros1 else "jazzy", **answers}).nodes[0]

    def user_file(self, node: str, language: str | None = None) -> str:
        return f"{PACKAGE}/{self._node(node, language).user_file}"

    def base_file(self, node: str, language: str | None = None) -> str:
        return f"{PACKAGE}/{self._node(node, language).base_file}"

    def config_file(self, node: str) -> str:
        return f"{PACKAGE}/{rna.layout.config_file(node)}"

    @property
    def launch_file(self) -> str:
        return f"{PACKAGE}/{rna.layout.launch_file(PACKAGE, 1 if self.ros1 else 2)}"

    @property
    def build_file(self) -> str:
        return f"{PACKAGE}/setup.py" if self.name == "ament_python" else f"{PACKAGE}/CMakeLists.txt"

    @property
    def package_xml(self) -> str:
        return f"{PACKAGE}/package.xml"


def find_node(nodes: list[dict], name: str) -> dict:
    for node in nodes:
        if node["name"] == name:
            return node
    raise KeyError(f"no node {name!r} in {[n['name'] for n in nodes]}")


# ─── Fixtures (this module is a pytest plugin of test_update and test_merge_safety) ──


def pytest_configure(config):
    # Registered here too, so `-m update` works wherever the plugin is loaded; the first
    # module that uses the mark is imported before this runs, hence one warning until
    # conftest.py registers it.
    config.addinivalue_line("markers", "update: runs `copier update` on generated projects (tests/test_update.py, "
                                       "tests/test_merge_safety.py)")


@pytest.fixture(scope="session")
def current_template(tmp_path_factory) -> TemplateRepo:
    """The working tree's template, tagged NEW_VERSION."""
    return snapshot_repo(tmp_path_factory.mktemp("template-current"), NEW_VERSION)


@pytest.fixture(scope="session")
def release_template(tmp_path_factory, current_template) -> TemplateRepo:
    """Every release of this repository (found by the changelog), then the working tree as NEW_VERSION."""
    return release_history_repo(tmp_path_factory.mktemp("template-history"), new_tree=current_template.path)


@pytest.fixture(scope="session")
def base_project(request, tmp_path_factory):
    """base_project(flavor, version): the base project generated once per session (do not edit it)."""
    cache: dict[tuple[str, str], Path] = {}

    def get(flavor: str, version: str = NEW_VERSION) -> Path:
        if (flavor, version) not in cache:
            template = request.getfixturevalue("release_template" if version in RELEASES else "current_template")
            destination = tmp_path_factory.mktemp(f"base-{flavor}-{version}") / "project"
            cache[flavor, version] = generate_project(template, destination, BASE_ANSWERS[flavor], vcs_ref=version)
        return cache[flavor, version]

    return get


@pytest.fixture
def project(base_project, tmp_path):
    """project(flavor, version): a private, committed copy of a base project."""
    def make(flavor: str, version: str = NEW_VERSION, name: str = "project") -> Path:
        return clone_project(base_project(flavor, version), tmp_path / name)

    return make


def conflict_excerpts(project: Path, context: int = 2) -> str:
    """Each conflict block of the project's files with a few lines around it, for a failure message."""
    parts = []
    for relative in conflicted_files(project):
        path = project / relative
        if not path.is_file():
            parts.append(f"--- {relative}: (not a file)")
            continue
        lines = path.read_text().splitlines()
        starts = [i for i, line in enumerate(lines) if line.startswith("<<<<<<< before updating")]
        for start in starts:
            end = next((i for i in range(start, len(lines)) if lines[i].startswith(">>>>>>> after updating")),
                       len(lines) - 1)
            excerpt = lines[max(0, start - context):end + context + 1]
            parts.append(f"--- {relative}, lines {max(0, start - context) + 1}-{end + context + 1}:\n"
                         + "\n".join(excerpt))
        if not starts:
            parts.append(f"--- {relative}\n" + path.read_text())
    return "\n".join(parts)
