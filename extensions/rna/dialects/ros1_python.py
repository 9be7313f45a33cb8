"""ROS 1 Python (rospy): imports of messages and of the parts of services and actions."""

from __future__ import annotations

from .python import PythonDialect, import_block


class Ros1Python(PythonDialect):
    @staticmethod
    def module(interface) -> str:
        # ROS 1 generates action types as messages (FooAction, FooGoal, ...).
        kind = "msg" if interface.kind == "action" else interface.kind
        return f"{interface.package}.{kind}"

    @property
    def base_imports(self) -> str:
        """Imports of the generated src/<package>/<node>_base.py."""
        node = self.node
        parts = [(t.type, "") for t in node.publishers + node.subscribers]
        parts += [(s.type, "") for s in node.service_servers + node.service_clients]
        parts += [(s.type, "Response") for s in node.service_servers]
        parts += [(a.type, "Action") for a in node.actions]
        return import_block([*self._needs("base"), *(self._import(t, part) for t, part in parts)])

    @property
    def node_imports(self) -> str:
        """Imports of the user's scripts/<node>.py: what its starter code uses."""
        node = self.node
        parts = [(t.type, "") for t in node.starter_built_messages]
        if node.driver_timer:
            parts += [(s.type, "Request") for s in node.service_clients]
            parts += [(a.type, "Goal") for a in node.action_clients]
        parts += [(s.type, "Response") for s in node.service_servers]
        parts += [(a.type, part) for a in node.action_servers for part in ("Feedback", "Result")]
        logs = ["rospy"] if self.starter_logs else []
        return import_block([*self._needs("user"), *logs, f"{self.base_module}:{node.base_class_name}",
                             f"{self.base_module}:run", *(self._import(t, part) for t, part in parts)])

    @property
    def starter_logs(self) -> bool:
        """The starter code uses rospy: it logs what it does, waits for an action server."""
        node = self.node
        return bool(node.parameters or node.subscribers or node.service_servers or node.service_clients
                    or node.actions or any(t.type.data_field for t in node.starter_built_messages))

    @staticmethod
    def period(timer) -> str:
        return str(timer.period)
