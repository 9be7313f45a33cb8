"""Speed-ups: every change this template makes to another library's behaviour, in one place.

Copier, Jinja and Python redo work in every run that a template of this size pays for
many times over. Each speed-up below changes how one library does one thing, never what
it produces; each was measured (docs/pages/reference/performance.md gives its share of a
default copy, a 50-node copy and an update, and decision 15 why it is kept); each is
turned off by its guard when the library is not the one it was written for; and the
output is the same with all of them off (tests/test_speedups.py, also against the newest
Copier, copier-template-extensions and Jinja).

  strings            Copier compiles the same string (a question's `when`, a path part)
                     hundreds of times a run: each Jinja environment compiles it once.
  jinja_code         Jinja's compiled code of the template's files and strings is kept in
                     the user's cache folder between runs and shared by the environments
                     of one run (Copier's clone is new each run; Jinja caches only files).
  plain_lines        A line of plain text gets the code of a kept stand-in line as wide,
                     with the text put in place (plain text is not kept: it names paths).
  python_code        The template's own modules are imported with code from that cache
                     (Copier's clone of the template has no __pycache__).
  dataclasses        The methods `dataclasses` writes and compiles for each class come
                     compiled from that cache while the template's modules load.
  git_file_mode      Copier asks git for `core.fileMode` after writing each file: once
                     per Copier worker here.
  answers_file_name  Copier renders the answers file's name about ten times per file:
                     once per render of a package here, when the answers are final.

RNA_TEMPLATE_SPEEDUPS_OFF=all turns every one off (the template then runs on the
libraries' documented behaviour alone); a comma-separated list of names turns those off.
RNA_TEMPLATE_CACHE_DIR moves the cache folder; set empty, nothing is kept between runs.

Imported by plain name, before `rna`, by what Copier loads or runs: copier_glue.py,
after_update.py, add_node.py. Several template versions can run in one process (an
update renders the old and the new one): what is process-wide here (the cache's stores,
the marks on Copier's methods) is shared with them, so its names and methods only grow.
"""

from __future__ import annotations

import atexit
import builtins
import contextlib
import functools
import hashlib
import importlib.machinery
import importlib.util
import marshal
import os
import subprocess
import sys
import tempfile
import types
from pathlib import Path

NAMES = ("strings", "jinja_code", "plain_lines", "python_code", "dataclasses", "git_file_mode", "answers_file_name")
SWITCH = "RNA_TEMPLATE_SPEEDUPS_OFF"

# The library versions each speed-up was written and tested for; another turns it off.
COPIER_MAJOR = 9
JINJA_MAJOR = 3
PYTHONS = ((3, 11), (3, 12), (3, 13))  # dataclasses' own compiling, as checked on each


# ─── Which speed-ups are on ───────────────────────────────────────────────────


def status() -> dict[str, str]:
    """Each speed-up's state: "on", or "off: " and why (the switch, or what its guard found)."""
    return {name: state(name) for name in NAMES}


def on(name: str) -> bool:
    return state(name) == "on"


def state(name: str) -> str:
    """One speed-up's state, its guard asked only for it (the after-update step, which loads
    the template's modules, must not import Copier to learn of a Copier speed-up)."""
    found = _state(name, os.environ.get(SWITCH, ""))
    if name == "plain_lines" and found == "on" and False in _plain_lines_fit.values():
        return "off: a probe line's code was not the stand-in's with the line in place"
    return found


@functools.lru_cache(maxsize=64)
def _state(name: str, switch: str) -> str:
    turned_off = {part.strip() for part in switch.split(",") if part.strip()}
    if name in turned_off or turned_off & {"all", "1", "true", "yes"}:
        return f"off: {SWITCH}={switch}"
    if name == "plain_lines" and _state("jinja_code", switch) != "on":
        return "off: it takes its stand-in's code from jinja_code, which is off"
    reason = _GUARDS[name]()
    return "on" if reason is None else f"off: {reason}"


def _major(version: str) -> int | None:
    head = version.split(".")[0]
    return int(head) if head.isdigit() else None


def _copier_differs() -> str | None:
    import copier

    version = getattr(copier, "__version__", "")
    return None if _major(version) == COPIER_MAJOR else f"Copier {version or '(unknown)'} is not {COPIER_MAJOR}.x"


def _jinja_differs() -> str | None:
    import jinja2

    return None if _major(jinja2.__version__) == JINJA_MAJOR else f"Jinja {jinja2.__version__} is not {JINJA_MAJOR}.x"


