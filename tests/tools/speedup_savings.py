"""What each speed-up of extensions/speedups.py saves, in instructions counted by callgrind.

    tests/env python tests/tools/speedup_savings.py [--template DIR] [--only NAME ...] [--json out.json]

Three cases of benchmark.py, each a whole `copier` process under valgrind's callgrind with
its git processes: the default package, a package of 50 nodes, and an update adding a node
to a 20-node package. Each is counted with every speed-up on, with each one turned off
alone (RNA_TEMPLATE_SPEEDUPS_OFF=<name>), and with all of them off; a speed-up saves what
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
import speedups  # noqa: E402

CASES = ("default", "nodes_50", "update_20")
SETTINGS = ("", *speedups.NAMES, "all")  # "" = every speed-up on; a name = that one off; "all" = all off


def count(bench: benchmark.Bench, cases: list[benchmark.Case], settings: tuple[str, ...]) -> dict:
    """{setting: {case: instructions}}."""
    runs = [dataclasses.replace(case, name=f"{case.name}-{setting or 'on'}", samples=[],
                                env={**case.env, speedups.SWITCH: setting})
            for setting in settings for case in cases]
    benchmark.count_cases(runs, bench)
    counts: dict[str, dict[str, int]] = {}
    for run in runs:
        name, _, setting = run.name.rpartition("-")
        counts.setdefault("" if setting == "on" else setting, {})[name] = run.instructions
    return counts


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
    settings = ("", *(arguments.only or SETTINGS[1:]))
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
