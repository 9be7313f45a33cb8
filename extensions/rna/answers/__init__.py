"""Copier's answers, read once each and checked, turned into the package model.

This is the only code that knows the questions of copier.yml. `build_package(answers)`
is the entry point: it reads the long form of every answer (mappings) and the short
forms typed at a prompt, checks them against the ROS rules and raises AnswerError
naming the question and the rule. The one-node quick questions, the demo and the
default description live here too.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import cached_property

import yaml

from .. import distros, layout, names, wording
from .. import lab as lab_choices
from ..definitions import Definition
from ..interfaces import InterfaceType
from ..licenses import get_license
from ..model import Node, Package
from .interfaces import parse_definitions
from .nodes import Types, parse_node, parse_nodes
from ..shapes import load_yaml, split_list

# The questions whose answers make the package, in the order they are checked.
QUESTIONS = ("package_name", "description", "maintainer", "maintainer_email", "license",
             "copyright_holder", "ros_distro", "build_type", "launch_format", "target", "interfaces",
             "interfaces_location", "nodes")

# Quick one-node questions and the `nodes` key each one fills.
QUICK_LISTS = {
    "node_publishers": "publishers",
    "node_subscribers": "subscribers",
    "node_service_servers": "service_servers",
    "node_service_clients": "service_clients",
    "node_action_servers": "action_servers",
    "node_action_clients": "action_clients",
    "node_timers": "timers",
    "node_parameters": "parameters",
}

# The one-node questions: a first copy's way to `nodes`, which the answers file records instead.
FIRST_COPY = ("node_language", "node_name", *QUICK_LISTS)

# The demo: a talker and a listener on one topic.
DEMO_NODES = [
    {"name": "talker", "publishers": ["chatter:std_msgs/msg/String"], "timers": [0.5]},
    {"name": "listener", "subscribers": ["chatter:std_msgs/msg/String"]},
]



class AnswerError(ValueError):
    """A broken rule in one answer: `str()` is the one line shown to the user."""

    def __init__(self, question: str, message: str) -> None:
        super().__init__(f"invalid answer to '{question}': {message}")
        self.question = question
        self.message = message


def _one_line(value: object) -> str:
    error = names.one_line_error(value)
    if error:
        raise ValueError(error)
    return value.strip()


class Answers:
    """The answers given so far, each read once, on first use."""

    def __init__(self, answers: Mapping, lab: Mapping | None = None) -> None:
        self.raw = dict(answers)
        self.lab = lab_choices.load() if lab is None else lab
        if self.ros == 1 and not self.raw.get("build_type"):
            self.raw["build_type"] = "catkin"  # not asked, so not in the answers file either

    @property
    def ros(self) -> int:
        return distros.generation(self.raw.get("ros_distro"))

    # --- one reader per question; each raises ValueError naming the rule

    def _package_name(self) -> str:
        value = self.raw.get("package_name")
        error = names.generated_package_name_error(value)
        if error:
            raise ValueError(error)
        return value

    def _license(self):
        return get_license(self.raw.get("license"))

    def _maintainer_email(self) -> str:
        value = self.raw.get("maintainer_email")
        error = names.email_error(value)
        if error:
            raise ValueError(error)
        return value.strip()

    def _ros_distro(self) -> str:
        value = self.raw.get("ros_distro")
        if value not in distros.DISTROS:
            raise ValueError(f"'{value}' is not one of {', '.join(distros.DISTROS)}")
        return value

    def _build_type(self) -> str:
        value, allowed = self.raw.get("build_type"), distros.BUILD_TYPES_OF[self.ros]
        if value not in allowed:
            raise ValueError(f"'{value}' is not one of {', '.join(allowed)} for ROS {self.ros}")
        return value

    def _launch_format(self) -> str:
        value = self.raw.get("launch_format")
        if value is None:  # not asked (ROS 1, a node added to a package): the default
            return layout.DEFAULT_LAUNCH_FORMAT
        error = layout.launch_format_error(value, self.ros)
        if error:
            raise ValueError(error)
        return value

    def _target(self) -> str:
        value = self.raw.get("target")
        if value not in (None, "package", "node"):
            raise ValueError(f"'{value}' is not package or node")
        if value == "node" and self.raw.get("interfaces"):
            raise ValueError("a node added to an existing package cannot define interfaces: name "
                             "existing ones, or generate a package")
        return value or "package"

    def _interfaces_location(self) -> str:
        value = self.raw.get("interfaces_location")
        if value not in (None, "separate", "package"):
            raise ValueError(f"'{value}' is not separate or package")
        build_type = self.raw.get("build_type")
        if value == "package" and build_type and build_type not in distros.BUILDS_INTERFACES:
            raise ValueError(f"an {build_type} package cannot build interfaces: keep them separate")
        return value or "separate"

    @property
    def interfaces_home(self) -> str:
        """Where the package's own interfaces live: <package>_interfaces, or the package itself."""
        package = self.raw.get("package_name") or "pkg"
        return package if self.raw.get("interfaces_location") == "package" else f"{package}_interfaces"

    @cached_property
    def definitions(self) -> tuple[Definition, ...]:
        return parse_definitions(self.raw.get("interfaces"), package=self.interfaces_home, ros=self.ros)

    @cached_property
    def types(self) -> Types:
        """How node answers read types: with the interfaces the answers define."""
        home = self.interfaces_home
        own = {(d.kind, d.name): InterfaceType(home, d.kind, d.name, self.ros) for d in self.definitions}
        return Types(self.ros, own, self.raw.get("ros_distro"), self.lab.get("qos"))

    @cached_property
    def nodes(self) -> tuple[Node, ...]:
        nodes = parse_nodes(self.raw.get("nodes"), package=self.raw.get("package_name") or "pkg",
                            build_type=self.raw.get("build_type"), types=self.types)
        if self.raw.get("target") == "node" and len(nodes) != 1:
            raise ValueError("a node added to an existing package is one node: give exactly one")
        return nodes

    def _quick_node(self) -> None:
        """The one node the quick questions describe so far, checked as the node it becomes.

        Its language is asked before its name, and the package is the real one, so a rule that
        depends on them (a ROS 1 Python script named like a module it imports, a C++ node's
        name with its package's) is met at the question that breaks it, not after the last.
        """
        language = distros.node_language(self.raw.get("build_type"), self.raw.get("node_language"))
        name = self.raw.get("node_name") if not names.node_name_error(self.raw.get("node_name")) else "node"
        package = self.raw.get("package_name")
        node = {"name": name, "language": language}
        node.update((key, self.raw[question]) for question, key in QUICK_LISTS.items() if self.raw.get(question))
        parse_node(node, package=package if not names.package_name_error(package) else "pkg",
                   build_type=self.raw.get("build_type"), types=Types(self.ros, distro=self.raw.get("ros_distro")))

    def _copyright_year(self) -> int:
        value = self.raw.get("copyright_year")
        year = int(value) if isinstance(value, str) and value.strip().isdigit() else value  # --data gives text
        if isinstance(year, bool) or not isinstance(year, int) or not 1970 <= year <= 9999:
            raise ValueError(f"'{value}' is not a year")
        return year

    def _node_name(self) -> None:
        error = names.node_name_error(self.raw.get("node_name"))
        if error:
            raise ValueError(error)
        self._quick_node()

    def read(self, question: str):
        """The answer to `question`, read and checked; ValueError names the rule broken."""
        if question in ("description", "maintainer"):
            return _one_line(self.raw.get(question))
        if question == "copyright_holder":
            holder = _one_line(self.raw.get(question))
            if holder.endswith(("\\", "??/")):  # ??/ is the trigraph of a backslash; GCC warns of it
                raise ValueError("a backslash (or ??/) at the end would continue the C++ comment line it ends")
            return holder
        if question in ("interfaces", "nodes"):
            return getattr(self, "definitions" if question == "interfaces" else question)
        if question in QUICK_LISTS:
            return self._quick_node()
        return getattr(self, f"_{question}")()

    def check(self, question: str) -> None:
        try:
            self.read(question)
        except ValueError as error:
            raise AnswerError(question, str(error)) from None

    @property
    def package(self) -> Package:
        """The model; AnswerError on the first broken rule."""
        read = {}
        for question in QUESTIONS:
            try:
                read[question] = self.read(question)
            except ValueError as error:
                raise AnswerError(question, str(error)) from None
        package_name, home = read["package_name"], self.interfaces_home
        used = {dependency for node in read["nodes"] for dependency in node.dependencies} - {home}
        if package_name in used:
            raise AnswerError("package_name", f"'{package_name}' is the name of a package its nodes use")
        try:
            year = self._copyright_year()
        except ValueError as error:
            raise AnswerError("copyright_year", str(error)) from None
        return Package(
            name=read["package_name"],
            description=read["description"],
            maintainer=read["maintainer"],
            maintainer_email=read["maintainer_email"],
            license=read["license"],
            copyright_holder=read["copyright_holder"],
            copyright_year=year,
            ros_distro=read["ros_distro"],
            build_type=read["build_type"],
            nodes=read["nodes"],
            definitions=read["interfaces"],
            interfaces_location=read["interfaces_location"],
            target=read["target"],
            launch_format=read["launch_format"],
            lab_dependencies=tuple(lab_choices.dependencies(self.lab)),
            lab_header=self.lab.get("header", ""),
            # A node added to a package the template did not make brings its own files only.
            lab_files=() if read["target"] == "node" else tuple(lab_choices.files(self.lab)),
        )

    def default_description(self, width: int | None = None) -> str:
        """What the nodes answered so far do, as the package's default description, in `width` columns."""
        try:
            return wording.describe_nodes(self.nodes, width)
        except ValueError:
            return "ROS nodes"

    @property
    def default_nodes(self) -> str:
        """The `nodes` default as YAML: the node described by the quick questions, or the demo."""
        if self.raw.get("node_setup") != "one":
            return yaml.safe_dump(DEMO_NODES, sort_keys=False)
        node = {"name": self.raw.get("node_name"),
                "language": distros.node_language(self.raw.get("build_type"), self.raw.get("node_language"))}
        for question, key in QUICK_LISTS.items():
            if self.raw.get(question):
                node[key] = split_list(self.raw[question])
        return yaml.safe_dump([node], sort_keys=False)


