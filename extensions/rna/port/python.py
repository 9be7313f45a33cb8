"""rospy -> rclpy: a Python file of the user's rewritten by the rules of rna.port.rules.

The file is read with Python's own parser, so a rewrite replaces exactly the expression
or statement a rule names, wherever it sits (inside another call, over several lines),
and everything else keeps its text, comments and layout. f-strings are left as written
(their inner positions are not reliable on Python 3.11); a ROS 1 name left in one is
marked like any other. A file that does not parse is returned as it was, with one
TODO(port) at its top.

`port(text, context)` returns the new text, each rewrite (rule, line, before, after) and
each line marked `TODO(port)`. `context` says what the file's node is (its parameters,
callbacks and members, rna.port.api); without one, only the generic rules apply and
logging goes to a named logger.
"""

from __future__ import annotations

import ast
import io
import re
import textwrap
import tokenize
from collections.abc import Mapping
from dataclasses import dataclass, field

from . import api
from .rule import TODO
from .rules import rule

WIDTH = 99  # flake8's line length in ROS 2 packages
# Modules ROS 2 does not have, whose remaining uses are marked.
ROS1_MODULES = ("rospy", "actionlib", "roslib", "rosparam", "rosbag", "rosgraph", "rostopic", "rosservice",
                "rosnode", "genpy", "tf", "tf_conversions", "dynamic_reconfigure", "actionlib_msgs")
# Nothing of these is kept: their uses are rewritten or marked.
REMOVED_IMPORTS = ("rospy", "actionlib", "roslib")
MODULE_TODOS = {"tf": "py.todo.tf", "tf_conversions": "py.todo.tf",
                "dynamic_reconfigure": "py.todo.dynamic_reconfigure"}
LEVELS = {"debug": "debug", "info": "info", "warn": "warning", "err": "error", "fatal": "fatal"}
LOG_CALL = re.compile(r"rospy\.log(debug|info|warn|err|fatal)(_throttle_identical|_throttle|_once)?$")
GOAL_STATUS = {"PENDING": "STATUS_ACCEPTED", "ACTIVE": "STATUS_EXECUTING", "PREEMPTED": "STATUS_CANCELED",
               "SUCCEEDED": "STATUS_SUCCEEDED", "ABORTED": "STATUS_ABORTED", "PREEMPTING": "STATUS_CANCELING",
               "RECALLING": "STATUS_CANCELING", "RECALLED": "STATUS_CANCELED"}
SERVICE_PARTS = ("Request", "Response")
ACTION_PARTS = ("ActionGoal", "ActionResult", "ActionFeedback", "Action", "Goal", "Result", "Feedback")
# rospy calls no rule rewrites, with the rule that marks them.
TODO_CALLS = {
    "rospy.set_param": "py.todo.global_param", "rospy.has_param": "py.todo.global_param",
    "rospy.delete_param": "py.todo.global_param", "rospy.search_param": "py.todo.global_param",
    "rospy.get_param_names": "py.todo.global_param", "rospy.ServiceProxy": "py.todo.service_call",
    "rospy.wait_for_service": "py.todo.service_call", "rospy.Service": "py.todo.service",
    "rospy.init_node": "py.todo.main", "rospy.spin": "py.todo.main", "rospy.signal_shutdown": "py.todo.main",
    "rospy.wait_for_message": "py.todo.wait_for_message",
}
# The action server's calls the execute callback's rules rewrite.
SERVER_CALLS = ("publish_feedback", "is_preempt_requested", "is_active", "set_succeeded", "set_aborted",
                "set_preempted")
GOAL_ENDS = {"set_succeeded": "succeed", "set_aborted": "abort", "set_preempted": "canceled"}
# ast nodes an expression needs parentheses in, when it is a division or a `not`
TIGHT_PARENTS = (ast.Attribute, ast.Subscript, ast.BinOp, ast.UnaryOp, ast.Await, ast.Compare)


@dataclass(frozen=True)
class Context:
    """What the rewriter knows of the file: its node's class and base-class API, if it is a node's."""

    base_class: str = ""  # the node's base class (ListenerBase): classes deriving from it are the node
    logger: str = ""  # the logger's name outside the node's class
    parameters: frozenset[str] = frozenset()  # ROS 1 keeps each in self.<name>
    subscribers: frozenset[str] = frozenset()  # endpoint ids
    timers: frozenset[str] = frozenset()
    service_clients: frozenset[str] = frozenset()
    action_clients: frozenset[str] = frozenset()
    action_results: tuple[tuple[str, str], ...] = ()  # (action server id, ROS 2 result type: Test.Result)
    callbacks: tuple[tuple[str, api.Callback], ...] = ()  # (method name, its entry)
    kinds: Mapping[tuple[str, str], str] = field(default_factory=dict)  # (package, type) -> msg, srv, action

    def kind_of(self, package: str, name: str) -> str | None:
        return self.kinds.get((package, name))


@dataclass(frozen=True)
class Rewrite:
    line: int  # in the original text, from 1
    rule: str
    before: str
    after: str


@dataclass
class Ported:
    text: str
    rewrites: list[Rewrite] = field(default_factory=list)
    todos: list[tuple[int, str]] = field(default_factory=list)  # (line in the original text, rule)
    needed: set[str] = field(default_factory=set)  # imports the rewrites use ('module' or 'module:Name')


def port(text: str, context: Context = Context()) -> Ported:
    """The file rewritten by the rules."""
    try:
        tree = ast.parse(text)
    except SyntaxError as error:
        comment = f"# {TODO}: this file is not Python this port reads ({error.msg}, line {error.lineno})\n"
        return Ported(comment + text, todos=[(1, "py.todo.other")])
    return _Rewriter(text, tree, context).run()


def wrapped(text: str, unchanged: set[str]) -> str:
    """`text` with each line a rewrite made longer than flake8's 99 columns broken as ROS 2 code is:
    after the call's opening bracket, and a long string argument cut at its spaces. A line that
    cannot be broken so (or was that long before) stays as it is."""
    lines = text.split("\n")
    out = []
    for line in lines:
        if len(line) <= WIDTH or line in unchanged:
            out.append(line)
            continue
        out += _broken(line) or [line]
    return "\n".join(out)


