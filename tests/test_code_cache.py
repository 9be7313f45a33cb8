"""Compiled code kept between Copier runs (extensions/code_cache.py): found again, never wrong.

A run that finds the code compiles nothing and writes the same package; a file that does
not read, a changed source or a cache turned off mean compiling as before.
"""

from __future__ import annotations

import dataclasses
import filecmp
import marshal
import os
import subprocess
import sys
from pathlib import Path

import code_cache
import pytest
from copier._main import Worker
from hypothesis import example, given, settings
from hypothesis import strategies as st

from support.generation import FIXED_ANSWERS, copy_counted, snapshot_template, subprocess_env

# What a Copier run compiled: how many Jinja sources, and which Python files.
COUNTING = """
    import importlib.machinery
    import jinja2
    counted = {"jinja": 0, "python": []}
    jinja_compile = jinja2.Environment.compile
    def counting(self, source, name=None, filename=None, raw=False, defer_init=False):
        counted["jinja"] += not raw and isinstance(source, str) and "{" in source  # Jinja, not plain text
        return jinja_compile(self, source, name, filename, raw, defer_init)
    jinja2.Environment.compile = counting
    python_compile = importlib.machinery.SourceFileLoader.source_to_code
    def counting_python(self, data, path, *args, **kwargs):
        counted["python"].append(path)
        return python_compile(self, data, path, *args, **kwargs)
    importlib.machinery.SourceFileLoader.source_to_code = counting_python
"""


def copy_counting(template: Path, run: Path, cache: str) -> dict:
    """A copy into run/robot (the package's name comes from its folder)."""
    run.mkdir()
    compiled = copy_counted(COUNTING, template, run / "robot", FIXED_ANSWERS, {"RNA_TEMPLATE_CACHE_DIR": cache})
    compiled["python"] = [path for path in compiled["python"] if "/extensions/" in path]
    return compiled


def differing_files(left: Path, right: Path) -> list[str]:
    """The files that differ between two trees (none when they are the same)."""
    comparison = filecmp.dircmp(left, right, ignore=[".git"])
    differ = [*comparison.left_only, *comparison.right_only, *comparison.diff_files, *comparison.funny_files]
    for sub in comparison.subdirs.values():
        differ += differing_files(Path(sub.left), Path(sub.right))
    return differ


def test_a_second_run_compiles_nothing_but_a_changed_file_and_writes_the_same_package(tmp_path):
    template = snapshot_template(tmp_path / "template")
    cache = tmp_path / "cache"
    first = copy_counting(template, tmp_path / "first", str(cache))
    second = copy_counting(template, tmp_path / "second", str(cache))
    off = copy_counting(template, tmp_path / "off", "")
    assert first["jinja"] > 10 and len(first["python"]) > 10
    # Copier loads the extension by its path, and the extension the cache, with Python's loader (a .pyc in the
    # clone at best); the glue and everything after it come from the cache.
    assert second["jinja"] == 0
    assert {Path(path).name for path in second["python"]} == {"copier_extension.py", "code_cache.py"}
    assert off["jinja"] == first["jinja"]
    assert sorted(path.name for path in cache.iterdir()) == sorted(path.name for path in cache.glob("*.marshal"))
    assert not differing_files(tmp_path / "first", tmp_path / "second")
    assert not differing_files(tmp_path / "first", tmp_path / "off")

    # A template file changed (a fork's own line) is compiled again, alone.
    readme = template / "template" / "README.md.jinja"
    readme.write_text(readme.read_text() + "\nA line of the lab's own.\n")
    subprocess.run(["git", "commit", "-qam", "lab line"], cwd=template, env=subprocess_env(), check=True)
    changed = copy_counting(template, tmp_path / "changed", str(cache))
    assert changed["jinja"] == 1
    assert "A line of the lab's own." in (tmp_path / "changed" / "robot" / "README.md").read_text()


def test_code_is_found_again_by_what_was_compiled(tmp_path):
    store = code_cache.Store(tmp_path / "codes.marshal")
    code = compile("answer = 42", "<test>", "exec")
    store.put(("answer = 42", "name", False), code)
    store.save()
    again = code_cache.Store(tmp_path / "codes.marshal")
    assert again.get(("answer = 42", "name", False)) == code
    assert again.get(("answer = 43", "name", False)) is None
    assert again.get(("answer = 42", "other name", False)) is None


def test_a_file_that_does_not_read_is_passed_over_and_written_anew(tmp_path):
    path = tmp_path / "codes.marshal"
    for broken in (b"", b"not marshal", marshal.dumps(("another format", {})), marshal.dumps([1, 2])):
        path.write_bytes(broken)
        store = code_cache.Store(path)
        assert store.get("anything") is None
        store.put("anything", compile("x = 1", "<test>", "exec"))
        store.save()
        assert code_cache.Store(path).get("anything") is not None


def test_saving_merges_what_other_processes_wrote(tmp_path):
    path = tmp_path / "codes.marshal"
    one, other = code_cache.Store(path), code_cache.Store(path)
    one.put("one", compile("x = 1", "<one>", "exec"))
    other.put("other", compile("x = 2", "<other>", "exec"))
    one.save()
    other.save()
    merged = code_cache.Store(path)
    assert merged.get("one") is not None and merged.get("other") is not None


