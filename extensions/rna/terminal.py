"""What the template prints at a terminal: lines wrapped at its width, whole words kept, nothing cut.

The wrapping of Copier's questions and of an answer's error at a prompt, which
prompt_toolkit would cut at the terminal's edge, is done by the patches `fitted_questions`
and `whole_errors` (extensions/patches/prompts.py) with these functions; the dialog's own
questions are wrapped here.
"""

from __future__ import annotations

import os
import re
import shutil
import sys
import textwrap
from collections.abc import Callable
from pathlib import Path

# The widest line a terminal shows without wrapping it: one column is left for the cursor.
MARGIN = 1
_COPIERS_LEAD = re.compile(r"^Validation error for question '[^']*': ")


def width() -> int:
    """The columns a printed line may take in the terminal at hand (79 in an 80-column one).

    The terminal's own size first: COLUMNS, which shutil reads first, may be left from another.
    """
    for stream in (sys.stdout, sys.stderr, sys.stdin):
        try:
            return max(os.get_terminal_size(stream.fileno()).columns - MARGIN, 20)
        except (AttributeError, OSError, ValueError):
            continue
    return max(shutil.get_terminal_size((80, 24)).columns - MARGIN, 20)


def wrap(text: str, columns: int) -> list[str]:
    """`text` as lines of at most `columns`, broken between words; its own line breaks kept.

    A word longer than a line (a long path) is the only thing broken inside: it goes on
    over the next lines, whole, instead of being cut at the edge.
    """
    lines = []
    for paragraph in text.splitlines() or [""]:
        indent = paragraph[:len(paragraph) - len(paragraph.lstrip())]
        lines.extend(textwrap.wrap(paragraph, columns, subsequent_indent=indent, break_on_hyphens=False)
                     or [""])
    return lines


def error_text(message: str) -> str:
    """A validation error as the toolbar shows it: without Copier's lead, which names the question
    the user is looking at."""
    return _COPIERS_LEAD.sub("", message, count=1)


def copier_command(environ: dict | None = None, executable: str | None = None,
                   which: Callable[[str], str | None] = shutil.which) -> str:
    """The command that runs this Copier again from the user's shell, for the commands a message prints
    (by default, of this process: its environment, its Python).

    Copier started through a clone's `tests/env` (the README's way) is not on the user's PATH:
    that script is named (tests/env exports RNA_TEMPLATE_ENV, and its environment's Python
    runs). A `copier` found on PATH that is this one (pipx links it there) is `copier`; a
    Copier run from an environment that is not on PATH is named by its path.
    """
    environ = dict(os.environ) if environ is None else environ
    executable = sys.executable if executable is None else executable
    running = Path(executable).parent / "copier"
    script = environ.get("RNA_TEMPLATE_ENV")
    venv = environ.get("VIRTUAL_ENV")
    if script and venv and Path(executable).resolve().is_relative_to(Path(venv).resolve()):
        return f"{script} copier"
    found = which("copier")
    if running.exists() and (found is None or Path(found).resolve() != running.resolve()):
        return str(running)
    return "copier"


def fitted_lines(text: str, columns: int, indent: str = "") -> str:
    """`text` with each line longer than `columns` wrapped between words (later lines after
    `indent`); lines that fit stay as they are."""
    lines = []
    for line in text.split("\n"):
        if len(line) <= columns:
            lines.append(line)
            continue
        lead = line[:len(line) - len(line.lstrip())]
        lines.extend(textwrap.wrap(line, columns, subsequent_indent=lead + indent, break_on_hyphens=False))
    return "\n".join(lines)
