"""What copier.yml names as the template's Jinja extension: copier_glue.py, its code kept.

Copier imports an extension by its file's path, compiling it in every run (its clone of
the template has no __pycache__) and in each of its Jinja environments (four in an
update): copier_glue.py, about 800 lines, took about 8 ms to compile each time (20 ms
on a busy machine). Only this file is compiled so; the glue is imported by its plain
name, with its code from the code cache (code_cache.py), and executed afresh for each
environment, as Copier would: its module state is meant to last one Copier worker.
"""

from __future__ import annotations

import sys
from pathlib import Path

_HERE = Path(__file__).resolve().parent


def _from_here(name: str) -> bool:
    origin = getattr(sys.modules.get(name), "__file__", None) or ""
    return Path(origin).resolve().parent == _HERE


if "code_cache" in sys.modules and not _from_here("code_cache"):
    del sys.modules["code_cache"]  # another checkout's: an update loads two template versions
sys.modules.pop("copier_glue", None)  # an earlier environment's
sys.path.insert(0, str(_HERE))
try:
    import code_cache

    code_cache.import_from(_HERE)
    from copier_glue import RnaExtension
finally:
    sys.path.remove(str(_HERE))

__all__ = ["RnaExtension"]
