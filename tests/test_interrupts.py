"""The SIGINT stress test's judgement of a run that did not stop (tests/support/interrupts.py)."""

from __future__ import annotations

from support.interrupts import crashed_in_middleware, middleware_log, stuck_in_middleware, unclean

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
    # CI, 2026-11-27: an action client being created (its constructor calls rcl_action).
    assert stuck_in_middleware(dump(f"{SITE}/rclpy/action/client.py:__init__",
                                    "/ws/install/pkg/client_base.py:__init__", "/ws/install/pkg/client.py:main"))
    assert stuck_in_middleware(dump(f"{SITE}/rclpy/action/server.py:__init__",
                                    "/ws/install/pkg/server_base.py:__init__"))


def test_a_run_stuck_anywhere_else_is_a_failure():
    assert not stuck_in_middleware(dump("/ws/install/pkg/talker.py:on_timer", f"{SITE}/rclpy/executors.py:spin"))
    assert not stuck_in_middleware(dump(f"{SITE}/rclpy/action/client.py:send_goal_async",
                                        "/ws/install/pkg/client.py:main"))
    assert not stuck_in_middleware(dump("/ws/install/pkg/client_base.py:__init__", "/ws/install/pkg/client.py:main"))
    assert not stuck_in_middleware(dump(f"{SITE}/rclpy/executors.py:_wait_for_ready_callbacks"))
    assert not stuck_in_middleware("still starting, printed nothing")


# A listener's whole output in a local run, 2026-11-26: it exited 0 as a talker vanished.
FAST_DDS_LINE = ("\x1b[37;1m2026-11-26 22:00:12.401 \x1b[31;1m[\x1b[37;1mTYPELOOKUP_SERVICE_REPLY_LISTENER\x1b[31;1m "
                 "Error] \x1b[37mError registering remote type: Inconsistent TypeObject\x1b[34;1m -> Function "
                 "\x1b[36mcheck_get_types_reply\x1b[m")


def test_fast_dds_log_lines_are_listed_and_not_held_against_the_run():
    assert unclean(FAST_DDS_LINE + "\n") is None
    assert middleware_log(FAST_DDS_LINE) == [
        "2026-11-26 22:00:12.401 [TYPELOOKUP_SERVICE_REPLY_LISTENER Error] Error registering remote type: "
        "Inconsistent TypeObject -> Function check_get_types_reply"]


def test_a_traceback_or_an_exception_outside_them_is_unclean():
    assert unclean(FAST_DDS_LINE + "\nTraceback (most recent call last):\n") == "Traceback"
    assert unclean("[ERROR] [1795722616.68] [talker]: RCLError: failed to initialize wait set") == "Error"
    assert unclean("2026-11-26 22:00:12.401 rclpy Error in a message of the node's own\n") == "Error"


def crash(thread_header: str, *frames: str) -> str:
    """faulthandler's output for a segmentation fault, the main thread with `frames`."""
    lines = [f'  File "{file}", line 1 in {function}' for file, function in (f.split(":") for f in frames)]
    return "\n".join(["Fatal Python error: Segmentation fault", "", f"{thread_header} (most recent call first):",
                      *(lines or ["  <no Python frame>"])])


def test_a_crash_in_the_middlewares_thread_during_the_nodes_teardown_is_told_apart():
    # Local run, 2026-11-26: a middleware thread crashed while main() destroyed the node.
    assert crashed_in_middleware(crash("Thread 0x00007f9eea7ba740", f"{SITE}/rclpy/node.py:destroy_node",
                                       "/ws/install/pkg/client_base.py:destroy_node", "/ws/install/pkg/client.py:main"))


def test_a_crash_in_python_code_or_after_main_returned_is_a_failure():
    # CI, 2026-11-26 (before main() destroyed its entities): after main() returned.
    assert not crashed_in_middleware(crash("Thread 0x00007f513702a740"))
    # The crashing thread is a Python one.
    assert not crashed_in_middleware(crash("Current thread 0x00007f9eea7ba740", f"{SITE}/rclpy/node.py:destroy_node"))
    assert not crashed_in_middleware(crash("Thread 0x00007f9eea7ba740", "/ws/install/pkg/talker.py:on_timer"))