def _parameters(function) -> list[str] | None:
    import inspect

    try:
        return list(inspect.signature(function).parameters)
    except (TypeError, ValueError):
        return None


def _strings_differ() -> str | None:
    from jinja2 import Environment

    if _parameters(Environment.from_string) != ["self", "source", "globals", "template_class"]:
        return "Jinja's Environment.from_string takes other arguments"
    if not hasattr(Environment, "preprocess") or not hasattr(Environment, "make_globals"):
        return "Jinja's Environment has no preprocess or make_globals"
    return _jinja_differs()


def _jinja_code_differs() -> str | None:
    from jinja2 import Environment

    if _parameters(Environment.compile) != ["self", "source", "name", "filename", "raw", "defer_init"]:
        return "Jinja's Environment.compile takes other arguments"
    if not hasattr(Environment, "preprocess"):
        return "Jinja's Environment has no preprocess"
    return _jinja_differs()


def _plain_lines_differ() -> str | None:
    return _jinja_code_differs() or (None if hasattr(types.CodeType, "replace") else "code objects lack replace()")


def _python_code_differs() -> str | None:
    import _imp

    if not hasattr(_imp, "_fix_co_filename") or not hasattr(importlib.machinery.SourceFileLoader, "source_to_code"):
        return "Python's import machinery differs"
    return None


def _dataclasses_differ(module: types.ModuleType | None = None) -> str | None:
    if sys.version_info[:2] not in PYTHONS:
        return f"Python {sys.version_info[0]}.{sys.version_info[1]} is not one of " + \
            ", ".join(f"{major}.{minor}" for major, minor in PYTHONS)
    if module is None:
        import dataclasses as module
    functions = [value for value in vars(module).values() if isinstance(value, types.FunctionType)]
    functions += [member for value in vars(module).values() if isinstance(value, type)
                  for member in vars(value).values() if isinstance(member, types.FunctionType)]
    if not any("exec" in function.__code__.co_names for function in functions):
        return "dataclasses does not call exec by name"
    return None


def _copier_worker_differs(method: str, parameters: list[str] | None, uses: tuple[str, ...]) -> str | None:
    """Whether Copier's Worker differs from the one the wrapper of `method` was written for: the
    method (or property) itself, and the members the wrapper reads (`uses`)."""
    import inspect

    try:
        from copier._main import Worker
    except ImportError:
        return "Copier has no copier._main.Worker"
    member = inspect.getattr_static(Worker, method, None)
    if parameters is None and not isinstance(member, property):
        return f"Copier's Worker.{method} is not a property"
    if parameters is not None and (not isinstance(member, types.FunctionType) or _parameters(member) != parameters):
        return f"Copier's Worker.{method} is not the method it was"
    fields = getattr(Worker, "__dataclass_fields__", {})
    missing = [name for name in uses if name not in fields and inspect.getattr_static(Worker, name, None) is None]
    if missing:
        return f"Copier's Worker has no {', '.join(missing)}"
    return _copier_differs()


def _git_file_mode_differs() -> str | None:
    return _copier_worker_differs("_sync_git_index_executable_bit", ["self", "dst_relpath", "src_mode"],
                                  ("jinja_env", "subproject"))


def _answers_file_name_differs() -> str | None:
    try:
        from copier._types import Phase
    except ImportError:
        return "Copier has no copier._types.Phase"
    if not hasattr(Phase, "RENDER") or not hasattr(Phase, "current"):
        return "Copier's Phase has no RENDER or current()"
    return _copier_worker_differs("answers_relpath", None, ("jinja_env", "answers", "answers_file", "template"))


_GUARDS = {"strings": _strings_differ, "jinja_code": _jinja_code_differs, "plain_lines": _plain_lines_differ,
           "python_code": _python_code_differs, "dataclasses": _dataclasses_differ,
           "git_file_mode": _git_file_mode_differs, "answers_file_name": _answers_file_name_differs}


# ─── Installing them ──────────────────────────────────────────────────────────


def install(environment) -> None:
    """Turn on, for a Copier worker's Jinja environment, the speed-ups that are on."""
    if on("strings"):
        _compile_each_string_once(environment)
    if on("jinja_code"):
        _compile_each_source_once_per_process(environment, plain_lines=on("plain_lines"))
    if on("git_file_mode"):
        _ask_git_for_the_file_mode_once_per_worker()
    if on("answers_file_name"):
        _render_the_answers_file_name_once_per_render()


