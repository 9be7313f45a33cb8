"""The patches (extensions/patches/): each does what it says, never changes the output, is
turned off by its switch and by its guard.

Work that Copier runs are spared by the speed-ups is counted in a Copier process of its
own, and the package each run writes is compared byte for byte: a first run, a run that
finds the compiled code kept, and a run with the patches off. What the prompt patches show
is read off a terminal emulator. The compat tier (tests/test_compat.py) compares every
example answers file and a sample of the update tier's cases on and off, and runs this
file, under the newest Copier, copier-template-extensions, Jinja, questionary and
prompt_toolkit, and under Python 3.12 and 3.13.
"""

from __future__ import annotations

import dataclasses
import marshal
import os
import subprocess
import sys
from pathlib import Path

import patches
import pytest
from copier._main import Worker
from copier._user_data import Question
from patches import code_cache, jinja
from hypothesis import example, given, settings
from hypothesis import strategies as st

from support.generation import FIXED_ANSWERS, copy_counted, git, snapshot_template, subprocess_env, tree

OFF = {patches.SWITCH: "all"}
EXTENSIONS = Path(patches.__file__).resolve().parents[1]


# ─── Switch and guards ────────────────────────────────────────────────────────


def test_one_variable_turns_every_patch_off_or_some_by_name_or_group(monkeypatch):
    monkeypatch.delenv(patches.SWITCH, raising=False)
    assert patches.status() == dict.fromkeys(patches.NAMES, "on")
    monkeypatch.setenv(patches.SWITCH, "all")
    assert all(state.startswith(f"off: {patches.SWITCH}") for state in patches.status().values())
    for switch, turned_off in (("strings, git_file_mode", ["strings", "git_file_mode"]),
                               ("prompts", ["whole_errors", "fitted_questions"]),
                               ("speed", list(patches.GROUPS["speed"])),
                               ("jinja_code", ["jinja_code", "plain_lines"])):  # plain lines take its code
        monkeypatch.setenv(patches.SWITCH, switch)
        states = patches.status()
        assert [name for name in patches.NAMES if states[name] != "on"] == turned_off, switch


class _OtherToolbar:
    def __init__(self, show_position=False, wrap=True):
        pass


@pytest.mark.parametrize(("where", "attribute", "value", "turned_off"), [
    ("copier", "__version__", "10.0.0", {"git_file_mode", "answers_file_name", "fitted_questions"}),
    ("jinja2", "__version__", "4.0.0", {"strings", "jinja_code", "plain_lines"}),
    ("worker", "_sync_git_index_executable_bit", lambda self, path: None, {"git_file_mode"}),
    ("worker", "answers_relpath", "not a property", {"answers_file_name"}),
    ("worker", "subproject", None, {"git_file_mode"}),
    ("environment", "compile", lambda self, source: None, {"jinja_code", "plain_lines"}),
    ("environment", "from_string", lambda self, source: None, {"strings"}),
    ("sys", "version_info", (3, 10, 0, "final", 0), {"dataclasses"}),
    ("question", "get_questionary_structure", lambda self, answers: {}, {"fitted_questions"}),
    ("worker", "_ask", lambda self: None, {"fitted_questions"}),  # asks no question's structure
    ("prompt_toolkit", "__version__", "4.0.0", {"whole_errors"}),
    ("prompt_module", "ValidationToolbar", _OtherToolbar, {"whole_errors"}),
    ("prompt_session", "_create_layout", lambda self: None, {"whole_errors"}),  # makes no toolbar by that name
])
def test_a_library_that_differs_turns_its_patches_off(monkeypatch, where, attribute, value, turned_off):
    import importlib

    import copier
    import jinja2
    import prompt_toolkit

    monkeypatch.delenv(patches.SWITCH, raising=False)
    prompt_module = importlib.import_module("prompt_toolkit.shortcuts.prompt")
    owner = {"copier": copier, "jinja2": jinja2, "worker": Worker, "environment": jinja2.Environment,
             "sys": sys, "question": Question, "prompt_toolkit": prompt_toolkit, "prompt_module": prompt_module,
             "prompt_session": prompt_module.PromptSession}[where]
    monkeypatch.setattr(owner, attribute, value)
    patches._state.cache_clear()
    try:
        states = patches.status()
    finally:
        monkeypatch.undo()
        patches._state.cache_clear()
    assert {name for name, state in states.items() if state != "on"} == turned_off, states


