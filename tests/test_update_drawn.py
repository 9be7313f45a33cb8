"""Property: an update that adds and removes nodes loses no byte of any file it does not own.

Hypothesis draws a package (one of the update tier's three flavours), files of the user's
own in places of the package, named with spaces and letters beyond ASCII (binary, PNG,
STL, text in Latin-1, Shift JIS, UTF-16, UTF-8 with a byte order mark, CRLF or mixed line
ends, empty, without a final newline, over the 1 MiB the update reads, links to files
inside or outside the project, to folders, to nothing), commits them, then updates the
package adding a node, removing one, or both. After the update every one of those files is there as it was, byte
for byte, link for link, mode for mode; the update exits 0 with nothing to do. Each update
counts in the tier's merge-safety figure (a file changed is a loss).

The same few sets are drawn on every run (a copy and an update each, about 7 s); with
HYPOTHESIS_PROFILE=thorough, many more. So that every kind comes through on every run
whatever is drawn, one set of each flavour holds them all.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

if "support.template_repo" not in sys.modules:  # its asserts explain themselves too
    pytest.register_assert_rewrite("support.template_repo")
from rna import files  # noqa: E402
from support.drawn import thorough  # noqa: E402
from support.real_packages import binary_stl, changes_outside_blocks, png  # noqa: E402
from support.template_repo import (  # noqa: E402
    FLAVORS, PACKAGE, Flavor, clone_project, commit_all, conflicted_files, run_update,
)

pytest_plugins = ("support.template_repo",)
pytestmark = pytest.mark.update

# Where users keep files of their own: beside the package, in its folders and in new ones.
PLACES = ("", PACKAGE, f"{PACKAGE}/data sets", f"{PACKAGE}/d\u00e9mo", f"{PACKAGE}/config",
          f"{PACKAGE}/launch", f"{PACKAGE}/src", f"{PACKAGE}/include/{PACKAGE}",
          f"{PACKAGE}/{PACKAGE}", f"{PACKAGE}/scripts", f"{PACKAGE}/test", f"{PACKAGE}/doc", f"{PACKAGE}/meshes/visual",
          f"{PACKAGE}/maps", "docs")
SUFFIXES = ("", ".png", ".stl", ".bag", ".txt", ".md", ".yaml", ".py", ".cpp", ".hpp", ".h", ".xml", ".rviz", ".launch")
TEXT = st.text(st.characters(codec="utf-8", exclude_categories=("Cs",), exclude_characters="\r\n"), max_size=60)
SHIFT_JIS = st.text(st.sampled_from("abc =#\u30ed\u30dc\u30c3\u30c8\u5236\u5fa1\u3067\u3059"), max_size=30)
LATIN_1 = st.text(st.characters(min_codepoint=0x20, max_codepoint=0xFF, exclude_characters="\x7f"), max_size=60)

CONTENTS = {
    "binary": st.binary(max_size=600).map(lambda data: b"\0" + data),
    "png": st.integers(1, 40).map(lambda size: png(size, size)),
    "mesh": st.integers(1, 60).map(binary_stl),
    "latin-1": st.lists(LATIN_1, min_size=1, max_size=6).map(
        lambda lines: ("# caf\xe9 " + "\n".join(lines) + "\n").encode("latin-1")),
    "utf-16": st.lists(TEXT, min_size=1, max_size=6).map(lambda lines: "\n".join(lines).encode("utf-16")),
    "utf-8 with a byte order mark": st.lists(TEXT, min_size=1, max_size=6).map(
        lambda lines: ("\n".join(lines) + "\n").encode("utf-8-sig")),
    "shift_jis": st.lists(SHIFT_JIS, min_size=1, max_size=6).map(
        lambda lines: ("# \u30ed\u30dc\u30c3\u30c8\n" + "\n".join(lines) + "\n").encode("shift_jis")),
    "crlf": st.lists(TEXT, min_size=1, max_size=6).map(lambda lines: ("\r\n".join(lines) + "\r\n").encode()),
    "mixed line ends": st.lists(st.tuples(TEXT, st.sampled_from(("\n", "\r\n", "\r"))), min_size=1, max_size=6).map(
        lambda lines: "".join(text + end for text, end in lines).encode()),
    "no final newline": st.lists(TEXT, min_size=1, max_size=6).map(lambda lines: "\n".join(lines).encode()),
    "empty": st.just(b""),
    "large": st.just(b"\0" * (files.LARGE + 1)),
}
# One of each, for the set that holds every kind.
EXAMPLES = {
    "binary": b"\0\x01\x02\xff\n\r\n", "png": png(4, 4), "mesh": binary_stl(3),
    "utf-16": "# \u30ed\u30dc\u30c3\u30c8\nrate = 10\n".encode("utf-16"),
    "utf-8 with a byte order mark": "# caf\u00e9\nrate: 10\n".encode("utf-8-sig"),
    "shift_jis": "# \u30ed\u30dc\u30c3\u30c8\u5236\u5fa1\nrate = 10\n".encode("shift_jis"),
    "latin-1": "# caf\u00e9 cr\u00e8me\nrate = 10\n".encode("latin-1"),
    "crlf": b"first\r\nsecond\r\n", "mixed line ends": b"lf\ncrlf\r\ncr\rend", "no final newline": b"one\ntwo",
    "empty": b"", "large": b"\0" * (files.LARGE + 1),
}
# Links, by what they name: (the target as the link writes it, given the link's folder).
LINKS = {
    "inside": lambda folder, others: os.path.relpath(f"{PACKAGE}/package.xml", folder or "."),
    "another of the user's": lambda folder, others: os.path.relpath(others[0], folder or ".") if others else "x",
    "a folder": lambda folder, others: os.path.relpath(f"{PACKAGE}/config", folder or "."),
    "outside": lambda folder, others: "/etc/hostname",
    "nothing": lambda folder, others: "no/such/file",
}
NEW_NODE = {"name": "planner", "subscribers": ["scan:sensor_msgs/msg/LaserScan"], "timers": ["0.5"]}


@st.composite
def extra_files(draw) -> dict[str, tuple[str, bytes | str]]:
    """path -> (kind, its bytes, or a link's target)."""
    drawn: dict[str, tuple[str, bytes | str]] = {}
    for _ in range(draw(st.integers(1, 6))):
        folder = draw(st.sampled_from(PLACES))
        name = draw(st.from_regex(r"x_[a-z0-9_\u00e9\u00fc\u30ed]{1,10}( [a-z\u00e4]{1,5})?", fullmatch=True)) + draw(
            st.sampled_from(SUFFIXES))
        path = f"{folder}/{name}" if folder else name
        if draw(st.integers(0, 4)) == 0:
            kind = draw(st.sampled_from(sorted(LINKS)))
            drawn[path] = (f"link to {kind}", LINKS[kind](folder, [p for p, (k, _) in drawn.items()
                                                                     if not k.startswith("link")]))
        else:
            kind = draw(st.sampled_from(sorted(CONTENTS)))
            drawn[path] = (kind, draw(CONTENTS[kind]))
    return drawn


@st.composite
def node_changes(draw, flavor: Flavor) -> list[dict]:
    """The nodes after the update: one of the package's removed, a node added, or both."""
    nodes = flavor.answers["nodes"]
    change = draw(st.sampled_from(("add", "remove", "both")))
    if change in ("remove", "both"):
        nodes.remove(draw(st.sampled_from(nodes)))
    if change in ("add", "both"):
        language = "python" if flavor.name == "ament_python" else draw(st.sampled_from(("cpp", "python")))
        nodes.append({**NEW_NODE, **({} if flavor.name == "ament_python" else {"language": language})})
    return nodes


def write_extras(project: Path, extras: dict[str, tuple[str, bytes | str]]) -> None:
    for path, (kind, content) in extras.items():
        target = project / path
        target.parent.mkdir(parents=True, exist_ok=True)
        if kind.startswith("link"):
            os.symlink(content, target)
        else:
            target.write_bytes(content)
        if path.endswith((".py", ".bag")) and not kind.startswith("link"):
            target.chmod(0o755)  # an executable script, a file of odd mode


def state(project: Path, paths) -> dict[str, files.Content]:
    return {path: files.read(project, path, owned=True) for path in paths}


def modes(project: Path, paths) -> dict[str, int]:
    return {path: os.lstat(project / path).st_mode for path in paths if os.path.lexists(project / path)}


@pytest.mark.parametrize("flavor_name", FLAVORS)
@settings(max_examples=60 if thorough() else 2, deadline=None, derandomize=not thorough(),
          suppress_health_check=(HealthCheck.function_scoped_fixture, HealthCheck.too_slow,
                                 HealthCheck.data_too_large))
@given(data=st.data())
def test_an_update_loses_no_byte_of_the_files_it_does_not_own(base_project, tmp_path_factory, figure, flavor_name,
                                                              data):
    flavor = Flavor(flavor_name)
    project = clone_project(base_project(flavor_name), tmp_path_factory.mktemp("drawn") / "project")
    extras = data.draw(extra_files(), label="the user's files")
    nodes = data.draw(node_changes(flavor), label="nodes")
    assert_kept_through_an_update(project, extras, nodes, figure)


def assert_kept_through_an_update(project: Path, extras: dict[str, tuple[str, bytes | str]], nodes: list[dict],
                                  figure) -> None:
    """Commit `extras` in `project`, update it to `nodes`: every extra as it was, exit 0, counted."""
    write_extras(project, extras)
    commit_all(project, "my files")
    before, mode_before = state(project, extras), modes(project, extras)

    result = run_update(project, {"nodes": nodes})

    problems = changes_outside_blocks(before, state(project, extras))
    problems += [f"{path}: its mode changed" for path, mode in mode_before.items()
                 if modes(project, [path]).get(path) != mode]
    figure(result, project, lost=len(problems))
    assert not problems, "\n".join(problems) + f"\n{result}"
    assert result.returncode == 0, result
    assert not conflicted_files(project), result
    assert "Traceback" not in result.stderr, result


def every_kind() -> dict[str, tuple[str, bytes | str]]:
    """One file of each kind and one link of each kind, each in a place of its own."""
    extras, places = {}, iter(PLACES * 2)
    for kind in sorted(CONTENTS):
        folder = next(places)
        extras[f"{folder}/x_{kind.replace(' ', '_')} \u00e9t\u00e9.dat".lstrip("/")] = (
            kind, EXAMPLES[kind])
    plain = [path for path in extras]
    for kind, target in sorted(LINKS.items()):
        folder = next(places)
        extras[f"{folder}/x_link to {kind}".lstrip("/")] = (f"link to {kind}", target(folder, plain))
    return extras


@pytest.mark.parametrize("flavor_name", FLAVORS)
def test_every_kind_of_file_at_once_comes_through_an_update(base_project, tmp_path, figure, flavor_name):
    flavor = Flavor(flavor_name)
    project = clone_project(base_project(flavor_name), tmp_path / "project")
    extras = every_kind()
    assert {kind for kind, _ in extras.values()} == set(CONTENTS) | {f"link to {kind}" for kind in LINKS}
    assert_kept_through_an_update(project, extras, flavor.answers["nodes"][1:] + [{**NEW_NODE, "language": "python"}],
                                  figure)