@contextlib.contextmanager
def template_modules(folder: Path):
    """While it lasts, modules imported from `folder` (on sys.path) come with code from the
    cache, and so do the methods their dataclasses write."""
    if on("python_code"):
        import_from(folder)
    if on("dataclasses"):
        with dataclass_methods_kept():
            yield
    else:
        yield


# ─── The cache of compiled code ───────────────────────────────────────────────
# Kept by what was compiled (the source, hashed) and by what compiled it (Python's
# bytecode version and flags; for Jinja, the environment's settings): a changed source,
# another Jinja or another Python compiles anew. One file per compiler; a file that
# cannot be read or written is passed over.

_FORMAT = 1
_MAX_CODES = 5000  # per file; past it, a run keeps only the code it used
_STORES = "rna_template_code_stores"  # process-wide: the glue is loaded afresh for each Jinja environment


def folder() -> Path | None:
    """Where the code is kept, or None when caching is turned off."""
    chosen = os.environ.get("RNA_TEMPLATE_CACHE_DIR")
    if chosen is not None:
        return Path(chosen) if chosen else None
    from platformdirs import user_cache_dir  # Copier's own choice for its cache

    return Path(user_cache_dir("rna-template", appauthor=False)) / "code"


class Store:
    """The code objects of one compiler: read at first use, written back at exit when it grew.

    Kept process-wide and used by other template versions: its methods only ever grow.
    """

    def __init__(self, path: Path | None):
        self.path = path
        self.codes = self._read() if path is not None else {}
        self.used: set[bytes] = set()
        self.added = False
        if path is not None:
            atexit.register(self.save)

    def get(self, key: object):
        digest = _digest(key)
        code = self.codes.get(digest)
        if code is not None:
            self.used.add(digest)
        return code

    def put(self, key: object, code) -> None:
        digest = _digest(key)
        self.codes[digest] = code
        self.used.add(digest)
        self.added = True

    def save(self) -> None:
        """Merge what this process compiled into the file (other processes may have written it)."""
        if not self.added or self.path is None:
            return
        codes = {**self._read(), **self.codes}
        if len(codes) > _MAX_CODES:
            codes = {digest: codes[digest] for digest in self.used}
        written = None
        try:
            self.path.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
            with tempfile.NamedTemporaryFile("wb", dir=self.path.parent, prefix=".tmp-", delete=False) as file:
                written = file.name
                marshal.dump((_FORMAT, codes), file)
            os.replace(written, self.path)  # whole or not at all, for a process reading it now
        except (OSError, ValueError):
            if written is not None:
                Path(written).unlink(missing_ok=True)
        self.added = False

    def _read(self) -> dict:
        try:
            data = marshal.loads(self.path.read_bytes())  # not through rna/files.py: the template's cache
        except (OSError, EOFError, ValueError, TypeError):
            return {}
        if not (isinstance(data, tuple) and len(data) == 2 and data[0] == _FORMAT and isinstance(data[1], dict)):
            return {}
        return data[1]


def _digest(key: object) -> bytes:
    return hashlib.blake2b(repr(key).encode("utf-8", "surrogatepass"), digest_size=20).digest()


def store(kind: str, compiler: str) -> Store:
    """The store of one compiler (`compiler` names it whole: settings, versions), one per process."""
    stores = sys.modules.setdefault(_STORES, types.ModuleType(_STORES)).__dict__
    python = f"{importlib.util.MAGIC_NUMBER.hex()}|{sys.version}|{sys.flags.optimize}"  # -O drops asserts
    name = hashlib.blake2b(f"{compiler}|{python}".encode(), digest_size=12).hexdigest()
    key = f"{kind}-{name}"
    if key not in stores:
        where = folder()
        stores[key] = Store(where / f"{key}.marshal" if where is not None else None)
    return stores[key]


# ─── python_code ──────────────────────────────────────────────────────────────


class _CachedSourceLoader(importlib.machinery.SourceFileLoader):
    """Python's loader for source files, with code from the store, and no __pycache__ written."""

    def get_code(self, fullname):
        path = self.get_filename(fullname)
        source = self.get_data(path)
        codes = store("python", "")
        key = (fullname, hashlib.sha256(source).hexdigest())
        code = codes.get(key)
        if code is None:
            code = self.source_to_code(source, path)
            codes.put(key, code)
        else:
            import _imp

            _imp._fix_co_filename(code, path)  # what importlib does with code read from a .pyc
        return code


