"""The patches of Jinja's compiling: `strings`, `jinja_code` and `plain_lines`.

Copier renders each string of copier.yml and each part of each path with
`environment.from_string`, for every file, and Jinja compiles each anew; Copier's clone of
the template is new each run, so Jinja compiles the template's files anew too. These
replace the environment's `from_string` and `compile` (on the one environment, not on
Jinja's class) so that each source is compiled once and its code kept (patches/code_cache.py).
"""

from __future__ import annotations

import types

from . import code_cache, guards


def _strings_differ() -> str | None:
    from jinja2 import Environment

    if guards.parameters(Environment.from_string) != ["self", "source", "globals", "template_class"]:
        return "Jinja's Environment.from_string takes other arguments"
    if not hasattr(Environment, "preprocess") or not hasattr(Environment, "make_globals"):
        return "Jinja's Environment has no preprocess or make_globals"
    return guards.jinja_differs()


def _jinja_code_differs() -> str | None:
    from jinja2 import Environment

    if guards.parameters(Environment.compile) != ["self", "source", "name", "filename", "raw", "defer_init"]:
        return "Jinja's Environment.compile takes other arguments"
    if not hasattr(Environment, "preprocess"):
        return "Jinja's Environment has no preprocess"
    return guards.jinja_differs()


def _plain_lines_differ() -> str | None:
    return _jinja_code_differs() or (None if hasattr(types.CodeType, "replace") else "code objects lack replace()")


GUARDS = {"strings": _strings_differ, "jinja_code": _jinja_code_differs, "plain_lines": _plain_lines_differ}
NEEDS = {"plain_lines": "jinja_code"}  # it takes its stand-in's code from the kept code


def late_finding(name: str) -> str | None:
    """What a run found out that the guard could not ask beforehand: a probe line's code."""
    if name == "plain_lines" and False in _plain_lines_fit.values():
        return "a probe line's code was not the stand-in's with the line in place"
    return None


def install(environment, on) -> None:
    if on("strings"):
        _compile_each_string_once(environment)
    if on("jinja_code"):
        _compile_each_source_once_per_process(environment, plain_lines=on("plain_lines"))


# ─── strings ──────────────────────────────────────────────────────────────────


def _compile_each_string_once(environment) -> None:
    """Keep what `from_string` compiled, per environment. A kept template is preprocessed
    again all the same: Copier's yield tag resets its state there, and checks that state
    after rendering each file.

    Such a template's globals are the environment's (Jinja chains them behind an empty map
    of its own, which nothing here fills): each render copies them into its context, and a
    chain copies in Python, key by key.
    """
    compile_string = environment.from_string
    compiled = {}

    def from_string(source, globals=None, template_class=None):  # noqa: A002 - Jinja's names
        if globals is not None or template_class is not None or not isinstance(source, str):
            return compile_string(source, globals, template_class)
        if source not in compiled:
            template = compile_string(source)
            template.globals = environment.globals
            compiled[source] = template
        else:
            environment.preprocess(source)
        return compiled[source]

    environment.from_string = from_string


# ─── jinja_code, plain_lines ──────────────────────────────────────────────────


