"""What the generated nodes cost while they run, against ros2/examples' (issue 28).

    tests/env python tests/tools/runtime_benchmark.py [--distro kilted] [--rate 1000] [--seconds 10]
                                                      [--rounds 5] [--warmup 2] [--json out.json]
                                                      [--nice N] [--pair NAME=TALKER,LISTENER ...]
                                                      [--only-extra] [--inherit-env]

A talker and a listener at --rate messages a second, per pair: the generated Python pair (the
template's demo nodes, the talker's timer at the rate; its starter logs once a second at such a
rate, made to log every message here, as ros2/examples' talker does and as the latency needs)
and ros2/examples' minimal publisher and subscriber (tests/tools/reference_pair: its rclpy
member-function nodes as its jazzy branch publishes them, written out again, the timer period
set to the rate). For each, after --warmup seconds: the CPU time (user + system, from /proc,
every thread) each process spends in --seconds, as a share of one core, and each message's
latency, from the talker's `Publishing: ... N` log line to the listener's `I heard: ... N`
(rcutils's own timestamps, one clock). CPU time of the process, not wall time, is what load from
other processes moves least. The pairs run round after round in a rotated order; the table shows
medians and the spread.

--nice runs the nodes at that niceness (a negative one, as root, has them take their share of
the cores first when other work loads the machine: their CPU time is what it is either way, but
a talker that loses the core falls behind its rate).

--pair adds a pair of commands run the same way (comma-separated programs, each run with
`--ros-args` after it; NAME is compared with a pair named reference_NAME), such as C++ talkers
and listeners built elsewhere: the private review
builds the generated C++ nodes and ros2/examples' rclcpp ones against a real rclcpp. With
--only-extra only those run; --inherit-env runs them in this process's environment (one that
sourced their workspace) instead of the suite's ROS 2 environment, on a domain of their own.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

TESTS = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(TESTS))

from support import ros2 as ros2_support  # noqa: E402
from support.generation import generate  # noqa: E402

REFERENCE = Path(__file__).resolve().parent / "reference_pair"
REFERENCE_PERIOD = "timer_period = 0.5  # seconds"
CLOCK_TICKS = os.sysconf("SC_CLK_TCK")
# rcutils's console format, the same for every node: its timestamp (seconds), then the message.
LOG_FORMAT = "{time} {message}"
# The starter's throttle of a fast timer's log line (once a second).
THROTTLE = re.compile(r",\s*throttle_duration_sec=[0-9.]+")
LINE = re.compile(r"^(?P<time>\d+\.\d+) (?P<what>Publishing|I heard): .*?(?P<count>\d+)\D*$", re.MULTILINE)


@dataclass
class Pair:
    name: str
    label: str
    talker: list[str]
    listener: list[str]
    rounds: list[dict] = field(default_factory=list)


def cpu_seconds(pid: int) -> float:
    """User + system time of a process and all its threads so far (/proc/<pid>/stat)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / CLOCK_TICKS


def stamps(log: str, what: str) -> dict[int, float]:
    """The time of each `what` line (Publishing, I heard), by the message's number."""
    return {int(m["count"]): float(m["time"]) for m in LINE.finditer(log) if m["what"] == what}


def latencies(sent: dict[int, float], heard: dict[int, float], start: float, end: float) -> list[float]:
    """Seconds from each message's `Publishing` line to its `I heard` line, for those sent in [start, end]."""
    return [heard[count] - stamp for count, stamp in sent.items() if count in heard and start <= stamp <= end]


def within(times: dict[int, float], start: float, end: float) -> int:
    return sum(start <= stamp <= end for stamp in times.values())


