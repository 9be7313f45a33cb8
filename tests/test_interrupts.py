"""The SIGINT stress test's judgement of a run that did not stop (tests/support/interrupts.py)."""

from __future__ import annotations

from support.interrupts import stuck_in_middleware

SITE = "/venv/lib/python3.11/site-packages"


def dump(*frames: str) -> str:
    """faulthandler's output for a main thread with `frames`, innermost first."""
    lines = [f'  File "{file}", line 1 in {function}' for file, function in (f.split(":") for f in frames)]
    return "\n".join(["Fatal Python error: Aborted", "", "Current thread 0x00007f2d3e9c6740 (most recent call first):",
                      *lines])


def test_a_run_stuck_creating_an_entity_in_the_middleware_is_told_apart():
    assert stuck_in_middleware(dump(f"{SITE}/rclpy/node.py:create_publisher", f"{SITE}/rclpy/node.py:__init__",
                                    "/ws/install/pkg/talker_base.py:__init__"))
    assert stuck_in_middleware(dump(f"{SITE}/rclpy/context.py:_logging_fini", f"{SITE}/rclpy/context.py:_cleanup"))
    assert stuck_in_middleware(dump(f"{SITE}/rclpy/node.py:destroy_node", f"{SITE}/rclpy/context.py:_cleanup"))
    # CI, 2026-11-26: a publisher's teardown inside try_shutdown (rclpy/publisher.py destroy).
    assert stuck_in_middleware(dump(f"{SITE}/rclpy/publisher.py:destroy", f"{SITE}/rclpy/node.py:destroy_publisher",
                                    f"{SITE}/rclpy/context.py:_cleanup"))


def test_a_run_stuck_anywhere_else_is_a_failure():
    assert not stuck_in_middleware(dump("/ws/install/pkg/talker.py:on_timer", f"{SITE}/rclpy/executors.py:spin"))
    assert not stuck_in_middleware(dump(f"{SITE}/rclpy/executors.py:_wait_for_ready_callbacks"))
    assert not stuck_in_middleware("still starting, printed nothing")
