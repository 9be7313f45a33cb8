"""Where the time of a `copier copy` or `copier update` goes (benchmark.py --profile).

Each profiled case runs a few times with tests/tools/profile_hooks on PYTHONPATH: every
Python process of the run (copier, the template's after-update migration and the Copier
runs inside it) records the exclusive wall time of its phases (see that sitecustomize).
Phases are then put into the categories of issue 12: start-up and imports, the clone,
the template's own code (import, model), rendering, Copier's update work and the
after-update script. One more run under cProfile ranks the template's own functions.
"""

from __future__ import annotations

import json
import os
import pstats
import statistics
import sys
import tempfile
from pathlib import Path

PROFILED = ("floor", "default", "nodes_1", "nodes_50", "update_20", "update_20_catkin")
HOOKS = Path(__file__).resolve().with_name("profile_hooks")
RUNS = 3
LIBRARIES = "import: Copier, its libraries and Python's"

CATEGORIES = (  # (category, does a phase name belong to it)
    ("start-up: interpreter and imports of Copier and its libraries",
     lambda p: p.startswith(("interpreter", LIBRARIES)) or ": import: " in p),
    ("clone and template metadata (git clone, describe, ls-files, copier.yml)",
     lambda p: p.startswith(("clone", "git: clone", "template ", "git: template", "read copier.yml",
                             "remove the clone"))),
    ("template's own code: import (compiled from the fresh clone)", lambda p: p == "import: template extensions"),
    ("template's own code: model building (context hook, build_package)", lambda p: p.startswith("model: ")),
    ("rendering: Copier and Jinja (answers, paths, files, compile)",
     lambda p: p.startswith(("render", "Jinja", "answers", "tasks and migrations", "git: render",
                             "git: answers"))),
    ("update: Copier's own diff and apply (git)", lambda p: p.startswith(("update:", "git: update"))),
    ("other Copier work (CLI, answers file, bookkeeping)", lambda p: True),
)


def _phase_name(phase: str) -> str:
    """The phase as reported: imports of Python's and Copier's libraries are one phase."""
    if phase.startswith("import: ") and phase != "import: template extensions":
        return LIBRARIES
    return phase


def category(phase: str) -> str:
    """The category of a phase; phases of a child process are categorised by that process."""
    if phase.startswith("["):
        return f"after-update work: {phase[1:phase.index(']')]} (a Python process of its own)"
    return next(name for name, belongs in CATEGORIES if belongs(phase))


def _records(directory: Path) -> list[dict]:
    return [json.loads(path.read_text()) for path in sorted(directory.glob("*.json"))]


def _phases_of_run(wall: float, records: list[dict]) -> tuple[dict[str, float], dict[str, int]]:
    """Seconds and calls per phase of one run, child processes' phases prefixed with their script's name."""
    by_pid = {record["pid"]: record for record in records}
    top = next(record for record in records if record["ppid"] not in by_pid)
    phases: dict[str, float] = {"interpreter start-up (before site)": wall - top["seconds"]}
    calls: dict[str, int] = {}

    def add(record: dict, prefix: str) -> None:
        named = 0.0
        for phase, (seconds, count) in record["phases"].items():
            if phase.startswith("process: "):
                continue  # split below into the child's phases and its start-up
            name = prefix + _phase_name(phase)
            phases[name] = phases.get(name, 0.0) + seconds
            calls[name] = calls.get(name, 0) + count
            named += seconds
        children = [r for r in records if r["ppid"] == record["pid"]]
        waited = sum(seconds for phase, (seconds, _) in record["phases"].items() if phase.startswith("process: "))
        for child in children:
            script = Path(child["argv"][0]).name
            add(child, f"[{script}] ")
        if children:
            startup = waited - sum(child["seconds"] for child in children)
            key = f"[{Path(children[0]['argv'][0]).name}] interpreter start-up and process"
            phases[key] = phases.get(key, 0.0) + startup
        rest = record["seconds"] - named - waited
        own = "the script's own code" if prefix else "Copier: the rest (CLI, answers file, bookkeeping)"
        phases[prefix + own] = phases.get(prefix + own, 0.0) + rest

    add(top, "")
    return phases, calls


def _run(case, env: dict[str, str], cprofile: bool) -> tuple[float, list[dict], pstats.Stats | None]:
    with tempfile.TemporaryDirectory(prefix="rna-profile-") as scratch:
        output = Path(scratch, "records")
        output.mkdir()
        python_path = os.pathsep.join(filter(None, [str(HOOKS), env.get("PYTHONPATH")]))
        profiled_env = {**env, "RNA_BENCH_PROFILE_DIR": str(output), "PYTHONPATH": python_path,
                        "RNA_BENCH_CPROFILE": "1" if cprofile else "0"}
        sample = case.run(Path(scratch, "run"), profiled_env)
        records = _records(output)
        stats = None
        if cprofile:
            stats = pstats.Stats(*map(str, sorted(output.glob("*.prof"))))
        return sample.wall, records, stats


