"""roscpp -> rclcpp: a C++ file of the user's rewritten by the rules of rna.port.rules.

C++ is not parsed here: the rules match code (comments and string literals masked out)
and take a call's arguments by balanced brackets, so a rewrite replaces exactly the call,
type or member a rule names, and leaves everything else as written. Passes run in an
order that keeps lines where they were until the last ones: types, members and calls;
then the logging macros (their arguments already ported); then what the base class's
API changes in the node's class (callback declarations, the constructor, parameters of a
new type); last, a `// TODO(port)` line above each line still naming ROS 1.

`port(text, context)` returns the new text, each rewrite (rule, line, before, after),
each line marked and the includes the rewrites need.
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Mapping
from dataclasses import dataclass, field

from .. import names
from ..dialects import lines as breaking
from . import api
from .python import Ported, Rewrite
from .rules import rule

WIDTH = 100  # cpplint's and ROS 2's line length
LEVELS = ("DEBUG", "INFO", "WARN", "ERROR", "FATAL")
LOG_MACRO = re.compile(r"\bROS_(DEBUG|INFO|WARN|ERROR|FATAL)(_STREAM)?(_THROTTLE|_ONCE|_COND|_NAMED)?\s*\(")
ROS1_LEFT = re.compile(r"\b(ros::\w+|actionlib::\w+|ROS_[A-Z_]+\s*\(|tf::\w+|nodelet::\w+|XmlRpc\w*|"
                       r"dynamic_reconfigure::\w+|boost::bind)")
# A message's stamp (msg.header.stamp, msg->header.stamp): a ros::Time in ROS 1, a message in ROS 2.
STAMP = re.compile(r"(?<![\w.>])(?:\w+(?:\[[^\]\n]*\])?\s*(?:\.|->)\s*)+stamp\b")
# An operand of time arithmetic or of a comparison (not of ->, <<, >>, ++, --, or an assignment).
TIME_OPERATOR_BEFORE = re.compile(r"(?:(?<![-+<>=!])[-+<>]|[<>=!]=)\s*$")
TIME_OPERATOR_AFTER = re.compile(r"\s*(?:[-+](?![-+=>])|[<>](?![<>=])|[<>=!]=)")
WRITTEN = re.compile(r"\s*(=(?!=)|\+\+|--|[-+*/]=)")
GOAL_STATES = {"SUCCEEDED": "SUCCEEDED", "ABORTED": "ABORTED", "PREEMPTED": "CANCELED", "RECALLED": "CANCELED"}
TODO_CALLS = {
    "ros::init": "cpp.todo.main", "ros::spin": "cpp.todo.main", "ros::spinOnce": "cpp.todo.main",
    "ros::NodeHandle": "cpp.todo.node_handle", "ros::param::get": "cpp.todo.param",
    "ros::param::set": "cpp.todo.global_param", "ros::param::has": "cpp.todo.global_param",
    "ros::param::del": "cpp.todo.global_param",
    "ros::ServiceClient": "cpp.todo.service_call", "ros::service::call": "cpp.todo.service_call",
    "ros::service::waitForService": "cpp.todo.service_call", "ros::topic::waitForMessage": "cpp.todo.other",
}
INCLUDES = {"ros/ros.h": "rclcpp/rclcpp.hpp", "ros/console.h": "rclcpp/rclcpp.hpp", "ros/time.h": "rclcpp/rclcpp.hpp",
            "ros/duration.h": "rclcpp/rclcpp.hpp", "ros/rate.h": "rclcpp/rclcpp.hpp",
            "boost/shared_ptr.hpp": "<memory>", "boost/make_shared.hpp": "<memory>"}
REMOVED_INCLUDES = ("actionlib/server/simple_action_server.h", "actionlib/client/simple_action_client.h",
                    "actionlib/client/terminal_state.h")


@dataclass(frozen=True)
class Context:
    """What the rewriter knows of the file: its node's class and base-class API, if it is a node's."""

    class_name: str = ""  # the user's node class (Driver)
    base_class: str = ""  # DriverBase
    logger: str = ""  # the logger's name outside the node's class
    parameters: tuple[tuple[str, str], ...] = ()  # (name, ROS 2 accessor: as_double...)
    publishers: frozenset[str] = frozenset()  # endpoint ids
    subscribers: frozenset[str] = frozenset()
    timers: frozenset[str] = frozenset()
    service_clients: tuple[tuple[str, str], ...] = ()  # (id, the type's alias: SetBool)
    action_clients: frozenset[str] = frozenset()
    action_servers: tuple[tuple[str, str], ...] = ()  # (id, the type's alias: Test)
    action_types: frozenset[str] = frozenset()  # aliases of action types (ROS 1: TestGoal is Test::Goal now)
    callbacks: tuple[tuple[str, api.CppCallback, str], ...] = ()  # (method, entry, ROS 2 declaration)
    constructor: str = ""  # the ROS 2 starter's constructor declaration (up to its body)
    kinds: Mapping[tuple[str, str], str] = field(default_factory=dict)  # (package, type) -> msg, srv, action
    headers: tuple[tuple[str, str], ...] = ()  # (ROS 1 header, ROS 2 one) of the package's own: the base class's


def mask(text: str) -> str:
    """`text` with comments and the insides of string and character literals as spaces (same length)."""
    out = list(text)
    index, length = 0, len(text)

    def blank(start: int, end: int) -> None:
        for position in range(start, end):
            if out[position] != "\n":
                out[position] = " "

    while index < length:
        char = text[index]
        if text.startswith("//", index):
            end = text.find("\n", index)
            end = length if end < 0 else end
            blank(index, end)
            index = end
        elif text.startswith("/*", index):
            end = text.find("*/", index + 2)
            end = length if end < 0 else end + 2
            blank(index, end)
            index = end
        elif char in "\"'":
            raw = char == '"' and index > 0 and text[index - 1] == "R"
            if raw:
                match = re.match(r'"([^(\s]*)\(', text[index:])
                closing = f"){match[1]}\"" if match else '"'
                end = text.find(closing, index + 1)
                end = length if end < 0 else end + len(closing) - 1
            else:
                end = index + 1
                while end < length and text[end] != char and text[end] != "\n":
                    end += 2 if text[end] == "\\" else 1
            blank(index + 1, min(end, length))
            index = end + 1
        else:
            index += 1
    return "".join(out)


def closing(masked: str, opening: int) -> int:
    """The index of the bracket closing the one at `opening` (-1 when it does not close)."""
    pairs = {"(": ")", "[": "]", "{": "}"}
    depth = 0
    for index in range(opening, len(masked)):
        char = masked[index]
        if char in pairs:
            depth += 1
        elif char in pairs.values():
            depth -= 1
            if depth == 0:
                return index
    return -1


def open_brackets(masked: str) -> int:
    """How many round and square brackets `masked` (comments and literals blanked) leaves open."""
    return masked.count("(") + masked.count("[") - masked.count(")") - masked.count("]")


def arguments(masked: str, opening: int, end: int) -> list[tuple[int, int]]:
    """(start, end) of each top-level argument between the brackets at `opening` and `end`."""
    spans, depth, start = [], 0, opening + 1
    for index in range(opening + 1, end):
        char = masked[index]
        if char in "([{":
            depth += 1
        elif char in ")]}":
            depth -= 1
        elif char == "," and depth == 0:
            spans.append((start, index))
            start = index + 1
    if masked[start:end].strip() or spans:
        spans.append((start, end))
    return spans


@dataclass
class _Edit:
    start: int
    end: int
    text: str
    rule: str


class _Rewriter:
    def __init__(self, text: str, context: Context) -> None:
        self.text = text
        self.original = set(text.split("\n"))  # lines as long as these were the user's already
        self.ctx = context
        self.rewrites: list[Rewrite] = []
        self.todos: dict[int, list[str]] = {}  # line (from 1, in the current text) -> rules
        self.needed: set[str] = set()
        self.ported: dict[str, tuple[api.CppCallback, list[str]]] = {}  # callback -> (entry, ROS 1 names)

    # --- the text and its edits

    @property
    def masked(self) -> str:
        return mask(self.text)

    def line_of(self, index: int) -> int:
        return self.text.count("\n", 0, index) + 1

    def apply(self, edits: list[_Edit]) -> None:
        """Apply non-overlapping edits (an edit inside one kept before it is dropped); each line they
        change is recorded whole, before and after, with the rules used on it."""
        kept, last = [], -1
        for edit in sorted(edits, key=lambda e: (e.start, -e.end)):
            if edit.start < last:
                continue
            kept.append(edit)
            last = edit.end
        if not kept:
            return
        lines = self.text.split("\n")
        changed: dict[int, list[str]] = {}
        for edit in kept:
            first, last_line = self.line_of(edit.start), self.line_of(max(edit.end - 1, edit.start))
            changed.setdefault(first, [])
            if edit.rule not in changed[first]:
                changed[first].append(edit.rule)
            for line in range(first + 1, last_line + 1):
                changed.setdefault(line, [])
        before = {line: lines[line - 1] for line in changed}
        for edit in reversed(kept):
            self.text = self.text[:edit.start] + edit.text + self.text[edit.end:]
        after = self.text.split("\n")
        if len(after) != len(lines):  # an edit changed the number of lines: recorded by its span alone
            for edit in kept:
                self.rewrites.append(Rewrite(self.line_of(edit.start), edit.rule, "", " ".join(edit.text.split())))
            return
        for line, keys in sorted(changed.items()):
            if keys:
                self.rewrites.append(Rewrite(line, ", ".join(keys), " ".join(before[line].split()),
                                             " ".join(after[line - 1].split())))

    def todo(self, index: int, key: str) -> None:
        """Mark the statement at `index`: its TODO(port) goes above its first line (one inside a call's
        arguments would be a place a port of the ported file marks again once the call is broken)."""
        masked = self.masked
        starts = [0] + [position + 1 for position, char in enumerate(masked) if char == "\n"]
        line = self.line_of(index)
        while line > 1 and open_brackets(masked[:starts[line - 1]]) > 0:
            line -= 1
        keys = self.todos.setdefault(line, [])
        if key not in keys and not (key == "cpp.todo.other" and keys):
            keys.append(key)

    # --- where the code is

    def class_span(self) -> tuple[int, int] | None:
        if not self.ctx.class_name:
            return None
        masked = self.masked
        match = re.search(rf"\bclass\s+{re.escape(self.ctx.class_name)}\b[^;{{]*\{{", masked)
        if not match:
            return None
        end = closing(masked, match.end() - 1)
        return (match.end() - 1, end) if end > 0 else None

    def in_class(self, index: int) -> bool:
        span = self.class_span()
        return span is not None and span[0] < index < span[1]

    def logger(self, index: int) -> str:
        return "get_logger()" if self.in_class(index) else f'rclcpp::get_logger("{self.ctx.logger or "node"}")'

    # --- the passes

    def run(self) -> Ported:
        self.pass_includes()
        self.pass_types()
        self.pass_calls()
        self.pass_logging()
        self.pass_callbacks()
        self.pass_constructor()
        self.pass_todos()
        todos = sorted((line, key) for line, keys in self.todos.items() for key in keys)
        self.insert_todos()
        return Ported(wrapped(self.text, self.original), self.merged_rewrites(), todos, self.needed)

    def merged_rewrites(self) -> list[Rewrite]:
        """The rewrites, those of later passes on a line rewritten before joined to the first:
        one a line, from what it was to what it is."""
        merged: list[Rewrite] = []
        for rewrite in self.rewrites:
            chained = next((index for index, earlier in enumerate(merged) if earlier.line == rewrite.line
                            and earlier.after and earlier.after == rewrite.before), None)
            if chained is None:
                merged.append(rewrite)
                continue
            earlier = merged[chained]
            keys = ", ".join(dict.fromkeys(earlier.rule.split(", ") + rewrite.rule.split(", ")))
            merged[chained] = Rewrite(rewrite.line, keys, earlier.before, rewrite.after)
        return sorted(merged, key=lambda r: r.line)

    def pass_includes(self) -> None:
        edits = []
        for match in re.finditer(r'^[ \t]*#[ \t]*include[ \t]*([<"])([^>"]+)[>"][^\n]*\n?', self.text, re.M):
            header = match[2]
            new = self.include_of(header)
            if new is None:
                continue
            if new == "":
                edits.append(_Edit(match.start(), match.end(), "", "cpp.includes"))
                continue
            spelled = f"#include {new}\n" if new.startswith("<") else f'#include "{new}"\n'
            if not match[0].endswith("\n"):
                spelled = spelled[:-1]
            if spelled.strip() != match[0].strip():
                edits.append(_Edit(match.start(), match.end(), spelled, "cpp.includes"))
        self.apply(edits)
        # the same header twice (ros/ros.h and ros/console.h both become rclcpp.hpp): once
        seen, lines = set(), []
        for line in self.text.split("\n"):
            if line.startswith("#include") and line in seen:
                continue
            seen.add(line)
            lines.append(line)
        self.text = "\n".join(lines)

    def include_of(self, header: str) -> str | None:
        """The ROS 2 header of a ROS 1 one; "" for one that goes; None for one that stays."""
        if header in INCLUDES:
            return INCLUDES[header]
        if header in dict(self.ctx.headers):
            return dict(self.ctx.headers)[header]
        if header in REMOVED_INCLUDES:
            return ""
        match = re.fullmatch(r"(\w+)/(\w+)\.h", header)
        if not match:
            return None
        package, name = match[1], match[2]
        kind = self.ctx.kinds.get((package, name))
        if kind is None and name.endswith("Action") and self.ctx.kinds.get((package, name[:-6])) == "action":
            kind, name = "action", name[:-6]
        if kind is None:
            return None
        return f"{package}/{kind}/{names.camel_to_snake(name)}.hpp"

    def pass_types(self) -> None:
        masked = self.masked
        edits = []
        # pkg::Type, pkg::TypeRequest, pkg::TypeGoal, with ::ConstPtr / ::Ptr or the typedefs
        pattern = re.compile(r"\b(\w+)::(\w+?)(Request|Response|ActionGoal|ActionResult|ActionFeedback|Action|Goal|"
                             r"Result|Feedback)?(ConstPtr|Ptr)?(::ConstPtr|::Ptr)?\b(?!::(?:msg|srv|action)\b)")
        for match in pattern.finditer(masked):
            package, name, part, typedef, pointer = match[1], match[2], match[3] or "", match[4], match[5]
            if package in ("std", "ros", "rclcpp", "boost", "actionlib"):
                continue
            kind = self.ctx.kinds.get((package, name))
            if kind is None and part:
                kind = self.ctx.kinds.get((package, name + part))
                if kind is not None:
                    name, part = name + part, ""
            if kind is None:
                continue
            if part and not ((kind == "srv" and part in ("Request", "Response"))
                             or (kind == "action" and part in ("Action", "Goal", "Result", "Feedback"))):
                continue
            spelled = f"{package}::{kind}::{name}" + (f"::{part}" if part and part != "Action" else "")
            if typedef or pointer:
                spelled += "::ConstSharedPtr" if "Const" in (typedef or pointer) else "::SharedPtr"
            edits.append(_Edit(match.start(), match.end(), spelled, "cpp.types"))
        # the node's action aliases: TestGoal is Test::Goal, TestGoal::ConstPtr a shared_ptr to a const one
        for alias in self.ctx.action_types:
            for match in re.finditer(rf"\b{re.escape(alias)}(Action|Goal|Result|Feedback)(::ConstPtr|ConstPtr)?\b",
                                     masked):
                spelled = alias if match[1] == "Action" else f"{alias}::{match[1]}"
                if match[2]:
                    spelled = f"std::shared_ptr<const {spelled}>"
                edits.append(_Edit(match.start(), match.end(), spelled, "cpp.types"))
        for match in re.finditer(r"\bboost::(shared_ptr|make_shared)\b", masked):
            edits.append(_Edit(match.start(), match.end(), f"std::{match[1]}", "cpp.types"))
        self.apply(edits)

    def pass_calls(self) -> None:
        masked = self.masked
        edits = []

        def call(pattern: str):
            for match in re.finditer(pattern, masked):
                opening = match.end() - 1
                end = closing(masked, opening)
                if end > 0:
                    yield match, opening, end

        # `ros::Time now = ros::Time::now();`: there `now()` would call the variable, this->now() the node's
        node_now = "this->now()" if re.search(r"[\w>&*]\s+now\s*[=;{(,)]", masked) else "now()"
        for match in re.finditer(r"\bros::Time::now\s*\(\s*\)", masked):
            edits.append(_Edit(match.start(), match.end(), node_now if self.in_class(match.start())
                               else "rclcpp::Clock().now()", "cpp.now"))
        for match, opening, end in call(r"\bros::Duration\s*\("):
            args = arguments(masked, opening, end)
            if re.match(r"\s*\.\s*sleep\s*\(\s*\)", masked[end + 1:end + 20]) and len(args) == 1:
                sleep = re.match(r"\s*\.\s*sleep\s*\(\s*\)", masked[end + 1:])
                seconds = self.text[args[0][0]:args[0][1]].strip()
                self.needed.add("<chrono>")
                edits.append(_Edit(match.start(), end + 1 + sleep.end(),
                                   f"rclcpp::sleep_for({self.chrono(seconds)})", "cpp.sleep"))
                continue
            if len(args) == 1:
                edits.append(_Edit(match.start(), end + 1, "rclcpp::Duration::from_seconds("
                                   f"{self.text[args[0][0]:args[0][1]].strip()})", "cpp.duration"))
            elif len(args) == 2:
                edits.append(_Edit(match.start(), opening, "rclcpp::Duration", "cpp.duration"))
        for match, opening, end in call(r"\bros::Time\s*\("):
            args = arguments(masked, opening, end)
            if len(args) in (0, 2):
                edits.append(_Edit(match.start(), opening, "rclcpp::Time", "cpp.time"))
        for match in re.finditer(r"\bros::(Rate|WallRate)\b", masked):
            edits.append(_Edit(match.start(), match.end(), f"rclcpp::{match[1]}", "cpp.rate"))
        for match in re.finditer(r"\bros::(Time|Duration)\b(?!\s*(?:::|\())", masked):  # the types
            edits.append(_Edit(match.start(), match.end(), f"rclcpp::{match[1]}", "cpp.time"))
        for match in re.finditer(r"\bros::ok\s*\(\s*\)", masked):
            edits.append(_Edit(match.start(), match.end(), "rclcpp::ok()", "cpp.ok"))
        for match in re.finditer(r"\bros::isShuttingDown\s*\(\s*\)", masked):
            edits.append(_Edit(match.start(), match.end(), "!rclcpp::ok()", "cpp.ok"))
        for match in re.finditer(r"\bros::shutdown\s*\(\s*\)", masked):
            edits.append(_Edit(match.start(), match.end(), "rclcpp::shutdown()", "cpp.ok"))
        for match in STAMP.finditer(masked):
            before, after = masked[:match.start()], masked[match.end():]
            if TIME_OPERATOR_BEFORE.search(before) or TIME_OPERATOR_AFTER.match(after):
                edits.append(_Edit(match.start(), match.end(), f"rclcpp::Time({self.text[match.start():match.end()]})",
                                   "cpp.stamp_time"))
            elif re.match(r"\s*\.\s*nsec\b", after):
                field = re.match(r"\s*\.\s*nsec\b", after)
                edits.append(_Edit(match.end(), match.end() + field.end(), ".nanosec", "cpp.stamp_fields"))
        for match in re.finditer(r"\.\s*toSec\s*\(\s*\)", masked):
            edits.append(self.seconds_of(match, "seconds()"))
        for match in re.finditer(r"\.\s*toNSec\s*\(\s*\)", masked):
            edits.append(self.seconds_of(match, "nanoseconds()"))
        # the base class's members, in the node's class
        for topic in self.ctx.publishers:
            for match in re.finditer(rf"\b{re.escape(topic)}_publisher_\s*\.\s*publish\s*\(", masked):
                edits.append(_Edit(match.start(), match.end(), f"{topic}_publisher_->publish(", "cpp.api.publisher"))
        for topic in self.ctx.subscribers:
            for match in re.finditer(rf"\b{re.escape(topic)}_subscriber_\b", masked):
                edits.append(_Edit(match.start(), match.end(), f"{topic}_subscription_", "cpp.api.subscriber"))
        for timer in self.ctx.timers:
            for match in re.finditer(rf"\b{re.escape(timer)}_timer_\s*\.\s*(stop|start)\s*\(\s*\)", masked):
                method = "cancel" if match[1] == "stop" else "reset"
                edits.append(_Edit(match.start(), match.end(), f"{timer}_timer_->{method}()", "cpp.api.timer"))
        for service, alias in self.ctx.service_clients:
            for match in re.finditer(rf"\b{re.escape(service)}_client_\s*\.\s*exists\s*\(\s*\)", masked):
                edits.append(_Edit(match.start(), match.end(), f"{service}_client_->service_is_ready()",
                                   "cpp.api.service_client"))
            for _, opening, end in call(rf"\bcall_{re.escape(service)}\s*\("):
                args = arguments(masked, opening, end)
                if len(args) != 1:
                    continue
                given = self.text[args[0][0]:args[0][1]].strip()
                empty = re.fullmatch(rf"{re.escape(alias)}::Request\s*\(\s*\)", given)
                made = (f"std::make_shared<{alias}::Request>()" if empty
                        else f"std::make_shared<{alias}::Request>({given})")
                edits.append(_Edit(args[0][0], args[0][1], made if not given.startswith("std::make_shared") else given,
                                   "cpp.api.service_call"))
        for action in self.ctx.action_clients:
            for match in re.finditer(rf"\b{re.escape(action)}_action_client_\s*\.\s*isServerConnected\s*\(\s*\)",
                                     masked):
                edits.append(_Edit(match.start(), match.end(), f"{action}_action_client_->action_server_is_ready()",
                                   "cpp.api.action_client"))
        for name, accessor in self.ctx.parameters:
            for match in re.finditer(rf"(?<![\w.>:]){re.escape(name)}_\b(?!\s*\()", masked):
                if not self.in_class(match.start()):
                    continue
                if WRITTEN.match(masked, match.end()):
                    continue  # written: marked by the last pass
                edits.append(_Edit(match.start(), match.end(), f'get_parameter("{name}").{accessor}()',
                                   "cpp.api.parameter"))
        self.apply([edit for edit in edits if edit is not None])

    def chrono(self, seconds: str) -> str:
        """A std::chrono duration of `seconds` (a number: exact milliseconds where it can)."""
        try:
            value = float(seconds)
        except ValueError:
            return f"std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>({seconds}))"
        if abs(value * 1000 - round(value * 1000)) < 1e-9:
            return f"std::chrono::milliseconds({round(value * 1000)})"
        return f"std::chrono::nanoseconds({round(value * 1e9)})"

    def seconds_of(self, match: re.Match, accessor: str) -> _Edit | None:
        """`t.toSec()`: `t.seconds()`; a message's stamp is an rclcpp::Time first."""
        before = self.masked[:match.start()]
        receiver = re.search(r"([\w.\->\[\]()]+)$", before)
        if receiver and re.search(r"(^|[.>])stamp$", receiver[1]):
            start = receiver.start(1)
            stamp = self.text[start:match.start()]
            return _Edit(start, match.end(), f"rclcpp::Time({stamp}).{accessor}", "cpp.to_sec")
        return _Edit(match.start(), match.end(), f".{accessor}", "cpp.to_sec")

    def pass_logging(self) -> None:
        masked = self.masked
        edits = []
        for match in LOG_MACRO.finditer(masked):
            level, stream, form = match[1], match[2] or "", match[3] or ""
            opening = match.end() - 1
            end = closing(masked, opening)
            if end < 0:
                continue
            args = arguments(masked, opening, end)
            logger = self.logger(match.start())
            macro = f"RCLCPP_{level}{stream}"
            if form == "_THROTTLE":
                if not args or not self.in_class(match.start()):
                    continue  # left as it is: marked by the last pass
                period = self.text[args[0][0]:args[0][1]].strip()
                try:
                    milliseconds = str(round(float(period) * 1000))
                except ValueError:
                    milliseconds = f"static_cast<int>(({period}) * 1000)"
                edits.append(_Edit(match.start(), args[0][1],
                                   f"{macro}_THROTTLE({logger}, *get_clock(), {milliseconds}", "cpp.log_throttle"))
            elif form == "_ONCE":
                edits.append(_Edit(match.start(), opening + 1, f"{macro}_ONCE({logger}, ", "cpp.log_once"))
            elif form == "_COND":
                edits.append(_Edit(match.start(), opening + 1, f"{macro}_EXPRESSION({logger}, ", "cpp.log_cond"))
            elif form == "_NAMED":
                if not args:
                    continue
                name = self.text[args[0][0]:args[0][1]].strip()
                following = self.text[args[0][1]:args[1][0]] if len(args) > 1 else ""
                edits.append(_Edit(match.start(), args[1][0] if len(args) > 1 else args[0][1],
                                   f"{macro}({logger}.get_child({name})" + following, "cpp.log"))
            else:
                # Arguments on the lines below the macro's: the logger goes first on theirs.
                below = re.match(r"\n[ \t]*", self.text[opening + 1:])
                if below:
                    edits.append(_Edit(match.start(), opening + 1 + below.end(),
                                       f"{macro}({below[0]}{logger}, ", "cpp.log"))
                else:
                    edits.append(_Edit(match.start(), opening + 1, f"{macro}({logger}, ", "cpp.log"))
        self.apply(edits)

    # --- the node's class: its callbacks and constructor

    def method(self, name: str) -> tuple[int, int, int, int] | None:
        """(declaration start, its parameters' opening bracket, their closing one, the body's opening brace)."""
        span = self.class_span()
        if span is None:
            return None
        masked = self.masked
        pattern = re.compile(rf"^[ \t]*(?:virtual[ \t]+)?[\w:<>,&* \t]*?\b{re.escape(name)}\s*\(", re.M)
        for match in pattern.finditer(masked, span[0], span[1]):
            opening = match.end() - 1
            end = closing(masked, opening)
            body = re.match(r"[\s\w]*\{", masked[end + 1:])
            if end > 0 and body:
                start = match.start() + len(match[0]) - len(match[0].lstrip())
                return start, opening, end, end + 1 + body.end()
        return None

    def pass_callbacks(self) -> None:
        found_all = [(self.method(name), name, entry, declaration) for name, entry, declaration in self.ctx.callbacks]
        for found, name, entry, declaration in sorted((item for item in found_all if item[0]), key=lambda i: -i[0][0]):
            start, opening, end, brace = found
            masked = self.masked
            names = [re.findall(r"\w+", self.text[a:b])[-1] if re.findall(r"\w+", self.text[a:b]) else ""
                     for a, b in arguments(masked, opening, end)]
            if len(names) != len(entry.ros1):
                continue
            self.ported[name] = (entry, names)
            body_end = closing(masked, brace - 1)
            body = self.text[brace:body_end]
            new_body = self.ported_body(entry, names, body, self.line_of(brace))
            indent = re.match(r"[ \t]*", self.text[self.text.rfind("\n", 0, start) + 1:])[0]
            header = self.declaration(declaration, entry, names, indent)
            self.rewrites.append(Rewrite(self.line_of(start), api.key("cpp", entry),
                                         " ".join(self.text[start:end + 1].split()), " ".join(header.split())))
            between = re.sub(r"[ \t]*\b(override|final)\b", "", self.text[end + 1:brace - 1])
            self.text = self.text[:start] + header + between + "{" + new_body + self.text[body_end:]

    def declaration(self, declaration: str, entry: api.CppCallback, names: list[str], indent: str) -> str:
        """The ROS 2 declaration, with the user's names of the parameters ROS 2 keeps."""
        masked = mask(declaration)
        opening = masked.index("(")
        end = closing(masked, opening)
        parameters = [declaration[a:b].strip() for a, b in arguments(masked, opening, end)]
        wanted = [spec.format(*names) for spec in entry.ros2]
        renamed = [re.sub(r"\w+$", wanted[index], parameter) if index < len(wanted) else parameter
                   for index, parameter in enumerate(parameters)]
        head = declaration[:opening].strip()
        one_line = f"{indent}{head}({', '.join(renamed)}) override"
        if len(one_line) <= WIDTH:
            return one_line.lstrip()
        inner = indent + "  "
        return f"{head}(\n" + ",\n".join(inner + parameter for parameter in renamed) + ") override"

    def ported_body(self, entry: api.CppCallback, names: list[str], body: str, line: int) -> str:
        indent_match = re.search(r"\n([ \t]+)\S", body)
        indent = indent_match[1] if indent_match else "    "
        for index, pattern, replacement in entry.uses:
            compiled = re.compile(pattern.format(name=re.escape(names[index])))
            new = replacement.format(name=names[index])
            masked = mask(body)
            for match in reversed(list(compiled.finditer(masked))):
                number = line + body.count("\n", 0, match.start())
                statement = body[body.rfind("\n", 0, match.start()) + 1:body.find("\n", match.end())]
                body = body[:match.start()] + new + body[match.end():]
                after = body[body.rfind("\n", 0, match.start()) + 1:body.find("\n", match.start() + len(new))]
                self.rewrites.append(Rewrite(number, api.key("cpp", entry), " ".join(statement.split()),
                                             " ".join(after.split())))
        if entry.endpoint == "timer":
            body = re.sub(rf"\n[ \t]*\(void\)\s*{re.escape(names[0])};[ \t]*(?=\n)", "", body)
        if entry.endpoint == "service_server":
            body = re.sub(r"\breturn\s+true\s*;", "return;", body)
            body = re.sub(r"\n[ \t]*return;(?=\s*$)", "", body)
        if entry.endpoint == "action_server":
            body = self.goal_calls(body)
        if entry.method == "on_{id}_result":
            state = re.escape(names[0])
            body = self.body_rule(body, line, rf"\b{state}\s*==\s*actionlib::SimpleClientGoalState::(\w+)",
                                  lambda m: (f"wrapped_result.code == rclcpp_action::ResultCode::{GOAL_STATES[m[1]]}"
                                             if m[1] in GOAL_STATES else m[0]), "cpp.goal_state")
            code = "std::to_string(static_cast<int>(wrapped_result.code))"
            spelled = self.body_rule(body, line, rf"\b{state}\s*\.\s*toString\s*\(\s*\)", lambda m: code,
                                     "cpp.goal_state")
            if spelled != body:
                body = spelled
                self.needed.add("<string>")
            body = re.sub(rf"\n[ \t]*\(void\)\s*{re.escape(names[1])};[ \t]*(?=\n)", "", body)
        prologue = [line.format(*names) for index, line in enumerate(entry.prologue)
                    if line and re.search(rf"\b{re.escape(names[index])}\b", mask(body))]
        if entry.endpoint == "action_server":
            body = re.sub(rf"\n[ \t]*\(void\)\s*{re.escape(names[0])};[ \t]*(?=\n)", "", body)
            prologue = [line for line in prologue if re.search(rf"\b{re.escape(names[0])}\b", mask(body))]
        if prologue:
            body = "".join(f"\n{indent}{line}" for line in prologue) + body
        return body

    def body_rule(self, body: str, line: int, pattern: str, replace, key: str) -> str:
        """`body` (starting on `line`) with each match of `pattern` replaced, each line it changes recorded."""
        for match in reversed(list(re.finditer(pattern, mask(body)))):
            new = replace(re.match(pattern, body[match.start():]) or match)
            if new == match[0]:
                continue
            start, end = body.rfind("\n", 0, match.start()) + 1, body.find("\n", match.end())
            before = body[start:end]
            body = body[:match.start()] + new + body[match.end():]
            after = body[start:body.find("\n", match.start() + len(new))]
            self.rewrites.append(Rewrite(line + body.count("\n", 0, match.start()), key, " ".join(before.split()),
                                         " ".join(after.split())))
        return body

    def goal_calls(self, body: str) -> str:
        """The action server's calls in its execute callback, on the goal handle."""
        for server, alias in self.ctx.action_servers:
            member = f"{server}_action_server_"
            receivers = [re.escape(member)] + [re.escape(m[1]) for m in re.finditer(
                rf"auto\s*&\s*(\w+)\s*=\s*{re.escape(member)}\s*;", body)]
            body = re.sub(rf"\n[ \t]*auto\s*&\s*\w+\s*=\s*{re.escape(member)}\s*;[ \t]*(?=\n)", "", body)
            receiver = rf"\b(?:{'|'.join(receivers)})\s*\.\s*"
            result = f"std::make_shared<{alias}::Result>"
            feedback = f"std::make_shared<{alias}::Feedback>"

            def ended(method: str, made: str = result):
                def replace(match: re.Match) -> str:
                    return f"goal_handle->{method}({made}({match[1].strip()}))"
                return replace

            for old, new in (("setSucceeded", "succeed"), ("setAborted", "abort"), ("setPreempted", "canceled")):
                body = re.sub(receiver + rf"{old}\s*\(([^()]*(?:\([^()]*\)[^()]*)*)\)", ended(new), body)
            body = re.sub(receiver + r"publishFeedback\s*\(([^()]*(?:\([^()]*\)[^()]*)*)\)",
                          ended("publish_feedback", feedback), body)
            body = re.sub(receiver + r"isPreemptRequested\s*\(\s*\)", "goal_handle->is_canceling()", body)
            body = re.sub(receiver + r"isActive\s*\(\s*\)", "goal_handle->is_active()", body)
        return body

    def pass_constructor(self) -> None:
        span = self.class_span()
        if span is None or not self.ctx.constructor:
            return
        masked = self.masked
        pattern = re.compile(rf"^([ \t]*)(?:explicit\s+)?{re.escape(self.ctx.class_name)}\s*\(\s*\)", re.M)
        match = pattern.search(masked, span[0], span[1])
        if not match:
            return
        indent = match[1]
        after = masked[match.end():]
        initializers = re.match(r"\s*:\s*", after)
        new = "\n".join(indent + line.strip() if index else line.strip()
                        for index, line in enumerate(self.ctx.constructor.split("\n")))
        new = new.replace(f"\n{indent}:", f"\n{indent}:")
        end = match.end()
        if initializers:  # the user's own initializers follow the base class's
            base = re.match(rf"\s*:\s*{re.escape(self.ctx.base_class)}\s*\(\s*\)\s*,?\s*", after)
            end += base.end() if base else initializers.end()
            rest = self.text[end:]
            new += ("," if rest.lstrip() and not rest.lstrip().startswith("{") else "") + (
                "\n" + indent + "  " if base and rest.lstrip() and not rest.lstrip().startswith("{") else
                (" " if not base else ""))
        start = match.start() + len(indent)
        self.rewrites.append(Rewrite(self.line_of(start), "cpp.api.constructor",
                                     " ".join(self.text[start:end].split()), " ".join(new.split())))
        self.text = self.text[:start] + new + self.text[end:]

    def pass_todos(self) -> None:
        """Each line still naming ROS 1, or using what the port took away, marked with its rule."""
        masked = self.masked
        for name, key in TODO_CALLS.items():
            for match in re.finditer(rf"\b{re.escape(name)}\b", masked):
                self.todo(match.start(), key)
        for match in re.finditer(r"\bros::Time\s*\(", masked):
            self.todo(match.start(), "cpp.todo.time")
        for service, _ in self.ctx.service_clients:
            for match in re.finditer(rf"\b{re.escape(service)}_client_\s*\.\s*call\b", masked):
                self.todo(match.start(), "cpp.todo.service_call")
        for name, _ in self.ctx.parameters:
            for match in re.finditer(rf"(?<![\w.>:]){re.escape(name)}_\b", masked):
                if self.in_class(match.start()) and WRITTEN.match(masked, match.end()):
                    self.todo(match.start(), "cpp.todo.parameter_written")
        for name, (entry, given) in self.ported.items():
            found = self.method(name)
            if found is None:
                continue
            brace = found[3]
            end = closing(masked, brace - 1)
            body = masked[brace:end]
            gone = {"timer": (0, "cpp.todo.timer_event")}.get(entry.endpoint)
            if entry.method == "on_{id}_result":
                gone = (0, "cpp.todo.goal_state")
            if gone:
                for match in re.finditer(rf"\b{re.escape(given[gone[0]])}\b", body):
                    self.todo(brace + match.start(), gone[1])
            if entry.endpoint == "service_server":
                for match in re.finditer(r"\breturn\s+false\s*;", body):
                    self.todo(brace + match.start(), "cpp.todo.service_failure")
            for server, _ in self.ctx.action_servers:
                for match in re.finditer(rf"\b{re.escape(server)}_action_server_\b", body):
                    self.todo(brace + match.start(), "cpp.todo.goal_handling")
        for match in ROS1_LEFT.finditer(masked):
            self.todo(match.start(), "cpp.todo.other")
        for match in re.finditer(r"^[ \t]*#[ \t]*include[ \t]*[<\"](actionlib|tf|nodelet|dynamic_reconfigure|ros)/"
                                 r"[^\"/>]*\.h[\">]", self.text, re.M):
            self.todo(match.start(), "cpp.todo.other")

    def insert_todos(self) -> None:
        lines = self.text.split("\n")
        for line in sorted(self.todos, reverse=True):
            index = line - 2
            while index >= 0 and lines[index].strip().startswith("//") and not lines[index].strip().startswith(
                    "// TODO(port)"):
                index -= 1
            if index >= 0 and lines[index].strip().startswith("// TODO(port)"):
                continue  # marked already (a file ported twice)
            indent = re.match(r"[ \t]*", lines[line - 1])[0]
            comments = []
            for key in self.todos[line]:
                width = max(WIDTH - len(indent) - 3, 40)
                comments += [f"{indent}// {text}" for text in textwrap.wrap(rule(key).comment, width,
                                                                            break_long_words=False,
                                                                            break_on_hyphens=False)]
            lines[line - 1:line - 1] = comments
        self.text = "\n".join(lines)


