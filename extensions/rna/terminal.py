"""What the template prints at a terminal: lines wrapped at its width, whole words kept, nothing cut.

prompt_toolkit (under questionary, under Copier) shows a prompt's validation error in a
toolbar one row high: a longer error is cut at the terminal's edge, and what a user needs
most, the corrected value, comes last. `show_whole_validation_errors()` gives Copier's
prompts and the nodes dialog a toolbar that wraps the error at the terminal's width
instead, as many rows as it takes, without Copier's "Validation error for question '...'"
lead: the question is the line above it. It replaces prompt_toolkit's class where its
prompt sessions look it up, with one built from prompt_toolkit's public widgets; with a
prompt_toolkit that has no such name, nothing changes. RNA_TEMPLATE_PLAIN_PROMPTS=1
leaves prompt_toolkit as it is.
"""

from __future__ import annotations

import importlib
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


def show_whole_validation_errors() -> bool:
    """Make prompt_toolkit's prompts show a validation error whole, wrapped (see the module's doc).

    Returns whether it is in place. Installing it twice changes nothing.
    """
    if os.environ.get("RNA_TEMPLATE_PLAIN_PROMPTS") == "1":
        return False
    try:
        from prompt_toolkit.application.current import get_app
        from prompt_toolkit.filters import has_validation_error
        from prompt_toolkit.layout.containers import ConditionalContainer, Window
        from prompt_toolkit.layout.controls import FormattedTextControl

        # The module (the package's `prompt` is its function of that name).
        prompt_module = importlib.import_module("prompt_toolkit.shortcuts.prompt")
    except ImportError:
        return False
    if not hasattr(prompt_module, "ValidationToolbar"):
        return False
    if getattr(prompt_module.ValidationToolbar, "rna_wraps", False):
        return True

    class WrappedValidationToolbar:
        """prompt_toolkit's ValidationToolbar, as many rows high as the wrapped error takes."""

        rna_wraps = True

        def __init__(self, show_position: bool = False) -> None:
            def lines():
                error = get_app().current_buffer.validation_error
                if not error:
                    return []
                columns = get_app().output.get_size().columns - MARGIN
                return [("class:validation-toolbar", "\n".join(wrap(error_text(error.message), columns)))]

            self.control = FormattedTextControl(lines)
            self.container = ConditionalContainer(content=Window(self.control, dont_extend_height=True),
                                                  filter=has_validation_error)

        def __pt_container__(self):
            return self.container

    prompt_module.ValidationToolbar = WrappedValidationToolbar
    return True


def copier_command(environ: dict, executable: str, which: Callable[[str], str | None]) -> str:
    """The command that runs this Copier again from the user's shell, for the commands a message prints.

    Copier started through a clone's `tests/env` (the README's way) is not on the user's PATH:
    that script is named (tests/env exports RNA_TEMPLATE_ENV, and its environment's Python
    runs). A `copier` found on PATH that is this one (pipx links it there) is `copier`; a
    Copier run from an environment that is not on PATH is named by its path.
    """
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


def fit_copiers_questions() -> bool:
    """Copier's questions drawn whole in a terminal narrower than the help was written for.

    The help of copier.yml's questions is written in lines of 79 columns, and prompt_toolkit
    cuts a question's lines, and a menu's choices, at the terminal's edge instead of wrapping
    them. This wraps them between words, at the width of the terminal at hand, as Copier hands
    each question to questionary (Question.get_questionary_structure, the one method Copier
    builds a prompt from); a line that fits is left alone. Returns whether it is in place:
    with a Copier without that method, or RNA_TEMPLATE_PLAIN_PROMPTS=1, nothing changes.
    """
    if os.environ.get("RNA_TEMPLATE_PLAIN_PROMPTS") == "1":
        return False
    try:
        from copier._user_data import Question
    except ImportError:
        return False
    structure = getattr(Question, "get_questionary_structure", None)
    if structure is None or getattr(structure, "rna_fits", False):
        return structure is not None

    def fitted_structure(self):
        result = structure(self)
        columns = width()
        # The question follows the question mark (2 columns) and a space; choices the pointer.
        if isinstance(result.get("message"), str):
            result["message"] = fitted_lines("   " + result["message"], columns)[3:]
        for choice in result.get("choices") or ():
            title = getattr(choice, "title", None)
            if isinstance(title, str) and len(title) + 3 > columns:
                choice.title = fitted_lines(title, columns - 3, indent="").replace("\n", "\n   ")
        return result

    fitted_structure.rna_fits = True
    Question.get_questionary_structure = fitted_structure
    return True
