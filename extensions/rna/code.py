"""How the generated code spells things, so that each template holds no such logic.

Import and include blocks ordered the way the ROS linters want them (Python:
flake8-import-order's google style as ament_flake8 configures it, standard library
first, then the rest sorted by module with a blank line between top-level packages,
as in ros2/examples; C++: cpplint's order, standard headers then the rest), the
ParameterDescriptor of a parameter, the sample values starter code publishes, the
CMake targets a node links, and a few wording helpers.
"""

from __future__ import annotations

import json
import textwrap
import sys
from collections import defaultdict
from collections.abc import Iterable

from .parameters import python_literal


def _sort_key(module: str) -> tuple[str, str]:
    return (module.lower(), module)


def python_imports(imports: Iterable[tuple[str, str | None]]) -> str:
    """`(module, name)` pairs, name None for `import module` -> the import block.

    A name may be 'Name as Alias'.
    """
    plain: set[str] = set()
    from_imports: dict[str, set[str]] = defaultdict(set)
    for module, name in imports:
        if name is None:
            plain.add(module)
        else:
            from_imports[module].add(name)
    statements = [(module, f"import {module}") for module in plain]
    statements += [
        (module, f"from {module} import {', '.join(sorted(names, key=_sort_key))}")
        for module, names in from_imports.items()
    ]
    statements.sort(key=lambda item: (_sort_key(item[0]), item[1].startswith("from")))

    stdlib = [line for module, line in statements if _top(module) in sys.stdlib_module_names]
    groups: dict[str, list[str]] = defaultdict(list)
    for module, line in statements:
        if _top(module) not in sys.stdlib_module_names:
            groups[_top(module)].append(line)
    blocks = ["\n".join(stdlib)] if stdlib else []
    blocks += ["\n".join(lines) for lines in groups.values()]
    return "\n\n".join(blocks)


def _top(module: str) -> str:
    return module.split(".")[0]


def cpp_includes(headers: Iterable[str]) -> str:
    """Headers ('<chrono>' or 'rclcpp/rclcpp.hpp') -> the #include block.

    Standard headers first, then the others in quotes, as in the ROS tutorials of
    both generations (cpplint counts <ros/ros.h> as a C system header).
    """
    standard = sorted({h for h in headers if h.startswith("<")})
    others = sorted({h for h in headers if not h.startswith("<")})
    blocks = []
    if standard:
        blocks.append("\n".join(f"#include {h}" for h in standard))
    if others:
        blocks.append("\n".join(f'#include "{h}"' for h in others))
    return "\n\n".join(blocks)


# --------------------------------------------------------------------------- Python nodes


def _interface_imports(node, types) -> list[tuple[str, str]]:
    imports = []
    for interface in types:
        alias = node.python_types[interface]
        name = interface.name if alias == interface.name else f"{interface.name} as {alias}"
        imports.append((interface.python_module, name))
    return imports


def python_base_imports(node) -> str:
    """Imports of the generated <node>_base.py."""
    imports = _interface_imports(node, node.interfaces)
    imports.append(("rclpy.lifecycle", "Node") if node.lifecycle else ("rclpy.node", "Node"))
    if node.lifecycle:
        imports += [("rclpy.lifecycle", "State"), ("rclpy.lifecycle", "TransitionCallbackReturn")]
    for parameter in node.parameters:
        if parameter.has_descriptor:
            imports.append(("rcl_interfaces.msg", "ParameterDescriptor"))
        if parameter.range:
            range_class = "IntegerRange" if parameter.range_kind == "integer_range" else "FloatingPointRange"
            imports.append(("rcl_interfaces.msg", range_class))
    if any(topic.qos.profile for topic in node.publishers + node.subscribers):
        imports.append(("rclpy.qos", "qos_profile_sensor_data"))
    if node.action_servers:
        imports += [("rclpy.action", "ActionServer"), ("rclpy.action", "CancelResponse"),
                    ("rclpy.action", "GoalResponse"),
                    ("rclpy.callback_groups", "ReentrantCallbackGroup")]
    if node.action_clients:
        imports.append(("rclpy.action", "ActionClient"))
    return python_imports(imports)


def python_node_imports(node) -> str:
    """Imports of the user's <node>.py: what its starter code uses."""
    imports = [("rclpy", None), ("rclpy.executors", "ExternalShutdownException"),
               (f"{node.package}.{node.base_name}", node.base_class_name)]
    used = []
    if node.driver_timer:
        used += [topic.type for topic in node.publishers]
        used += [service.type for service in node.service_clients]
        used += [action.type for action in node.action_clients]
    used += [action.type for action in node.action_servers]
    imports += _interface_imports(node, sorted(set(used), key=lambda t: t.full_name))
    if node.action_servers:
        imports += [("time", None), ("rclpy.executors", "MultiThreadedExecutor")]
    if node.action_clients:
        imports.append(("action_msgs.msg", "GoalStatus"))
    return python_imports(imports)


