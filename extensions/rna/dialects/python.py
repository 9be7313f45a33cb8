"""Python as both ROS generations spell it: literals, import blocks and type names.

Import blocks are ordered the way ament_flake8's import-order check wants them
(google style: the standard library first, then one group per top-level package, each
sorted by module, as in ros2/examples).
"""

from __future__ import annotations

import math
import re
from collections import defaultdict
from collections.abc import Iterable
from functools import cached_property

from .. import features, names, python_names
from .lines import NESTED_BREAK, NESTED_SPLIT, SPLIT, splittable

# Names the generated Python files import or define besides interface types.
RESERVED = frozenset({
    "ActionClient", "ActionServer", "CancelResponse", "ExternalShutdownException",
    "FloatingPointRange", "Future", "GoalResponse", "GoalStatus", "IntegerRange",
    "MultiThreadedExecutor", "MutuallyExclusiveCallbackGroup", "Node", "ParameterDescriptor",
    "ReentrantCallbackGroup", "SignalHandlerOptions", "SingleThreadedExecutor", "State",
    "TransitionCallbackReturn",
})

# Starter code's values for a std_msgs `data` field, changing with a counter.
_SAMPLES = {
    "string": "f'Hello World: {{{count}}}'",
    "int": "{count}",
    "float": "float({count})",
    "bool": "{count} % 2 == 0",
}


def _escape(text: str, quote: str) -> str:
    """The inside of a Python string literal in `quote` that reads back as `text`."""
    out = []
    for char in text:
        if char in ("\\", quote):
            out.append("\\" + char)
        elif char in "\n\r\t":
            out.append({"\n": "\\n", "\r": "\\r", "\t": "\\t"}[char])
        elif not char.isprintable():
            code = ord(char)
            out.append(f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}")
        else:
            out.append(char)
    return "".join(out)


def literal(value: object, split: bool = False) -> str:
    """A Python literal in the quote style ROS's flake8 settings want (single quotes).

    `split`: a string may be cut at its spaces (rna.dialects.lines) when its line is too long,
    a list broken after its bracket and its commas, and its strings cut.
    """
    if isinstance(value, bool):
        return "True" if value else "False"
    if isinstance(value, float):
        # repr() spells infinity and NaN as names Python does not define.
        return repr(value) if math.isfinite(value) else f"float('{value}')"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        # flake8-quotes: single quotes, unless the text holds some and no double ones.
        quote = '"' if "'" in value and '"' not in value else "'"
        if split:
            return quote + splittable((char, _escape(char, quote)) for char in value) + quote
        return quote + _escape(value, quote) + quote
    if isinstance(value, list):
        if split:
            items = (literal(item, split=True).replace(SPLIT, NESTED_SPLIT) for item in value)
            return "[" + NESTED_BREAK + f",{NESTED_BREAK} ".join(items) + "]"
        return "[" + ", ".join(literal(item) for item in value) + "]"
    raise TypeError(f"no Python literal for {value!r}")


def docstring_prefix(text: str) -> str:
    """'r' for a docstring holding a backslash, or three double quotes (docstring_text escapes
    them with one): pydocstyle (D301) wants it raw."""
    return "r" if "\\" in text or '"""' in text else ""


def docstring_text(line: str) -> str:
    """Free text for a docstring: no three double quotes in a row, which would end it, nor in
    the text it reads as (pydocstyle then wants the docstring in single quotes, D300): every
    third quote of a run is escaped, as in `""\\""\\""` for six (the raw docstring,
    docstring_prefix, keeps the backslashes)."""
    written, run = [], 0
    for char in line:
        if char == '"' and run == 2:
            written.append('\\"')
            run = 1
        else:
            written.append(char)
            run = run + 1 if char == '"' else 0
    return "".join(written)


def fstring_text(text: str) -> str:
    """Text for an f-string as it stands (a ROS 2 name's {node} would be an expression there),
    cut where a long word may be (the braces written twice make it longer than the name)."""
    return splittable((char, char * 2 if char in "{}" else char) for char in text)


def text_literal(text: str, column: int, indent: int, width: int = 99) -> str:
    """A string literal starting at `column` that fits in `width` columns, followed by a comma.

    Too long, it becomes parenthesised parts, one per line, indented by `indent`; each part
    is cut by its spelled width (an escape is up to ten columns), the last leaving room for
    the `),` after it.
    """
    spelled = literal(text)
    if column + len(spelled) + 1 <= width:
        return spelled
    parts = _cut_by_spelling(text, width - indent - len("),"))
    return "(\n" + "\n".join(" " * indent + literal(part) for part in parts) + ")"


