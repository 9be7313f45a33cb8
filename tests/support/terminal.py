"""`copier` in a pseudo-terminal of 80x24 (pexpect), drawn by a terminal emulator (pyte)."""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

import pexpect
import pyte
from wcwidth import wcswidth

COPIER = str(Path(sys.executable).with_name("copier"))
WIDTH = 79  # the widest line an 80-column terminal shows without wrapping it
# What Copier prints once the questions are over: its tasks, the files it writes.
FILES_WRITTEN = (" > Running task", "    create  ", "    identical  ", "    overwrite  ", "    conflict  ",
                 "    skip  ", "    force  ", "    delete  ")


def spawn_copier(args: list[str], dimensions: tuple[int, int], cwd: Path | None = None,
                 env: dict | None = None) -> pexpect.spawn:
    """`copier <args>` in a pseudo-terminal of `dimensions` (rows, columns), as a person starts it."""
    # No cursor-position requests: pexpect does not answer them, and each would wait.
    env = {**os.environ, **(env or {}), "TERM": "xterm", "PROMPT_TOOLKIT_NO_CPR": "1"}
    child = pexpect.spawn(COPIER, args, env=env, encoding="utf-8", timeout=30, dimensions=dimensions,
                          cwd=str(cwd) if cwd else None)
    # Keys are sent once their prompt is drawn (expect first), so pexpect's default pause
    # before each send, meant for programs that drop early typing, only adds up.
    child.delaybeforesend = None
    return child


class Terminal:
    """A terminal (80x24 unless told) that `copier <args>` draws on.

    Every time something is drawn, until Copier runs the template's tasks (it prints their
    command, with its clone's path in TMPDIR, which may be as long as any), the screen is
    checked: `wide_rows` keeps every row drawn wider than its last column but one, `cut_rows`
    every row that reaches the edge (a line the terminal wrapped, or prompt_toolkit cut) or
    holds an ellipsis (a line shortened), each with the screen it was on.
    """

    def __init__(self, args: list[str], log: Path, cwd: Path | None = None, env: dict | None = None,
                 size: tuple[int, int] = (24, 80)):
        rows, self.columns = size
        self.screen = pyte.Screen(self.columns, rows)
        self.stream = pyte.Stream(self.screen)
        self.log = log.open("w")
        self.wide_rows: list[str] = []
        self.cut_rows: list[tuple[str, list[str]]] = []
        self.tasks_started = False
        self.child = spawn_copier(args, size, cwd, env)
        self.child.logfile_read = self

    def write(self, data: str) -> None:
        self.log.write(data)
        self.stream.feed(data)
        if self.tasks_started:
            return
        rows = self.rows()
        # Copier's list of the files it writes, and what follows (the message, with the destination's path).
        tasks = next((index for index, row in enumerate(rows) if row.startswith(FILES_WRITTEN)), None)
        if tasks is not None:
            self.tasks_started, rows = True, rows[:tasks]
        # A row that fills the terminal is a line the terminal wrapped (or one that just fits).
        self.wide_rows.extend(row for row in rows if wcswidth(row) > self.columns - 1)
        self.cut_rows.extend((row, rows) for row in rows if wcswidth(row) >= self.columns or "…" in row)

    def flush(self) -> None:
        self.log.flush()

    def rows(self) -> list[str]:
        return [row.rstrip() for row in self.screen.display]

    def rows_at(self, lines: list[str]) -> list[str]:
        """The screen's rows once a prompt's help `lines` (without the question mark) are drawn."""
        self.child.expect_exact(lines[0][:30])
        if len(lines) > 1:
            self.child.expect_exact(lines[-1].strip()[-30:])
        return self.rows()

    def answer(self, prompt: str, keys: str) -> None:
        """Wait for `prompt`, then type `keys` and Enter."""
        self.child.expect_exact(prompt)
        self.child.send(keys + "\r")

    def choose(self, message: str, keys: str, send: bool = True) -> None:
        """Wait for a fresh select prompt `message` (its instruction is drawn only while it is open,
        on the same line or, in the nodes dialog, the next), then type `keys` (which filter the
        choices in the nodes dialog) and Enter."""
        self.child.expect(re.escape(message) + r"(?:\x1b\[[0-9;?]*[A-Za-z]|\s)*\(Use arrow keys")
        if send:
            self.child.send(keys + "\r")

    def settled_rows(self, pause: float = 0.3) -> list[str]:
        """The screen once nothing more has been drawn for `pause` seconds."""
        while True:
            try:
                self.child.expect(r"[\s\S]+", timeout=pause)
            except pexpect.TIMEOUT:
                return self.rows()

    def close(self) -> None:
        self.child.close(force=True)
        self.log.close()
