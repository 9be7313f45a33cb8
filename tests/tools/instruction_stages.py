"""Where a copy's instructions go, stage by stage: the default package against the floor.

    tests/env python tests/tools/instruction_stages.py [--template DIR]

Each stage is a `copier copy` (Copier's API, in a Python process of its own, under
valgrind's callgrind with its git processes) stopped at the end of that stage; one stage's
instructions are its count less the stage's before it. Counts repeat run after run, so
the differences hold even when they are small. The repositories and answers are
benchmark.py's (the default case and the floor), the compiled code kept as there.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import benchmark

# The copy stops by raising at the start of the step after the stage.
STAGES = (
    ("start-up: Python, importing Copier", "import"),
    ("clone, copier.yml, settings", "config"),
    ("Jinja environment: Copier's extensions, the template's modules", "environment"),
    ("questions (their defaults, choices and conditions)", "questions"),
    ("render: paths and files, the answers file, clean-up", "all"),
)
STAGED_COPY = """
import json, sys
stage, template, destination, data = sys.argv[1], sys.argv[2], sys.argv[3], json.loads(sys.argv[4])
import copier
import copier._main as main
if stage == "import":
    sys.exit(0)

class Stop(Exception):
    pass

ask, render = main.Worker._ask, main.Worker._render_template

def stop_at_questions(self, *args, **kwargs):
    if stage == "config":
        raise Stop
    if stage == "environment":
        self.jinja_env
        raise Stop
    return ask(self, *args, **kwargs)

def stop_at_render(self, *args, **kwargs):
    if stage == "questions":
        raise Stop
    return render(self, *args, **kwargs)

main.Worker._ask, main.Worker._render_template = stop_at_questions, stop_at_render
try:
    copier.run_copy(template, destination, data=data, defaults=True, unsafe=True, quiet=True)
except Stop:
    pass
"""


def count_stages(bench: benchmark.Bench, template: Path, answers: dict, work: Path) -> list[int]:
    """Each stage's own instructions."""
    totals = []
    for _, stage in STAGES:
        folder = work / stage
        folder.mkdir(parents=True)
        totals.append(benchmark.count_instructions(
            [sys.executable, "-c", STAGED_COPY, stage, str(template), str(folder / "project"), json.dumps(answers)],
            folder, bench.env, work / f"{stage}-callgrind"))
    return [total - before for total, before in zip(totals, [0, *totals[:-1]], strict=True)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--template", type=Path, default=benchmark.ROOT, help="the template's working tree")
    arguments = parser.parse_args(argv)
    if benchmark.VALGRIND is None:
        print("instruction_stages: valgrind is not installed (apt-get install valgrind)", file=sys.stderr)
        return 1
    with tempfile.TemporaryDirectory(prefix="rna-stages-") as scratch:
        bench = benchmark.Bench(Path(scratch), arguments.template.resolve(), {"default"})
        bench.fill_code_cache()
        with ThreadPoolExecutor(max_workers=2) as pool:  # callgrind runs one process on one core
            floor = pool.submit(count_stages, bench, bench.floor, {"name": "demo"}, Path(scratch) / "floor")
            default = pool.submit(count_stages, bench, bench.template, benchmark.FIXED_ANSWERS,
                                  Path(scratch) / "default")
            floor, default = floor.result(), default.result()
    print(f"| {'stage of a copy (instructions, millions)':<66} | floor | default | more |")
    print(f"| {'-' * 66} | ----: | ------: | ---: |")
    for (label, _), low, high in zip(STAGES, floor, default, strict=True):
        print(f"| {label:<66} | {low / 1e6:5,.0f} | {high / 1e6:7,.0f} | {(high - low) / 1e6:+4,.0f} |")
    print(f"| {'all':<66} | {sum(floor) / 1e6:5,.0f} | {sum(default) / 1e6:7,.0f} | "
          f"{(sum(default) - sum(floor)) / 1e6:+4,.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