def python_descriptor(parameter, indent: int = 12) -> str:
    """The ParameterDescriptor argument of declare_parameter(), one field per line."""
    fields = []
    if parameter.description:
        fields.append(f"description={python_literal(parameter.description)}")
    if parameter.read_only:
        fields.append("read_only=True")
    if parameter.range:
        low, high, step = (python_literal(value) for value in parameter.range)
        range_class = "IntegerRange" if parameter.range_kind == "integer_range" else "FloatingPointRange"
        fields.append(f"{parameter.range_kind}=[\n{' ' * (indent + 8)}"
                      f"{range_class}(from_value={low}, to_value={high}, step={step})]")
    pad = " " * (indent + 4)
    return "ParameterDescriptor(\n" + ",\n".join(pad + field for field in fields) + ")"


_PYTHON_SAMPLES = {
    "string": "f'Hello World: {{{count}}}'",
    "int": "{count}",
    "float": "float({count})",
    "bool": "{count} % 2 == 0",
}


def python_sample(data_field: str, count: str) -> str:
    """An expression giving a std_msgs `data` field a value that changes with `count`."""
    return _PYTHON_SAMPLES[data_field].format(count=count)


def python_format(data_field: str, expression: str) -> str:
    """The f-string part that prints a `data` field: quoted for text."""
    return f'"{{{expression}}}"' if data_field == "string" else f"{{{expression}}}"


# --------------------------------------------------------------------------- C++ nodes


def cpp_base_includes(node) -> str:
    """Includes of the generated include/<package>/<node>_base.hpp."""
    headers = ["rclcpp/rclcpp.hpp", *(t.cpp_header for t in node.interfaces)]
    if node.timers:
        headers.append("<chrono>")
    if node.service_servers or node.service_clients or node.actions:
        headers.append("<memory>")
    if node.actions:
        headers.append("rclcpp_action/rclcpp_action.hpp")
    if node.action_clients:
        headers.append("<atomic>")
    if node.lifecycle:
        headers += ["rclcpp_lifecycle/lifecycle_node.hpp", "rclcpp_lifecycle/lifecycle_publisher.hpp"]
    if any(p.has_descriptor for p in node.parameters):
        headers.append("rcl_interfaces/msg/parameter_descriptor.hpp")
    return cpp_includes(headers + _parameter_headers(node))


def _parameter_headers(node) -> list[str]:
    """The standard headers a base class's parameter members need, in both ROS generations."""
    headers = []
    if any(p.type.scalar == "string" for p in node.parameters):
        headers.append("<string>")
    if any(p.type.is_array for p in node.parameters):
        headers.append("<vector>")
    return headers


def _starter_headers(node) -> list[str]:
    """What the starter code of a user's C++ node uses, in both ROS generations."""
    headers = [a.type.cpp_header for a in node.action_servers]
    if node.driver_timer:
        headers += [t.type.cpp_header for t in node.publishers]
        headers += [s.type.cpp_header for s in node.service_clients]
        headers += [a.type.cpp_header for a in node.action_clients]
        if node.publishers:
            headers.append("<cstddef>")
        if any(t.type.data_field in ("string", "int", "float") for t in node.publishers):
            headers.append("<string>")  # std::to_string
    if any(t.type.data_field in ("int", "float") for t in node.subscribers):
        headers.append("<string>")
    return headers


def cpp_node_includes(node) -> str:
    """Includes of the user's src/<node>.cpp: what its starter code uses."""
    headers = [f"{node.package}/{node.base_name}.hpp", "rclcpp/rclcpp.hpp", "<memory>", *_starter_headers(node)]
    if node.component:
        headers.append("rclcpp_components/register_node_macro.hpp")
    return cpp_includes(headers)


def cpp_parameter_descriptor(parameter, name: str = "descriptor") -> str:
    """Statements that fill a ParameterDescriptor named `name` (4-space indented)."""
    lines = [f"rcl_interfaces::msg::ParameterDescriptor {name};"]
    if parameter.description:
        lines.append(f"{name}.description = {json.dumps(parameter.description, ensure_ascii=False)};")
    if parameter.read_only:
        lines.append(f"{name}.read_only = true;")
    if parameter.range:
        low, high, step = parameter.range
        kind = parameter.range_kind
        lines += [f"{name}.{kind}.resize(1);",
                  f"{name}.{kind}[0].from_value = {low!r};",
                  f"{name}.{kind}[0].to_value = {high!r};",
                  f"{name}.{kind}[0].step = {step!r};"]
    return "\n    ".join(lines)


_CPP_SAMPLES = {
    "string": '"Hello World: " + std::to_string({count})',
    "int": "static_cast<decltype({msg}.data)>({count})",
    "float": "static_cast<decltype({msg}.data)>({count})",
    "bool": "{count} % 2 == 0",
}


