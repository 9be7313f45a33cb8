"""The patches of what Copier's prompts show at a terminal: `whole_errors` and `fitted_questions`.

prompt_toolkit (under questionary, under Copier) cuts what does not fit at the terminal's
edge: a question's lines, a menu's choices, and an answer's error, shown in a toolbar one
row high, where what a user needs most, the corrected value, comes last. These wrap them
between words at the terminal's width instead (the wrapping is rna/terminal.py's), for
Copier's prompts and the nodes dialog alike; what is asked and answered is unchanged.
"""

from __future__ import annotations

import functools
import importlib

from . import guards

_PROMPT_MODULE = "prompt_toolkit.shortcuts.prompt"  # the module (the package's `prompt` is its function)


def _whole_errors_differ() -> str | None:
    try:
        import prompt_toolkit
        from prompt_toolkit.application.current import get_app  # noqa: F401 - what the toolbar uses
        from prompt_toolkit.filters import has_validation_error  # noqa: F401
        from prompt_toolkit.layout.containers import ConditionalContainer, Window  # noqa: F401
        from prompt_toolkit.layout.controls import FormattedTextControl  # noqa: F401
        from prompt_toolkit.validation import ValidationError

        prompt_module = importlib.import_module(_PROMPT_MODULE)
    except ImportError as error:
        return f"prompt_toolkit lacks what the toolbar uses ({error})"
    toolbar = getattr(prompt_module, "ValidationToolbar", None)
    if toolbar is None or guards.parameters(toolbar) != ["show_position"]:
        return "prompt_toolkit's ValidationToolbar is not the class it was"
    if not guards.looked_up_by_name(getattr(prompt_module.PromptSession, "_create_layout", None), "ValidationToolbar"):
        return "prompt_toolkit's PromptSession no longer makes its toolbar by the name ValidationToolbar"
    if "message" not in (guards.parameters(ValidationError) or []):
        return "prompt_toolkit's ValidationError has no message"
    return guards.major_differs("prompt_toolkit", prompt_toolkit.__version__, guards.PROMPT_TOOLKIT_MAJOR)


def _fitted_questions_differ() -> str | None:
    try:
        from copier._main import Worker
        from copier._user_data import Question
    except ImportError:
        return "Copier has no copier._user_data.Question"
    reason = guards.method_differs(Question, "get_questionary_structure", ["self"])
    if reason is not None:
        return f"Copier's {reason}"
    if not guards.looked_up_by_name(getattr(Worker, "_ask", None), "get_questionary_structure"):
        return "Copier's Worker._ask no longer asks Question.get_questionary_structure"
    return guards.copier_differs()


GUARDS = {"whole_errors": _whole_errors_differ, "fitted_questions": _fitted_questions_differ}
NEEDS: dict[str, str] = {}


def install(environment, on) -> None:
    if on("whole_errors"):
        _show_whole_validation_errors()
    if on("fitted_questions"):
        _fit_copiers_questions()


# ─── whole_errors ─────────────────────────────────────────────────────────────


def _show_whole_validation_errors() -> None:
    """A prompt's validation error shown whole: prompt_toolkit's PromptSession makes its toolbar
    from the module's name `ValidationToolbar`, replaced there by one built from prompt_toolkit's
    public widgets, as many rows high as the error wrapped at the terminal's width, without
    Copier's "Validation error for question '...'" lead (the question is the line above it)."""
    from prompt_toolkit.application.current import get_app
    from prompt_toolkit.filters import has_validation_error
    from prompt_toolkit.layout.containers import ConditionalContainer, Window
    from prompt_toolkit.layout.controls import FormattedTextControl
    from rna import terminal

    prompt_module = importlib.import_module(_PROMPT_MODULE)
    if getattr(prompt_module.ValidationToolbar, "rna_wraps", False):  # another load, or template version, did it
        return

    class WrappedValidationToolbar:
        """prompt_toolkit's ValidationToolbar, as many rows high as the wrapped error takes."""

        rna_wraps = True

        def __init__(self, show_position: bool = False) -> None:
            def lines():
                error = get_app().current_buffer.validation_error
                if not error:
                    return []
                columns = get_app().output.get_size().columns - terminal.MARGIN
                text = "\n".join(terminal.wrap(terminal.error_text(error.message), columns))
                return [("class:validation-toolbar", text)]

            self.control = FormattedTextControl(lines)
            self.container = ConditionalContainer(content=Window(self.control, dont_extend_height=True),
                                                  filter=has_validation_error)

        def __pt_container__(self):
            return self.container

    prompt_module.ValidationToolbar = WrappedValidationToolbar


# ─── fitted_questions ─────────────────────────────────────────────────────────


def _fit_copiers_questions() -> None:
    """Copier's questions and choices wrapped at the terminal's width, between words.

    The help of copier.yml's questions is written in lines of 79 columns; in a narrower
    terminal prompt_toolkit would cut them. Copier builds each prompt from
    Question.get_questionary_structure: its message and its choices' titles are wrapped
    there, at the width of the terminal at hand; a line that fits is left alone.
    """
    from copier._user_data import Question
    from rna import terminal

    structure = Question.get_questionary_structure
    if getattr(structure, "rna_fits", False):
        return

    @functools.wraps(structure)
    def fitted_structure(self):
        result = structure(self)
        columns = terminal.width()
        # The question follows the question mark (2 columns) and a space; choices the pointer.
        if isinstance(result.get("message"), str):
            result["message"] = terminal.fitted_lines("   " + result["message"], columns)[3:]
        for choice in result.get("choices") or ():
            title = getattr(choice, "title", None)
            if isinstance(title, str) and len(title) + 3 > columns:
                choice.title = terminal.fitted_lines(title, columns - 3, indent="").replace("\n", "\n   ")
        return result

    fitted_structure.rna_fits = True
    Question.get_questionary_structure = fitted_structure
