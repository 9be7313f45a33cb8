"""A separate ROS 2 process that asks a running node something, for the ros tier.

Run with the ROS venv's Python (the test process itself has no rclpy):
  ros2_probe.py params NODE NAME...            print {name: value} as JSON
  ros2_probe.py lifecycle NODE TRANSITION...   drive a lifecycle node, print each new state
  ros2_probe.py busy_goal ACTION SERVICE TOPIC
      during a test_msgs/Fibonacci goal to ACTION, time the std_msgs/Int32 messages on
      TOPIC and a std_srvs/Trigger call to SERVICE; then cancel a second goal mid-way;
      print what was measured as JSON
  ros2_probe.py busy_service SERVICE TOPIC
      time the std_msgs/Int32 messages on TOPIC while a std_srvs/Trigger call to SERVICE
      is answered (a slow one); print what was measured as JSON
  ros2_probe.py clocked TOPIC TYPE
      count the messages of TYPE (pkg/msg/Name) on TOPIC for a second with no /clock, then
      for a second of /clock published from here; print both counts as JSON
  ros2_probe.py relay TOPIC TYPE OUT_TOPIC OUT_TYPE
      publish messages of TYPE on TOPIC (reliable, keeping the last 10), count those of
      OUT_TYPE on OUT_TOPIC; print the counts as JSON
  ros2_probe.py transitions NODE               print "watching" once it hears NODE's transition
                                               events, then each one until NODE is finalized
  ros2_probe.py decoy NODE...                  hold nodes of these names, each publishing on
                                               /decoy, print "decoys up", run until killed
  ros2_probe.py sees NODE                      print "seen" once another process's NODE is in
                                               the graph
  ros2_probe.py hears TOPIC PKG/msg/TYPE       print "heard" once a message arrives on TOPIC
  ros2_probe.py goal_result ACTION             send a test_msgs/Fibonacci goal, print "executing"
                                               at its first feedback, then its result as JSON
  ros2_probe.py gating NODE SERVICE ACTION     drive a lifecycle node: while inactive, is the
                                               std_srvs/Trigger SERVICE offered, a Fibonacci goal
                                               accepted; once active, the same; then a goal
                                               running as the node is deactivated; print JSON
Exits non-zero when the node does not answer.
"""

from __future__ import annotations

import importlib
import json
import sys
import time

from action_msgs.msg import GoalStatus
import rclpy
from rclpy.action import ActionClient
from rclpy.executors import SingleThreadedExecutor
from lifecycle_msgs.msg import State, Transition, TransitionEvent
from lifecycle_msgs.srv import ChangeState
from rcl_interfaces.msg import ParameterType
from rcl_interfaces.srv import GetParameters
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Int32
from std_srvs.srv import Trigger
from test_msgs.action import Fibonacci

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


def busy_goal(node, action, names):
    service, topic = names
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    arrivals = []
    node.create_subscription(Int32, topic, lambda _: arrivals.append(time.monotonic()), 10)
    client = ActionClient(node, Fibonacci, action)
    trigger = node.create_client(Trigger, service)
    if not (client.wait_for_server(timeout_sec=TIMEOUT) and trigger.wait_for_service(timeout_sec=TIMEOUT)):
        sys.exit(f"{action} or {service} is not available")

    def until(future, within=TIMEOUT):
        deadline = time.monotonic() + within
        while not future.done() and time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.01)
        if not future.done():
            sys.exit(f"no answer within {within} s")
        return future.result()

    def pause(seconds):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.01)

    # A goal run to its end, with a service call in the middle.
    goal = until(client.send_goal_async(Fibonacci.Goal(order=5)))
    start = time.monotonic()
    pause(0.3)
    called = time.monotonic()
    until(trigger.call_async(Trigger.Request()))
    service_seconds = time.monotonic() - called
    status = until(goal.get_result_async()).status
    end = time.monotonic()
    during = [start, *(t for t in arrivals if start <= t <= end), end]
    gaps = [later - earlier for earlier, later in zip(during, during[1:], strict=False)]

    # A goal canceled in the middle.
    second = until(client.send_goal_async(Fibonacci.Goal(order=5)))
    pause(0.3)
    canceling = until(second.cancel_goal_async()).goals_canceling
    canceled = until(second.get_result_async()).status
    print(json.dumps({
        "accepted": goal.accepted and second.accepted,
        "goal_seconds": end - start,
        "succeeded": status == GoalStatus.STATUS_SUCCEEDED,
        "messages": len(during) - 2,
        "largest_gap": max(gaps),
        "service_seconds": service_seconds,
        "cancel_accepted": len(canceling) == 1,
        "canceled": canceled == GoalStatus.STATUS_CANCELED,
    }))