def test_dataclasses_that_compile_otherwise_turn_their_speed_up_off():
    import types

    without_exec = types.ModuleType("dataclasses")
    exec("def _create_fn(name, args, body):\n    return compile(body, name, 'exec')\n", vars(without_exec))
    assert code_cache._dataclasses_differ(without_exec) == "dataclasses does not call exec by name"
    assert code_cache._dataclasses_differ() is None


def test_the_template_modules_load_without_importing_copier(tmp_path):
    # The after-update step and add_node load them; importing Copier would double their work.
    script = f"import sys; sys.path.insert(0, {str(EXTENSIONS)!r}); import patches\n" \
             f"with patches.template_modules(__import__('pathlib').Path({str(tmp_path)!r})): pass\n" \
             "print(sorted(name for name in sys.modules if name.split('.')[0] in ('copier', 'jinja2')))"
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True,
                            env={**subprocess_env(), "RNA_TEMPLATE_CACHE_DIR": str(tmp_path / "cache")})
    assert result.stdout.strip() == "[]", result.stdout


def test_turned_off_nothing_of_jinja_or_copier_is_replaced(template_folder, tmp_path, monkeypatch):
    monkeypatch.setenv(patches.SWITCH, "all")
    environment = Worker(src_path=str(template_folder), dst_path=tmp_path, unsafe=True).jinja_env
    assert "compile" not in vars(environment) and "from_string" not in vars(environment)
    with patches.template_modules(tmp_path):
        assert "exec" not in vars(dataclasses)
        assert not any(getattr(hook, "rna_template_root", None) == str(tmp_path) for hook in sys.path_hooks)


# ─── Prompts: what the terminal shows ─────────────────────────────────────────


def test_copiers_questions_and_choices_wrap_between_words_in_a_narrow_terminal(template_folder, tmp_path,
                                                                                monkeypatch):
    """fitted_questions, on Copier's own Question: every line of a question and of a choice fits
    40 columns (after the question mark's and the pointer's 3), and says what Copier's did."""
    from copier._user_data import AnswersMap

    monkeypatch.delenv(patches.SWITCH, raising=False)
    worker = Worker(src_path=str(template_folder), dst_path=tmp_path, unsafe=True)
    environment = worker.jinja_env  # loads the glue, which turns the patches on
    # A 40-column terminal, for whichever checkout's rna.terminal the process-wide patch was made with.
    monkeypatch.setattr(os, "get_terminal_size", lambda *_: os.terminal_size((40, 24)))
    answers = AnswersMap(init=dict(FIXED_ANSWERS))
    asked = 0

    def fits(text: str) -> bool:  # the first line after 3 columns (question mark or pointer), the others whole
        first, *others = text.split("\n")
        return len(first) <= 36 and all(len(line) <= 39 for line in others)

    def words(text: str) -> str:  # what is shown, wherever the lines break (a URL longer than a line, too)
        return "".join(text.split())

    for name, details in worker.template.questions_data.items():
        question = Question(answers=answers, context=worker._render_context(), jinja_env=environment,
                            settings=worker.settings, var_name=name, **details)
        fitted = question.get_questionary_structure()
        copiers = Question.get_questionary_structure.__wrapped__(question)
        assert words(fitted["message"]) == words(copiers["message"]), name
        assert fits(fitted["message"]), (name, fitted["message"])
        for choice, copiers_choice in zip(fitted.get("choices") or (), copiers.get("choices") or (), strict=True):
            assert words(choice.title) == words(copiers_choice.title) and choice.value == copiers_choice.value
            assert fits(choice.title), (name, choice.title)
        asked += len(copiers["message"]) > 39
        answers.user[name] = question.get_default()
    assert asked >= 10  # questions Copier would have shown cut


