"""Run ROS nodes as separate OS processes and watch what they print.

Each node runs in its own process group with stdout and stderr merged into a
log file, so a test can wait for a line, stop the node with SIGINT like a user
pressing Ctrl-C, and show the whole log when an expectation fails.
"""

from __future__ import annotations

import contextlib
import os
import re
import signal
import subprocess
import time
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path


class NodeProcess:
    """One running node (or any command) whose output is captured in a log file."""

    def __init__(
        self,
        argv: Sequence[str],
        *,
        env: Mapping[str, str],
        log_path: Path,
        cwd: Path | None = None,
    ) -> None:
        self.argv = list(argv)
        self.log_path = log_path
        log_path.parent.mkdir(parents=True, exist_ok=True)
        self._log = log_path.open("wb")
        self.popen = subprocess.Popen(
            self.argv,
            env=dict(env),
            cwd=cwd,
            stdin=subprocess.DEVNULL,
            stdout=self._log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )

    @property
    def name(self) -> str:
        return Path(self.argv[0]).name

    @property
    def output(self) -> str:
        # Still readable after close(), e.g. for a failure message after the block.
        if not self._log.closed:
            self._log.flush()
        return self.log_path.read_text(errors="replace")

    def wait_for(self, pattern: str, timeout: float = 20.0) -> re.Match[str]:
        """Wait until the output matches the regular expression `pattern`."""
        regex = re.compile(pattern)
        deadline = time.monotonic() + timeout
        while True:
            match = regex.search(self.output)
            if match:
                return match
            if self.popen.poll() is not None:
                # One last read: the process may have printed and exited at once.
                match = regex.search(self.output)
                if match:
                    return match
                raise AssertionError(
                    f"{self.name} exited with {self.popen.returncode} before printing "
                    f"{pattern!r}:\n{self.tail()}"
                )
            if time.monotonic() > deadline:
                raise AssertionError(
                    f"{self.name} did not print {pattern!r} within {timeout} s:\n{self.tail()}"
                )
            time.sleep(0.05)

    def interrupt(self, timeout: float = 15.0) -> int:
        """Send SIGINT (Ctrl-C) to the node and return its exit code."""
        if self.popen.poll() is None:
            self.popen.send_signal(signal.SIGINT)
        try:
            return self.popen.wait(timeout)
        except subprocess.TimeoutExpired:
            self.kill()
            raise AssertionError(
                f"{self.name} did not stop within {timeout} s of SIGINT:\n{self.tail()}"
            ) from None

    def wait(self, timeout: float = 30.0) -> int:
        """Wait for the process to end by itself and return its exit code."""
        try:
            return self.popen.wait(timeout)
        except subprocess.TimeoutExpired:
            self.kill()
            raise AssertionError(f"{self.name} still ran after {timeout} s:\n{self.tail()}") from None

    def kill(self) -> None:
        """Kill the whole process group, whatever state it is in."""
        if self.popen.poll() is None:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(self.popen.pid, signal.SIGKILL)
            self.popen.wait(5)

    def close(self) -> None:
        self.kill()
        self._log.close()

    def tail(self, lines: int = 40) -> str:
        return "\n".join(self.output.splitlines()[-lines:])


@contextlib.contextmanager
def started(*processes: NodeProcess) -> Iterator[tuple[NodeProcess, ...]]:
    """Make sure every process is killed when the block ends, however it ends."""
    try:
        yield processes
    finally:
        for process in processes:
            process.close()


def assert_clean_exit(process: NodeProcess, exit_code: int) -> None:
    """A node stopped with SIGINT must exit 0 without a Python traceback."""
    output = process.output
    assert exit_code == 0, f"{process.name} exited with {exit_code}:\n{process.tail()}"
    assert "Traceback" not in output, f"{process.name} printed a traceback:\n{output}"