def busy_service(node, service, names):
    (topic,) = names
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    arrivals = []
    node.create_subscription(Int32, topic, lambda _: arrivals.append(time.monotonic()), 10)
    trigger = node.create_client(Trigger, service)
    if not trigger.wait_for_service(timeout_sec=TIMEOUT):
        sys.exit(f"{service} is not available")
    deadline = time.monotonic() + TIMEOUT
    while len(arrivals) < 5:  # the timer is running, as seen from here
        if time.monotonic() > deadline:
            sys.exit(f"nothing on {topic}")
        executor.spin_once(timeout_sec=0.01)
    future = trigger.call_async(Trigger.Request())
    start = time.monotonic()
    while not future.done() and time.monotonic() < start + TIMEOUT:
        executor.spin_once(timeout_sec=0.01)
    if not future.done():
        sys.exit(f"{service} did not answer")
    end = time.monotonic()
    during = [start, *(t for t in arrivals if start <= t <= end), end]
    gaps = [later - earlier for earlier, later in zip(during, during[1:], strict=False)]
    print(json.dumps({"service_seconds": end - start, "messages": len(during) - 2, "largest_gap": max(gaps)}))


def message_type(name):
    package, kind, type_name = name.split("/")
    return getattr(importlib.import_module(f"{package}.{kind}"), type_name)


def wait_for_publisher(node, topic):
    deadline = time.monotonic() + TIMEOUT
    while node.count_publishers(topic) == 0:
        if time.monotonic() > deadline:
            sys.exit(f"nothing publishes {topic}")
        rclpy.spin_once(node, timeout_sec=0.1)


def clocked(node, topic, names):
    (type_name,) = names
    heard = []
    node.create_subscription(message_type(type_name), topic, lambda _: heard.append(1), 10)
    clock = node.create_publisher(Clock, "/clock", 10)
    wait_for_publisher(node, topic)
    end = time.monotonic() + 1.0
    while time.monotonic() < end:  # simulated time stands still at 0: no timer of the node's fires
        rclpy.spin_once(node, timeout_sec=0.01)
    before = len(heard)
    now = 0
    end = time.monotonic() + 1.0
    while time.monotonic() < end:  # a second of simulated time, 10 ms a step
        now += 10_000_000
        message = Clock()
        message.clock.sec, message.clock.nanosec = divmod(now, 1_000_000_000)
        clock.publish(message)
        rclpy.spin_once(node, timeout_sec=0.01)
    print(json.dumps({"before_clock": before, "with_clock": len(heard) - before}))


def relay(node, topic, names):
    type_name, out_topic, out_type = names
    heard = []
    node.create_subscription(message_type(out_type), out_topic, lambda _: heard.append(1), 10)
    publisher = node.create_publisher(message_type(type_name), topic, 10)
    deadline = time.monotonic() + TIMEOUT
    while publisher.get_subscription_count() == 0:
        if time.monotonic() > deadline:
            sys.exit(f"nothing subscribes to {topic}")
        rclpy.spin_once(node, timeout_sec=0.1)
    sent = 0
    end = time.monotonic() + 1.0
    while time.monotonic() < end or (not heard and time.monotonic() < deadline):
        publisher.publish(message_type(type_name)())
        sent += 1
        for _ in range(10):
            rclpy.spin_once(node, timeout_sec=0.01)
    print(json.dumps({"sent": sent, "heard": len(heard)}))