def _own_function(key: tuple[str, int, str]) -> str | None:
    """`extensions/rna/model.py:build_package` for a function of the template's own code, else None."""
    filename, _line, function = key
    if "/extensions/" not in filename or "site-packages" in filename:
        return None
    return "extensions/" + filename.rsplit("/extensions/", 1)[1] + ":" + function


def _top_own_functions(stats: pstats.Stats, wall: float, count: int = 12) -> list[dict]:
    """The template's functions by cumulative time, summed over the processes and clones that ran them."""
    rows: dict[str, dict] = {}
    for key, (_primitive, calls, tottime, cumtime, _callers) in stats.stats.items():
        name = _own_function(key)
        if name:
            row = rows.setdefault(name, {"function": name, "calls": 0, "cumulative": 0.0, "own": 0.0})
            row["calls"] += calls
            row["cumulative"] += cumtime
            row["own"] += tottime
    for row in rows.values():
        row["share"] = row["cumulative"] / wall
    return sorted(rows.values(), key=lambda row: row["cumulative"], reverse=True)[:count]


def profile_case(case, env: dict[str, str], runs: int = RUNS) -> dict:
    """Median seconds per phase and per category over `runs` runs, and cProfile's ranking."""
    with tempfile.TemporaryDirectory(prefix="rna-profile-") as scratch:
        case.run(Path(scratch, "warm-up"), env)  # the file cache, the peer's first start
    walls, per_run = [], []
    for _ in range(runs):
        wall, records, _ = _run(case, env, cprofile=False)
        walls.append(wall)
        phases, calls = _phases_of_run(wall, records)
        per_run.append(phases)
    names = sorted({name for phases in per_run for name in phases})
    phases = {name: statistics.median(phases.get(name, 0.0) for phases in per_run) for name in names}
    categories: dict[str, float] = {}
    for name, seconds in phases.items():
        categories[category(name)] = categories.get(category(name), 0.0) + seconds
    wall = statistics.median(walls)
    cprofile_wall, _, stats = _run(case, env, cprofile=True)
    return {"case": case.name, "label": case.label, "runs": runs, "wall": wall, "phases": phases, "calls": calls,
            "categories": categories, "cprofile_wall": cprofile_wall,
            "own_functions": _top_own_functions(stats, cprofile_wall)}


def _table(title: str, rows: dict[str, float], wall: float, reference: dict[str, float] | None,
           reference_name: str = "", calls: dict[str, int] | None = None, smallest: float = 0.0) -> None:
    columns = ["calls"] if calls is not None else []
    columns += ["s", "share"] + ([f"{reference_name} s", f"more than {reference_name}"] if reference else [])
    print(f"\n| {title:<78} | " + " | ".join(columns) + " |")
    print(f"| {'-' * 78} | " + " | ".join("-" * max(len(c) - 1, 3) + ":" for c in columns) + " |")
    names = set(rows) | set(reference or {})
    for name in sorted(names, key=lambda n: -max(rows.get(n, 0.0), (reference or {}).get(n, 0.0))):
        seconds = rows.get(name, 0.0)
        if max(seconds, (reference or {}).get(name, 0.0)) < smallest:
            continue
        cells = [str(calls.get(name, ""))] if calls is not None else []
        cells += [f"{seconds:.3f}", f"{seconds / wall:.1%}"]
        if reference is not None:
            cells += [f"{reference.get(name, 0.0):.3f}", f"{seconds - reference.get(name, 0.0):+.3f}"]
        print(f"| {name:<78} | " + " | ".join(cells) + " |")


def print_profile(result: dict, reference: dict | None = None) -> None:
    wall = result["wall"]
    name = reference["case"] if reference else ""
    versus = f"; {name}: {reference['wall']:.3f} s" if reference else ""
    print(f"\n### {result['case']}: {result['label']} (median of {result['runs']} profiled runs: {wall:.3f} s"
          f"{versus})")
    _table("category", result["categories"], wall, reference and reference["categories"], name)
    _table("phase (exclusive wall time, >= 2 ms)", result["phases"], wall, reference and reference["phases"], name,
           result["calls"], smallest=0.002)
    print(f"\nThe template's own functions under cProfile (run of {result['cprofile_wall']:.3f} s; "
          "cProfile slows Python code, so shares are indicative):\n")
    print(f"| {'function':<66} | calls  | cumulative s | own s | share |")
    print(f"| {'-' * 66} | -----: | -----------: | ----: | ----: |")
    for row in result["own_functions"]:
        print(f"| {row['function']:<66} | {row['calls']:6d} | {row['cumulative']:12.3f} | {row['own']:5.3f} | "
              f"{row['share']:5.1%} |")


REFERENCE_OF = {"default": "floor", "nodes_50": "nodes_1"}  # a case profiled beside its reference


def profile_cases(cases, env: dict[str, str]) -> list[dict]:
    results: dict[str, dict] = {}
    for case in cases:
        print(f"profiling: {case.name}", flush=True, file=sys.stderr)
        results[case.name] = profile_case(case, env)
        print_profile(results[case.name], results.get(REFERENCE_OF.get(case.name, "")))
    return list(results.values())