def import_from(root: Path) -> None:
    """Have modules under `root` (a folder on sys.path) imported with code from the store."""
    prefix = str(root)
    if any(getattr(hook, "rna_template_root", None) == prefix for hook in sys.path_hooks):
        return

    def finder(path: str):
        if path != prefix and not path.startswith(prefix + os.sep):
            raise ImportError("not the template's folder")
        return importlib.machinery.FileFinder(path, (_CachedSourceLoader, importlib.machinery.SOURCE_SUFFIXES))

    finder.rna_template_root = prefix
    sys.path_hooks.insert(0, finder)
    sys.path_importer_cache.pop(prefix, None)


# ─── dataclasses ──────────────────────────────────────────────────────────────


@contextlib.contextmanager
def dataclass_methods_kept():
    """While it lasts, the methods `dataclasses` writes for a class come compiled from the store.

    `@dataclass` writes each method's source from the fields and compiles it, for every
    class, in every run. The source is compiled as `dataclasses` compiles it (by `exec`,
    with no future imports), so the code is the same (tests/test_speedups.py compares it).
    """
    import dataclasses

    codes = store("python", "dataclasses")

    def exec_kept(source, globals=None, locals=None, /):  # noqa: A002 - exec's own names
        if isinstance(source, str):
            code = codes.get(source)
            if code is None:
                code = compile(source, "<string>", "exec", dont_inherit=True)
                codes.put(source, code)
            source = code
        return builtins.exec(source, globals, locals)

    before = vars(dataclasses).get("exec")  # another's, when this is nested in it
    dataclasses.exec = exec_kept  # found before the builtin by the module's own calls
    try:
        yield
    finally:
        if before is None:
            del dataclasses.exec
        else:
            dataclasses.exec = before


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
            codes = store("jinja", signature)
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


# ─── git_file_mode ────────────────────────────────────────────────────────────


def _ask_git_for_the_file_mode_once_per_worker() -> None:
    """Copier asks git for `core.fileMode` after writing each file, a git process per file
    (Worker._sync_git_index_executable_bit changes git's index only when that setting is
    false). The answer is the same for every file one worker writes: it is asked once per
    worker (its Jinja environment holds it), and Copier's method runs when it is false.
    """
    from copier._main import Worker

    sync = Worker._sync_git_index_executable_bit
    if getattr(sync, "rna_once_per_worker", False):  # another load, or another template version, did it
        return

    @functools.wraps(sync)
    def once_per_worker(self, dst_relpath, src_mode):
        settings = self.jinja_env.__dict__.setdefault("rna_git_file_mode", {})
        root = str(self.subproject.local_abspath)
        if root not in settings:
            settings[root] = _git_file_mode(root)
        if settings[root] != "false":
            return None
        return sync(self, dst_relpath, src_mode)

    once_per_worker.rna_once_per_worker = True
    Worker._sync_git_index_executable_bit = once_per_worker


def _git_file_mode(root: str) -> str | None:
    """`git config --type=bool --get core.fileMode` in `root`, or None (no repository, unset, no git)."""
    try:
        result = subprocess.run(["git", "config", "--type=bool", "--get", "core.fileMode"], cwd=root,
                                capture_output=True, text=True, check=False)
    except OSError:
        return None
    return result.stdout.strip() if result.returncode == 0 else None


# ─── answers_file_name ────────────────────────────────────────────────────────


def _render_the_answers_file_name_once_per_render() -> None:
    """Copier renders the answers file's name (`_answers_file`, templated here) anew for each
    file it renders, and each time a context hook reads `_copier_conf.answers_file`.

    While a worker renders its files (Copier's render phase), its answers are final, so the
    name is too: it is rendered once per render phase of a worker (its Jinja environment
    holds it) and asked anew in every other phase. A kept name is preprocessed all the
    same, as compiling it would: Copier's yield tag resets its state there, and Copier
    checks that state after rendering each file.
    """
    from copier._main import Worker
    from copier._types import Phase

    answers_relpath = Worker.answers_relpath
    if getattr(answers_relpath.fget, "rna_once_per_render", False):
        return
    render_name = answers_relpath.fget

    @functools.wraps(render_name)
    def once_per_render(self):
        if Phase.current() is not Phase.RENDER:
            return render_name(self)
        held = self.jinja_env.__dict__.get("rna_answers_relpath")
        if held is None or held[0] is not self.answers:  # the answers object is the worker's render's
            held = self.jinja_env.__dict__["rna_answers_relpath"] = (self.answers, render_name(self))
        else:
            self.jinja_env.preprocess(str(self.answers_file or self.template.answers_relpath))
        return held[1]

    once_per_render.rna_once_per_render = True
    Worker.answers_relpath = property(once_per_render, doc=answers_relpath.__doc__)
