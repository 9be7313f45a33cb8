"""Ctrl-C at random moments: the stress test of clean shutdown shared by the ROS tiers.

Each run is one node process with a ROS log directory of its own. Its clock starts
when the client library opens its log file there, which rclpy.init() and
rospy.init_node() do first thing in the node's main(); before that the interpreter is
still importing modules, where Ctrl-C ends any Python program with a KeyboardInterrupt
traceback and no node code has run yet to handle it. The SIGINT then comes a seeded
random delay later: during start-up (creating the node, its publishers and parameters),
mid-callback, mid-goal, or while another run it talks to is shutting down.
"""

from __future__ import annotations

import contextlib
import random
import re
import signal
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

from .processes import NodeProcess

# What a clean stop never prints: a Python traceback or an exception's name.
UNCLEAN_OUTPUT = re.compile(r"Traceback|Error")
# Except in Fast DDS's own log lines ("2026-11-26 22:00:12.401 [TYPELOOKUP_SERVICE_REPLY_LISTENER
# Error] Error registering remote type: Inconsistent TypeObject", in colour): the middleware
# telling of a peer that vanished mid-exchange (about 1 run in 400, the run itself exiting 0).
# They are listed with the test's warnings, not counted against the run.
_COLOUR = re.compile(r"\x1b\[[0-9;]*m")
MIDDLEWARE_LOG_LINE = re.compile(r"^\d{4}-\d\d-\d\d [\d:.]+ \[[A-Z_]+ (?:Error|Warning)\] .*$", re.MULTILINE)


def middleware_log(output: str) -> list[str]:
    """Fast DDS's own log lines in a run's output, colours taken off."""
    return MIDDLEWARE_LOG_LINE.findall(_COLOUR.sub("", output))


def unclean(output: str) -> str | None:
    """What UNCLEAN_OUTPUT finds in the output outside Fast DDS's own log lines, or None."""
    found = UNCLEAN_OUTPUT.search(MIDDLEWARE_LOG_LINE.sub("", _COLOUR.sub("", output)))
    return found.group() if found else None
# A run still alive after its SIGINT is made to dump its Python stacks (faulthandler, on
# SIGABRT). One stuck in rclpy's call into the middleware, creating or tearing down an
# entity or the log, met a deadlock inside Fast DDS as a peer vanished (gdb showed its
# receive thread waiting for its event thread, which waited for a lock the receive thread
# held; about 1 run in 300, whatever main() did). Those runs are reported, not counted;
# any other hang is a failure.
FAULTHANDLER_ENV = {"PYTHONFAULTHANDLER": "1"}
MIDDLEWARE_CALLS = ("create_publisher", "create_subscription", "create_service", "create_client",
                    "_logging_fini", "destroy_node", "destroy")  # destroy: an entity's own teardown
# An action client or server is created by its constructor's one call into rcl_action,
# which makes its services and topics in the middleware (CI, 2026-11-27: a client stuck
# there after a SIGINT 0.15 s into its start-up, 1 run in 100).
ACTION_CONSTRUCTORS = ("/rclpy/action/client.py", "/rclpy/action/server.py")
INNERMOST_FRAME = re.compile(r"^(?:Current thread|Thread) 0x[0-9a-f]+ \(most recent call first\):\n"
                             r"  File \"(?P<file>[^\"]+)\", line \d+ in (?P<function>\w+)", re.MULTILINE)
LATEST = 1.5  # seconds: by then the runs are exchanging messages, calls and goals


def draw_delay(rng: random.Random) -> float:
    """Anywhere from at once (start-up: the node, its parameters and endpoints) to LATEST."""
    return rng.uniform(0.0, LATEST)


@dataclass
class Run:
    kind: str
    process: NodeProcess
    log_dir: Path  # the node's ROS_LOG_DIR, empty until its client library starts
    delay: float
    started: float | None = None  # monotonic time the log file appeared
    interrupted: bool = False

    @property
    def label(self) -> str:
        return f"{self.kind} ({self.process.log_path.stem}), SIGINT {self.delay:.2f} s after start"