def run_pair(pair: Pair, env: dict, scratch: Path, warmup: float, seconds: float, nice: int = 0) -> dict:
    """One round: start the listener, then the talker; measure; stop both with SIGINT."""
    logs = {role: scratch / f"{pair.name}_{role}_{len(pair.rounds)}.log" for role in ("talker", "listener")}
    processes = {}
    try:
        for role in ("listener", "talker"):
            with logs[role].open("wb") as log:
                processes[role] = subprocess.Popen(
                    [*getattr(pair, role), "--ros-args", "-r", f"__node:=bench_{role}"], env=env,
                    stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT, start_new_session=True,
                    preexec_fn=(lambda: os.nice(nice)) if nice else None)
        time.sleep(warmup)
        before = {role: cpu_seconds(p.pid) for role, p in processes.items()}
        start = time.time()
        time.sleep(seconds)
        after = {role: cpu_seconds(p.pid) for role, p in processes.items()}
        end = time.time()
    finally:
        for process in processes.values():
            if process.poll() is None:
                process.send_signal(signal.SIGINT)
        for process in processes.values():
            try:
                process.wait(15)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
    texts = {role: path.read_text(errors="replace") for role, path in logs.items()}
    sent, heard = stamps(texts["talker"], "Publishing"), stamps(texts["listener"], "I heard")
    delays = sorted(latencies(sent, heard, start, end))
    if not delays:
        raise RuntimeError(f"{pair.name}: no message heard\n{texts['talker'][-2000:]}\n{texts['listener'][-2000:]}")
    used = {role: after[role] - before[role] for role in processes}
    # Per message as well as per second: a talker that falls behind the rate on a loaded
    # machine sends fewer messages, and its listener then has less to do.
    return {"talker_cpu": used["talker"] / (end - start), "listener_cpu": used["listener"] / (end - start),
            "talker_us_per_message": 1e6 * used["talker"] / max(within(heard, start, end), 1),
            "listener_us_per_message": 1e6 * used["listener"] / max(within(heard, start, end), 1),
            "messages": within(heard, start, end) / (end - start),
            "latency_median": statistics.median(delays), "latency_p90": delays[int(0.9 * (len(delays) - 1))]}


def build(ros2, scratch: Path, rate: float, env: dict) -> Path:
    """The generated demo pair and the reference pair, built with colcon in `scratch`."""
    workspace = scratch / "ws"
    generate(TESTS.parent, workspace / "src" / "bench_generated",
             {"package_name": "bench_generated", "ros_distro": ros2.distro, "build_type": "ament_python",
              "nodes": [{"name": "talker", "publishers": ["chatter:std_msgs/msg/String"], "timers": [1.0 / rate]},
                        {"name": "listener", "subscribers": ["chatter:std_msgs/msg/String"]}]})
    reference = workspace / "src" / "reference_pair"
    shutil.copytree(REFERENCE, reference)
    publisher = reference / "reference_pair" / "publisher_member_function.py"
    text = publisher.read_text()
    assert REFERENCE_PERIOD in text
    publisher.write_text(text.replace(REFERENCE_PERIOD, f"timer_period = {1.0 / rate!r}  # seconds"))
    talker = workspace / "src" / "bench_generated" / "bench_generated" / "bench_generated" / "talker.py"
    talker.write_text(THROTTLE.sub("", talker.read_text()))
    ros2.colcon_build(workspace, env)
    return workspace / "install"


def summary(values: list[float]) -> dict:
    return {"median": statistics.median(values), "min": min(values), "max": max(values)}


def _cpu(figures: dict) -> tuple[str, str]:
    """A share of one core: the median, and the spread."""
    return f"{100 * figures['median']:.1f}%", f"{100 * figures['min']:.1f}..{100 * figures['max']:.1f}"


def _ms(figures: dict) -> tuple[str, str]:
    """Milliseconds: the median, and the spread."""
    return f"{1000 * figures['median']:.3f}", f"{1000 * figures['min']:.3f}..{1000 * figures['max']:.3f}"


def table(pairs: list[Pair]) -> str:
    rows = [("pair", "listener CPU", "spread", "µs/msg", "talker CPU", "spread", "µs/msg", "latency median ms",
             "spread", "p90 ms", "msgs/s")]
    for pair in pairs:
        figures = {key: summary([r[key] for r in pair.rounds]) for key in pair.rounds[0]}
        rows.append((pair.label, *_cpu(figures["listener_cpu"]), f"{figures['listener_us_per_message']['median']:.0f}",
                     *_cpu(figures["talker_cpu"]), f"{figures['talker_us_per_message']['median']:.0f}",
                     *_ms(figures["latency_median"]), f"{1000 * figures['latency_p90']['median']:.3f}",
                     f"{figures['messages']['median']:.0f}"))
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = ["| " + " | ".join(cell.ljust(width) for cell, width in zip(row, widths, strict=True)) + " |"
             for row in rows]
    lines.insert(1, "| " + " | ".join("-" * width for width in widths) + " |")
    return "\n".join(lines)