def _cut_by_spelling(text: str, room: int) -> list[str]:
    """`text` in parts whose literals fit `room` columns, cut after spaces where a word fits."""
    parts, current = [], ""
    for word in re.findall(r"[^ ]+ *| +", text):
        if len(literal(current + word)) <= room:
            current += word
            continue
        if current:
            parts.append(current)
            current = ""
        for char in word:
            if current and len(literal(current + char)) > room:
                parts.append(current)
                current = ""
            current += char
    return parts + [current] if current else parts


def _sort_key(module: str) -> tuple[str, str]:
    return (module.lower(), module)


def _top(module: str) -> str:
    return module.split(".")[0]


def _from_import(module: str, names: list[str], width: int = 99) -> str:
    line = f"from {module} import {', '.join(names)}"
    if len(line) <= width:
        return line
    return f"from {module} import (\n" + "".join(_import_name(name, width) for name in names) + ")"


def _import_name(name: str, width: int) -> str:
    """One name of a parenthesized import; an alias too long for its line goes on the next."""
    if len(f"    {name},") <= width or " as " not in name:
        return f"    {name},\n"
    original, alias = name.split(" as ")
    return f"    {original} as\n    {alias},\n"


def import_block(imports: Iterable[str]) -> str:
    """'module' or 'module:Name' (Name may be 'Name as Alias') -> the import block."""
    plain: set[str] = set()
    from_imports: dict[str, set[str]] = defaultdict(set)
    for item in imports:
        module, _, name = item.partition(":")
        if name:
            from_imports[module].add(name)
        else:
            plain.add(module)
    statements = [(module, f"import {module}") for module in plain]
    statements += [(module, _from_import(module, sorted(names, key=_sort_key)))
                   for module, names in from_imports.items()]
    statements.sort(key=lambda item: (_sort_key(item[0]), item[1].startswith("from")))
    stdlib = [line for module, line in statements if _top(module) in python_names.STDLIB_MODULES]
    groups: dict[str, list[str]] = defaultdict(list)
    for module, line in statements:
        if _top(module) not in python_names.STDLIB_MODULES:
            groups[_top(module)].append(line)
    blocks = ["\n".join(stdlib)] if stdlib else []
    blocks += ["\n".join(lines) for lines in groups.values()]
    return "\n\n".join(blocks)


class PythonDialect:
    """What ROS 1 and ROS 2 Python code share."""

    def __init__(self, node) -> None:
        self.node = node

    literal = staticmethod(literal)

    @staticmethod
    def parameter_default(parameter) -> str:
        """The default as a literal that breaks when its line is too long."""
        return literal(parameter.default, split=True)

    text_literal = staticmethod(text_literal)
    docstring_prefix = staticmethod(docstring_prefix)
    docstring_text = staticmethod(docstring_text)
    fstring_text = staticmethod(fstring_text)

    @cached_property
    def types(self) -> dict:
        """The name of each interface type in the node's Python files.

        A type whose name clashes with another type, the node's classes or an
        imported helper is imported under its package's name: NavMsgsOdometry.
        """
        node = self.node
        return names.type_aliases(node.interfaces, {node.class_name, node.base_class_name, *RESERVED,
                                                    *self._starter_names})

    @property
    def _starter_names(self) -> set[str]:
        """Names the starter code imports besides the node's types: DiagnosticStatus, for its level."""
        if not self.node.diagnostics or any(
                (t.package, t.kind, t.name) == ("diagnostic_msgs", "msg", "DiagnosticStatus")
                for t in self.node.interfaces):
            return set()
        return {"DiagnosticStatus"}

    def type(self, interface) -> str:
        return self.types[interface]

    @staticmethod
    def module(interface) -> str:
        return f"{interface.package}.{interface.kind}"

    def _import(self, interface, part: str = "") -> str:
        """The import of a type (or a part of it, ROS 1: TriggerResponse), aliased like the type."""
        alias, name = self.types[interface] + part, interface.name + part
        return f"{self.module(interface)}:{name}" + ("" if alias == name else f" as {alias}")

    def _needs(self, which: str) -> list[str]:
        return [item for need in features.needs(self.node) for item in getattr(need, which)]

    @property
    def base_module(self) -> str:
        """What the user's file imports the base class from."""
        return f"{self.node.package}.{self.node.base_name}"

    @staticmethod
    def sample(data_field: str, count: str) -> str:
        """An expression giving a std_msgs `data` field a value that changes with `count`."""
        return _SAMPLES[data_field].format(count=count)

    @staticmethod
    def format(data_field: str, expression: str) -> str:
        """The f-string part that prints a `data` field: quoted for text."""
        return f'"{{{expression}}}"' if data_field == "string" else f"{{{expression}}}"