def _broken(line: str) -> list[str] | None:
    indent = line[:len(line) - len(line.lstrip())]
    try:
        statement = ast.parse(line.strip()).body
    except SyntaxError:
        return _after_bracket(line, indent)  # a compound statement's first line (if ...:)
    if len(statement) != 1 or not isinstance(statement[0], (ast.Expr, ast.Assign)):
        return _after_bracket(line, indent)
    call = statement[0].value
    if not isinstance(call, ast.Call) or not (call.args or call.keywords) or call.end_col_offset != len(line.strip()):
        return _after_bracket(line, indent)
    code = line.strip()
    opening = call.func.end_col_offset
    if code[opening] != "(":
        return None
    inner, inside = code[opening + 1:-1], indent + "    "
    lines = [indent + code[:opening + 1], inside + inner + ")"]
    if len(lines[1]) <= WIDTH:
        return lines
    first = call.args[0] if call.args else None
    if not isinstance(first, (ast.Constant, ast.JoinedStr)) or (isinstance(first, ast.Constant) and not isinstance(
            first.value, str)):
        return None
    literal = code[first.col_offset:first.end_col_offset]
    rest = code[first.end_col_offset:-1] + ")"
    pieces = _cut_literal(literal, WIDTH - len(inside))
    if pieces is None:
        return None
    result = [lines[0], *(inside + piece for piece in pieces[:-1]), inside + pieces[-1] + rest]
    if any(len(piece) > WIDTH for piece in result):
        return None
    try:
        ast.parse("\n".join(piece.strip() if index == 0 else piece for index, piece in enumerate(result)).strip())
    except SyntaxError:
        return None
    return result


def _after_bracket(line: str, indent: str) -> list[str] | None:
    """A statement that is no call broken after its first bracket (a hanging indent), if that makes it fit:
    `age = (\n    now - Time.from_msg(stamp)).nanoseconds / 1e9`."""
    code = line.strip()
    try:
        tokens = list(tokenize.generate_tokens(io.StringIO(code).readline))
        if code.endswith(":"):
            ast.parse(code + "\n    pass")
        else:
            ast.parse(code)
    except (tokenize.TokenError, SyntaxError):
        return None
    opening = next((token for token, following in zip(tokens, tokens[1:], strict=False)
                    if token.type == tokenize.OP and token.string in "([" and following.string not in ")]"), None)
    if opening is None or opening.start[0] != 1:
        return None
    column = opening.end[1]
    header = code.endswith(":")  # its block follows at 4 more: the continuation goes 8 deeper (E125)
    lines = [indent + code[:column], indent + " " * (8 if header else 4) + code[column:].lstrip()]
    if any(len(piece) > WIDTH for piece in lines) or not code[column:].strip():
        return None
    try:
        ast.parse("\n".join(piece.strip() for piece in lines) + ("\n    pass" if header else ""))
    except SyntaxError:
        return None
    return lines


def _cut_literal(literal: str, room: int) -> list[str] | None:
    """A one-line string literal as adjacent literals of at most `room` columns, cut after spaces
    outside its {fields}; an f-string's piece without a field is a plain string (flake8 F541)."""
    match = re.fullmatch(r"([fF]?)(['\"])(.*)\2", literal)
    if not match or "\\" in literal:
        return None
    prefix, quote, body = match[1], match[2], match[3]
    cuts, depth = [], 0
    for index, char in enumerate(body):
        if prefix and char == "{":
            depth += 1
        elif prefix and char == "}":
            depth -= 1
        elif char == " " and depth == 0:
            cuts.append(index + 1)
    pieces, start = [], 0
    while len(body) - start + 3 > room:
        fitting = [cut for cut in cuts if start < cut and cut - start + 3 <= room]
        if not fitting:
            return None
        pieces.append(body[start:fitting[-1]])
        start = fitting[-1]
    pieces.append(body[start:])

    def spelled(piece: str) -> str:
        fields = prefix and re.search(r"(?<!\{)\{(?!\{)", piece)
        if prefix and not fields:
            piece = piece.replace("{{", "{").replace("}}", "}")
        # flake8-quotes: single quotes, unless the piece holds one
        own = quote if quote in piece else ("'" if "'" not in piece else '"')
        if (own == "'" and "'" in piece) or (own == '"' and '"' in piece):
            own = quote
        return (prefix if fields else "") + own + piece + own
    return [spelled(piece) for piece in pieces]


def _dotted(node: ast.AST) -> str | None:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        inner = _dotted(node.value)
        return f"{inner}.{node.attr}" if inner else None
    return None


def _types_module(module: str) -> bool:
    """pkg.msg, pkg.srv: the types of a package (actionlib.msg holds actionlib's test actions)."""
    return module.rsplit(".", 1)[-1] in ("msg", "srv")


def _simple_literal(source: str) -> str | None:
    """The quote of a plain one-line string literal's source ('...' or "..."), else None."""
    if len(source) >= 2 and source[0] == source[-1] and source[0] in "'\"" and "\n" not in source:
        inner = source[1:-1]
        if source[0] not in inner.replace("\\" + source[0], ""):
            return source[0]
    return None


_SPEC = re.compile(r"%(%|(?:\.\d+)?[srf])")


