"""Hypothesis strategies for answer sets (issue 8): valid ones, and ones that break one rule each.

Valid answers are drawn from the rules of extensions/rna itself: names built to the
patterns and lengths of rna.names and kept only when its own checks accept them,
interface types from the distro's catalogue (rna.catalogue), from made-up packages
that rna.interfaces accepts or from the package's own messages, services and actions
(the `interfaces` answer, drawn too), parameter values of every type within rna.parameters'
limits. A few rules look at several answers at once (names used twice in a node, a
package named like one its nodes use): a drawn set that breaks one of those is drawn
again, and any other refusal of a "valid" set fails loudly, as a strategy that no
longer matches the rules.

An invalid set is a valid one with one rule broken, paired with the question whose
one-line error must name it (`invalid_answers()`).
"""

from __future__ import annotations

import functools
import keyword
import math
import re
import string
import sys
from dataclasses import dataclass
from pathlib import Path

import yaml
from hypothesis import assume
from hypothesis import strategies as st
from rna import AnswerError, build_package, catalogue, distros, layout, model, names
from rna import qos as qos_rules
from rna.configs import yaml_literal
from rna.licenses import LICENSES
from rna.parameters import INT_RANGE, INT_RANGES, TYPE_ALIASES, infer_type

ALNUM = string.ascii_lowercase + string.digits

# Arrays long enough to break over several lines however short their elements (40 bools).
ARRAY_MAX = 40

# Rules that look at several answers at once: a set drawn as valid that breaks one is redrawn.
CROSS_ANSWER_RULES = ("give its nodes one type", "(give both the same qos preset)",
                      "both use the name", "is the name of a package its nodes use", "would shadow the Python module",
                      "characters together: a C++ node's", "message generation already makes a type")

# Text that has broken, or could break, the files free text lands in: quotes and triple
# quotes (Python), backslashes (string escapes, comment continuations), Jinja, XML and
# CMake delimiters, comment ends, trigraphs, Markdown, non-ASCII and invisible characters.
AWKWARD_TEXT = (
    '"', "'", '"""', "'''", "\\", "\\n", "\\x", "\\N", "\\u2019", "{{ x }}", "{% if %}", "{#", "}}",
    "<tag>", "&amp;", "&", "]]>", "-->", "<!--", "--", "*/", "/*", "//", "#", "${PROJECT_NAME}",
    "$(find x)", "@", "%", "%s", "{}", "`", "|", "??/", "??=", "café", "Łukasiewicz", "Zoë",
    "O'Brien", "日本語", "🤖", "\u00a0", "\u200b", "\u2019", "ﬁ", "e\u0301",
)

# Characters one line of text may hold (rna.names.one_line_error refuses the others).
PRINTABLE = st.characters(exclude_categories=("Cc", "Co", "Cs", "Cn", "Zl", "Zp"))
# Characters it refuses: line and paragraph breaks, controls (tab, NUL, escape, NEL).
NOT_ONE_LINE = ("\n", "\r", "\t", "\x00", "\x07", "\x1b", "\x7f", "\x85", "\u2028", "\u2029")

# Doubles at the edges: the largest, the smallest normal and subnormal, an exponent
# both ways, integral values beyond 2**53, negative zero.
EXTREME_DOUBLES = (1e308, -1e308, sys.float_info.max, -sys.float_info.max, sys.float_info.min, 5e-324,
                   -5e-324, 1e-06, 1.5e-07, 1e16, 2.0**53 + 2, -0.0, 0.0, 0.1)
EXTREME_INTS = (INT_RANGE[0], INT_RANGE[1], -(2**31), 2**31 - 1, 2**53 + 1, 0, -1)


# ----------------------------------------------------------------------------- names

_LETTER = st.sampled_from(string.ascii_lowercase)


@functools.cache
def snake_case(max_size: int, min_size: int = 1) -> st.SearchStrategy[str]:
    """A lower_snake_case name (rna.names.SNAKE_CASE), often exactly `max_size` long."""
    sizes = st.one_of(st.integers(min_size, max(min_size, min(max_size, 12))), st.just(max_size),
                      st.integers(min_size, max_size))
    return sizes.flatmap(lambda size: st.tuples(_LETTER, st.text(ALNUM + "____", min_size=size - 1,
                                                                 max_size=size - 1))).map(_snake)


def _snake(parts: tuple[str, str]) -> str:
    """A letter and letters, digits and underscores, made snake_case without changing the length."""
    first, rest = parts
    rest = re.sub("_(?=_)", "a", rest)
    return first + (rest[:-1] + "z" if rest.endswith("_") else rest)


@functools.cache
def package_names() -> st.SearchStrategy[str]:
    return snake_case(names.PACKAGE_NAME_MAX, min_size=2).filter(
        lambda name: names.generated_package_name_error(name) is None)


