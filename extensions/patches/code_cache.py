"""The cache of compiled code, and the patches that read Python's code from it: `python_code`
(the template's modules) and `dataclasses` (the methods `dataclasses` writes for a class).

Code is kept by what was compiled (the source, hashed) and by what compiled it (Python's
bytecode version and flags; for Jinja, the environment's settings, patches/jinja.py): a
changed source, another Jinja or another Python compiles anew. One file per compiler in the
user's cache folder; a file that cannot be read or written is passed over.
"""

from __future__ import annotations

import atexit
import builtins
import contextlib
import hashlib
import importlib.machinery
import importlib.util
import marshal
import os
import sys
import tempfile
import types
from pathlib import Path

PYTHONS = ((3, 11), (3, 12), (3, 13))  # dataclasses' own compiling, as checked on each

_FORMAT = 1
_MAX_CODES = 5000  # per file; past it, a run keeps only the code it used
_STORES = "rna_template_code_stores"  # process-wide: the glue is loaded afresh for each Jinja environment


# ─── Guards ───────────────────────────────────────────────────────────────────


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


GUARDS = {"python_code": _python_code_differs, "dataclasses": _dataclasses_differ}
NEEDS: dict[str, str] = {}


def install(environment, on) -> None:
    """Nothing to do per Jinja environment: these patches act while the template's modules load."""


@contextlib.contextmanager
def template_modules(folder: Path, on):
    """While it lasts, modules imported from `folder` (on sys.path) come with code from the
    cache (`python_code`), and so do the methods their dataclasses write (`dataclasses`)."""
    if on("python_code"):
        import_from(folder)
    if on("dataclasses"):
        with dataclass_methods_kept():
            yield
    else:
        yield


# ─── The stores ───────────────────────────────────────────────────────────────


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
    for path in [path for path in sys.path_importer_cache
                 if isinstance(path, str) and (path == prefix or path.startswith(prefix + os.sep))]:
        del sys.path_importer_cache[path]  # found before: the rest of this package, imported later, comes through it


# ─── dataclasses ──────────────────────────────────────────────────────────────


@contextlib.contextmanager
def dataclass_methods_kept():
    """While it lasts, the methods `dataclasses` writes for a class come compiled from the store.

    `@dataclass` writes each method's source from the fields and compiles it, for every
    class, in every run. The source is compiled as `dataclasses` compiles it (by `exec`,
    with no future imports), so the code is the same (tests/test_patches.py compares it).
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
