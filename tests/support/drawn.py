"""Drawn answer sets under the real linters (issue 8): generate many, lint them together, reduce a failure.

Hypothesis draws the answer sets (tests/support/strategies.py) and each one is generated
in-process, as `copier copy --data-file` would. The packages are then linted together,
one call per linter, since starting a linter costs more than the files it reads. Only
when a call fails is each package linted alone, to name the answers that fail.

Hypothesis's shrinking would re-generate and re-lint a whole batch for every step, so it
is off; instead a failing answer set is reduced here, linting only that package with only
the linter that failed: nodes, endpoints, parameters, interfaces and free text are taken
away one at a time while the same linter still fails, until nothing more can go or the
time is up. The report gives both the drawn answers (the exact reproduction) and the
reduced ones, as YAML for `copier copy --data-file`.
"""

from __future__ import annotations

import copy as copying
import re
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import copier
import yaml
from hypothesis import Phase, given, settings
from rna import AnswerError, build_package

from .strategies import read_data_file, write_data_file

# A linter's run over files (exit code, output); and which of a package's files it takes.
Run = Callable[[list[Path]], tuple[int, str]]
REDUCE_SECONDS = 120  # for all the reductions of one test: a report in good time beats a minimal one
OUTPUT_LINES = 40


def copy(template: Path, destination: Path, answers: dict) -> None:
    """`copier copy --data-file answers.yml --defaults --trust`, in-process."""
    destination.parent.mkdir(parents=True, exist_ok=True)
    data = read_data_file(write_data_file(answers, destination.parent / f"{destination.name}.answers.yml"))
    copier.run_copy(str(template), str(destination), data=data, defaults=True, unsafe=True, quiet=True)


def python_files(destination: Path) -> list[Path]:
    return sorted(destination.rglob("*.py"))


def cpp_files(destination: Path) -> list[Path]:
    return sorted(path for suffix in ("*.cpp", "*.hpp", "*.h") for path in destination.rglob(suffix))


def whole(destination: Path) -> list[Path]:
    """The copy's folder itself: catkin_lint finds the packages under it."""
    return [destination]


@dataclass(frozen=True)
class Linter:
    name: str
    run: Run
    files: Callable[[Path], list[Path]]
    passed: Callable[[int, str], bool] = lambda returncode, output: returncode == 0

    def check(self, destinations: list[Path]) -> tuple[bool, str]:
        files = [path for destination in destinations for path in self.files(destination)]
        if not files:
            return True, ""
        returncode, output = self.run(files)
        return self.passed(returncode, output), output


@dataclass
class Drawn:
    answers: dict
    destination: Path


@dataclass
class Failure:
    drawn: Drawn
    linter: Linter
    output: str
    reduced: dict | None = None
    reduced_output: str = ""
    steps: int = 0
    notes: list[str] = field(default_factory=list)


def draw_and_generate(template: Path, root: Path, strategy, count: int) -> list[Drawn]:
    """`count` answer sets drawn by `strategy` (seeded as the Hypothesis profile says), each generated."""
    drawn: list[Drawn] = []

    @settings(max_examples=count, phases=(Phase.explicit, Phase.generate))
    @given(strategy)
    def generate_one(answers):
        answers = dict(answers)
        answers.pop("_expected", None)
        destination = root / f"drawn{len(drawn):03d}"
        copy(template, destination, answers)
        drawn.append(Drawn(answers, destination))

    generate_one()
    return drawn


def _unique_rounds(drawn: list[Drawn]) -> Iterator[list[Drawn]]:
    """The sets in groups without two packages of one name (a linter may see them as one)."""
    left = list(drawn)
    while left:
        names, group, rest = set(), [], []
        for item in left:
            name = item.answers["package_name"]
            (rest if name in names else group).append(item)
            names.add(name)
        yield group
        left = rest


def lint(drawn: list[Drawn], linters: list[Linter]) -> list[Failure]:
    """Each linter once over every package; where it fails, over each package alone to say which."""
    failures = []
    for linter in linters:
        for group in _unique_rounds(drawn):
            ok, output = linter.check([item.destination for item in group])
            if ok:
                continue
            alone = []
            for item in group:
                ok_alone, output_alone = linter.check([item.destination])
                if not ok_alone:
                    alone.append(Failure(item, linter, output_alone))
            if not alone:  # only together: report the call as it failed
                alone = [Failure(item, linter, output) for item in group]
                for failure in alone:
                    failure.notes.append("fails only when linted with the others of its batch")
            failures += alone
    return failures


