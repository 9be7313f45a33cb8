"""A node's file ported: the user's code, ROS 1 -> ROS 2, on top of the new starter.

The user's file is the ROS 1 starter plus their edits. The rules rewrite both the user's
text and the ROS 1 starter the same way; what still differs between that rewritten starter
and the ROS 2 starter is the template's part of the change (main(), the constructor's
plumbing, the starter's own lines), and what differs between it and the rewritten user's
text is the user's part. A three-way merge (rna.update.merge) takes both, so the file is
the ROS 2 starter with the user's code in it, ported. The imports (includes) are settled
apart: the ROS 2 starter's, the user's own, and what the ported code uses.

Lines of the user's the rules rewrote are listed, and every `TODO(port)` left is counted.
"""

from __future__ import annotations

import ast
import difflib
import re
from dataclasses import dataclass, field

from ..dialects.cpp import include_block
from ..dialects.python import import_block
from ..update.merge import merge3
from . import cpp, python
from .rule import TODO


@dataclass
class NodePort:
    text: str
    rewrites: list[python.Rewrite] = field(default_factory=list)  # of the user's own lines
    todos: int = 0  # TODO(port) lines in the text that the ROS 2 starter does not have
    conflicted: bool = False


def user_lines(mine: str, starter: str) -> set[int]:
    """The lines (from 1) of `mine` that are not the starter's: the user's own."""
    ours, theirs = mine.split("\n"), starter.split("\n")
    found = set()
    for tag, i1, i2, _, _ in difflib.SequenceMatcher(None, ours, theirs, autojunk=False).get_opcodes():
        if tag in ("replace", "delete"):
            found |= set(range(i1 + 1, i2 + 1))
    return found


def todo_count(text: str, starter: str) -> int:
    return max(text.count(TODO) - starter.count(TODO), 0)


# --- Python


@dataclass
class _Parts:
    head: str
    imports: list[str]  # one statement each, as written
    body: str
    region: list[str]  # the import block's lines as written (blank lines between its groups)


def _python_parts(text: str) -> _Parts | None:
    """The file around its import block (the top-level imports from the first one on, in a row)."""
    try:
        tree = ast.parse(text)
    except SyntaxError:
        return None
    statements = tree.body
    first = next((index for index, node in enumerate(statements) if isinstance(node, (ast.Import, ast.ImportFrom))),
                 None)
    if first is None:
        return None
    run = []
    for node in statements[first:]:
        if not isinstance(node, (ast.Import, ast.ImportFrom)):
            break
        run.append(node)
    lines = text.split("\n")
    head = "\n".join(lines[:run[0].lineno - 1])
    body = "\n".join(lines[run[-1].end_lineno:])
    imports = ["\n".join(lines[node.lineno - 1:node.end_lineno]) for node in run]
    return _Parts(head, imports, body, lines[run[0].lineno - 1:run[-1].end_lineno])


def _specs(statement: str) -> tuple[list[str], list[str]]:
    """(import_block specs, statements kept as written) of one import statement."""
    node = ast.parse(statement).body[0]
    if isinstance(node, ast.Import):
        if any(alias.asname for alias in node.names):
            return [], [statement]
        return [alias.name for alias in node.names], []
    if node.level or node.module is None or any(alias.name == "*" for alias in node.names):
        return [], [statement]
    return [f"{node.module}:{alias.name}" + (f" as {alias.asname}" if alias.asname else "")
            for alias in node.names], []


def _provides(spec: str) -> str:
    module, _, name = spec.partition(":")
    if name:
        return name.split(" as ")[-1]
    return module.split(".")[0]


def _names_used(code: str) -> set[str]:
    """The names the code reads (from Python's parser; word by word when it does not parse)."""
    try:
        tree = ast.parse(code)
    except SyntaxError:
        lines = [line for line in code.split("\n") if not line.lstrip().startswith("#")]
        return set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", "\n".join(lines)))
    return {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)}


