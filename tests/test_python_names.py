"""The rules on names read Python's names from data (rna/python_names.py), not from the
Python that runs Copier: an answer valid under 3.11 is valid under 3.12 and 3.13 (the
compat tier runs this file under each)."""

from __future__ import annotations

import builtins
import keyword
import sys

from rna import names, python_names


def test_the_lists_hold_the_running_pythons_own():
    assert set(keyword.kwlist) == python_names.KEYWORDS  # the same hard keywords from 3.8 on
    assert set(sys.stdlib_module_names) <= python_names.STDLIB_MODULES
    assert {"_", "case", "match"} == python_names.SOFT_KEYWORDS
    assert {"ExceptionGroup", "Exception", "None"} <= python_names.CAPITALIZED_BUILTINS
    new = {name for name in dir(builtins) if name[:1].isupper()} - python_names.CAPITALIZED_BUILTINS
    assert new <= {"PythonFinalizationError"}, new  # 3.13's; not refused, as under 3.11


def test_a_name_is_judged_the_same_under_every_python():
    assert names.keyword_error("type") is None  # a soft keyword from 3.12 on, a valid name in all
    assert names.keyword_error("match") == "choose another name: 'match' is a Python keyword"
    assert "standard library" in names.generated_package_name_error("telnetlib")  # gone from 3.13's
