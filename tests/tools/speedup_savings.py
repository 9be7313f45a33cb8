"""What each speed-up of extensions/patches/ saves, in instructions counted by callgrind.

    tests/env python tests/tools/speedup_savings.py [--template DIR] [--only NAME ...] [--json out.json]

Three cases of benchmark.py, each a whole `copier` process under valgrind's callgrind with
its git processes: the default package, a package of 50 nodes, and an update adding a node
to a 20-node package. Each is counted with every speed-up on, with each one turned off
alone (RNA_TEMPLATE_PATCHES_OFF=<name>), and with all of them off; a speed-up saves what
the case costs more without it, given as a share of the case with every speed-up on.
Every count follows one uncounted run of the same case and setting, so the compiled code
kept is what a user's later runs find. Counts repeat to a tenth of a per cent whatever
else the machine does; wall time here does not (docs/pages/reference/performance.md).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import tempfile
from pathlib import Path

import benchmark

sys.path.insert(0, str(benchmark.ROOT / "extensions"))
import patches  # noqa: E402

CASES = ("default", "nodes_50", "update_20")
SPEED_UPS = tuple(patches.GROUPS["speed"])  # the patches for speed (the others change what prompts show)
SETTINGS = ("", *SPEED_UPS, "all")  # "" = every speed-up on; a name = that one off; "all" = all off


def count(bench: benchmark.Bench, cases: list[benchmark.Case], settings: tuple[str, ...]) -> dict:
    """{setting: {case: instructions}}, each count printed as it comes (a long run can be cut short)."""
    from concurrent.futures import ThreadPoolExecutor

    runs = [(setting, dataclasses.replace(case, samples=[], env={**case.env, patches.SWITCH: setting}))
            for setting in settings for case in cases]
    scratch = bench.work / "counted" if bench is not None else None

    def one(index: int) -> tuple[str, str, int]:
        setting, run = runs[index]
        folder = scratch / f"{index}-{run.name}" if scratch is not None else None
        return setting, run.name, _count_one(run, bench, folder)

    counts: dict[str, dict[str, int]] = {}
    with ThreadPoolExecutor(max_workers=2) as pool:  # callgrind runs a process on one core
        for setting, name, instructions in pool.map(one, range(len(runs))):
            print(f"speedup_savings: {name} with {patches.SWITCH}={setting!r}: {instructions:,}", file=sys.stderr,
                  flush=True)
            counts.setdefault(setting, {})[name] = instructions
    return counts


def _count_one(run: benchmark.Case, bench: benchmark.Bench, folder: Path) -> int:
    """One uncounted run of the case (its compiled code kept for the setting), then one counted."""
    run.run(folder.with_name(f"{folder.name}-warm-up"), bench.env)
    run.count(folder, bench.env)
    return run.instructions


def table(counts: dict, cases: tuple[str, ...]) -> str:
    on = counts[""]
    lines = [f"| {'speed-up turned off':<19} | " + " | ".join(f"{case:>22}" for case in cases) + " |",
             f"| {'-' * 19} | " + " | ".join(f"{'-' * 21}:" for _ in cases) + " |",
             f"| {'(none: all on)':<19} | " + " | ".join(f"{on[case] / 1e6:>14,.0f} M instr" for case in cases) + " |"]
    for setting, counted in counts.items():
        if setting:
            cells = [f"{(counted[case] - on[case]) / 1e6:+8,.0f} M ({(counted[case] - on[case]) / on[case]:+6.1%})"
                     for case in cases]
            lines.append(f"| {setting:<19} | " + " | ".join(f"{cell:>22}" for cell in cells) + " |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--template", type=Path, default=benchmark.ROOT, help="the template's working tree")
    parser.add_argument("--only", action="append", choices=SETTINGS[1:], metavar="NAME",
                        help="count only these speed-ups off (and every one on)")
    parser.add_argument("--cases", action="append", choices=CASES, help="count only these cases")
    parser.add_argument("--json", type=Path, help="also write the counts to this JSON file")
    arguments = parser.parse_args(argv)
    if benchmark.VALGRIND is None:
        print("speedup_savings: valgrind is not installed (apt-get install valgrind)", file=sys.stderr)
        return 1
    names = tuple(arguments.cases or CASES)
    settings = ("", *(arguments.only or ("all", *SPEED_UPS)))
    with tempfile.TemporaryDirectory(prefix="rna-savings-") as scratch:
        bench = benchmark.Bench(Path(scratch), arguments.template.resolve(), {"default", "scale", "update"})
        cases = [case for case in bench.cases() if case.name in names]
        bench.fill_code_cache()
        counts = count(bench, cases, settings)
    print(table(counts, names))
    if arguments.json:
        arguments.json.write_text(json.dumps({"machine": benchmark.machine(), "counts": counts}, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