# Answers Copier itself checks (a choice) or parses (YAML) when they are given without a
# prompt; its error would be a traceback, so they are checked first (check_given).
_CHOICES = {
    "interfaces_location": ("separate", "package"),
    "target": ("package", "node"),
    "node_setup": ("demo", "one", "dialog", "list"),
    "node_language": ("cpp", "python"),
}


def _shape_error(value: object, question_type: str | None) -> str | None:
    """Why Copier cannot cast an answer given as data to its question's type (copier.yml's `type:`)."""
    if question_type == "str" and not isinstance(value, (str, int, float)):
        shape = ("an empty answer" if value is None else "a list" if isinstance(value, list)
                 else "a mapping" if isinstance(value, Mapping) else "a " + type(value).__name__)
        return f"give text here, not {shape}"
    return None


# Answers whose choices depend on others: checked once those are known (check_given), and
# at once against every choice they may have.
DEPENDS_ON = {"build_type": ("ros_distro",), "launch_format": ("ros_distro",),
              "interfaces_location": ("ros_distro", "build_type")}
ANY_OF = {"build_type": distros.BUILD_TYPES, "launch_format": layout.LAUNCH_FORMATS[2],
          "interfaces_location": ("separate", "package")}


def check_given(given: Mapping, types: Mapping[str, str] | None = None, around: Mapping | None = None,
                skip: set[str] = frozenset()) -> set[str]:
    """AnswerError for the first answer given on the command line that Copier would refuse;
    returns the questions checked (not those in `skip`, already checked).

    `types`: each question's `type:` in copier.yml; Copier casts a given answer to it, and
    one it cannot cast ends in a traceback. `around`: the other answers known so far (the
    answers file's on an update, those answered or defaulted before on a copy). An answer
    whose choices depend on others (a build type for the distro) is checked once they are
    given or known; until then it is left for a later call.
    """
    around = {**(around or {}), **given}
    if distros.generation(around.get("ros_distro")) == 1 and "build_type" not in given:
        around["build_type"] = "catkin"  # not asked in ROS 1
    checked = set()
    for question, value in given.items():
        if question in skip:
            continue
        try:
            shape = _shape_error(value, (types or {}).get(question))
            if shape:
                raise ValueError(shape)
            if question in ANY_OF and value not in ANY_OF[question]:  # whatever the other answers
                raise ValueError(f"'{value}' is not one of {', '.join(ANY_OF[question])}")
            if any(around.get(other) is None for other in DEPENDS_ON.get(question, ())):
                continue  # checked again once what it depends on is known
            if question == "copyright_year":
                Answers(given).read(question)
            if question in _CHOICES and value not in _CHOICES[question]:
                raise ValueError(f"'{value}' is not one of {', '.join(_CHOICES[question])}")
            if question in ("ros_distro", "license"):
                Answers(given).read(question)
            elif question in DEPENDS_ON:
                Answers(around).read(question)
            elif question in ("nodes", "interfaces"):
                load_yaml(value)
        except ValueError as error:
            raise AnswerError(question, str(error)) from None
        checked.add(question)
    return checked


def build_package(answers: Mapping) -> Package:
    """Check every answer and build the model; raises AnswerError on the first broken rule."""
    return Answers(answers).package


def question_error(question: str, answers: Mapping) -> str | None:
    """The error for one question given the answers so far, or None: for Copier validators."""
    try:
        Answers(answers).read(question)
    except ValueError as error:
        return str(error)
    return None


__all__ = ["FIRST_COPY", "QUESTIONS", "QUICK_LISTS", "AnswerError", "Answers", "build_package", "check_given",
           "question_error", "split_list"]
