"""A separate ROS 2 process that asks a running node something, for the ros tier.

Run with the ROS venv's Python (the test process itself has no rclpy):
  ros2_probe.py params NODE NAME...            print {name: value} as JSON
  ros2_probe.py lifecycle NODE TRANSITION...   drive a lifecycle node, print each new state
Exits non-zero when the node does not answer.
"""

from __future__ import annotations

import json
import sys

import rclpy
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState
from rcl_interfaces.msg import ParameterType
from rcl_interfaces.srv import GetParameters

TIMEOUT = 15.0

_VALUE_FIELDS = {
    ParameterType.PARAMETER_BOOL: "bool_value",
    ParameterType.PARAMETER_INTEGER: "integer_value",
    ParameterType.PARAMETER_DOUBLE: "double_value",
    ParameterType.PARAMETER_STRING: "string_value",
    ParameterType.PARAMETER_BOOL_ARRAY: "bool_array_value",
    ParameterType.PARAMETER_INTEGER_ARRAY: "integer_array_value",
    ParameterType.PARAMETER_DOUBLE_ARRAY: "double_array_value",
    ParameterType.PARAMETER_STRING_ARRAY: "string_array_value",
}


def call(node, service_type, name, request):
    client = node.create_client(service_type, name)
    if not client.wait_for_service(timeout_sec=TIMEOUT):
        sys.exit(f"{name} is not available")
    future = client.call_async(request)
    rclpy.spin_until_future_complete(node, future, timeout_sec=TIMEOUT)
    if not future.done():
        sys.exit(f"{name} did not answer")
    return future.result()


def params(node, target, names):
    response = call(node, GetParameters, f"/{target}/get_parameters", GetParameters.Request(names=names))
    values = {}
    for name, value in zip(names, response.values, strict=True):
        field = _VALUE_FIELDS.get(value.type)
        values[name] = list(getattr(value, field)) if field and "array" in field else (
            getattr(value, field) if field else None)
    print(json.dumps(values))


def lifecycle(node, target, transitions):
    for label in transitions:
        transition = Transition(id=getattr(Transition, f"TRANSITION_{label.upper()}"))
        response = call(node, ChangeState, f"/{target}/change_state", ChangeState.Request(transition=transition))
        if not response.success:
            sys.exit(f"{target} refused to {label}")
        print(f"{target}: {label} done", flush=True)


def main():
    command, target, *rest = sys.argv[1:]
    rclpy.init()
    node = rclpy.create_node("rna_test_probe")
    try:
        {"params": params, "lifecycle": lifecycle}[command](node, target, rest)
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