class _Rewriter:
    def __init__(self, text: str, tree: ast.Module, context: Context) -> None:
        self.text = text
        self.tree = tree
        self.ctx = context
        self.lines = text.splitlines(keepends=True)
        self.starts = [0]
        for line in self.lines:
            self.starts.append(self.starts[-1] + len(line))
        self.parents: dict[int, ast.AST] = {}
        for parent in ast.walk(tree):
            for child in ast.iter_child_nodes(parent):
                self.parents[id(child)] = parent
        self._spans: list[tuple[tuple[int, int], Rewrite]] = []  # each rewrite and the text it replaced
        self.todos: dict[int, list[str]] = {}  # statement id -> rules
        self.before: dict[int, list[str]] = {}  # statement id -> lines to put before it
        self.after: dict[int, list[str]] = {}
        self.returns: dict[int, str] = {}  # a bare return statement id -> the value it returns now
        self.needed: set[str] = set()
        self.modules: dict[str, str] = {}  # local name -> the ROS 1 module or name it stands for
        self.types: dict[str, str] = {}  # local name of a ROS 1 type part -> its ROS 2 spelling
        self.goal_status: set[str] = set()  # local names of actionlib_msgs' GoalStatus
        self.timer_methods: set[str] = set()  # methods given to rospy.Timer: they lose their event
        self._scan()

    # --- positions

    def offset(self, line: int, col: int) -> int:
        text = self.lines[line - 1] if line - 1 < len(self.lines) else ""
        return self.starts[line - 1] + len(text.encode()[:col].decode(errors="ignore"))

    def span(self, node: ast.AST) -> tuple[int, int]:
        start = self.offset(node.lineno, node.col_offset)
        decorators = getattr(node, "decorator_list", None)
        if decorators:
            first = decorators[0].lineno
            line = self.lines[first - 1]
            start = self.starts[first - 1] + len(line) - len(line.lstrip())
        return start, self.offset(node.end_lineno, node.end_col_offset)

    def source(self, node: ast.AST) -> str:
        start, end = self.span(node)
        return self.text[start:end]

    def starts_line(self, node: ast.AST) -> bool:
        start, _ = self.span(node)
        line_start = self.starts[node.lineno - 1]
        return not self.text[line_start:start].strip()

    def indent(self, node: ast.AST) -> str:
        line = self.lines[node.lineno - 1]
        return line[:len(line) - len(line.lstrip())]

    def statement(self, node: ast.AST) -> ast.stmt:
        """The statement holding `node` that starts a line (where a TODO or a prologue goes)."""
        current = node
        while not (isinstance(current, ast.stmt) and self.starts_line(current)):
            current = self.parents[id(current)]
        return current

    # --- what the file imports

    def _scan(self) -> None:
        for node in ast.walk(self.tree):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    top = alias.name.split(".")[0]
                    if top in ROS1_MODULES:
                        self.modules[alias.asname or top] = alias.name if alias.asname else top
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                top = node.module.split(".")[0]
                for alias in node.names:
                    local = alias.asname or alias.name
                    if top in ROS1_MODULES and top != "actionlib_msgs" and not _types_module(node.module):
                        self.modules[local] = f"{node.module}.{alias.name}"
                    if node.module == "actionlib_msgs.msg" and alias.name == "GoalStatus":
                        self.goal_status.add(local)
                    spelled = self._type_part(node.module, alias.name)
                    if spelled:
                        self.types[local] = spelled
            elif isinstance(node, ast.Call) and self.qualified(node.func) == "rospy.Timer" and len(node.args) > 1:
                callback = _dotted(node.args[1]) or ""
                if callback.startswith("self."):
                    self.timer_methods.add(callback[5:])

    def _type_part(self, module: str, name: str) -> str | None:
        """`X.Request` for a ROS 1 service part, `X.Goal` for an action part (X imported), else None."""
        package, _, kind = module.rpartition(".")
        if kind == "srv" and self.ctx.kind_of(package, name) != "srv":
            for part in SERVICE_PARTS:
                if name.endswith(part) and len(name) > len(part):
                    return f"{name[:-len(part)]}.{part}"
        if kind == "msg":
            for part in ACTION_PARTS:
                stem = name[:-len(part)]
                if name.endswith(part) and stem and self.ctx.kind_of(package, stem) == "action":
                    return stem if part == "Action" else f"{stem}.{part}"
        return None

    def qualified(self, node: ast.AST) -> str | None:
        """The dotted name of `node` with a local name of a ROS 1 module written out: rospy.loginfo."""
        dotted = _dotted(node)
        if dotted is None:
            return None
        first, _, rest = dotted.partition(".")
        if first in self.modules:
            return self.modules[first] + (f".{rest}" if rest else "")
        return dotted

    # --- where the code is

    def node_class(self, node: ast.AST) -> bool:
        """Whether `node` is in a method of the node's class, where `self` is the node."""
        current, method = node, False
        while id(current) in self.parents:
            current = self.parents[id(current)]
            if isinstance(current, (ast.FunctionDef, ast.AsyncFunctionDef)):
                arguments = current.args.posonlyargs + current.args.args
                method = method or bool(arguments and arguments[0].arg == "self")
            if isinstance(current, ast.ClassDef):
                return method and bool(self.ctx.base_class) and any(
                    _dotted(base) == self.ctx.base_class for base in current.bases)
        return False

    def function(self, node: ast.AST) -> ast.FunctionDef | None:
        current = node
        while id(current) in self.parents:
            current = self.parents[id(current)]
            if isinstance(current, (ast.FunctionDef, ast.AsyncFunctionDef)):
                return current
        return None

    def logger(self, node: ast.AST) -> str:
        if self.node_class(node):
            return "self.get_logger()"
        self.needed.add("rclpy.logging:get_logger")
        return f"get_logger({self.ctx.logger or 'node'!r})"

    def clock(self, node: ast.AST) -> str:
        if self.node_class(node):
            return "self.get_clock()"
        self.needed.add("rclpy.clock:Clock")
        return "Clock()"

    def atom(self, node: ast.AST) -> str:
        """`node` rewritten, in parentheses where an attribute access on it needs them."""
        text = self.emit(node)
        if isinstance(node, (ast.Name, ast.Attribute, ast.Call, ast.Subscript, ast.Constant, ast.List, ast.Tuple,
                             ast.Dict, ast.Set, ast.JoinedStr)):
            return text
        return f"({text})"

    def tight(self, node: ast.AST, text: str) -> str:
        """`text` (a division, a `not`) parenthesized where its place needs it."""
        parent = self.parents.get(id(node))
        if isinstance(parent, TIGHT_PARENTS) or (isinstance(parent, ast.Call) and parent.func is node):
            return f"({text})"
        return text

    # --- recording

    def rewrote(self, node: ast.AST, key: str, after: str) -> str:
        """Record a rewrite of `node` (one inside it recorded before is part of it now)."""
        start, end = self.span(node)
        kept = [(span, rewrite) for span, rewrite in self._spans if not (start <= span[0] and span[1] <= end)]
        self._spans = [*kept, ((start, end), Rewrite(node.lineno, key, " ".join(self.source(node).split()),
                                                     " ".join(after.split())))]
        return after

    def todo(self, node: ast.AST, key: str) -> None:
        keys = self.todos.setdefault(id(self.statement(node)), [])
        if key not in keys and not (key == "py.todo.other" and keys):
            keys.append(key)

    # --- the walk

    def run(self) -> Ported:
        text = wrapped(self.splice(self.tree, 0, len(self.text)), set(self.text.split("\n")))
        if self.needed and not self.ctx.base_class:  # a file of the user's own: its imports are added here
            text = self._add_imports(text)
        todos = [(self._line_of(key), rule_key) for key, rules in self.todos.items() for rule_key in rules]
        rewrites = sorted((rewrite for _, rewrite in self._spans), key=lambda r: r.line)
        return Ported(text, rewrites, sorted(todos), set(self.needed))

    def _line_of(self, statement_id: int) -> int:
        node = next(node for node in ast.walk(self.tree) if id(node) == statement_id)
        return node.lineno

    def _add_imports(self, text: str) -> str:
        """The imports the rewrites need, after the file's last top-level import (or its docstring)."""
        lines = text.split("\n")
        new = [f"from {module} import {name}" if name else f"import {module}"
               for module, _, name in (spec.partition(":") for spec in sorted(self.needed))]
        new = [line for line in new if line not in lines]
        if not new:
            return text
        try:
            body = ast.parse(text).body
        except SyntaxError:
            body = []
        imports = [node for node in body if isinstance(node, (ast.Import, ast.ImportFrom))]
        if imports:
            at = imports[-1].end_lineno
        elif body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
            at = body[0].end_lineno
            new = ["", *new]
        else:
            at = 0
        return "\n".join(lines[:at] + new + lines[at:])

    def emit(self, node: ast.AST) -> str:
        if isinstance(node, ast.JoinedStr):
            self._mark_names(node)
            return self.source(node)
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            self._enter_function(node)
        replaced = self.rewrite(node)
        start, end = self.span(node)
        text = replaced if replaced is not None else self.splice(node, start, end)
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            text = self._signature(node, text)
        if isinstance(node, ast.stmt):
            text = self._with_lines(node, text)
        return text

    def children(self, node: ast.AST) -> list[ast.AST]:
        found = []
        for child in ast.iter_child_nodes(node):
            if hasattr(child, "lineno") and getattr(child, "end_lineno", None) is not None:
                found.append(child)
            else:
                found += self.children(child)
        return sorted(found, key=lambda child: self.span(child)[0])

    def splice(self, node: ast.AST, start: int, end: int) -> str:
        out, position = [], start
        for child in self.children(node):
            child_start, child_end = self.span(child)
            if child_start < position:
                continue  # inside a child already written (a decorator's place)
            text = self.emit(child)
            if text == self.text[child_start:child_end]:
                continue
            if text == "" and isinstance(child, ast.stmt) and self.starts_line(child):
                line_start = self.starts[child.lineno - 1]
                line_end = self.starts[child.end_lineno] if child.end_lineno < len(self.starts) else child_end
                if self.text[child_end:line_end].strip() == "":  # the whole lines go
                    child_start, child_end = line_start, line_end
                    previous = self.lines[child.lineno - 2] if child.lineno > 1 else ""
                    following = self.lines[child.end_lineno] if child.end_lineno < len(self.lines) else ""
                    if not previous.strip() and not following.strip() and following:
                        child_end += len(following)
            out += [self.text[position:child_start], text]
            position = child_end
        out.append(self.text[position:end])
        return "".join(out)

    def _with_lines(self, node: ast.stmt, text: str) -> str:
        """The statement with the lines put before and after it (prologues, TODOs); a TODO already
        above it (a file ported twice) is not written again."""
        before = [] if self._todo_above(node) else [
            comment for key in self.todos.get(id(node), []) for comment in self._comment(key, node)]
        before += self.before.get(id(node), [])
        after = self.after.get(id(node), [])
        if not before and not after:
            return text
        indent = self.indent(node)
        if text == "":  # a statement that went: its TODO stays
            return "\n".join(before[:1] + [indent + line for line in before[1:]])
        return "".join(line + "\n" + indent for line in before) + text + "".join(
            "\n" + indent + line for line in after)

    def _todo_above(self, node: ast.stmt) -> bool:
        """Whether the comment lines right above the statement hold a TODO(port) already."""
        index = node.lineno - 2
        while index >= 0 and self.lines[index].strip().startswith("#"):
            if self.lines[index].strip().startswith(f"# {TODO}"):
                return True
            index -= 1
        return False

    def _comment(self, key: str, node: ast.AST) -> list[str]:
        width = max(WIDTH - len(self.indent(node)) - 2, 40)
        lines = textwrap.wrap(rule(key).comment, width, break_long_words=False, break_on_hyphens=False)
        return ["# " + line for line in lines]

    def _mark_names(self, node: ast.AST) -> None:
        for inner in ast.walk(node):
            if isinstance(inner, ast.Name) and inner.id in self.modules:
                self.todo(node, "py.todo.other")
                return

    # --- callbacks: the base-class API

    def _callback(self, function: ast.AST) -> api.Callback | None:
        if not self.node_class(function.body[0]):
            return None
        for name, entry in self.ctx.callbacks:
            if name == function.name:
                return entry
        if function.name in self.timer_methods:
            return next(entry for entry in api.PYTHON_CALLBACKS if entry.endpoint == "timer")
        return None

    def _enter_function(self, function: ast.FunctionDef) -> None:
        entry = self._callback(function)
        if entry is None:
            return
        arguments = function.args.args[1:]
        names = [argument.arg for argument in arguments]
        if len(names) != len(entry.ros1) or function.args.vararg or function.args.kwarg:
            return  # not the ROS 1 signature: left as written (and marked by what it calls)
        used = {inner.id for statement in function.body for inner in ast.walk(statement)
                if isinstance(inner, ast.Name)}
        body = function.body
        docstring = isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) and isinstance(
            body[0].value.value, str)
        lines = [line.format(*names) for index, line in enumerate(entry.prologue) if names[index] in used]
        if entry.endpoint == "timer" and names[0] in used:
            for statement in body:
                if any(isinstance(inner, ast.Name) and inner.id == names[0] for inner in ast.walk(statement)):
                    self._todo_each_use(statement, names[0], "py.todo.timer_event")
        if lines:
            if docstring and len(body) == 1:
                self.after.setdefault(id(body[0]), []).extend(lines)
            else:
                target = body[1] if docstring else body[0]
                self.before.setdefault(id(target), []).extend(lines)

    def _todo_each_use(self, statement: ast.stmt, name: str, key: str) -> None:
        for inner in ast.walk(statement):
            if isinstance(inner, ast.Name) and inner.id == name:
                self.todo(inner, key)

    def _signature(self, function: ast.FunctionDef, text: str) -> str:
        """The def line of a callback or of the constructor with ROS 2's parameters."""
        if function.name == "__init__" and self.node_class(function.body[0]):
            if self._plain_constructor(function.body[0]):
                new = re.sub(r"^(def\s+__init__\s*\()\s*self\s*\)", r"\1self, **kwargs)", text, count=1)
                if new != text:
                    self._spans.append(((-1, -1), Rewrite(function.lineno, "py.api.constructor",
                                                          "def __init__(self):", "def __init__(self, **kwargs):")))
                return new
            return text
        entry = self._callback(function)
        if entry is None:
            return text
        names = [argument.arg for argument in function.args.args[1:]]
        if len(names) != len(entry.ros1) or function.args.vararg or function.args.kwarg:
            return text
        ros2 = ["self", *(name.format(*names) for name in entry.ros2)]
        pattern = re.compile(rf"^((?:async\s+)?def\s+{re.escape(function.name)}\s*)\((.*?)\)(\s*(?:->[^:]*)?:)", re.S)
        match = pattern.match(text)
        if not match:
            return text
        old = [part.strip() for part in match[2].split(",") if part.strip()]
        if [part.split(":")[0].split("=")[0].strip() for part in old] != ["self", *names]:
            return text  # annotations or defaults: left as written
        if ros2 == ["self", *names]:
            return text
        header = f"{match[1]}({', '.join(ros2)}){match[3]}"
        key = api.key("python", entry)
        self._spans.append(((-1, -1), Rewrite(function.lineno, key,
                                              f"def {function.name}({', '.join(['self', *names])})",
                                              f"def {function.name}({', '.join(ros2)})")))
        return header + text[match.end():]

    # --- the rules

    def rewrite(self, node: ast.AST) -> str | None:
        if isinstance(node, ast.Call):
            return self._call(node)
        if isinstance(node, ast.Expr) and isinstance(node.value, ast.Call):
            return self._statement_call(node)
        if isinstance(node, ast.Return) and id(node) in self.returns and node.value is None:
            return f"return {self.returns[id(node)]}"
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not) and isinstance(node.operand, ast.Call):
            if self.qualified(node.operand.func) in ("rospy.is_shutdown", "rospy.core.is_shutdown",
                                                     "rospy.core.is_shutdown_requested"):
                return self.rewrote(node, "py.is_shutdown", self._ok(node))
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)) and self._stamp(node):
            return self._time_to_stamp(node)
        if isinstance(node, ast.Attribute):
            return self._attribute(node)
        if isinstance(node, ast.Name):
            return self._name(node)
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            return self._import(node)
        if isinstance(node, ast.Assign) and self._server_alias(node):
            return self.rewrote(node, api.EXECUTE_CALLS, "")
        if isinstance(node, (ast.Assign, ast.AugAssign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            for target in targets:
                if self._parameter_member(target):
                    self.todo(node, "py.todo.global_param")
        return None

    def _ok(self, node: ast.AST) -> str:
        if self.node_class(node):
            return "self.context.ok()"
        self.needed.add("rclpy")
        return "rclpy.ok()"

    def _name(self, node: ast.Name) -> str | None:
        if isinstance(node.ctx, ast.Load) and self._stamp(node) and self._holds_time(node):
            return self.rewrote(node, "py.stamp_time", f"{node.id}.to_msg()")
        if node.id in self.types and isinstance(node.ctx, ast.Load):
            spelled = self.types[node.id]
            key = "py.srv_types" if spelled.endswith(SERVICE_PARTS) else "py.action_types"
            return self.rewrote(node, key, spelled)
        if node.id in self.modules and isinstance(node.ctx, ast.Load):
            module = self.modules[node.id].split(".")[0]
            self.todo(node, MODULE_TODOS.get(module, "py.todo.other"))
        return None

    def _parameter_member(self, node: ast.AST) -> bool:
        return (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "self"
                and node.attr in self.ctx.parameters and self.node_class(node))

    def _attribute(self, node: ast.Attribute) -> str | None:
        value = node.value
        if self._parameter_member(node):
            if isinstance(node.ctx, ast.Load):
                return self.rewrote(node, "py.api.parameter", api.parameter_read("python", node.attr))
            return None  # written: the assignment is marked
        if (isinstance(value, ast.Name) and value.id == "self" and node.attr.endswith("_subscriber")
                and node.attr[:-len("_subscriber")] in self.ctx.subscribers and self.node_class(node)):
            return self.rewrote(node, "py.api.subscriber", f"self.{node.attr[:-len('_subscriber')]}_subscription")
        if isinstance(value, ast.Name) and value.id in self.goal_status and node.attr in GOAL_STATUS:
            return self.rewrote(node, "py.goal_status", f"{value.id}.{GOAL_STATUS[node.attr]}")
        if isinstance(value, ast.Name) and value.id in self.goal_status and node.attr.isupper():
            self.todo(node, "py.todo.other")
            return None
        if node.attr == "seq" and (_dotted(value) or "").split(".")[-1] == "header":
            self.todo(node, "py.todo.header_seq")
            return None
        if node.attr in ("secs", "nsecs") and (_dotted(value) or "").split(".")[-1] == "stamp":
            new = {"secs": "sec", "nsecs": "nanosec"}[node.attr]
            return self.rewrote(node, "py.stamp_fields", f"{self.atom(value)}.{new}")
        if node.attr == "stamp" and isinstance(node.ctx, ast.Load) and self._time_operand(node):
            self.needed.add("rclpy.time:Time")
            return self.rewrote(node, "py.stamp_time", f"Time.from_msg({self.atom(value)}.stamp)")
        return None

    def _time_operand(self, node: ast.AST) -> bool:
        """Whether `node` (a message's stamp) is an operand of time arithmetic or of a comparison:
        a rospy.Time in ROS 1, a message in ROS 2, which rclpy's Time does not take."""
        parent = self.parents.get(id(node))
        if isinstance(parent, ast.BinOp):
            return isinstance(parent.op, (ast.Add, ast.Sub))
        if isinstance(parent, ast.Compare):
            ordered = all(isinstance(op, (ast.Lt, ast.LtE, ast.Gt, ast.GtE, ast.Eq, ast.NotEq)) for op in parent.ops)
            return ordered and not any(isinstance(side, ast.Constant) for side in (parent.left, *parent.comparators))
        return False

    def _import(self, node: ast.Import | ast.ImportFrom) -> str | None:
        if isinstance(node, ast.Import):
            kept = []
            for alias in node.names:
                top = alias.name.split(".")[0]
                if top in REMOVED_IMPORTS:
                    continue
                if top in MODULE_TODOS:
                    self.todo(node, MODULE_TODOS[top])
                kept.append(alias)
            if len(kept) == len(node.names):
                return None
            after = ", ".join(a.name + (f" as {a.asname}" if a.asname else "") for a in kept)
            return self.rewrote(node, "py.imports", f"import {after}" if kept else "")
        if node.level or not node.module:
            return None
        top = node.module.split(".")[0]
        if top in REMOVED_IMPORTS and not _types_module(node.module):
            return self.rewrote(node, "py.imports", "")
        if top in MODULE_TODOS:
            self.todo(node, MODULE_TODOS[top])
            return None
        statements: dict[str, list[str]] = {}
        changed = False
        key = "py.imports"
        for alias in node.names:
            module, name = node.module, alias.name
            if node.module == "actionlib_msgs.msg":
                module, changed, key = "action_msgs.msg", True, "py.goal_status"
            spelled = self.types.get(alias.asname or alias.name)
            if spelled:
                stem = spelled.split(".")[0]
                module = node.module.rsplit(".", 1)[0] + (".action" if node.module.endswith(".msg") else ".srv")
                name, changed = stem, True
                key = "py.action_types" if module.endswith(".action") else "py.srv_types"
            elif alias.asname:
                name = f"{alias.name} as {alias.asname}"
            if name not in statements.setdefault(module, []):
                statements[module].append(name)
        if not changed:
            return None
        lines = [f"from {module} import {', '.join(names)}" for module, names in sorted(statements.items())]
        return self.rewrote(node, key, ("\n" + self.indent(node)).join(lines))

    def _statement_call(self, node: ast.Expr) -> str | None:
        """A call standing as a statement: the ones that become statements of their own."""
        call = node.value
        name = self.qualified(call.func)
        if name == "roslib.load_manifest":
            return self.rewrote(node, "py.imports", "")
        if not isinstance(call.func, ast.Attribute) or call.func.attr not in GOAL_ENDS:
            return None
        receiver = self._action_server(call.func.value, node)
        if receiver is None:
            return None
        server_id, handle = receiver
        function = self.function(node)
        method = GOAL_ENDS[call.func.attr]
        result = self.emit(call.args[0]) if call.args else f"{dict(self.ctx.action_results)[server_id]}()"
        siblings = self._siblings(node)
        following = siblings[siblings.index(node) + 1] if siblings.index(node) + 1 < len(siblings) else None
        if isinstance(following, ast.Return) and following.value is None:
            self.returns[id(following)] = result
            return self.rewrote(node, api.EXECUTE_CALLS, f"{handle}.{method}()")
        if following is None and function is not None and siblings is function.body:
            indent = self.indent(node)
            return self.rewrote(node, api.EXECUTE_CALLS, f"{handle}.{method}()\n{indent}return {result}")
        self.todo(node, "py.todo.goal_handling")
        return self.rewrote(node, api.EXECUTE_CALLS, f"{handle}.{method}()")

    def _server_alias(self, node: ast.Assign) -> bool:
        """`server = self.<id>_action_server` in its execute callback, every use of `server` rewritten."""
        if len(node.targets) != 1 or not isinstance(node.targets[0], ast.Name):
            return False
        if self._action_server(node.value, node) is None:
            return False
        name, function = node.targets[0].id, self.function(node)
        for inner in ast.walk(function):
            if isinstance(inner, ast.Name) and inner.id == name and inner is not node.targets[0]:
                parent = self.parents[id(inner)]
                call = self.parents.get(id(parent))
                if not (isinstance(parent, ast.Attribute) and parent.attr in SERVER_CALLS
                        and isinstance(call, ast.Call) and call.func is parent):
                    return False
        return True

    def _siblings(self, node: ast.stmt) -> list[ast.stmt]:
        parent = self.parents[id(node)]
        for name in ("body", "orelse", "finalbody", "handlers"):
            block = getattr(parent, name, None)
            if isinstance(block, list) and node in block:
                return block
        return [node]

    def _action_server(self, receiver: ast.AST, node: ast.AST) -> tuple[str, str] | None:
        """(server id, the goal handle's name) when `receiver` is the action server of the callback
        `node` is in (the member, or a local name given it)."""
        function = self.function(node)
        if function is None or not self.node_class(node):
            return None
        entry = self._callback(function)
        if entry is None or entry.endpoint != "action_server":
            return None
        server_id = function.name[len("execute_"):]
        if server_id not in dict(self.ctx.action_results):
            return None
        member = f"self.{server_id}_action_server"
        aliases = {target.id for statement in ast.walk(function) if isinstance(statement, ast.Assign)
                   and _dotted(statement.value) == member for target in statement.targets
                   if isinstance(target, ast.Name)}
        dotted = _dotted(receiver)
        if dotted == member or dotted in aliases:
            return server_id, "goal_handle"
        return None

    def _call(self, node: ast.Call) -> str | None:
        name = self.qualified(node.func) or ""
        log = LOG_CALL.match(name)
        if log:
            return self._log(node, log[1], log[2] or "")
        if name in TODO_CALLS:
            self.todo(node, TODO_CALLS[name])
            return None
        handler = getattr(self, "_call_" + name.replace(".", "_"), None) if name.startswith("rospy.") else None
        if handler is not None:
            return handler(node)
        if name in ("rospy.core.is_shutdown", "rospy.core.is_shutdown_requested"):
            return self._call_rospy_is_shutdown(node)
        if isinstance(node.func, ast.Attribute):
            return self._method_call(node, node.func)
        return None

    def _method_call(self, node: ast.Call, func: ast.Attribute) -> str | None:
        receiver = _dotted(func.value) or ""
        attr = func.attr
        if attr in ("to_sec", "to_nsec") and not node.args and not node.keywords:
            inner = self.atom(func.value)
            if (_dotted(func.value) or "").split(".")[-1] == "stamp":
                self.needed.add("rclpy.time:Time")
                inner = f"Time.from_msg({inner})"
            if attr == "to_nsec":
                return self.rewrote(node, "py.to_nsec", f"{inner}.nanoseconds")
            return self.rewrote(node, "py.to_sec", self.tight(node, f"{inner}.nanoseconds / 1e9"))
        if self.node_class(node) and receiver.startswith("self."):
            member = receiver[5:]
            if member.endswith("_timer") and member[:-6] in self.ctx.timers and attr == "shutdown" and not node.args:
                return self.rewrote(node, "py.api.timer", f"{receiver}.cancel()")
            if member.endswith("_client") and member[:-7] in self.ctx.service_clients:
                if attr == "wait_for_service":
                    return self._timeout(node, "py.wait_for_service", ("timeout",))
            if member.endswith("_action_client") and member[:-14] in self.ctx.action_clients:
                if attr == "wait_for_server":
                    return self._timeout(node, "py.wait_for_server", ("timeout",))
                if attr in ("cancel_goal", "cancel_all_goals", "get_state", "get_result", "wait_for_result",
                            "send_goal", "send_goal_and_wait", "get_goal_status_text"):
                    self.todo(node, "py.todo.other")
        if receiver == "self" and self.node_class(node):
            if attr.endswith("_client") and attr[:-7] in self.ctx.service_clients:
                self.todo(node, "py.todo.service_call")  # the ServiceProxy called: a blocking call
                return None
            if attr.startswith("call_") and attr[5:] in self.ctx.service_clients and not isinstance(
                    self.parents.get(id(node)), ast.Expr):
                self.todo(node, "py.todo.call_result")
                return None
        if (attr == "__init__" and not node.args and not node.keywords and isinstance(func.value, ast.Call)
                and _dotted(func.value.func) == "super" and not func.value.args and self._plain_constructor(node)):
            return self.rewrote(node, "py.api.constructor", "super().__init__(**kwargs)")
        server = self._action_server(func.value, node) if attr in (
            "publish_feedback", "is_preempt_requested", "is_active", "is_new_goal_available",
            "accept_new_goal", "set_succeeded", "set_aborted", "set_preempted") else None
        if server is not None:
            handle = server[1]
            if attr == "publish_feedback" and len(node.args) == 1:
                return self.rewrote(node, api.EXECUTE_CALLS, f"{handle}.publish_feedback({self.emit(node.args[0])})")
            if attr == "is_preempt_requested" and not node.args:
                return self.rewrote(node, api.EXECUTE_CALLS, f"{handle}.is_cancel_requested")
            if attr == "is_active" and not node.args:
                return self.rewrote(node, api.EXECUTE_CALLS, f"{handle}.is_active")
            self.todo(node, "py.todo.goal_handling")
        return None

    def _plain_constructor(self, node: ast.AST) -> bool:
        """Whether `node` is in the node class's `__init__(self)`, which becomes `__init__(self, **kwargs)`."""
        function = self.function(node)
        if function is None or function.name != "__init__" or not self.node_class(node):
            return False
        arguments = function.args
        return [a.arg for a in arguments.args] == ["self"] and not (arguments.vararg or arguments.kwarg)

    def _timeout(self, node: ast.Call, key: str, names: tuple[str, ...]) -> str | None:
        """A wait with its timeout in seconds, as `timeout_sec=` (a rospy.Duration given: its seconds)."""
        func = self.emit(node.func)
        given = node.args[0] if node.args else next((k.value for k in node.keywords if k.arg in names), None)
        if given is None:
            return None
        others = [k for k in node.keywords if k.arg not in names]
        if len(node.args) > 1 or others:
            return None
        return self.rewrote(node, key, f"{func}(timeout_sec={self._seconds(given)})")

    def _seconds(self, node: ast.AST) -> str:
        """Seconds as an expression: rospy.Duration(s) -> s, a number as it is."""
        if isinstance(node, ast.Call) and self.qualified(node.func) in ("rospy.Duration", "rospy.Duration.from_sec"):
            if len(node.args) == 1 and not node.keywords:
                return self.emit(node.args[0])
        if isinstance(node, ast.Call) and self.qualified(node.func) == "rospy.Duration" and not node.args:
            return "0.0"
        text = self.emit(node)
        if isinstance(node, ast.Constant):
            return text
        if "Duration(" in text:
            return f"{text}.nanoseconds / 1e9"
        return text

    # logging

    def _log(self, node: ast.Call, level: str, form: str) -> str | None:
        args = list(node.args)
        if node.keywords or any(isinstance(a, ast.Starred) for a in args):
            self.todo(node, "py.todo.other")
            return None
        extra = ""
        if form in ("_throttle", "_throttle_identical"):
            if len(args) < 2:
                return None
            extra = f", throttle_duration_sec={self._seconds(args[0])}"
            args = args[1:]
        elif form == "_once":
            extra = ", once=True"
        if not args:
            return None
        message = self._message(args[0], args[1:])
        key = {"": "py.log", "_throttle": "py.log_throttle", "_throttle_identical": "py.log_throttle_identical",
               "_once": "py.log_once"}[form]
        return self.rewrote(node, key, f"{self.logger(node)}.{LEVELS[level]}({message}{extra})")

    def _message(self, fmt: ast.AST, args: list[ast.AST]) -> str:
        """The log message: `fmt` with `args` formatted in (rclpy's logger takes one string)."""
        text = self.emit(fmt)
        if not args:
            return text
        values = [self.emit(arg) for arg in args]
        quote = _simple_literal(text) if isinstance(fmt, ast.Constant) and isinstance(fmt.value, str) else None
        if quote and text == self.source(fmt):
            inner = text[1:-1]
            specs = _SPEC.findall(inner)
            plain = [spec for spec in specs if spec != "%"]
            if any(quote in value for value in values) and not any(
                    other in inner or other in value for value in values for other in "\"'" if other != quote):
                other = "\"" if quote == "'" else "'"
                inner, quote = inner.replace("\\" + quote, quote), other
            if (len(plain) == len(values) and "%" not in _SPEC.sub("", inner) and "\\" + quote not in inner
                    and not any(quote in value or "\\" in value or "\n" in value or "{" in value for value in values)):
                parts = iter(values)

                def field_of(match: re.Match) -> str:
                    spec = match[1]
                    if spec == "%":
                        return "%"
                    value = next(parts)
                    return {"s": f"{{{value}}}", "r": f"{{{value}!r}}"}.get(spec, f"{{{value}:{spec}}}")

                escaped = inner.replace("{", "{{").replace("}", "}}")
                return "f" + quote + _SPEC.sub(field_of, escaped) + quote
        if len(values) == 1:
            return f"{text} % ({values[0]},)"
        return f"{text} % ({', '.join(values)})"

    # time

    def _stamp(self, node: ast.AST) -> bool:
        """Whether the time this call makes fills a message's stamp (wants .to_msg())."""
        parent = self.parents.get(id(node))
        if isinstance(parent, ast.Assign) and parent.value is node:
            return any((_dotted(target) or "").split(".")[-1] == "stamp" for target in parent.targets)
        if isinstance(parent, ast.keyword):
            return parent.arg == "stamp"
        return False

    def _holds_time(self, node: ast.Name) -> bool:
        """Whether the function `node` is in assigns its name a rospy time (now(), a Time, their sums)."""
        function = self.function(node)
        for inner in ast.walk(function) if function is not None else ():
            if isinstance(inner, ast.Assign) and any(isinstance(target, ast.Name) and target.id == node.id
                                                     for target in inner.targets):
                made = [call for call in ast.walk(inner.value) if isinstance(call, ast.Call)
                        and self.qualified(call.func) in ("rospy.Time.now", "rospy.get_rostime", "rospy.Time",
                                                          "rospy.Time.from_sec")]
                if made:
                    return True
        return False

    def _time_to_stamp(self, node: ast.BinOp) -> str | None:
        """Time arithmetic that fills a message's stamp: an rclpy Time, which a stamp takes as a message."""
        times = [inner for inner in ast.walk(node) if (isinstance(inner, ast.Call) and self.qualified(inner.func) in (
            "rospy.Time.now", "rospy.get_rostime")) or (isinstance(inner, ast.Attribute) and inner.attr == "stamp")]
        if not times:
            return None
        start, end = self.span(node)
        return self.rewrote(node, "py.stamp_time", f"({self.splice(node, start, end)}).to_msg()")

    def _call_rospy_Time_now(self, node: ast.Call) -> str:
        after = f"{self.clock(node)}.now()" + (".to_msg()" if self._stamp(node) else "")
        return self.rewrote(node, "py.now", after)

    _call_rospy_get_rostime = _call_rospy_Time_now

    def _call_rospy_get_time(self, node: ast.Call) -> str:
        return self.rewrote(node, "py.get_time", self.tight(node, f"{self.clock(node)}.now().nanoseconds / 1e9"))

    def _time_or_duration(self, node: ast.Call, kind: str) -> str | None:
        names = {"secs": "seconds", "nsecs": "nanoseconds"}
        parts = []
        for index, arg in enumerate(node.args[:2]):
            parts.append(f"{('seconds', 'nanoseconds')[index]}={self.emit(arg)}")
        for keyword in node.keywords:
            if keyword.arg not in names:
                return None
            parts.append(f"{names[keyword.arg]}={self.emit(keyword.value)}")
        if len(node.args) > 2:
            return None
        self.needed.add(f"rclpy.{kind.lower()}:{kind}")
        key = "py.time" if kind == "Time" else "py.duration"
        return self.rewrote(node, key, f"{kind}({', '.join(parts)})")

    def _call_rospy_Time(self, node: ast.Call) -> str | None:
        return self._time_or_duration(node, "Time")

    def _call_rospy_Duration(self, node: ast.Call) -> str | None:
        return self._time_or_duration(node, "Duration")

    def _from_sec(self, node: ast.Call, kind: str) -> str | None:
        if len(node.args) != 1 or node.keywords:
            return None
        self.needed.add(f"rclpy.{kind.lower()}:{kind}")
        key = "py.time" if kind == "Time" else "py.duration"
        return self.rewrote(node, key, f"{kind}(seconds={self.emit(node.args[0])})")

    def _call_rospy_Time_from_sec(self, node: ast.Call) -> str | None:
        return self._from_sec(node, "Time")

    def _call_rospy_Duration_from_sec(self, node: ast.Call) -> str | None:
        return self._from_sec(node, "Duration")

    def _call_rospy_sleep(self, node: ast.Call) -> str | None:
        if len(node.args) != 1 or node.keywords:
            return None
        self.needed.add("time")
        return self.rewrote(node, "py.sleep", f"time.sleep({self._seconds(node.args[0])})")

    def _call_rospy_Rate(self, node: ast.Call) -> str | None:
        if not self.node_class(node) or len(node.args) != 1 or node.keywords:
            self.todo(node, "py.todo.other")
            return None
        return self.rewrote(node, "py.rate", f"self.create_rate({self.emit(node.args[0])})")

    def _call_rospy_is_shutdown(self, node: ast.Call) -> str:
        return self.rewrote(node, "py.is_shutdown", self.tight(node, f"not {self._ok(node)}"))

    def _call_rospy_on_shutdown(self, node: ast.Call) -> str | None:
        if not self.node_class(node) or len(node.args) != 1:
            self.todo(node, "py.todo.other")
            return None
        return self.rewrote(node, "py.on_shutdown", f"self.context.on_shutdown({self.emit(node.args[0])})")

    # endpoints made by the user's own code

    def _arguments(self, node: ast.Call, names: tuple[str, ...]) -> dict[str, ast.AST] | None:
        """Positional and keyword arguments by name, or None when one is not among `names`."""
        if len(node.args) > len(names) or any(isinstance(a, ast.Starred) for a in node.args):
            return None
        given = dict(zip(names, node.args, strict=False))
        for keyword in node.keywords:
            if keyword.arg not in names or keyword.arg in given:
                return None
            given[keyword.arg] = keyword.value
        return given

    def _call_rospy_Publisher(self, node: ast.Call) -> str | None:
        given = self._arguments(node, ("name", "data_class", "subscriber_listener", "tcp_nodelay", "latch",
                                       "headers", "queue_size"))
        if (given is None or not self.node_class(node) or "name" not in given or "data_class" not in given
                or set(given) - {"name", "data_class", "latch", "queue_size"}):
            self.todo(node, "py.todo.other")
            return None
        depth = self.emit(given["queue_size"]) if "queue_size" in given else "10"
        latch = given.get("latch")
        if latch is not None and not (isinstance(latch, ast.Constant) and latch.value in (True, False)):
            self.todo(node, "py.todo.other")
            return None
        qos = depth
        if latch is not None and latch.value is True:
            self.needed |= {"rclpy.qos:QoSProfile", "rclpy.qos:DurabilityPolicy"}
            qos = f"QoSProfile(depth={depth}, durability=DurabilityPolicy.TRANSIENT_LOCAL)"
        return self.rewrote(node, "py.publisher", f"self.create_publisher({self.emit(given['data_class'])}, "
                                                  f"{self.emit(given['name'])}, {qos})")

    def _call_rospy_Subscriber(self, node: ast.Call) -> str | None:
        given = self._arguments(node, ("name", "data_class", "callback", "callback_args", "queue_size",
                                       "buff_size", "tcp_nodelay"))
        if given is not None and "callback_args" in given:
            self.todo(node, "py.todo.callback_args")
            return None
        if given is None or not self.node_class(node) or not {"name", "data_class", "callback"} <= set(given):
            self.todo(node, "py.todo.other")
            return None
        depth = self.emit(given["queue_size"]) if "queue_size" in given else "10"
        return self.rewrote(node, "py.subscriber", f"self.create_subscription({self.emit(given['data_class'])}, "
                                                   f"{self.emit(given['name'])}, {self.emit(given['callback'])}, "
                                                   f"{depth})")

    def _call_rospy_Timer(self, node: ast.Call) -> str | None:
        given = self._arguments(node, ("period", "callback", "oneshot", "reset"))
        if given is None or not self.node_class(node) or not {"period", "callback"} <= set(given) or (
                set(given) - {"period", "callback"}):
            self.todo(node, "py.todo.other")
            return None
        return self.rewrote(node, "py.timer", f"self.create_timer({self._seconds(given['period'])}, "
                                              f"{self.emit(given['callback'])})")

    def _call_rospy_get_param(self, node: ast.Call) -> str | None:
        first = node.args[0] if node.args else None
        name = first.value if isinstance(first, ast.Constant) and isinstance(first.value, str) else None
        if name and name.startswith("~") and name[1:] in self.ctx.parameters and self.node_class(node):
            return self.rewrote(node, "py.param", api.parameter_read("python", name[1:]))
        self.todo(node, "py.todo.param" if name and name.startswith("~") else "py.todo.global_param")
        return None