def cpp_sample(data_field: str, count: str, msg: str = "msg") -> str:
    """A C++ expression giving a std_msgs `data` field a value that changes with `count`."""
    return _CPP_SAMPLES[data_field].format(count=count, msg=msg)


def cpp_format(data_field: str) -> str:
    """The printf conversion that prints a `data` field (quoted for text)."""
    return '\\"%s\\"' if data_field == "string" else "%s"


def cpp_format_arg(data_field: str, expression: str) -> str:
    """The printf argument for cpp_format()."""
    if data_field == "string":
        return f"{expression}.c_str()"
    if data_field == "bool":
        return f'{expression} ? "true" : "false"'
    return f"std::to_string({expression}).c_str()"


_CMAKE_TARGETS = {
    "rclcpp": "rclcpp::rclcpp",
    "rclcpp_action": "rclcpp_action::rclcpp_action",
    "rclcpp_components": "rclcpp_components::component",
    "rclcpp_lifecycle": "rclcpp_lifecycle::rclcpp_lifecycle",
}


def cmake_targets(node) -> list[str]:
    """What a C++ node's target links: the client library targets, ${<pkg>_TARGETS} otherwise."""
    return [
        # The package's own interfaces: rosidl_get_typesupport_target() names them.
        '"${cpp_typesupport_target}"' if dep == node.package else _CMAKE_TARGETS.get(dep, f"${{{dep}_TARGETS}}")
        for dep in node.dependencies
    ]


# --------------------------------------------------------------------------- ROS 1 nodes


def _ros1_parts(node, parts: Iterable[tuple[object, str]]) -> list[tuple[str, str]]:
    """(type, part) -> imports of e.g. TriggerResponse or FibonacciGoal, aliased like the type."""
    imports = []
    for interface, part in parts:
        alias = node.python_types[interface] + part
        name = interface.name + part
        imports.append((interface.python_module, name if alias == name else f"{name} as {alias}"))
    return imports


def ros1_python_base_imports(node) -> str:
    """Imports of the generated src/<package>/<node>_base.py (rospy)."""
    parts = [(t.type, "") for t in node.publishers + node.subscribers]
    parts += [(s.type, "") for s in node.service_servers + node.service_clients]
    parts += [(s.type, "Response") for s in node.service_servers]
    parts += [(a.type, "Action") for a in node.actions]
    imports = [("rospy", None), *_ros1_parts(node, parts)]
    if node.actions:
        imports.append(("actionlib", None))
    return python_imports(imports)


def ros1_python_node_imports(node) -> str:
    """Imports of the user's scripts/<node>.py: what its starter code uses."""
    parts = []
    if node.driver_timer:
        parts += [(t.type, "") for t in node.publishers]
        parts += [(s.type, "Request") for s in node.service_clients]
        parts += [(a.type, "Goal") for a in node.action_clients]
    parts += [(s.type, "Response") for s in node.service_servers]
    parts += [(a.type, part) for a in node.action_servers for part in ("Feedback", "Result")]
    imports = [("rospy", None), (f"{node.package}.{node.base_name}", node.base_class_name),
               *_ros1_parts(node, parts)]
    if node.action_clients:
        imports.append(("actionlib_msgs.msg", "GoalStatus"))
    return python_imports(imports)


def ros1_cpp_base_includes(node) -> str:
    """Includes of the generated include/<package>/<node>_base.h (roscpp)."""
    headers = ["ros/ros.h", *(t.cpp_header for t in node.interfaces)]
    if node.action_servers:
        headers.append("actionlib/server/simple_action_server.h")
    if node.action_clients:
        headers.append("actionlib/client/simple_action_client.h")
    return cpp_includes(headers + _parameter_headers(node))


def ros1_cpp_node_includes(node) -> str:
    """Includes of the user's src/<node>.cpp (roscpp)."""
    return cpp_includes([f"{node.package}/{node.base_name}.h", "ros/ros.h", *_starter_headers(node)])


def python_text(text: str, column: int, indent: int, width: int = 99) -> str:
    """A string literal starting at `column` that fits in `width` columns.

    Too long, it becomes parenthesised parts, one per line, indented by `indent`.
    """
    literal = python_literal(text)
    if column + len(literal) + 1 <= width:
        return literal
    chunks = textwrap.wrap(text, width - indent - 4, drop_whitespace=False)
    return "(\n" + "\n".join(" " * indent + python_literal(chunk) for chunk in chunks) + ")"


def with_article(word: str) -> str:
    """'approach' -> 'an approach', 'reset' -> 'a reset' (for log messages and docs)."""
    return ("an " if word.lstrip("/~")[:1].lower() in "aeiou" else "a ") + word