# ----------------------------------------------------------------------------- reduction

NODE_KEYS = ("publishers", "subscribers", "service_servers", "service_clients", "action_servers",
             "action_clients", "timers", "parameters", "description", "lifecycle", "component")
SIMPLE_TEXT = {"description": "A package.", "maintainer": "Ada", "maintainer_email": "ada@example.com",
               "copyright_holder": "Ada"}


def _normalised(answers: dict) -> dict:
    """The answers with `nodes` and `interfaces` as data, not YAML text."""
    answers = copying.deepcopy(answers)
    for key in ("nodes", "interfaces"):
        if isinstance(answers.get(key), str):
            answers[key] = yaml.safe_load(answers[key])
    return answers


def _smaller(answers: dict) -> Iterator[dict]:
    """Answer sets with one thing less than `answers`, the biggest cuts first."""
    nodes = answers["nodes"]
    if len(nodes) > 1:
        for index in range(len(nodes)):
            yield {**answers, "nodes": [nodes[index]]}
        for index in range(len(nodes)):
            yield {**answers, "nodes": nodes[:index] + nodes[index + 1:]}
    if answers.get("interfaces"):
        yield {key: value for key, value in answers.items() if key not in ("interfaces", "interfaces_location")}
    for index, node in enumerate(nodes):
        def with_node(new, index=index):
            return {**answers, "nodes": [*nodes[:index], new, *nodes[index + 1:]]}
        for key in NODE_KEYS:
            if key in node:
                yield with_node({k: v for k, v in node.items() if k != key})
        for key in NODE_KEYS:
            value = node.get(key)
            if isinstance(value, list) and len(value) > 1:
                for item in range(len(value)):
                    yield with_node({**node, key: value[:item] + value[item + 1:]})
            if isinstance(value, list):
                for item, entry in enumerate(value):
                    if isinstance(entry, dict):
                        for part in ("id", "qos", "description", "range", "read_only"):
                            if part in entry:
                                smaller = {k: v for k, v in entry.items() if k != part}
                                yield with_node({**node, key: [*value[:item], smaller, *value[item + 1:]]})
    interfaces = answers.get("interfaces") or {}
    for key, entries in interfaces.items():
        for item in range(len(entries or [])):
            yield {**answers, "interfaces": {**interfaces, key: entries[:item] + entries[item + 1:]}}
    for key, simple in SIMPLE_TEXT.items():
        if answers.get(key) != simple:
            yield {**answers, key: simple}
    for index, node in enumerate(nodes):
        if len(node["name"]) > 4:
            yield {**answers, "nodes": [*nodes[:index], {**node, "name": f"n{index}"}, *nodes[index + 1:]]}
    if len(answers["package_name"]) > 4:
        yield {**answers, "package_name": "pkg"}


def reduce(failure: Failure, template: Path, root: Path, deadline: float) -> None:
    """Cut the failure's answers down while its linter still fails on them (until `deadline`)."""
    answers = _normalised(failure.drawn.answers)
    output = failure.output
    tried = 0
    progress = True
    while progress and time.monotonic() < deadline:
        progress = False
        for candidate in _smaller(answers):
            if time.monotonic() >= deadline:
                failure.notes.append("reduction stopped at its time limit")
                break
            try:
                build_package(candidate)
            except AnswerError:
                continue  # a cut that the rules refuse
            tried += 1
            destination = root / f"try{tried:04d}"
            try:
                copy(template, destination, candidate)
            except Exception:  # noqa: BLE001 - another defect; keep to the one being reduced
                continue
            ok, candidate_output = failure.linter.check([destination])
            if not ok:
                answers, output, progress = candidate, candidate_output, True
                failure.steps += 1
                break
    if failure.steps:
        failure.reduced, failure.reduced_output = answers, output


def _yaml(answers: dict) -> str:
    text = yaml.safe_dump(answers, allow_unicode=True, sort_keys=False, width=100)
    if yaml.safe_load(text) != answers:
        text = yaml.safe_dump(answers, allow_unicode=False, sort_keys=False, width=100)
    return text