# An error as Copier words it, for a node name typed at a prompt, and a prompt in a terminal of 40 columns.
ERROR = ("Validation error for question 'node_name': use motor_driver: 'motor-driver' is not a valid node name "
         "(lower_snake_case: letters, digits and single underscores, starting with a letter)")
PROMPT = f"""
import sys
sys.path.insert(0, {str(EXTENSIONS)!r})
import patches, questionary
patches.install(None)
questionary.text("Node name", validate=lambda text: {ERROR!r}).unsafe_ask()
"""


@pytest.mark.parametrize("turned_off", ["speed", "speed,whole_errors"], ids=["on", "off"])
def test_an_answers_error_is_shown_whole_under_the_prompt(turned_off):
    """whole_errors, at a real terminal: the error wrapped at its width, without Copier's lead
    (the question is the line above it); off, prompt_toolkit's one row cuts it."""
    import pexpect
    import pyte

    screen = pyte.Screen(40, 12)
    stream = pyte.Stream(screen)
    env = {**subprocess_env(), "TERM": "xterm", "PROMPT_TOOLKIT_NO_CPR": "1", patches.SWITCH: turned_off}
    child = pexpect.spawn(sys.executable, ["-c", PROMPT], env=env, encoding="utf-8", timeout=60,
                          dimensions=(12, 40))
    child.logfile_read = type("Screen", (), {"write": lambda self, data: stream.feed(data),
                                             "flush": lambda self: None})()
    try:
        child.expect_exact("Node name")
        child.send("motor-driver\r")
        child.expect("letter\\)" if turned_off == "speed" else "Validation")
        child.expect(pexpect.TIMEOUT, timeout=1)  # the rest of the screen, drawn
    finally:
        child.close(force=True)
    shown = " ".join(row.strip() for row in screen.display if row.strip())
    whole = ERROR.split(": ", 1)[1]
    if turned_off == "speed":
        assert whole in shown and "Validation error" not in shown, screen.display
        assert all(len(row.rstrip()) < 40 for row in screen.display), screen.display
    else:
        assert whole not in shown and "starting with a letter" not in shown, screen.display


# ─── Work spared, counted in a Copier process ─────────────────────────────────

# What a Copier run compiled: how many Jinja sources, and which Python files; how many times
# it rendered the answers file's name; how many times Copier's own git file mode method ran,
# and how many git processes asked for core.fileMode.
COUNTING = """
    import importlib.machinery, subprocess
    import jinja2
    from copier._main import Worker
    counted = {"jinja": 0, "python": [], "answers_file_name": 0, "file_mode_method": 0, "file_mode_asked": 0}
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
    render_name = Worker.answers_relpath.fget
    def counting_name(self):
        counted["answers_file_name"] += 1
        return render_name(self)
    Worker.answers_relpath = property(counting_name)
    sync = Worker._sync_git_index_executable_bit
    def counting_sync(self, dst_relpath, src_mode):
        counted["file_mode_method"] += 1
        return sync(self, dst_relpath, src_mode)
    Worker._sync_git_index_executable_bit = counting_sync
    popen = subprocess.Popen.__init__
    def counting_popen(self, args, *rest, **kwargs):
        counted["file_mode_asked"] += "core.fileMode" in [str(arg) for arg in args]
        return popen(self, args, *rest, **kwargs)
    subprocess.Popen.__init__ = counting_popen
"""


def package_answers(nodes: int) -> dict:
    return {**FIXED_ANSWERS, "package_name": "robot", "build_type": "ament_cmake",
            "nodes": [{"name": f"node_{number}", "language": "cpp", "publishers": ["status:std_msgs/msg/String"]}
                      for number in range(1, nodes + 1)]}