def interrupt_all(runs: list[Run], timeout: float = 30.0) -> list[tuple[Run, str]]:
    """Send each run SIGINT `delay` seconds after its start; return the runs that did not end cleanly.

    A clean end is exit code 0 with nothing in the output that UNCLEAN_OUTPUT matches
    (Fast DDS's own log lines aside);
    a run stuck in the middleware comes back as MIDDLEWARE_DEADLOCK.
    """
    pending = list(runs)
    deadline = time.monotonic() + timeout
    while pending:
        now = time.monotonic()
        for run in list(pending):
            if run.started is None and run.log_dir.is_dir() and any(run.log_dir.iterdir()):
                run.started = now
            if run.started is not None and now >= run.started + run.delay:
                run.process.popen.send_signal(signal.SIGINT)
                run.interrupted = True
                pending.remove(run)
            elif run.process.popen.poll() is not None or now > deadline:
                pending.remove(run)  # ended by itself or never started: reported below
        time.sleep(0.005)
    return [(run, problem) for run in runs if (problem := _problem(run, timeout))]


def _problem(run: Run, timeout: float) -> str | None:
    try:
        code = run.process.popen.wait(timeout)
    except subprocess.TimeoutExpired:
        _dump_stacks(run)
        if run.interrupted and stuck_in_middleware(run.process.output):
            return MIDDLEWARE_DEADLOCK
        return f"still ran {timeout} s after SIGINT" if run.interrupted else "never started ROS"
    if not run.interrupted:
        return f"ended with exit code {code} before its SIGINT"
    if code == -signal.SIGSEGV and crashed_in_middleware(run.process.output):
        return MIDDLEWARE_CRASH
    if code != 0:
        return f"exited with code {code}"
    printed = unclean(run.process.output)
    return f"exited with code 0 but printed {printed!r}" if printed else None


MIDDLEWARE_DEADLOCK = "stuck in a middleware call (Fast DDS deadlock)"
# A SIGSEGV in one of the middleware's own threads while main() destroyed the node (about 1
# run in 1000 on an idle machine; before main() destroyed its entities itself, the same
# crash came after main() returned, about 1 in 200, and is still a failure).
MIDDLEWARE_CRASH = "crashed in a middleware thread while rclpy tore an entity down (Fast DDS)"
NOT_COUNTED = (MIDDLEWARE_DEADLOCK, MIDDLEWARE_CRASH)


def _dump_stacks(run: Run) -> None:
    """Make the run print its Python stacks (faulthandler, if FAULTHANDLER_ENV is set), then kill it."""
    with contextlib.suppress(ProcessLookupError):
        run.process.popen.send_signal(signal.SIGABRT)
    with contextlib.suppress(subprocess.TimeoutExpired):
        run.process.popen.wait(5)
    run.process.kill()


def stuck_in_middleware(output: str) -> bool:
    """Whether a thread's innermost Python frame is rclpy calling into the middleware."""
    return any(("/rclpy/" in frame["file"] and frame["function"] in MIDDLEWARE_CALLS)
               or (frame["file"].endswith(ACTION_CONSTRUCTORS) and frame["function"] == "__init__")
               for frame in INNERMOST_FRAME.finditer(output))


def crashed_in_middleware(output: str) -> bool:
    """A segmentation fault in a thread that is not Python's (faulthandler marks no thread
    as the current one) while a thread's innermost Python frame is rclpy calling into the
    middleware (main() destroying the node)."""
    return ("Fatal Python error: Segmentation fault" in output and "Current thread" not in output
            and stuck_in_middleware(output))


def split_deadlocks(failures: list[tuple[Run, str]]) -> tuple[list[tuple[Run, str]], list[tuple[Run, str]]]:
    """(the real failures, the runs the middleware deadlocked or crashed: NOT_COUNTED)."""
    return ([(run, problem) for run, problem in failures if problem not in NOT_COUNTED],
            [(run, problem) for run, problem in failures if problem in NOT_COUNTED])


def report(failures: list[tuple[Run, str]], total: int, seed: int) -> str:
    """The failing runs, one per line, then the whole output of the first one."""
    lines = [f"{len(failures)} of {total} nodes stopped with SIGINT did not end cleanly (seed {seed}):"]
    lines += [f"  {run.label}: {problem}" for run, problem in failures]
    first = failures[0][0]
    lines += ["", f"output of {first.label}:", first.process.output]
    return "\n".join(lines)
