"""Patches: every change this template makes to another library's behaviour, in one place.

The template's own code (copier_glue.py, `rna`) uses Copier, Jinja and questionary as they
document. Everything it changes in how Copier, Jinja, prompt_toolkit and Python behave is
here, each change a named patch, for one of two reasons:

Speed (docs/pages/reference/performance.md gives each one's share of a default copy, a
50-node copy and an update; decision 15 says why each is kept). Copier, Jinja and Python
redo work in every run that a template of this size pays for many times over; each of
these changes how a library does one thing, never what it produces.

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

Prompts (issue 30): what Copier's prompts show at a terminal, never what is asked or answered.

  whole_errors       prompt_toolkit shows an answer's error in a toolbar one row high, cut
                     at the terminal's edge: here it is shown whole, wrapped, without
                     Copier's lead (the question is the line above it).
  fitted_questions   prompt_toolkit cuts a question's lines and a menu's choices at the
                     terminal's edge: here they are wrapped between words.

Each patch has a guard that turns it off when the library is not the one it was written
for (its major version, and the shape of what it replaces: a method's signature, a name
the library looks up), and the output is the same with all of them off
(tests/test_patches.py; the compat tier, tests/test_compat.py, also against the newest
Copier, copier-template-extensions, Jinja, questionary and prompt_toolkit).

RNA_TEMPLATE_PATCHES_OFF=all turns every one off (the template then runs on the libraries'
documented behaviour alone); a comma-separated list of names, or of the groups `speed` and
`prompts`, turns those off. RNA_TEMPLATE_CACHE_DIR moves the cache folder of the compiled
code; set empty, nothing is kept between runs.

Imported by plain name, before `rna`, by what Copier loads or runs: copier_glue.py,
after_update.py, add_node.py; its modules import Copier, Jinja and prompt_toolkit only when
a patch of theirs is asked about (the after-update step loads no Copier). Several template
versions can run in one process (an update renders the old and the new one): what is
process-wide (the cache's stores, the marks on Copier's methods) is shared with them, so
its names and methods only grow.
"""

from __future__ import annotations

import contextlib
import functools
import os
from pathlib import Path

from . import code_cache

_HOLDERS = {"code_cache": code_cache}  # the modules of this package, by name (the others join at the end)
SWITCH = "RNA_TEMPLATE_PATCHES_OFF"

# Each patch, by group, and the module of this package that holds it with its guard.
GROUPS = {
    "speed": {"strings": "jinja", "jinja_code": "jinja", "plain_lines": "jinja", "python_code": "code_cache",
              "dataclasses": "code_cache", "git_file_mode": "copier_worker", "answers_file_name": "copier_worker"},
    "prompts": {"whole_errors": "prompts", "fitted_questions": "prompts"},
}
MODULES = {name: module for patches in GROUPS.values() for name, module in patches.items()}
NAMES = tuple(MODULES)


def status() -> dict[str, str]:
    """Each patch's state: "on", or "off: " and why (the switch, or what its guard found)."""
    return {name: state(name) for name in NAMES}


def on(name: str) -> bool:
    return state(name) == "on"


def state(name: str) -> str:
    """One patch's state, its guard asked only for it (the after-update step, which loads the
    template's modules, must not import Copier to learn of a patch of Copier's)."""
    found = _state(name, os.environ.get(SWITCH, ""))
    late_finding = getattr(_module(name), "late_finding", None)  # a guard that needs a run to ask
    if found == "on" and late_finding is not None and (reason := late_finding(name)) is not None:
        return f"off: {reason}"
    return found


@functools.lru_cache(maxsize=64)
def _state(name: str, switch: str) -> str:
    turned_off = {part.strip() for part in switch.split(",") if part.strip()}
    groups = {group for group, patches in GROUPS.items() if name in patches}
    if turned_off & {name, "all", "1", "true", "yes", *groups}:
        return f"off: {SWITCH}={switch}"
    needed = _module(name).NEEDS.get(name)
    if needed is not None and _state(needed, switch) != "on":
        return f"off: it works through {needed}, which is off"
    reason = _module(name).GUARDS[name]()
    return "on" if reason is None else f"off: {reason}"


def _module(name: str):
    """The module of this package that holds the patch `name`."""
    return _HOLDERS[MODULES[name]]


def install(environment) -> None:
    """Turn on, for a Copier worker's Jinja environment, the patches that are on (those that
    change a library as a whole are made once per process)."""
    for module in dict.fromkeys(MODULES.values()):
        if any(on(name) for name, holder in MODULES.items() if holder == module):
            _HOLDERS[module].install(environment, on)


@contextlib.contextmanager
def template_modules(folder: Path):
    """While it lasts, modules imported from `folder` (on sys.path) come with code from the
    cache, and so do the methods their dataclasses write."""
    with code_cache.template_modules(folder, on):
        yield


# The rest of the package after the cache: with python_code on, its code comes from there.
if on("python_code"):
    code_cache.import_from(Path(__file__).resolve().parents[1])
from . import copier_worker, jinja, prompts  # noqa: E402

_HOLDERS.update(copier_worker=copier_worker, jinja=jinja, prompts=prompts)