def copy_counting(template: Path, destination: Path, answers: dict | None = None, **env) -> dict:
    """A copy into `destination` (its folder names the package), counted; with `env` over the test's."""
    destination.parent.mkdir(parents=True, exist_ok=True)
    counted = copy_counted(COUNTING, template, destination, answers or FIXED_ANSWERS, env)
    counted["python"] = [path for path in counted["python"] if "/extensions/" in path]
    counted["tree"] = tree(destination)
    counted["files"] = len(counted["tree"])
    return counted


@pytest.fixture(scope="module")
def template(tmp_path_factory) -> Path:
    return snapshot_template(tmp_path_factory.mktemp("template"))


@pytest.fixture(scope="module")
def runs(template, tmp_path_factory):
    """Copies of the template, each counted once, by name: `first` (nothing kept yet), `second`
    (the first's code kept), `off` (the speed-ups off), `one` and `six` (a package of 1 and of
    6 nodes), `false` and `true` (into a repository whose core.fileMode is that)."""
    folder = tmp_path_factory.mktemp("runs")
    cache = {"RNA_TEMPLATE_CACHE_DIR": str(folder / "cache")}
    made = {}

    def run(name: str) -> dict:
        if name not in made:
            destination = folder / name / "robot"
            if name in ("false", "true"):
                destination.mkdir(parents=True)
                git("init", "-q", cwd=destination)
                git("config", "core.fileMode", name, cwd=destination)
            answers = {"one": package_answers(1), "six": package_answers(6)}.get(name)
            made[name] = copy_counting(template, destination, answers, **cache, **(OFF if name == "off" else {}))
        return made[name]

    run("first")  # before any other, whichever test asks first
    return run


SPARED = pytest.mark.xdist_group("test_patches:runs")  # one worker makes the runs for all of them


@SPARED
def test_a_second_run_compiles_nothing_and_writes_the_same_package(runs, tmp_path):
    first, second, off = runs("first"), runs("second"), runs("off")
    assert first["jinja"] > 10 and len(first["python"]) > 10
    # Copier loads the glue by its path, and the glue the patches' register and code cache, with Python's
    # loader (a .pyc in the clone at best); the template's modules, the other patches among them, come
    # from the cache.
    assert second["jinja"] == 0
    assert {path.split("/extensions/", 1)[1] for path in second["python"]} == \
        {"copier_glue.py", "patches/__init__.py", "patches/code_cache.py"}
    assert off["jinja"] > first["jinja"] and len(off["python"]) >= len(first["python"])  # each string, each time
    assert first["tree"] == second["tree"] == off["tree"]


def test_a_changed_template_file_is_compiled_again_alone(tmp_path):
    template = snapshot_template(tmp_path / "template")
    cache = str(tmp_path / "cache")
    copy_counting(template, tmp_path / "first" / "robot", RNA_TEMPLATE_CACHE_DIR=cache)
    readme = template / "template" / "README.md.jinja"  # a fork's own line
    readme.write_text(readme.read_text() + "\nA line of the lab's own.\n")
    subprocess.run(["git", "commit", "-qam", "lab line"], cwd=template, env=subprocess_env(), check=True)
    changed = copy_counting(template, tmp_path / "changed" / "robot", RNA_TEMPLATE_CACHE_DIR=cache)
    assert changed["jinja"] == 1
    assert "A line of the lab's own." in (tmp_path / "changed" / "robot" / "README.md").read_text()
    assert sorted(path.name for path in Path(cache).iterdir()) == sorted(
        path.name for path in Path(cache).glob("*.marshal"))


@SPARED
def test_the_answers_file_name_is_rendered_once_per_package_not_per_file(runs):
    one, six, off = runs("one"), runs("six"), runs("off")
    assert six["files"] >= one["files"] + 15  # a config, a header, a source and a test per node
    assert six["answers_file_name"] == one["answers_file_name"], (one, six)
    assert off["answers_file_name"] > off["files"] + one["answers_file_name"]  # Copier's own: several per file