def test_past_its_size_a_file_keeps_the_code_of_the_last_run(tmp_path, monkeypatch):
    path = tmp_path / "codes.marshal"
    old = code_cache.Store(path)
    for index in range(5):
        old.put(f"old {index}", compile(f"x = {index}", "<old>", "exec"))
    old.save()
    monkeypatch.setattr(code_cache, "_MAX_CODES", 4)
    run = code_cache.Store(path)
    run.get("old 0")
    run.put("new", compile("y = 1", "<new>", "exec"))
    run.save()
    kept = code_cache.Store(path)
    assert [kept.get(key) is not None for key in ("old 0", "old 1", "new")] == [True, False, True]


def test_turned_off_or_unwritable_it_only_compiles(tmp_path, monkeypatch):
    monkeypatch.setenv("RNA_TEMPLATE_CACHE_DIR", "")
    assert code_cache.folder() is None
    store = code_cache.Store(None)
    store.put("key", compile("x = 1", "<test>", "exec"))
    store.save()
    (tmp_path / "file").write_text("not a folder")
    blocked = code_cache.Store(tmp_path / "file" / "codes.marshal")
    blocked.put("key", compile("x = 1", "<test>", "exec"))
    blocked.save()  # no error: the run goes on without a cache
    assert sorted(os.listdir(tmp_path)) == ["file"]


def test_the_template_folder_is_left_without_pycache(tmp_path):
    template = snapshot_template(tmp_path / "template")
    env = {**subprocess_env(), "RNA_TEMPLATE_CACHE_DIR": str(tmp_path / "cache")}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    script = f"import sys; sys.path.insert(0, {str(template / 'extensions')!r}); import code_cache; " \
             f"code_cache.import_from(__import__('pathlib').Path({str(template / 'extensions')!r})); import rna"
    for _ in range(2):
        subprocess.run([sys.executable, "-c", script], env=env, check=True, timeout=60)
    assert {path.name.partition(".")[0] for path in template.rglob("*.pyc")} <= {"code_cache"}  # imported first
    assert list((tmp_path / "cache").glob("python-*.marshal"))


@pytest.fixture(scope="module")
def copier_environment(template_folder, tmp_path_factory):
    """The Jinja environment of a Copier worker on this template, the glue's compiling in it."""
    return Worker(src_path=str(template_folder), dst_path=tmp_path_factory.mktemp("robot"), unsafe=True).jinja_env


ONE_LINE = st.text(st.characters(blacklist_characters="\r\n"), min_size=1).filter(
    lambda text: not any(start in text for start in ("{{", "{%", "{#")))


@settings(max_examples=300, deadline=None)
@given(text=ONE_LINE)
@example(text="xxxx")  # a stand-in line itself
@example(text="a separate package, robot_interfaces")
@example(text="}} %} #} {")
@example(text="'\"\\\x00\udc80 ✓")
def test_a_line_of_plain_text_gets_the_code_jinja_compiles_for_it(copier_environment, text):
    # The glue's code (a kept stand-in line's code with the text in place) against Jinja's own.
    compiled = copier_environment.compile(text)
    assert compiled == type(copier_environment).compile(copier_environment, text)
    assert copier_environment.from_string(text).render() == text


def _record_class():
    @dataclasses.dataclass(frozen=True)
    class Record:
        name: str
        rate: float = 10.0
        topics: tuple = dataclasses.field(default_factory=tuple)

    return Record


METHODS = ("__init__", "__repr__", "__eq__", "__hash__", "__setattr__", "__delattr__")


def test_dataclass_methods_come_compiled_from_the_store_as_dataclasses_compiles_them(monkeypatch):
    made_by_dataclasses = _record_class()
    compiled = []

    def counting(*args, **kwargs):
        compiled.append(args)
        return compile(*args, **kwargs)

    monkeypatch.setattr(code_cache, "compile", counting, raising=False)
    with code_cache.dataclass_methods_kept():
        first = _record_class()
    with code_cache.dataclass_methods_kept(), code_cache.dataclass_methods_kept():  # nested, as a load may be
        again = _record_class()
    assert "exec" not in vars(dataclasses)  # the builtin again, for everyone else
    assert len(compiled) <= len(METHODS)  # the first class compiled at most each method once, the second nothing
    for record in (first, again):
        for method in METHODS:
            assert getattr(record, method).__code__ == getattr(made_by_dataclasses, method).__code__, method
        made = record("driver")
        assert made == record("driver", 10.0, ()) and made != record("planner")
        assert repr(made).endswith("Record(name='driver', rate=10.0, topics=())")
        with pytest.raises(dataclasses.FrozenInstanceError):
            made.name = "planner"


def test_code_that_does_not_hold_the_stand_in_line_is_not_taken_for_it():
    import copier_glue

    code = compile("yield_me = 'a line'", "<test>", "exec")
    assert copier_glue._with_constant(code, "xxxx", "text") is None  # the caller compiles the text itself
    replaced = copier_glue._with_constant(compile("def f():\n    return 'xxxx'\n", "<test>", "exec"), "xxxx", "text")
    namespace = {}
    exec(replaced, namespace)
    assert namespace["f"]() == "text"