def _import_text(ours: list[str], base: list[str], theirs: _Parts, needed: set[str], code: str) -> list[str]:
    """The import block: the starter's and the user's imports, and what the ported code uses."""
    specs = {"ours": set(), "base": set(), "theirs": set()}
    raw = {"ours": [], "base": [], "theirs": []}
    for side, statements in (("ours", ours), ("base", base), ("theirs", theirs.imports)):
        for statement in statements:
            found, kept = _specs(statement)
            specs[side] |= set(found)
            raw[side] += kept
    added = specs["ours"] - specs["base"]
    words = _names_used(code)
    wanted = {spec for spec in specs["theirs"] | specs["ours"] | needed if _provides(spec) in words} | added
    statements = [statement for statement in raw["theirs"] + raw["ours"] if statement not in raw["base"]
                  or statement in raw["theirs"]]
    statements = list(dict.fromkeys(statements))
    if wanted == specs["theirs"] and statements == raw["theirs"]:
        return theirs.region
    block = import_block(sorted(wanted)).split("\n") if wanted else []
    return block + ([""] if block and statements else []) + statements


def _merged(ours: str, base: str, theirs: str) -> tuple[str, bool]:
    """The update's merge (rna.update.merge), which settles neighbouring changes too."""
    if ours == base:
        return theirs, False
    return merge3(ours, base, theirs)


def _python_methods(text: str, base_class: str) -> dict[str, tuple[int, int]]:
    """The methods of the class deriving from `base_class`: name -> (first line, last line), from 0."""
    try:
        tree = ast.parse(text)
    except SyntaxError:
        return {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef) and any(getattr(b, "id", None) == base_class for b in node.bases):
            return {item.name: (min([item.lineno] + [d.lineno for d in item.decorator_list]) - 1, item.end_lineno - 1)
                    for item in node.body if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef))}
    return {}


def users_methods(ours: str, base: str, theirs: str, methods) -> str:
    """`theirs` with each method the user changed as the old starter had it (`base`), so that the merge
    takes the user's method whole: the starter's example code in a callback is the user's to replace,
    and how the template changed that example does not matter any more. `methods(text)` finds them."""
    mine, old, new = methods(ours), methods(base), methods(theirs)
    ours_lines, base_lines, theirs_lines = ours.split("\n"), base.split("\n"), theirs.split("\n")
    for name in sorted((name for name in mine if name in old and name in new), key=lambda n: -new[n][0]):
        if ours_lines[mine[name][0]:mine[name][1] + 1] == base_lines[old[name][0]:old[name][1] + 1]:
            continue
        start, end = new[name]
        theirs_lines[start:end + 1] = base_lines[old[name][0]:old[name][1] + 1]
    return "\n".join(theirs_lines)


def port_python(mine: str, old_starter: str, new_starter: str, context: python.Context) -> NodePort:
    ours, base = python.port(mine, context), python.port(old_starter, context)
    fresh = new_starter  # the ROS 2 starter: the TODO(port) lines it does not have are counted
    new_starter = users_methods(ours.text, base.text, new_starter,
                                lambda text: _python_methods(text, context.base_class))
    mine_user = user_lines(mine, old_starter)
    rewrites = [rewrite for rewrite in ours.rewrites if rewrite.line in mine_user]
    parts = [_python_parts(text) for text in (ours.text, base.text, new_starter)]
    if None in parts:
        text, conflicted = _merged(ours.text, base.text, new_starter)
        return NodePort(text, rewrites, todo_count(text, fresh), conflicted)
    (our, basis, their) = parts
    head, head_conflict = _merged(our.head, basis.head, their.head)
    body, body_conflict = _merged(our.body, basis.body, their.body)
    imports = _import_text(our.imports, basis.imports, their, ours.needed, head + "\n" + body)
    text = "\n".join([head, *imports, body]) if head else "\n".join([*imports, body])
    return NodePort(text, rewrites, todo_count(text, fresh), head_conflict or body_conflict)


def port_other_python(text: str, context: python.Context) -> NodePort:
    """A Python file of the user's own (no starter): the rules alone."""
    ported = python.port(text, context)
    return NodePort(ported.text, ported.rewrites, todo_count(ported.text, ""))


# --- C++

_INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*([<"][^>"]+[>"])')


def _cpp_parts(text: str) -> tuple[str, list[str], str] | None:
    """(before, the #include lines, after) around the first run of #include lines (blank lines between)."""
    lines = text.split("\n")
    found = [index for index, line in enumerate(lines) if _INCLUDE.match(line)]
    if not found:
        return None
    first = last = found[0]
    for index in range(first + 1, len(lines)):
        if _INCLUDE.match(lines[index]):
            last = index
        elif lines[index].strip():
            break
    return "\n".join(lines[:first]), lines[first:last + 1], "\n".join(lines[last + 1:])


def _headers(lines: list[str]) -> list[str]:
    return [_INCLUDE.match(line)[1] for line in lines if _INCLUDE.match(line)]


def _include_lines(ours: list[str], base: list[str], theirs: list[str], needed: set[str]) -> list[str]:
    """The starter's includes, the user's own, and what the ported code needs."""
    mine, generated, fresh = _headers(ours), _headers(base), _headers(theirs)
    added = [header for header in mine if header not in generated and header not in fresh]
    kept = [header for header in mine if header in generated and header not in fresh
            and re.fullmatch(r'"\w+/(msg|srv|action)/\w+\.hpp"', header)]
    extra = [f"<{h[1:-1]}>" if h.startswith("<") else h for h in sorted(needed)]
    wanted = added + kept + [header for header in extra if header not in fresh]
    if not wanted:
        return theirs
    every = [header[1:-1] if header.startswith('"') else header for header in fresh + wanted]
    return include_block(every).split("\n")


def _cpp_methods(text: str, class_name: str) -> dict[str, tuple[int, int]]:
    """The methods defined in the class `class_name`: name -> (first line, last line), from 0."""
    masked = cpp.mask(text)
    match = re.search(rf"\bclass\s+{re.escape(class_name)}\b[^;{{]*\{{", masked)
    if not match:
        return {}
    opening = match.end() - 1
    end = cpp.closing(masked, opening)
    found, index = {}, opening + 1
    declaration = re.compile(r"^[ \t]*(?:virtual[ \t]+|explicit[ \t]+)?(?:[\w:<>,&*~]+[ \t]+)*?[&*]?[ \t]*(~?\w+)\s*\(",
                             re.M)
    while True:
        method = declaration.search(masked, index, end)
        if not method:
            return found
        parameters_end = cpp.closing(masked, method.end() - 1)
        body = re.match(r"[^;{]*\{", masked[parameters_end + 1:]) if parameters_end > 0 else None
        if body is None:
            index = method.end()
            continue
        brace = parameters_end + body.end()
        body_end = cpp.closing(masked, brace)
        if body_end < 0:
            return found
        found[method[1]] = (masked.count("\n", 0, method.start()), masked.count("\n", 0, body_end))
        index = body_end + 1


def port_cpp(mine: str, old_starter: str, new_starter: str, context: cpp.Context) -> NodePort:
    ours, base = cpp.port(mine, context), cpp.port(old_starter, context)
    fresh = new_starter  # the ROS 2 starter: the TODO(port) lines it does not have are counted
    new_starter = users_methods(ours.text, base.text, new_starter,
                                lambda text: _cpp_methods(text, context.class_name))
    mine_user = user_lines(mine, old_starter)
    rewrites = [rewrite for rewrite in ours.rewrites if rewrite.line in mine_user]
    parts = [_cpp_parts(text) for text in (ours.text, base.text, new_starter)]
    if None in parts:
        text, conflicted = _merged(ours.text, base.text, new_starter)
        return NodePort(text, rewrites, todo_count(text, fresh), conflicted)
    (our_head, our_includes, our_body), (base_head, base_includes, base_body), (head, includes, body) = parts
    merged_head, head_conflict = _merged(our_head, base_head, head)
    merged_body, body_conflict = _merged(our_body, base_body, body)
    lines = _include_lines(our_includes, base_includes, includes, ours.needed)
    text = "\n".join([merged_head, *lines, merged_body])
    return NodePort(text, rewrites, todo_count(text, fresh), head_conflict or body_conflict)


def port_other_cpp(text: str, context: cpp.Context) -> NodePort:
    """A C++ file of the user's own (no starter): the rules alone."""
    ported = cpp.port(text, context)
    return NodePort(ported.text, ported.rewrites, todo_count(ported.text, ""))