def _tail(text: str) -> str:
    lines = text.strip().splitlines()
    return "\n".join(lines[:OUTPUT_LINES] + ([f"... ({len(lines) - OUTPUT_LINES} more lines)"]
                                              if len(lines) > OUTPUT_LINES else []))


# What names a complaint, without its file, line or package: a cpplint category, a flake8 or
# pep257 code, catkin_lint's message, uncrustify's divergence.
_COMPLAINT = re.compile(r"\[[a-z_]+/[a-z_]+\]|\b[A-Z]\d{3}\b|(?:error|warning|notice): .*|Code style divergence")


def signature(failure: Failure) -> tuple[str, frozenset[str]]:
    return failure.linter.name, frozenset(_COMPLAINT.findall(failure.output))


def _size(failure: Failure) -> int:
    return len(_yaml(failure.drawn.answers))


def report(failures: list[Failure], drawn_count: int, root: Path) -> str:
    """Each kind of failure with its smallest answer set as drawn and as reduced, the others named.

    The answers are written as YAML files for `copier copy --data-file`.
    """
    parts = [f"{len(failures)} linter failure(s) in {drawn_count} drawn packages. Reproduce one with\n"
             "  tests/env copier copy --trust --defaults --vcs-ref HEAD --data-file <answers.yml> . /tmp/out\n"
             "then run the linter named on the files it names."]
    for number, failure in enumerate(failures, 1):
        exact = root / f"failure{number}.yml"
        exact.write_text(_yaml(failure.drawn.answers), encoding="utf-8")
        if failure.notes[:1] == ["same complaints as above"]:
            parts.append(f"\n=== {number}. {failure.linter.name} on {failure.drawn.destination.name}: the same "
                         f"complaints as another failure above ({exact})")
            continue
        notes = failure.notes or ["reduced" if failure.reduced is not None else "not reduced"]
        part = [f"\n=== {number}. {failure.linter.name} on {failure.drawn.destination.name} ({'; '.join(notes)})"]
        if failure.reduced is not None:
            reduced = root / f"failure{number}.reduced.yml"
            reduced.write_text(_yaml(failure.reduced), encoding="utf-8")
            part += [f"--- reduced in {failure.steps} steps ({reduced}):", _yaml(failure.reduced).rstrip(),
                     f"--- {failure.linter.name} on the reduced package:", _tail(failure.reduced_output)]
        part += [f"--- as drawn ({exact}):", _yaml(failure.drawn.answers).rstrip(),
                 f"--- {failure.linter.name} on the drawn package:", _tail(failure.output)]
        parts.append("\n".join(part))
    return "\n".join(parts)


def check_drawn(template: Path, root: Path, strategy, count: int, linters: list[Linter]) -> tuple[int, str | None]:
    """Draw, generate and lint `count` packages: (how many, a report of the failures or None)."""
    drawn = draw_and_generate(template, root / "drawn", strategy, count)
    failures = lint(drawn, linters)
    if not failures:
        return len(drawn), None
    # One failure of each kind, the smallest, is reduced and shown in full.
    shown: list[Failure] = []
    failures.sort(key=_size)
    for failure in failures:
        if any(signature(failure) == signature(other) for other in shown):
            failure.notes.insert(0, "same complaints as above")
        else:
            shown.append(failure)
    failures = shown + [failure for failure in failures if not any(failure is other for other in shown)]
    deadline = time.monotonic() + REDUCE_SECONDS
    for failure in shown:
        folder = f"{failure.drawn.destination.name}-{failure.linter.name.split()[0]}"
        reduce(failure, template, root / "reduce" / folder, deadline)
    return len(drawn), report(failures, len(drawn), root)


def thorough() -> bool:
    """The Hypothesis profile asks for many examples (HYPOTHESIS_PROFILE=thorough)."""
    return settings.default.max_examples > 100


def code_linters(ros2) -> list[Linter]:
    """The linters a generated ROS 2 package runs on its code, from the ros tier's environment."""
    return [Linter("ament_flake8", ros2.flake8, python_files), Linter("ament_pep257", ros2.pep257, python_files),
            Linter("ament_cpplint", ros2.cpplint, cpp_files), Linter("ament_uncrustify", ros2.uncrustify, cpp_files)]