def transitions(node, target, _):
    finalized = []

    def on_event(event):
        print(f"{target}: {event.start_state.label} -> {event.goal_state.label}", flush=True)
        if event.goal_state.id == State.PRIMARY_STATE_FINALIZED:
            finalized.append(event)

    subscription = node.create_subscription(TransitionEvent, f"/{target}/transition_event", on_event, 10)
    deadline = time.monotonic() + TIMEOUT
    while subscription.get_publisher_count() == 0:
        if time.monotonic() > deadline:
            sys.exit(f"{target} publishes no transition events")
        rclpy.spin_once(node, timeout_sec=0.1)
    settle = time.monotonic() + 1.0  # the node's side of discovery may lag behind this one's
    while time.monotonic() < settle:
        rclpy.spin_once(node, timeout_sec=0.1)
    print("watching", flush=True)
    deadline = time.monotonic() + TIMEOUT
    while not finalized:
        if time.monotonic() > deadline:
            sys.exit(f"{target} was not finalized")
        rclpy.spin_once(node, timeout_sec=0.1)


def decoy(node, first, names):
    decoys = [rclpy.create_node(name) for name in (first, *names)]
    for held in decoys:
        held.create_publisher(Int32, "/decoy", 10)
    print("decoys up", flush=True)
    executor = SingleThreadedExecutor()
    for held in (node, *decoys):
        executor.add_node(held)
    executor.spin()


def sees(node, target, _):
    deadline = time.monotonic() + TIMEOUT
    while target not in node.get_node_names():
        if time.monotonic() > deadline:
            sys.exit(f"no node {target} in the graph")
        rclpy.spin_once(node, timeout_sec=0.1)
    print("seen", flush=True)


def hears(node, topic, names):
    """Print "heard" once a message of type names[0] (pkg/msg/Type) arrives on `topic`."""
    package, _, name = names[0].split("/")
    message = getattr(importlib.import_module(f"{package}.msg"), name)
    heard = []
    node.create_subscription(message, topic, heard.append, 10)
    deadline = time.monotonic() + TIMEOUT
    while not heard:
        if time.monotonic() > deadline:
            sys.exit(f"nothing heard on {topic}")
        rclpy.spin_once(node, timeout_sec=0.1)
    print("heard", flush=True)


def _spin_until(node, future, within=TIMEOUT):
    deadline = time.monotonic() + within
    while not future.done() and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.01)
    if not future.done():
        sys.exit(f"no answer within {within} s")
    return future.result()


def goal_result(node, action, _):
    client = ActionClient(node, Fibonacci, action)
    if not client.wait_for_server(timeout_sec=TIMEOUT):
        sys.exit(f"{action} is not available")
    fed = []
    goal = _spin_until(node, client.send_goal_async(Fibonacci.Goal(order=5), feedback_callback=fed.append))
    if not goal.accepted:
        sys.exit("the goal was rejected")
    result = goal.get_result_async()
    deadline = time.monotonic() + TIMEOUT
    while not fed and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.01)
    print("executing", flush=True)
    since = time.monotonic()
    status = _spin_until(node, result).status
    print(json.dumps({"status": status, "seconds": time.monotonic() - since}), flush=True)


def gating(node, target, names):
    service, action = names
    trigger = node.create_client(Trigger, service)
    client = ActionClient(node, Fibonacci, action)

    def goal_accepted():
        if not client.wait_for_server(timeout_sec=TIMEOUT):
            sys.exit(f"{action} is not available")
        return _spin_until(node, client.send_goal_async(Fibonacci.Goal(order=5)))

    lifecycle(node, target, ["configure"])
    inactive = {"service_offered": trigger.wait_for_service(timeout_sec=2.0),
                "goal_accepted": goal_accepted().accepted}
    lifecycle(node, target, ["activate"])
    active = {"service_offered": trigger.wait_for_service(timeout_sec=TIMEOUT)}
    active["service_answered"] = _spin_until(node, trigger.call_async(Trigger.Request())) is not None
    running = goal_accepted()
    active["goal_accepted"] = running.accepted
    result = running.get_result_async()
    lifecycle(node, target, ["deactivate"])
    deactivated = {"running_goal_status": _spin_until(node, result).status}
    print(json.dumps({"inactive": inactive, "active": active, "deactivated": deactivated}), flush=True)


def main():
    command, target, *rest = sys.argv[1:]
    rclpy.init()
    node = rclpy.create_node("rna_test_probe")
    try:
        {"params": params, "lifecycle": lifecycle, "busy_goal": busy_goal, "busy_service": busy_service,
         "clocked": clocked, "relay": relay, "transitions": transitions, "decoy": decoy, "sees": sees,
         "hears": hears, "goal_result": goal_result, "gating": gating}[command](node, target, rest)
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
