"""The prompts fit an ordinary terminal: every line of every question, as Copier shows it, is
at most 79 columns wide (an 80x24 terminal wraps nothing), and help links to the docs site.

Copier hands each question to questionary as one message: the rendered help, verbatim,
after the question mark (an emoji two columns wide and a space). Most tests take the
messages from that hand-over, with the prompts answered by their defaults: the text a
person would see, without a terminal. The last one drives `copier copy` in a pseudo-
terminal of 80x24 (pexpect) drawn by a terminal emulator (pyte), and finds each of those
lines whole on the screen.
"""

from __future__ import annotations

import re

import copier
import copier._main
import pexpect
import pytest
import yaml
from rna import lab, wording
from support.generation import ROOT
from support.terminal import Terminal
from wcwidth import wcswidth

WIDTH = 79
LONGEST_NAME = "warehouse_fleet_navigation_and_docking1"
QUESTIONS = {name: question for name, question in yaml.safe_load((ROOT / "copier.yml").read_text()).items()
             if not name.startswith("_")}


def shown_prompts(template_dir, destination, monkeypatch, **given) -> dict[str, list[str]]:
    """The lines each question shows at its prompt, for a copy answered by the defaults and `given`:
    the help after the question mark, then each choice after the pointer's three columns."""
    shown = {}

    def prompt(questions, answers):
        """questionary's prompt, answering with `given` or the default Copier passes in `answers`."""
        (question,) = questions
        name = question["name"]
        if not question["when"](answers):  # questionary skips it: the default stands
            return answers
        shown[name] = f"{question['qmark']} {question['message']}".splitlines()
        shown[name] += [f"   {choice.title}" for choice in question.get("choices", [])]
        return {name: question["filter"](given[name])} if name in given else answers

    monkeypatch.setattr(copier._main, "unsafe_prompt", prompt)
    copier.run_copy(str(template_dir), str(destination), vcs_ref="HEAD", unsafe=True, quiet=True, pretend=True)
    return shown


def workspace(root):
    """A destination in a workspace with more interfaces than a prompt lists, with long names."""
    package = root / "ws" / "src" / "warehouse_navigation_interfaces"
    package.mkdir(parents=True)
    (package / "package.xml").write_text(
        "<package format='3'><name>warehouse_navigation_interfaces</name></package>")
    for kind, names in {"msg": ("DetectedObstacle", "NavigationGoal", "PlannedTrajectory", "RobotFleetStatus",
                                "ShelfLocation", "WaypointList", "ZoneOccupancy", "BatteryHealthReport",
                                "ChargingStationState", "ConveyorBeltStatus", "DockingApproach", "ForkliftPose",
                                "LiftHeight", "PalletDescription"),
                        "srv": ("ReserveChargingStation", "RequestShelfPickup"),
                        "action": ("NavigateThroughWaypoints", "DockAtChargingStation")}.items():
        (package / kind).mkdir()
        for name in names:
            (package / kind / f"{name}.{kind}").write_text("bool done\n")
    return root / "ws" / "src" / "planner"


@pytest.fixture(scope="module")
def prompts(template_dir, tmp_path_factory):
    """Every question a first copy can ask: one node prompt by prompt, and nodes and interfaces as YAML,
    in a workspace whose interfaces the type questions list."""
    with pytest.MonkeyPatch.context() as monkeypatch:
        destination = workspace(tmp_path_factory.mktemp("prompts"))
        one = shown_prompts(template_dir, destination, monkeypatch, build_type="ament_cmake", node_setup="one")
        # The longest package name REP 144 allows, for the choices that show it.
        listed = shown_prompts(template_dir, destination, monkeypatch, build_type="ament_cmake", node_setup="list",
                               package_name=LONGEST_NAME, interfaces="messages: [{name: Target, fields: [float64 x]}]")
    return {**one, **listed}


def test_every_question_that_can_be_asked_is_seen(prompts):
    never_asked = {name for name, question in QUESTIONS.items() if question.get("ask") is False}
    # edit_nodes is asked on an update only (tests/test_dialog.py draws it).
    assert set(prompts) == set(QUESTIONS) - never_asked - {"edit_nodes"}


def test_every_prompt_line_fits_an_80_column_terminal(prompts):
    assert "   a separate package, warehouse_fleet_navigation_and_docking1_interfaces" in prompts[
        "interfaces_location"]
    too_wide = {name: line for name, lines in prompts.items() for line in lines if wcswidth(line) > WIDTH}
    assert not too_wide


def test_help_never_asked_fits_too():
    """`ask: false` questions are not shown, but their help is the reference's text all the same."""
    for name, question in QUESTIONS.items():
        if question.get("ask") is False:
            assert all(len(line) <= WIDTH - 3 for line in question["help"].splitlines()), name


def test_examples_stand_on_lines_of_their_own(prompts):
    for name, lines in prompts.items():
        for line in lines:
            assert "e.g." not in line or line.lstrip().startswith("e.g.") or line.endswith("e.g."), (name, line)


def test_help_links_to_the_docs_site_not_to_the_repository(prompts):
    assert lab.docs_url("reference/answers/#nodes") in prompts["nodes"]
    assert lab.docs_url("reference/answers/#interfaces") in prompts["interfaces"]
    assert not [name for name, lines in prompts.items() if any("docs/" in line for line in lines)]