_STRING = re.compile(r'"(?:[^"\\\n]|\\.)*"')
_COMMENT = re.compile(r"//|/\*")


def wrapped(text: str, unchanged: set[str]) -> str:
    """`text` with each line a rewrite made longer than cpplint's 100 columns broken as uncrustify
    breaks ROS 2 code (rna.dialects.lines): after the call's opening bracket, then as many of its
    arguments a line as fit, a long string argument cut after its spaces. A line as long before the
    port is the user's, and one that cannot be broken so (a comment on it, no call) stays as it is."""
    out, level = [], 0
    for line, masked in zip(text.split("\n"), mask(text).split("\n"), strict=True):
        inside = level > 0
        level = max(level + open_brackets(masked), 0)
        if breaking.columns(line, "cpp") <= WIDTH or line in unchanged or masked.lstrip().startswith("#"):
            out.append(line)
            continue
        marked = _marked(line, masked, inside)
        out += breaking.fit_line(marked, "cpp", inside=inside) if marked else [line]
    return "\n".join(out)


def _marked(line: str, masked: str, inside: bool) -> str | None:
    """The line with rna.dialects.lines' markers where it may break: after the opening bracket of
    its first call (unless it continues an open one) and the commas between that call's
    arguments, and after the spaces of the string literals among them; None when it has none."""
    if _COMMENT.search(_STRING.sub(lambda m: " " * len(m[0]), line)):
        return None
    level = 0  # the depth of the arguments a line breaks between
    if not inside:
        # the call the statement ends with (a condition's || and && uncrustify breaks otherwise)
        call = re.search(r"(?:\b(?!(?:if|while|for|switch|return)\b)\w+|>)\s*\(", masked)
        if call is None or open_brackets(masked[:call.end() - 1]) != 0:
            return None
        end = closing(masked, call.end() - 1)
        if end < 0 or not re.fullmatch(r"\s*(;|\{|\)\s*;)?\s*", masked[end + 1:]):
            return None
        level = 1
    breaks, splits, depth = [], [], 0
    if not inside:
        breaks.append(call.end())
    for index, char in enumerate(masked):
        if char in "([{":
            depth += 1
        elif char in ")]}":
            depth -= 1
            if depth < level:
                break
        elif char == "," and depth == level and (inside or index >= call.end()):
            breaks.append(index + 1 + (masked[index + 1:index + 2] == " "))
        elif masked.startswith("<< ", index) and depth == level and (inside or index >= call.end()):
            breaks.append(index + 3)
    for literal in _STRING.finditer(line):
        whole = re.search(r"[(,]\s*$", line[:literal.start()]) and re.match(r"\s*[,)]", line[literal.end():])
        if whole and open_brackets(masked[:literal.start()]) == level and (inside or literal.start() >= call.end()):
            splits += [index + 1 for index in range(literal.start() + 1, literal.end() - 2) if line[index] == " "]
    if not breaks and not splits:
        return None
    marks = {**{index: breaking.SPLIT for index in splits}, **{index: breaking.BREAK for index in breaks}}
    return "".join(marks.get(index, "") + char for index, char in enumerate(line)) + marks.get(len(line), "")


def port(text: str, context: Context = Context()) -> Ported:
    """The file rewritten by the rules."""
    return _Rewriter(text, context).run()