@SPARED
def test_git_is_asked_for_the_file_mode_once_and_copiers_method_runs_when_it_is_false(runs):
    on, off, false, true = runs("first"), runs("off"), runs("false"), runs("true")
    assert off["file_mode_method"] >= off["files"] and off["file_mode_asked"] == off["file_mode_method"]
    assert on["file_mode_method"] == 0 and on["file_mode_asked"] == 1
    assert true["file_mode_method"] == 0 and true["file_mode_asked"] == 1
    # git ignores file modes there: Copier's own method runs for every file, and asks git itself
    assert false["file_mode_method"] == off["file_mode_method"]
    assert false["file_mode_asked"] == 1 + false["file_mode_method"]
    assert false["tree"] == true["tree"] == on["tree"]


# ─── The cache of compiled code ───────────────────────────────────────────────


def test_code_is_found_again_by_what_was_compiled(tmp_path):
    store = code_cache.Store(tmp_path / "codes.marshal")
    code = compile("answer = 42", "<test>", "exec")
    store.put(("answer = 42", "name", False), code)
    store.save()
    again = code_cache.Store(tmp_path / "codes.marshal")
    assert again.get(("answer = 42", "name", False)) == code
    assert again.get(("answer = 43", "name", False)) is None
    assert again.get(("answer = 42", "other name", False)) is None


def test_each_python_keeps_its_own_code(tmp_path, monkeypatch):
    monkeypatch.setenv("RNA_TEMPLATE_CACHE_DIR", str(tmp_path))
    ours = code_cache.store("python", "")
    monkeypatch.setattr(sys, "version", sys.version + " (another build)")
    assert code_cache.store("python", "") is not ours and code_cache.store("python", "").path != ours.path


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
    extensions = str(template / "extensions")
    script = f"import sys; sys.path.insert(0, {extensions!r}); import patches; " \
             f"patches.template_modules(__import__('pathlib').Path({extensions!r})).__enter__(); import rna; " \
             "import patches.copier_worker, patches.guards, patches.jinja, patches.prompts"
    for _ in range(2):
        subprocess.run([sys.executable, "-c", script], env=env, check=True, timeout=60)
    # What Python imports before the cache is in place: the package's register and the cache itself.
    assert {str(path.relative_to(template / "extensions")).split(".")[0] for path in template.rglob("*.pyc")} <= \
        {"patches/__pycache__/__init__", "patches/__pycache__/code_cache"}
    assert list((tmp_path / "cache").glob("python-*.marshal"))


# ─── Plain lines and dataclasses: the very code the library makes ─────────────


@pytest.fixture(scope="module")
def copier_environment(template_folder, tmp_path_factory):
    """The Jinja environment of a Copier worker on this template, the speed-ups in it."""
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
    # The speed-up's code (a kept stand-in line's code with the text in place) against Jinja's own.
    assert "compile" in vars(copier_environment)  # the speed-up's, when it is on
    compiled = copier_environment.compile(text)
    assert compiled == type(copier_environment).compile(copier_environment, text)
    assert copier_environment.from_string(text).render() == text


def test_code_that_does_not_hold_the_stand_in_line_is_not_taken_for_it():
    code = compile("yield_me = 'a line'", "<test>", "exec")
    assert jinja._with_constant(code, "xxxx", "text") is None  # the caller compiles the text itself
    replaced = jinja._with_constant(compile("def f():\n    return 'xxxx'\n", "<test>", "exec"), "xxxx", "text")
    namespace = {}
    exec(replaced, namespace)
    assert namespace["f"]() == "text"


def test_a_jinja_whose_plain_lines_compile_otherwise_gets_its_own_code(monkeypatch):
    monkeypatch.delenv(patches.SWITCH, raising=False)
    monkeypatch.setattr(jinja, "_plain_lines_fit", {})
    assert jinja._plain_lines_fit_in("a compiler", lambda source: compile(repr(source), "<test>", "eval"))
    monkeypatch.setattr(jinja, "_plain_lines_fit", {})
    assert not jinja._plain_lines_fit_in("another", lambda source: compile(f"({source!r}, {len(source)})",
                                                                          "<test>", "eval"))
    assert patches.status()["plain_lines"].startswith("off: a probe line")


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