def test_the_docs_pages_linked_from_help_exist():
    pages = ROOT / "docs" / "pages"
    for question in QUESTIONS.values():
        for page, anchor in re.findall(r"docs_url\('([^'#]*)#?([^']*)'\)", question.get("help", "")):
            source = (pages / page.rstrip("/")).with_suffix(".md")
            assert source.is_file(), page
            headings = re.findall(r"^#+ (.+)$", source.read_text(), re.M)
            assert not anchor or anchor in [heading.lower().replace(" ", "-") for heading in headings], anchor


def test_interfaces_found_in_the_workspace_are_listed_in_lines_of_72_columns(prompts):
    lines = prompts["node_publishers"]
    listed = lines[lines.index("Found in your workspace:"):-1]
    assert listed[1] == "  warehouse_navigation_interfaces/msg/BatteryHealthReport,"
    assert listed[-1] == "  warehouse_navigation_interfaces/msg/ShelfLocation and 2 more"
    assert all(len(line) <= 72 for line in listed)
    assert any("warehouse_navigation_interfaces/action/DockAtChargingStation" in line
               for line in prompts["node_action_servers"])


def test_found_lines_wrap_whole_names():
    names = [f"some_interfaces/msg/Type{number:02}" for number in range(15)]
    lines = wording.found_lines(names, width=40, shown=12)
    assert lines[0] == "Found in your workspace:"
    assert lines[1:3] == ["  some_interfaces/msg/Type00,", "  some_interfaces/msg/Type01,"]
    assert lines[-1] == "  some_interfaces/msg/Type11 and 3 more"
    assert wording.found_lines([]) == []


# ----------------------------------------------------------------------------- at an 80x24 terminal

DOWN = "\x1b[B"
# The prompts of a first copy in order, with the keys that answer them; ament_cmake asks the language.
BEFORE_THE_NODES = [("package_name", ""), ("maintainer", ""), ("maintainer_email", ""), ("license", ""),
                    ("copyright_holder", ""), ("ros_distro", ""), ("build_type", DOWN), ("launch_format", "")]
ONE_NODE = [("node_setup", DOWN), ("node_language", ""), ("node_name", ""), ("node_publishers", ""),
            ("node_subscribers", ""), ("node_service_servers", ""), ("node_service_clients", ""),
            ("node_action_servers", ""), ("node_action_clients", ""), ("node_timers", ""),
            ("node_parameters", ""), ("description", ""), ("ci_workflow", "")]
# A YAML answer ends with Esc then Enter.
AS_YAML = [("node_setup", DOWN * 3), ("interfaces", "\x1b"), ("nodes", "\x1b"), ("description", ""),
           ("ci_workflow", "")]


@pytest.mark.parametrize("path", [ONE_NODE, AS_YAML], ids=["one node", "as yaml"])
def test_each_prompt_keeps_its_lines_whole_at_80_columns(template_dir, tmp_path, monkeypatch, path):
    """Every help line Copier hands over is a whole row of the screen: nothing wrapped."""
    destination = workspace(tmp_path)
    expected = shown_prompts(template_dir, destination, monkeypatch, build_type="ament_cmake",
                             node_setup="one" if path is ONE_NODE else "list")
    terminal = Terminal(["copy", "--trust", "--vcs-ref=HEAD", str(template_dir), str(destination)],
                        tmp_path / "terminal.log")
    try:
        for name, keys in BEFORE_THE_NODES + path:
            lines = [line.rstrip() for line in expected[name] if line.strip()]
            rows = [row.replace(" » ", "   ", 1) for row in terminal.rows_at([lines[0].split(" ", 1)[1], *lines[1:]])]
            assert [line for line in lines if line not in rows] == [], (name, rows)
            terminal.child.send(keys + "\r")
        terminal.child.expect(pexpect.EOF, timeout=60)
    finally:
        terminal.child.close(force=True)
        terminal.log.close()
    assert terminal.child.exitstatus == 0, (tmp_path / "terminal.log").read_text()


def test_no_question_reads_a_later_one():
    """copier-tui (a form over Copier's questions) orders the questions by what their `when`,
    `default` and `choices` read, and refuses a template where one reads a later one as a
    circular dependency (docs/pages/how-to/install.md): each reads only questions before it."""
    import jinja2
    from jinja2 import meta

    class AnyFilter(dict):  # the template's filters come from its extension: any name is one here
        def __contains__(self, name):
            return True

        def get(self, name, default=None):
            return super().get(name, str)

    environment = jinja2.Environment(extensions=["jinja2.ext.do"])
    environment.filters = AnyFilter(environment.filters)
    names = list(QUESTIONS)
    for position, (name, question) in enumerate(QUESTIONS.items()):
        read = set()
        for key in ("when", "default", "choices"):
            value = question.get(key)
            sources = value.values() if isinstance(value, dict) else [value]
            for source in sources:
                if isinstance(source, str):
                    read |= meta.find_undeclared_variables(environment.parse(source)) & set(names)
        later = read - set(names[:position]) - {name}
        assert not later, f"{name} reads {sorted(later)}, asked after it"