def _compile_each_source_once_per_process(environment, plain_lines: bool) -> None:
    """Jinja's code from the store: Jinja compiles a template to a code object that takes its
    environment when it runs (what its bytecode cache stores), so environments that compile
    alike share it: the key is the source, its name and everything of the environment that
    the compiler reads. A hit is preprocessed all the same (Copier's yield tag).

    A line of plain text (a choice's label, a question's type, a path's part) is not kept:
    some of it names the destination. Jinja compiles every such line to the same code but
    for the text and the columns it takes, so its code is a kept stand-in's of the same
    width, with the text put in place (plain_lines).
    """
    compile_source = environment.compile
    codes = signature = None
    fits = None if plain_lines else False  # whether plain lines take a stand-in's code: probed at the first

    def compile(source, name=None, filename=None, raw=False, defer_init=False):  # noqa: A001 - Jinja's name
        nonlocal codes, signature, fits
        if raw or not isinstance(source, str):
            return compile_source(source, name, filename, raw, defer_init)
        if codes is None:  # the settings are complete once Copier compiles
            signature = _compiler_signature(environment)
            codes = code_cache.store("jinja", signature)
        plain = not _has_jinja_syntax(environment, source)
        if plain:
            if not _is_one_plain_line(source, name, filename, defer_init):
                return compile_source(source, name, filename, raw, defer_init)
            if fits is None:
                fits = _plain_lines_fit_in(signature, compile_source)
            if not fits:
                return compile_source(source, name, filename, raw, defer_init)
        compiled = _stand_in(source) if plain else source
        key = (compiled, name, defer_init)
        code = codes.get(key)
        if code is None:
            code = compile_source(compiled, name, filename, raw, defer_init)
            codes.put(key, code)
            if not plain:
                return code
        if plain:
            code = _with_constant(code, compiled, source)
            if code is None:  # a Jinja whose code does not hold the line as one constant
                return compile_source(source, name, filename, raw, defer_init)
        environment.preprocess(source, name, filename)
        return code

    environment.compile = compile


_PROBE = "A plain line: \u2713 'quoted' \\ and \"double\""
_plain_lines_fit: dict[str, bool] = {}  # per compiler: whether the probe line's code was the stand-in's


def _plain_lines_fit_in(signature: str, compile_source) -> bool:
    """Whether a probe line gets the very code Jinja compiles for it, once per compiler and process."""
    if signature not in _plain_lines_fit:
        stand_in = _stand_in(_PROBE)
        _plain_lines_fit[signature] = _with_constant(compile_source(stand_in), stand_in, _PROBE) == \
            compile_source(_PROBE)
    return _plain_lines_fit[signature]


def _compiler_signature(environment) -> str:
    import jinja2

    finalize = environment.finalize
    return repr((
        jinja2.__version__, type(environment).__module__, type(environment).__qualname__,
        sorted(environment.extensions), environment.block_start_string, environment.block_end_string,
        environment.variable_start_string, environment.variable_end_string, environment.comment_start_string,
        environment.comment_end_string, environment.line_statement_prefix, environment.line_comment_prefix,
        environment.trim_blocks, environment.lstrip_blocks, environment.newline_sequence,
        environment.keep_trailing_newline, environment.optimized, environment.is_async,
        environment.autoescape if isinstance(environment.autoescape, bool) else id(environment.autoescape),
        None if finalize is None else (getattr(finalize, "__module__", None),
                                       getattr(finalize, "__qualname__", id(finalize)),
                                       getattr(finalize, "jinja_pass_arg", None)),
        sorted(environment.filters), sorted(environment.tests), sorted(environment.policies.items(), key=repr)))


def _has_jinja_syntax(environment, source: str) -> bool:
    starts = (environment.block_start_string, environment.variable_start_string, environment.comment_start_string,
              environment.line_statement_prefix, environment.line_comment_prefix)
    return any(start and start in source for start in starts)


def _stand_in(line: str) -> str:
    """A line that names nothing, as wide as `line` in Python's source (Jinja's code yields
    it as a literal, and Python's code records the columns, in UTF-8 bytes, of each expression)."""
    return "x" * (len(repr(line).encode()) - 2)


def _is_one_plain_line(source: str, name, filename, defer_init) -> bool:
    """Whether Jinja's code for this plain text is the stand-in line's with the text in its
    place: one line (Jinja rewrites line breaks), not empty, compiled by `from_string`."""
    return bool(source) and "\n" not in source and "\r" not in source and name is None and filename is None \
        and not defer_init


def _with_constant(code: types.CodeType, old: str, new: str) -> types.CodeType | None:
    """`code`, with the string constant `old` replaced by `new` in it and its nested code;
    None when `old` is in none of them."""
    found = False

    def replaced(constant):
        nonlocal found
        if isinstance(constant, types.CodeType):
            nested = _with_constant(constant, old, new)
            found = found or nested is not None
            return constant if nested is None else nested
        if type(constant) is str and constant == old:
            found = True
            return new
        return constant

    constants = tuple(replaced(constant) for constant in code.co_consts)
    return code.replace(co_consts=constants) if found else None