@functools.cache
def node_names() -> st.SearchStrategy[str]:
    # A ROS 1 Python node may not share a standard module's name (its script would shadow it).
    return snake_case(names.NODE_NAME_MAX).filter(
        lambda name: names.node_name_error(name) is None and name not in sys.stdlib_module_names)


@functools.cache
def parameter_names(ros: int) -> st.SearchStrategy[str]:
    return snake_case(names.IDENTIFIER_MAX).filter(lambda name: names.parameter_name_error(name, ros) is None)


@functools.cache
def identifiers(what: str = "id") -> st.SearchStrategy[str]:
    return snake_case(names.IDENTIFIER_MAX).filter(lambda name: names.identifier_error(name, what) is None)


# A part between '/' of a ROS name (rna.names.NAME_TOKEN), CamelCase and leading '_' included.
_TOKENS = st.one_of(
    snake_case(20),
    st.from_regex(names.NAME_TOKEN, fullmatch=True).filter(lambda token: len(token) <= 30),
    st.sampled_from(("cmdVel", "PointCloud2", "_private", "_1", "x_", "A_B", "depth__raw")),
)


# ROS 2's {node} substitution, in a part of its own or in one with other text.
_SUBSTITUTED_TOKENS = st.one_of(st.just("{node}"), st.tuples(_TOKENS, st.sampled_from(("", "_"))).map(
    lambda parts: f"{parts[0]}{parts[1]}{{node}}"), st.sampled_from(("{node}_state", "cam_{node}_raw")))


@st.composite
def ros_names(draw, what: str = "topic", ros: int = 2) -> str:
    """A topic, service or action name that rna.names.topic_name_error accepts, up to its longest
    ({node} substitutions in ROS 2's)."""
    prefix = draw(st.sampled_from(("", "", "/", "~/")))
    tokens = draw(st.lists(_TOKENS if ros == 1 else st.one_of(_TOKENS, _TOKENS, _SUBSTITUTED_TOKENS),
                           min_size=1, max_size=4))
    name = prefix + "/".join(tokens)
    if draw(st.booleans()) and len(name) < names.ROS_NAME_MAX:  # as long as allowed
        name += "x" * (names.ROS_NAME_MAX - len(name))
    name = name[:names.ROS_NAME_MAX]
    if names.topic_name_error(name, what, ros):
        name = draw(snake_case(20))
    return name


def _needs_id(ros_name: str) -> bool:
    """The code name derived from a ROS name is refused (rna.answers.nodes._parse_id), or too long."""
    derived = names.identifier_from_name(ros_name)
    return not derived[:1].isalpha() or bool(names.too_long(derived, names.IDENTIFIER_MAX))