def ratios(pairs: list[Pair]) -> list[dict]:
    """Each pair's medians over its reference's: `generated` over `reference`, and a --pair NAME over
    a --pair reference_NAME."""
    by_name = {pair.name: pair for pair in pairs}
    found = []
    for pair in pairs:
        reference = by_name.get("reference" if pair.name == "generated" else f"reference_{pair.name}")
        if pair.name.startswith("reference") or reference is None:
            continue
        row = {"pair": pair.name, "reference": reference.name}
        for key in ("listener_cpu", "listener_us_per_message", "talker_cpu", "talker_us_per_message",
                    "latency_median"):
            row[key] = (statistics.median(r[key] for r in pair.rounds)
                        / statistics.median(r[key] for r in reference.rounds))
        found.append(row)
    return found


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--distro", default=ros2_support.DEFAULT_DISTRO, choices=ros2_support.DISTROS)
    parser.add_argument("--rate", type=float, default=1000.0, help="messages a second")
    parser.add_argument("--seconds", type=float, default=10.0, help="measured per round and pair")
    parser.add_argument("--warmup", type=float, default=2.0, help="seconds before measuring")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--json", type=Path)
    parser.add_argument("--nice", type=int, default=0, help="the nodes' niceness (negative: as root)")
    parser.add_argument("--pair", action="append", default=[], metavar="NAME=TALKER,LISTENER")
    parser.add_argument("--only-extra", action="store_true", help="measure the --pair pairs only")
    parser.add_argument("--inherit-env", action="store_true", help="run the nodes in this environment")
    args = parser.parse_args(argv)
    if args.inherit_env and not args.only_extra:
        parser.error("--inherit-env runs the --pair pairs only: give --only-extra")

    scratch = Path(tempfile.mkdtemp(prefix="rna-runtime-bench-"))
    try:
        if args.inherit_env:
            env = {**os.environ, "ROS_DOMAIN_ID": str(ros2_support.pick_domain_id()),
                   "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}
        else:
            ros2 = ros2_support.ensure_environment(args.distro)
            env = ros2.env(ros2_support.pick_domain_id())
        pairs = []
        if not args.only_extra:
            install = build(ros2, scratch, args.rate, env)
            env = ros2_support.workspace_env(install, env)
            def program(package: str, name: str) -> list[str]:
                return [str(install / package / "lib" / package / name)]

            pairs += [Pair("generated", "generated Python (rclpy)", program("bench_generated", "talker"),
                           program("bench_generated", "listener")),
                      Pair("reference", "ros2/examples Python (rclpy)", program("reference_pair", "talker"),
                           program("reference_pair", "listener"))]
        for spec in args.pair:
            name, _, commands = spec.partition("=")
            talker, _, listener = commands.partition(",")
            pairs.append(Pair(name, name, talker.split(), listener.split()))
        env = {**env, "RCUTILS_CONSOLE_OUTPUT_FORMAT": LOG_FORMAT, "RCUTILS_LOGGING_BUFFERED_STREAM": "1"}
        for number in range(args.rounds):
            order = pairs[number % len(pairs):] + pairs[:number % len(pairs)]
            for pair in order:
                pair.rounds.append(run_pair(pair, env, scratch, args.warmup, args.seconds, args.nice))
            print(f"round {number + 1}/{args.rounds} done", file=sys.stderr, flush=True)
        print(f"{args.rate:.0f} messages a second, {args.seconds:.0f} s measured per round after {args.warmup:.0f} s, "
              f"{args.rounds} rounds, ROS 2 {args.distro}, nice {args.nice}, load average {os.getloadavg()[0]:.2f}")
        print(table(pairs))
        compared = ratios(pairs)
        for row in compared:
            print(f"{row['pair']} / {row['reference']}: listener CPU {row['listener_cpu']:.3f}x "
                  f"({row['listener_us_per_message']:.3f}x a message), talker CPU {row['talker_cpu']:.3f}x "
                  f"({row['talker_us_per_message']:.3f}x a message), latency {row['latency_median']:.3f}x")
        if args.json:
            args.json.write_text(json.dumps({"rate": args.rate, "seconds": args.seconds, "distro": args.distro,
                                             "pairs": {p.name: {"label": p.label, "rounds": p.rounds} for p in pairs},
                                             "ratios": compared}, indent=2))
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
