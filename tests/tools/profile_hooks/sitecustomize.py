"""Phase timers for every Python process of a profiled Copier run (tests/tools/profiling.py).

tests/tools/profiling.py puts this folder on PYTHONPATH, so Python imports this file at
start-up in the `copier` process and in every Python process it starts (the template's
tasks and migrations, and the Copier runs inside them). With RNA_BENCH_PROFILE_DIR set it:

* wraps a few functions of Copier, Jinja and the template (by name, after their module
  is imported) so that each adds its *exclusive* wall time (its time minus that of the
  wrapped calls inside it) to a named phase;
* counts module imports as phases too ("import: <top-level package>", or "import:
  template extensions" for modules outside the Python installation: the template's own
  Python, imported from Copier's fresh clone, hence compiled on every run);
* with RNA_BENCH_CPROFILE=1, runs cProfile for the whole process instead of measuring
  phases (cProfile slows Python code down unevenly, so the two are separate runs);
* at exit, writes <pid>.json (and <pid>.prof) into RNA_BENCH_PROFILE_DIR.

Without RNA_BENCH_PROFILE_DIR it does nothing.
"""

from __future__ import annotations

import os
import time

_DIRECTORY = os.environ.get("RNA_BENCH_PROFILE_DIR")
_START = time.perf_counter()

if _DIRECTORY:
    import atexit
    import functools
    import importlib._bootstrap_external as _external
    import json
    import subprocess
    import sys

    _totals: dict[str, list[float]] = {}  # phase -> [seconds, calls]
    _stack: list[list] = []  # [phase, started, seconds spent in wrapped calls inside]
    _profiler = None
    _PREFIXES = tuple({os.path.realpath(p) for p in (sys.prefix, sys.base_prefix, sys.exec_prefix)})

    def _add(phase: str, seconds: float) -> None:
        entry = _totals.setdefault(phase, [0.0, 0])
        entry[0] += seconds
        entry[1] += 1

    def _timed(phase, function):
        """`function`, adding its exclusive time to `phase` (a name, or a callable of its arguments)."""

        @functools.wraps(function)
        def wrapper(*args, **kwargs):
            frame = [phase(*args, **kwargs) if callable(phase) else phase, time.perf_counter(), 0.0]
            _stack.append(frame)
            try:
                return function(*args, **kwargs)
            finally:
                _stack.pop()
                elapsed = time.perf_counter() - frame[1]
                _add(frame[0], elapsed - frame[2])
                if _stack:
                    _stack[-1][2] += elapsed

        wrapper.__rna_bench_wrapped__ = True
        return wrapper

    def _wrap(owner, name: str, phase) -> None:
        function = getattr(owner, name, None)
        if function is not None and not getattr(function, "__rna_bench_wrapped__", False):
            setattr(owner, name, _timed(phase, function))

    def _wrap_cached(owner, name: str, phase) -> None:
        """A functools.cached_property's function."""
        prop = owner.__dict__.get(name)
        if prop is not None and not getattr(prop.func, "__rna_bench_wrapped__", False):
            prop.func = _timed(phase, prop.func)

    def _enclosing() -> str:
        return _stack[-1][0] if _stack else "outside the timed phases"

    def _subprocess_phase(*args, **kwargs) -> str:
        argv = args[0] if args else kwargs.get("args", "")
        argv = argv.split() if isinstance(argv, str) else [str(part) for part in argv]
        program = os.path.basename(argv[0]) if argv else "?"
        if program.startswith("python") and len(argv) > 1:
            return f"process: {os.path.basename(argv[1])}"
        return f"{program}: {_enclosing()}"

    # ─── What to time, applied when each module has been imported ──────────────

    def _patch_copier_vcs(module) -> None:
        _wrap(module, "clone", "clone the template (git clone, checkout)")

    def _patch_copier_template(module) -> None:
        _wrap(module, "load_template_config", "read copier.yml")
        for name, phase in (("version", "template version (git describe)"),
                            ("git_index_modes", "template file modes (git ls-files)"),
                            ("commit", "template commit (git)")):
            _wrap_cached(module.Template, name, phase)
        _wrap(module.Template, "_cleanup", "remove the clone")

    def _patch_copier_main(module) -> None:
        worker = module.Worker
        _wrap(worker, "_ask", "answers (copier.yml defaults and validators)")
        _wrap(worker, "_render_template", "render: Copier + Jinja (paths, files, writes)")
        _wrap(worker, "_execute_tasks", "tasks and migrations (Copier side)")
        _wrap(worker, "_apply_update", "update: Copier's diff and apply")
        _wrap_cached(worker, "jinja_env", "Jinja environment")

    def _patch_jinja_environment(module) -> None:
        def phase(environment, source, name=None, *args, **kwargs):
            return "Jinja compile: template files" if name else "Jinja compile: strings (paths, copier.yml values)"

        _wrap(module.Environment, "compile", phase)

    def _patch_plumbum(module) -> None:
        _wrap(module.BaseCommand, "run", lambda command, *a, **k: f"git: {_enclosing()}")

    def _patch_context_hook(module) -> None:
        base = module.ContextHook

        def init_subclass(cls, **kwargs):
            super(base, cls).__init_subclass__(**kwargs)
            _wrap(cls, "hook", f"model: {cls.__name__}.hook (the template's context hook)")

        base.__init_subclass__ = classmethod(init_subclass)

    def _patch_template_module(module) -> None:
        _wrap(module, "build_package", "model: build_package (answers -> package model)")

    _PATCHES = {
        "copier._vcs": _patch_copier_vcs,
        "copier._template": _patch_copier_template,
        "copier._main": _patch_copier_main,
        "jinja2.environment": _patch_jinja_environment,
        "plumbum.commands.base": _patch_plumbum,
        "copier_template_extensions._internal.context": _patch_context_hook,
    }

    def _import_phase(loader, module) -> str:
        origin = os.path.realpath(getattr(module, "__file__", None) or "/")
        if not origin.startswith(_PREFIXES):
            return "import: template extensions"
        return f"import: {module.__name__.partition('.')[0]}"

    def _patched_exec(exec_module):
        timed = _timed(_import_phase, exec_module)

        def exec_and_patch(loader, module):
            timed(loader, module)
            patch = _PATCHES.get(module.__name__)
            if patch is None and _import_phase(loader, module) == "import: template extensions":
                patch = _patch_template_module
            if patch is not None:
                patch(module)

        return exec_and_patch

    def _report() -> None:
        if _profiler is not None:
            _profiler.disable()
            _profiler.dump_stats(os.path.join(_DIRECTORY, f"{os.getpid()}.prof"))
        record = {"pid": os.getpid(), "ppid": os.getppid(), "argv": sys.argv,
                  "seconds": time.perf_counter() - _START, "phases": _totals}
        with open(os.path.join(_DIRECTORY, f"{os.getpid()}.json"), "w") as handle:
            json.dump(record, handle)

    if os.environ.get("RNA_BENCH_CPROFILE") == "1":
        import cProfile

        _profiler = cProfile.Profile()
        _profiler.enable()
    else:
        _external._LoaderBasics.exec_module = _patched_exec(_external._LoaderBasics.exec_module)
        _external.ExtensionFileLoader.exec_module = _patched_exec(_external.ExtensionFileLoader.exec_module)
        subprocess.run = _timed(_subprocess_phase, subprocess.run)
    atexit.register(_report)
