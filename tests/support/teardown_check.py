"""Run a generated node's main() in this process, Ctrl-C it while it works, then list the
rclpy entities main() left for the garbage collector to destroy as Python exits.

Run with the ROS venv's Python (the test process itself has no rclpy):
  teardown_check.py MODULE SECONDS    e.g. robot_services.server 1.5
Prints the kinds of the entities still alive as a JSON list: empty when main() destroyed
the node and everything it created before it returned.
"""

from __future__ import annotations

import gc
import importlib
import json
import os
import signal
import sys
import threading

from rclpy.action import ActionClient, ActionServer
from rclpy.client import Client
from rclpy.exceptions import InvalidHandle
from rclpy.node import Node
from rclpy.publisher import Publisher
from rclpy.service import Service
from rclpy.subscription import Subscription
from rclpy.timer import Timer

# Each kind of entity, and the attribute holding its handle in rclpy's C++ binding.
HANDLES = {Node: "handle", Publisher: "handle", Subscription: "handle", Service: "handle",
           Client: "handle", Timer: "handle", ActionServer: "_handle", ActionClient: "_client_handle"}


def is_alive(entity: object, attribute: str) -> bool:
    try:
        with getattr(entity, attribute):  # a destroyed handle refuses to be used
            return True
    except InvalidHandle:
        return False


def main() -> None:
    module, seconds = importlib.import_module(sys.argv[1]), float(sys.argv[2])
    threading.Timer(seconds, os.kill, (os.getpid(), signal.SIGINT)).start()
    module.main()
    alive = [kind.__name__ for entity in gc.get_objects() for kind, attribute in HANDLES.items()
             if isinstance(entity, kind) and is_alive(entity, attribute)]
    print(json.dumps(sorted(alive)))


if __name__ == "__main__":
    main()