@functools.cache
def type_names() -> st.SearchStrategy[str]:
    """A CamelCase type name (rna.names.CAMEL_CASE), often as long as the rules allow (TYPE_NAME_MAX)."""
    words = st.lists(st.tuples(st.sampled_from(string.ascii_uppercase),
                               st.text(string.ascii_lowercase + string.digits, max_size=9)).map("".join),
                     min_size=1, max_size=12).map("".join)
    long = st.integers(2, names.TYPE_NAME_MAX).flatmap(
        lambda size: words.map(lambda name: (name * (size // len(name) + 1))[:size]))
    return st.one_of(st.from_regex(names.CAMEL_CASE, fullmatch=True), words, long).filter(
        lambda name: len(name) <= names.TYPE_NAME_MAX and names.is_camel_case(name)
        and names.type_name_error(name) is None)


def _fitting(name: str, package: str, kind: str) -> str | None:
    """`name`, shortened until its C++ header path fits (rna.names.header_path_error)."""
    while name and names.header_path_error(package, kind, name):
        name = name[:-1]
    return name if name and names.type_name_error(name) is None else None


# ----------------------------------------------------------------------------- text

@functools.cache
def one_line_text(max_size: int = 120) -> st.SearchStrategy[str]:
    """One line of printable text, mixing awkward fragments with arbitrary characters."""
    pieces = st.one_of(st.sampled_from(AWKWARD_TEXT), st.text(PRINTABLE, min_size=1, max_size=12))
    return (st.lists(pieces, min_size=1, max_size=12).map("".join)
            .map(lambda text: text[:max_size])
            .filter(lambda text: names.one_line_error(text) is None))


@functools.cache
def emails() -> st.SearchStrategy[str]:
    return st.from_regex(names.EMAIL, fullmatch=True).filter(lambda address: names.email_error(address) is None)


# ----------------------------------------------------------------------------- types

@functools.cache
def _catalogue_types(distro: str, kind: str) -> list[str]:
    packages = catalogue.load(distro)["packages"]
    return sorted(f"{package}/{kind}/{name}" for package, kinds in packages.items() for name in kinds.get(kind, ()))


@st.composite
def interface_types(draw, kind: str, distro: str, own: OwnInterfaces | None = None) -> str:
    """A type of the distro's catalogue, of a made-up package or of the package's own interfaces,
    spelled as users may spell it."""
    ros = distros.generation(distro)
    if own and own.names[kind] and draw(st.booleans()):
        name = draw(st.sampled_from(own.names[kind]))
        return name if draw(st.booleans()) else own.full_name(kind, name)
    if draw(st.integers(0, 3)):
        full = draw(st.sampled_from(_catalogue_types(distro, kind)))
        package, _, name = full.split("/")
    else:
        # A few shared packages, so that one node meets one package's message and service of one name.
        package = draw(st.one_of(st.sampled_from(("my_msgs", "robot_interfaces")), snake_case(30, min_size=2).filter(
            lambda name: names.package_name_error(name) is None)))
        name = draw(st.one_of(
            st.from_regex(names.CAMEL_CASE, fullmatch=True).filter(lambda text: len(text) <= names.TYPE_NAME_MAX),
            # As long as allowed: with long code names, the longest C++ lines (goal handles).
            st.text(string.ascii_lowercase + string.digits, min_size=names.TYPE_NAME_MAX - 1,
                    max_size=names.TYPE_NAME_MAX - 1).map(lambda tail: "L" + tail),
            # Names the generated files use themselves, or that another package has too.
            st.sampled_from(("Node", "State", "String", "Time", "Duration", "Parameter", "Empty", "Goal",
                             "Log", "Twist", "Feedback", "Result", "Request", "Response"))))
        name = _fitting(name, package, kind) or "Thing"
    # ROS 1 users may keep the ROS 2 spelling; both may leave the kind out.
    short = ros == 1 or draw(st.booleans())
    return f"{package}/{name}" if short and draw(st.booleans()) else f"{package}/{kind}/{name}"


@dataclass(frozen=True)
class OwnInterfaces:
    """The package's own interfaces drawn for the `interfaces` answer, as its nodes may name them."""

    home: str  # <package>_interfaces, or the package itself
    ros: int
    names: dict[str, list[str]]

    def full_name(self, kind: str, name: str) -> str:
        return f"{self.home}/{name}" if self.ros == 1 else f"{self.home}/{kind}/{name}"


_FIELD_LINES = ("float64 x", "int32 count", "string frame_id", "bool ok", "uint8[] data", "std_msgs/Header header",
                "geometry_msgs/Point position", "int32 MAX_COUNT=5", "float64[] values")


@st.composite
def own_interfaces(draw, ros: int, home: str) -> tuple[dict, OwnInterfaces]:
    """(the `interfaces` answer: a few messages, services and actions with plain fields, the names drawn)."""
    drawn = draw(st.lists(st.one_of(type_names(), st.sampled_from(("Target", "Set", "Go", "State", "Node", "Goal"))),
                          min_size=1, max_size=4))
    kinds = {"messages": "msg", "services": "srv", "actions": "action"}
    answer: dict = {}
    by_kind: dict[str, list[str]] = {"msg": [], "srv": [], "action": []}
    fields = st.lists(st.sampled_from(_FIELD_LINES), min_size=0, max_size=2, unique_by=lambda line: line.split()[1])
    stems = set()
    for name in drawn:
        key = draw(st.sampled_from(tuple(kinds)))
        kind = kinds[key]
        name = _fitting(name, home, kind)
        if name is None or names.camel_to_snake(name) in stems:
            continue
        stems.add(names.camel_to_snake(name))
        sections = {"msg": ("fields",), "srv": ("request", "response"), "action": ("goal", "result", "feedback")}
        entry = {"name": name, **{section: draw(fields) for section in sections[kind]}}
        answer.setdefault(key, []).append(entry)
        by_kind[kind].append(name)
    return answer, OwnInterfaces(home, ros, by_kind)


# ----------------------------------------------------------------------------- endpoints

@st.composite
def qos_policies(draw) -> dict:
    """The long form of a topic's qos: some policies over a preset, a depth where the history keeps one."""
    preset = draw(st.sampled_from((None, *qos_rules.PRESETS)))
    if preset == "system_default":
        return {"preset": preset}  # the middleware's defaults, whole
    qos = {key: draw(st.sampled_from(allowed)) for key, allowed in qos_rules.POLICIES.items() if draw(st.booleans())}
    if preset:
        qos["preset"] = preset
    history = qos.get("history", qos_rules.PRESETS[preset or "default"].history)
    if history == "keep_last" and draw(st.booleans()):
        qos["depth"] = draw(st.integers(*qos_rules.DEPTH_RANGE))
    return qos


@st.composite
def topics(draw, distro: str, own: OwnInterfaces | None = None) -> dict | str:
    topic = draw(ros_names("topic", distros.generation(distro)))
    item = {"topic": topic, "type": draw(interface_types("msg", distro, own))}
    qos = draw(st.one_of(st.none(), st.integers(1, 10000), st.sampled_from((1, 10000, *qos_rules.PRESETS)),
                         qos_policies()))
    if qos is not None:
        item["qos"] = qos
    if _needs_id(topic) or draw(st.integers(0, 4)) == 0:
        item["id"] = draw(identifiers())
    if "id" not in item and not isinstance(qos, dict) and draw(st.booleans()):  # the short form
        return ":".join(str(item[key]) for key in ("topic", "type", "qos") if key in item)
    return item


@st.composite
def services_or_actions(draw, kind: str, distro: str, own: OwnInterfaces | None = None) -> dict | str:
    name = draw(ros_names("service" if kind == "srv" else "action", distros.generation(distro)))
    item = {"name": name, "type": draw(interface_types(kind, distro, own))}
    if _needs_id(name) or draw(st.integers(0, 4)) == 0:
        item["id"] = draw(identifiers())
    if "id" not in item and draw(st.booleans()):
        return f"{item['name']}:{item['type']}"
    return item


PERIODS = st.one_of(
    st.floats(min_value=1e-9, max_value=86400, allow_nan=False),
    st.integers(1, 86400),
    st.sampled_from((1e-9, 0.001, 0.05, 0.1, 1 / 3, 86400, 86400.0)),
)


@st.composite
def timers(draw) -> dict | float | str:
    period = draw(PERIODS)
    name = draw(identifiers("timer"))
    form = draw(st.sampled_from(("mapping", "short", "period")))
    if form == "mapping":
        return {"name": name, "period": period}
    if form == "short":
        return f"{name}:{period!r}"
    return period  # a timer named `timer`


def _callback_names(node: dict) -> list[set[str]]:
    """What a callback group's members may call each of a node's endpoints with callbacks: its name and id."""
    found = []
    for key in ("subscribers", "service_servers", "service_clients", "action_servers", "action_clients", "timers"):
        for item in node.get(key) or []:
            if key == "timers":
                name = (item.get("name", "timer") if isinstance(item, dict)
                        else item.split(":")[0] if isinstance(item, str) and ":" in item else "timer")
                found.append({name})
                continue
            if isinstance(item, str):
                item = {"name": item.split(":")[0]}
            name = item.get("topic", item.get("name"))
            found.append({name, item.get("id") or names.identifier_from_name(name)})
    return found


@st.composite
def callback_groups(draw, node: dict) -> list[dict]:
    """Groups of the node's endpoints with callbacks, each named by a name that names it alone."""
    endpoints = _callback_names(node)
    alone = [sorted(names_of - set().union(*(other for other in endpoints if other is not names_of)))
             for names_of in endpoints]
    members = [draw(st.sampled_from(choices)) for choices in alone if choices and draw(st.booleans())]
    groups, taken = [], set()
    while members:
        size = draw(st.integers(1, len(members)))
        name = draw(identifiers("callback group").filter(lambda n: n not in taken))
        taken.add(name)
        group = {"name": name, "members": members[:size]}
        if draw(st.booleans()):
            group["type"] = draw(st.sampled_from(model.CALLBACK_GROUP_TYPES))
        groups.append(group)
        members = members[size:]
    return groups


@st.composite
def remappings(draw, ros: int) -> dict:
    """Names the launch file remaps (ROS 1's private names are written without '/' after '~': none here)."""
    name = ros_names().filter(lambda text: ros == 2 or not text.startswith("~"))
    pairs = draw(st.dictionaries(name, name, max_size=3))
    kept = {}  # no two rules for one name (refused), none remapping a name to itself
    for source, target in pairs.items():
        resolved = names.fully_qualified(source, "n")
        if resolved != names.fully_qualified(target, "n") and resolved not in kept:
            kept[resolved] = (source, target)
    return dict(kept.values())


# ----------------------------------------------------------------------------- parameters

def _ints(ros: int) -> st.SearchStrategy[int]:
    low, high = INT_RANGES[ros]
    return st.one_of(st.integers(low, high), st.sampled_from(EXTREME_INTS)).filter(lambda n: low <= n <= high)


DOUBLES = st.one_of(st.floats(allow_nan=False, allow_infinity=False), st.sampled_from(EXTREME_DOUBLES))
STRINGS = st.one_of(st.text(max_size=40), one_line_text(150), st.sampled_from((
    "", "true", "1", "1e+308", "null", "~", "[1, 2]", "{}", "- x", "a: b", "a\x85b", "a\u2028b", "a\nb\tc")))
_TYPE_SPELLINGS = {scalar: [scalar] + [alias for alias, name in TYPE_ALIASES.items() if name == scalar]
                   for scalar in ("bool", "int", "double", "string")}


@st.composite
def parameters(draw, ros: int) -> tuple[dict | str, str, object]:
    """(the answer, its type, its default): a parameter of every type, arrays included."""
    scalar = draw(st.sampled_from(("bool", "int", "double", "string")))
    is_array = draw(st.booleans())
    values = {"bool": st.booleans(), "int": _ints(ros), "double": DOUBLES, "string": STRINGS}[scalar]
    if is_array:
        # Few elements or many, at their longest: the widest doubles, strings of any text.
        elements = {"double": st.one_of(DOUBLES, st.sampled_from(EXTREME_DOUBLES))}.get(scalar, values)
        default = draw(st.lists(elements, min_size=1, max_size=draw(st.sampled_from((3, ARRAY_MAX)))))
    else:
        default = draw(values)
    spelled_type = draw(st.sampled_from(_TYPE_SPELLINGS[scalar]))
    if is_array:
        spelled_type += draw(st.sampled_from(("[]", "_array")))
    item: dict = {"name": draw(parameter_names(ros)), "type": spelled_type, "default": default}
    if draw(st.integers(0, 2)) == 0:
        item["description"] = draw(one_line_text(150))
    if draw(st.integers(0, 3)) == 0:
        item["read_only"] = draw(st.booleans())
    if scalar in ("int", "double") and not is_array and draw(st.booleans()):
        item["range"] = draw(_ranges(scalar, default))
    expected = [_expected(v, scalar) for v in default] if is_array else _expected(default, scalar)
    if set(item) <= {"name", "type", "default"} and draw(st.booleans()):
        # The short form, its default written as YAML (as the config file spells it).
        typed = "" if draw(st.booleans()) and _inferred(default, scalar) else f":{spelled_type}"
        return f"{item['name']}{typed}={yaml_literal(default)}", scalar + "[]" * is_array, expected
    if draw(st.integers(0, 3)) == 0 and _inferred(default, scalar):
        del item["type"]
    return item, scalar + "[]" * is_array, expected


def _expected(value: object, scalar: str) -> object:
    return float(value) if scalar == "double" else value


def _inferred(default: object, scalar: str) -> bool:
    """The type rna.parameters.infer_type gives the default is the one drawn."""
    try:
        return infer_type(default).scalar == scalar
    except ValueError:
        return False


@st.composite
def _ranges(draw, scalar: str, default: int | float):
    """A range around the default; with a step, the default on it (rna.parameters.on_step)."""
    numbers = _ints(2) if scalar == "int" else DOUBLES
    low, high = min(default, draw(numbers)), max(default, draw(numbers))
    form = draw(st.sampled_from(("pair", "triple", "mapping")))
    if form == "pair":
        return [low, high]
    step = 0 if draw(st.booleans()) else draw(st.integers(1, 100) if scalar == "int" else st.floats(1e-3, 100))
    if step and scalar == "int":
        low = default - step * draw(st.integers(0, 10))
        low = low if low >= INT_RANGE[0] else default
    elif step:
        low = default  # a bound is always on the range
    return [low, high, step] if form == "triple" else {"min": low, "max": high, "step": step}


# ----------------------------------------------------------------------------- nodes

ENDPOINT_KEYS = ("publishers", "subscribers", "service_servers", "service_clients", "action_servers",
                 "action_clients", "timers", "parameters")


@st.composite
def nodes(draw, name: str, distro: str, build_type: str, own: OwnInterfaces | None = None) -> tuple[dict, dict]:
    """(a node's answer, {parameter name: (type, default)} of what its config must hold)."""
    ros = distros.generation(distro)
    language = draw(st.sampled_from(distros.languages(build_type)))
    node: dict = {"name": name}
    if len(distros.languages(build_type)) > 1 or draw(st.booleans()):
        node["language"] = draw(st.sampled_from([k for k, v in distros.LANGUAGES.items() if v == language]
                                                + [language.upper()]))
    if ros == 2 and draw(st.booleans()):
        node["lifecycle"] = draw(st.booleans())
    if ros == 2 and language == "cpp" and draw(st.booleans()):
        node["component"] = draw(st.booleans())
    if draw(st.integers(0, 2)) == 0:
        node["diagnostics"] = draw(st.booleans())
    if draw(st.integers(0, 2)) == 0:
        node["description"] = draw(one_line_text(150))
    small = st.integers(0, 2)
    if draw(small):
        node["publishers"] = draw(st.lists(topics(distro, own), max_size=2))
    if draw(small):
        node["subscribers"] = draw(st.lists(topics(distro, own), max_size=2))
    for key, kind in (("service_servers", "srv"), ("service_clients", "srv"), ("action_servers", "action"),
                      ("action_clients", "action")):
        if draw(st.integers(0, 3)) == 0:
            node[key] = draw(st.lists(services_or_actions(kind, distro, own), max_size=2))
    if draw(small):
        node["timers"] = draw(st.lists(timers(), max_size=2))
    executor = draw(st.sampled_from(model.EXECUTORS).filter(
        lambda executor: not distros.executor_error(executor, ros, language, distro)))
    if executor != model.DEFAULT_EXECUTOR or draw(st.integers(0, 4)) == 0:
        node["executor"] = executor
    if executor == "multi_threaded" and draw(st.booleans()):
        node["threads"] = draw(st.integers(1, distros.THREADS_MAX))
    if ros == 2 and draw(st.integers(0, 2)) == 0:
        groups = draw(callback_groups(node))
        if groups:
            node["callback_groups"] = groups
    if draw(st.integers(0, 2)) == 0:
        node["remappings"] = draw(remappings(ros))
    expected = {}
    if draw(small):
        drawn = draw(st.lists(parameters(ros), max_size=4))
        node["parameters"] = [answer for answer, _, _ in drawn]
        for answer, ptype, default in drawn:
            expected[answer["name"] if isinstance(answer, dict) else answer.split(":")[0].split("=")[0]] = (
                ptype, default)
    return node, expected


@st.composite
def valid_answers(draw, max_nodes: int = 3, ros: int | None = None, interfaces: bool = False,
                  distro: str | None = None) -> dict:
    """A complete answer set that rna accepts; `answers["_expected"]` holds each node's parameters.

    `ros` keeps to one ROS generation, `distro` to one distribution; with `interfaces`, the
    package often defines its own messages, services and actions, and its nodes use them.
    Pop `_expected` before handing the answers to Copier.
    """
    if distro is None:
        distro = draw(st.sampled_from([d for d in distros.DISTROS if ros in (None, distros.generation(d))]))
    ros = distros.generation(distro)
    build_type = draw(st.sampled_from(distros.BUILD_TYPES_OF[ros]))
    answers = {
        "package_name": draw(package_names()),
        "description": draw(one_line_text(200)),
        "maintainer": draw(one_line_text(60)),
        "maintainer_email": draw(emails()),
        "license": draw(st.sampled_from(sorted(LICENSES))),
        "copyright_holder": draw(one_line_text(60).filter(lambda text: not text.strip().endswith(("\\", "??/")))),
        "copyright_year": draw(st.integers(1970, 9999)),
        "ros_distro": distro,
        "build_type": build_type,
    }
    if ros == 2 and draw(st.integers(0, 3)):  # else the default, XML
        answers["launch_format"] = draw(st.sampled_from(layout.LAUNCH_FORMATS[2]))
    own = None
    if interfaces and draw(st.booleans()):
        location = "separate"
        if build_type in distros.BUILDS_INTERFACES and draw(st.booleans()):
            answers["interfaces_location"] = location = "package"
        home = answers["package_name"] + ("_interfaces" if location == "separate" else "")
        answers["interfaces"], own = draw(own_interfaces(ros, home))
    node_list, expected = [], {}
    for name in draw(st.lists(node_names(), min_size=1, max_size=max_nodes, unique=True)):
        node, parameters_of_node = draw(nodes(name, distro, build_type, own))
        node_list.append(node)
        expected[name] = parameters_of_node
    answers["nodes"] = node_list if draw(st.integers(0, 3)) else yaml_text(node_list)
    try:
        build_package(answers)
    except AnswerError as error:
        if any(rule in error.message for rule in CROSS_ANSWER_RULES):
            assume(False)
        raise AssertionError(f"a drawn valid answer set was refused: {error}\n{answers}") from None
    return {**answers, "_expected": expected}


# ----------------------------------------------------------------------------- invalid sets

def _first_node(answers: dict) -> dict:
    nodes_answer = answers["nodes"]
    if isinstance(nodes_answer, str):
        answers["nodes"] = nodes_answer = yaml.safe_load(nodes_answer)
    return nodes_answer[0]


def _with_char(text: str, char: str, draw) -> str:
    """`char` inside `text` (leading and trailing white space is stripped from answers)."""
    text = text.strip()
    if len(text) < 2:
        return f"a{char}b"
    at = draw(st.integers(1, len(text) - 1))
    return text[:at] + char + text[at:]


def _break_package_name(draw, answers):
    name = answers["package_name"]
    stdlib = sorted(n for n in sys.stdlib_module_names if names.package_name_error(n) is None
                    and not names.too_long(n, names.PACKAGE_NAME_MAX) and n != "test")
    keywords = sorted(k for k in (*keyword.kwlist, *names.CPP_KEYWORDS) if names.PACKAGE_NAME.fullmatch(k)
                      and len(k) > 1)
    used = sorted(d.name for d in build_package(answers).dependencies)
    way = draw(st.sampled_from(("char", "shape", "long", "keyword", "stdlib", "used")))
    if way == "char":
        return _with_char(name, draw(st.sampled_from(("A", "-", " ", ".", "é"))), draw)
    if way == "shape":
        return draw(st.sampled_from((f"_{name}", f"{name}_", f"1{name}", name[:1], "test", "",
                                     name.replace("_", "__") if "_" in name else "a__b")))
    if way == "long":
        return draw(snake_case(names.PACKAGE_NAME_MAX + 20, min_size=names.PACKAGE_NAME_MAX + 1).filter(
            lambda n: len(n) > names.PACKAGE_NAME_MAX))
    return draw(st.sampled_from({"keyword": keywords, "stdlib": stdlib, "used": used}[way]))


def _broken_text(draw, text: str) -> object:
    if draw(st.booleans()):
        return draw(st.sampled_from(("", " ", "\u3000", None, ["a list"], {"a": "mapping"})))
    return _with_char(text, draw(st.sampled_from(NOT_ONE_LINE)), draw)


# What breaks one answer: question -> a function of (draw, a valid answer set) that returns
# the broken value of that answer (or, for nodes, changes the first node in place).
def _break_nodes(draw, answers):
    node = _first_node(answers)
    ros = distros.generation(answers["ros_distro"])
    kind = draw(st.sampled_from((
        "empty", "not_a_list", "yaml", "name", "duplicate", "unknown_key", "language", "description", "topic",
        "type", "qos", "timer", "parameter", "flags", "endpoint_twice")))
    if kind == "empty":
        return []
    if kind == "not_a_list":
        return {"name": node["name"]}
    if kind == "yaml":
        return "- name: [unclosed"
    if kind == "name":
        node["name"] = draw(st.sampled_from(("Driver", "driver node", "2fast", "_x", "x__y", "x_", "driver_base",
                                             "class", "namespace", "", "n" * (names.NODE_NAME_MAX + 1),
                                             node["name"] + "-1", node["name"] + "/x", "A" + node["name"])))
    elif kind == "duplicate":
        answers["nodes"].append({**node})
    elif kind == "unknown_key":
        node[draw(st.sampled_from(("publisher", "subscriber", "timer", "param", "parameter", "type", "lang")))] = []
    elif kind == "language":
        if answers["build_type"] == "ament_python" and draw(st.booleans()):
            node["language"] = "cpp"
        else:
            node["language"] = draw(st.sampled_from(("rust", "c", "java", "python3")))
    elif kind == "description":
        node["description"] = draw(st.one_of(st.just(["a", "list"]),
                                             st.sampled_from(NOT_ONE_LINE).map(lambda c: f"one{c}two")))
    elif kind == "topic":
        bad = draw(st.sampled_from(("cmd vel", "a//b", "a/", "/", "~", "~x", "{ns}/x", "{foo}/x", "a{node", "1abc",
                                    "a/2b", "a-b", "/" + "a" * names.ROS_NAME_MAX, "é", "/_1/x", "~/_")
                                   + (("{node}/x",) if answers.get("ros_distro") == "noetic" else ())))
        node["publishers"] = [{"topic": bad, "type": "std_msgs/msg/String"}]
    elif kind == "type":
        distro = answers["ros_distro"]
        real = _catalogue_types(distro, "msg")
        misspelt = draw(st.sampled_from(real).map(lambda t: t[:-1]).filter(
            lambda t: catalogue.unknown_type_error(t.split("/")[0], "msg", t.split("/")[-1], distro)))
        node["subscribers"] = [{"topic": "x", "type": draw(st.sampled_from((
            "std_srvs/srv/Trigger", "test_msgs/action/Fibonacci", "std_msgs/msg/string", "Std/msg/String",
            "std_msgs", "a/b/c/D", "std_msgs/foo/String", "my_msgs/msg/None", "my_msgs/msg/NULL",
            "my_msgs/msg/" + "A" * (names.TYPE_NAME_MAX + 1), misspelt)))}]
    elif kind == "qos":
        node["publishers"] = [{"topic": "x", "type": "std_msgs/msg/String",
                               "qos": draw(st.sampled_from((0, -1, 10001, "fast", True, 2.5,
                                                            {"reliability": "sometimes"},
                                                            {"history": "keep_all", "depth": 5}, {"colour": 1})))}]
    elif kind == "timer":
        node["timers"] = [{"name": "tick", "period": draw(st.one_of(
            st.sampled_from((0, -1, "fast", None, 86400.5, 1e9, "nan", "inf", 1e-10, 5e-324)),
            st.floats(max_value=0, allow_nan=False, allow_infinity=False)))}]
    elif kind == "parameter":
        node["parameters"] = [draw(_broken_parameter(ros))]
    elif kind == "flags":
        if ros == 1:
            node[draw(st.sampled_from(("lifecycle", "component")))] = True
        else:
            flag, value = draw(st.sampled_from((("lifecycle", "yes"), ("component", 1), ("component", True),
                                                ("diagnostics", "on"))))
            node[flag] = value
            if flag == "component" and value is True:
                node["language"] = "python"
    elif kind == "endpoint_twice":
        node["publishers"] = ["chatter:std_msgs/msg/String", "chatter:std_msgs/msg/Int32"]
    return answers["nodes"]


def _broken_parameter(ros: int) -> st.SearchStrategy:
    low, high = INT_RANGE
    return st.sampled_from([
        {"name": "Rate", "default": 1.0}, {"name": "lambda", "default": 1}, {"name": "", "default": 1},
        {"name": "r", "type": "complex", "default": 1}, {"name": "r", "type": "int", "default": 1.5},
        {"name": "r", "type": "bool", "default": "yes"}, {"name": "r", "type": "double", "default": "fast"},
        {"name": "r", "default": high + 1}, {"name": "r", "type": "int[]", "default": [1, low - 1]},
        {"name": "r", "default": math.inf}, {"name": "r", "type": "double", "default": math.nan},
        {"name": "r", "type": "double[]", "default": []}, {"name": "r", "default": [1, "a"]},
        {"name": "r", "default": {"a": 1}}, {"name": "r", "default": 5, "range": [0, 1]},
        {"name": "r", "default": 0, "range": [2, 1]}, {"name": "r", "default": 1.0, "range": [0.0, 2.0, -1.0]},
        {"name": "r", "type": "string", "default": "a", "range": [0, 1]},
        {"name": "r", "default": 1.0, "range": [0.0, math.inf]}, {"name": "r", "default": 1, "read_only": "no"},
        {"name": "r", "default": 1, "description": "two\nlines"}, "rate", "rate:double=[1", 7,
        *([{"name": "use_sim_time", "default": True}, {"name": "r", "default": 5, "range": [0, 10, 3]},
           {"name": "r", "default": 0.25, "range": [0.0, 1.0, 0.1]}] if ros == 2 else
          [{"name": "r", "default": INT_RANGES[1][1] + 1}, {"name": "r", "type": "int[]", "default": [-2**31 - 1]}]),
    ])


def _break_interfaces(draw, answers):
    return draw(st.sampled_from((
        {"messages": [{"name": "None", "fields": ["int32 x"]}]},
        {"messages": [{"name": "target", "fields": ["int32 x"]}]},
        {"messages": [{"name": "Target", "fields": ["int32 Bad-Name"]}]},
        {"messages": [{"name": "Target", "fields": ["float128 x"]}]},
        {"messages": [{"name": "A", "fields": ["int32 x"]}, {"name": "A", "fields": ["int32 y"]}]},
        [1], "messages: [unclosed",
    )))


BREAKERS = {
    "package_name": _break_package_name,
    "description": lambda draw, answers: _broken_text(draw, answers["description"]),
    "maintainer": lambda draw, answers: _broken_text(draw, answers["maintainer"]),
    "copyright_holder": lambda draw, answers: (answers["copyright_holder"] + "\\" if draw(st.booleans())
                                               else _broken_text(draw, answers["copyright_holder"])),
    "maintainer_email": lambda draw, answers: draw(st.one_of(
        st.sampled_from(("ada", "ada@localhost", "a b@c.de", "@example.com", "ada@example.c", "ada@@x.org", "",
                         None)),
        st.text(max_size=20).filter(lambda text: names.email_error(text) is not None))),
    "license": lambda draw, answers: draw(st.one_of(
        st.sampled_from(("WTFPL", "apache-2.0", "MIT ", "GPL-3.0", "", None)),
        st.text(max_size=12).filter(lambda text: text not in LICENSES))),
    "ros_distro": lambda draw, answers: draw(st.sampled_from(("foxy", "Jazzy", "ros2", "melodic", "", None))),
    "build_type": lambda draw, answers: draw(st.sampled_from(
        ("ament_cmake", "ament_python") if answers["ros_distro"] == "noetic" else ("catkin", "cmake", ""))),
    "launch_format": lambda draw, answers: draw(st.sampled_from(
        ("python", "yaml") if answers["ros_distro"] == "noetic" else ("json", "XML", "py", "launch.py", ""))),
    "copyright_year": lambda draw, answers: draw(st.sampled_from(("soon", 1969, 10000, 2026.5, "", None, [2026]))),
    "interfaces": _break_interfaces,
    "interfaces_location": lambda draw, answers: "elsewhere" if answers["build_type"] != "ament_python" or draw(
        st.booleans()) else "package",
    "nodes": _break_nodes,
}


@st.composite
def invalid_answers(draw) -> tuple[dict, str]:
    """(an answer set that breaks exactly one rule, the question its error must name)."""
    answers = draw(valid_answers(max_nodes=2))
    answers.pop("_expected")
    # `nodes` has most rules; Hypothesis favours the first choices, so it comes first, and often.
    question = draw(st.sampled_from(("nodes", "nodes", *sorted(BREAKERS), "nodes")))
    answers[question] = BREAKERS[question](draw, answers)
    return answers, question


# ----------------------------------------------------------------------------- data files

def yaml_text(value: object) -> str:
    """YAML that reads back as `value`: escaped where PyYAML would write a character raw that
    it reads back as another (NEL, a line break inside a quoted scalar, folds to a space)."""
    text = yaml.safe_dump(value, allow_unicode=True, sort_keys=False)
    return text if yaml.safe_load(text) == value else yaml.safe_dump(value, allow_unicode=False, sort_keys=False)


def write_data_file(answers: dict, path: Path) -> Path:
    """The answers as a YAML file for `copier copy --data-file` (which reads it with yaml.safe_load)."""
    path.write_text(yaml_text(answers), encoding="utf-8")
    return path


def read_data_file(path: Path) -> dict:
    """The answers as `copier copy --data-file` reads them."""
    with path.open("rb") as file:
        return yaml.safe_load(file)
