"""Quality of service of a topic: the ROS 2 policies, their presets, and which pairs connect.

An endpoint names a preset, a history depth, or a mapping of policies over a preset:

    qos: sensor_data
    qos: 20
    qos: {preset: latched, depth: 5}
    qos: {reliability: best_effort, history: keep_all}

ROS 1 has queue sizes and latching only: depth becomes queue_size (keep_all, 0: no
limit) and transient_local durability a latched publisher; reliability has no ROS 1
counterpart and is left out there.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace

# The policies an answer may set; the middleware's own defaults come whole, as system_default.
RELIABILITY = ("reliable", "best_effort")
DURABILITY = ("volatile", "transient_local")
HISTORY = ("keep_last", "keep_all")
DEPTH_RANGE = (1, 10000)


@dataclass(frozen=True)
class Qos:
    """The policies of one endpoint; `preset` names the preset they equal, if any."""

    depth: int = 10
    reliability: str = "reliable"
    durability: str = "volatile"
    history: str = "keep_last"
    preset: str | None = None

    @property
    def profile(self) -> str | None:
        """A preset the client libraries name (sensor_data, system_default), else None."""
        return self.preset if self.preset in ("sensor_data", "system_default") else None

    @property
    def latched(self) -> bool:
        return self.durability == "transient_local"

    @property
    def queue_size(self) -> int:
        """ROS 1's queue size: the depth, 0 (no limit) for keep_all, roscpp's usual 10 for the system's."""
        return {"keep_all": 0, "system_default": 10}.get(self.history, self.depth)

    @property
    def is_plain(self) -> bool:
        """Reliable, volatile, keeping the last `depth` messages: what a bare depth means to rclcpp and rclpy."""
        return (self.reliability, self.durability, self.history) == ("reliable", "volatile", "keep_last")


def intra_process_error(qos: Qos, distro: str) -> str | None:
    """Why rclcpp refuses intra-process communication with this QoS on the distro, or None.

    rclcpp's publishers and subscriptions throw std::invalid_argument at creation when
    use_intra_process_comms is set and the history is not keep_last with a depth, or, in
    Humble, the durability is not volatile (transient_local came with Iron)."""
    if qos.history != "keep_last" or qos.depth <= 0:
        return "intra-process communication needs keep_last history with a depth"
    if qos.durability != "volatile" and (distro == "humble" or qos.durability != "transient_local"):
        return f"intra-process communication in {distro} needs volatile durability"
    return None


def describe(qos: Qos, ros: int = 2, publisher: bool = False) -> str:
    """The QoS in a few words, for the package README: its preset, or its policies; for
    ROS 1, what it maps to (a queue size, and latching on a publisher)."""
    if ros == 1:
        return f"queue {qos.queue_size}" + (", latched" if qos.latched and publisher else "")
    if qos.preset:
        return qos.preset if qos.preset != "default" else "default (depth 10)"
    kept = "keep_all" if qos.history == "keep_all" else f"depth {qos.depth}"
    return ", ".join(p for p in (qos.reliability, qos.durability, kept) if p not in ("reliable", "volatile")) or kept


# ROS 2's presets (rmw_qos_profiles); "latched" is the usual state topic: the last value
# kept for subscribers that join later.
PRESETS: dict[str, Qos] = {
    "default": Qos(preset="default"),
    "sensor_data": Qos(depth=5, reliability="best_effort", preset="sensor_data"),
    "latched": Qos(depth=1, durability="transient_local", preset="latched"),
    "system_default": Qos(depth=0, reliability="system_default", durability="system_default",
                          history="system_default", preset="system_default"),
}
POLICIES = {"reliability": RELIABILITY, "durability": DURABILITY, "history": HISTORY}
KEYS = ("preset", "depth", *POLICIES)


def _depth(value: object) -> int:
    if isinstance(value, bool) or not (isinstance(value, int) or (isinstance(value, str) and value.isdigit())):
        raise ValueError(f"give the qos depth as a whole number, not {value!r}")
    depth = int(value)
    if not DEPTH_RANGE[0] <= depth <= DEPTH_RANGE[1]:
        raise ValueError(f"give a qos depth between {DEPTH_RANGE[0]} and {DEPTH_RANGE[1]}, not {depth}")
    return depth


def _named(qos: Qos) -> Qos:
    """The same policies, with the name of the preset they equal (or none)."""
    plain = replace(qos, preset=None)
    for preset in PRESETS.values():
        if replace(preset, preset=None) == plain:
            return preset
    return plain


def parse(value: object) -> Qos:
    """An endpoint's qos answer: a preset name, a depth, or a mapping of policies over a preset."""
    if isinstance(value, str) and value.strip() in PRESETS:
        return PRESETS[value.strip()]
    if isinstance(value, (int, str)) and not isinstance(value, bool):
        try:
            return _named(Qos(depth=_depth(value)))
        except ValueError:
            if isinstance(value, int) or value.strip().isdigit():
                raise
        raise ValueError(f"give qos as a history depth (e.g. 10) or one of {', '.join(PRESETS)}, not {value!r}")
    if not isinstance(value, Mapping):
        raise ValueError(f"give qos as a history depth (e.g. 10), one of {', '.join(PRESETS)}, or a mapping "
                         f"of {', '.join(KEYS)}")
    unknown = [key for key in value if key not in KEYS]
    if unknown:
        raise ValueError(f"use {', '.join(KEYS)}: qos has no key {unknown[0]!r}")
    preset = value.get("preset", "default")
    if preset not in PRESETS:
        raise ValueError(f"use a qos preset of {', '.join(PRESETS)}, not {preset!r}")
    if preset == "system_default" and len(value) > 1:
        raise ValueError("give qos preset system_default no other key: it is the middleware's defaults")
    qos = PRESETS[preset]
    for key, allowed in POLICIES.items():
        if key in value:
            if value[key] not in allowed:
                raise ValueError(f"give qos {key} one of {', '.join(allowed)}, not {value[key]!r}")
            qos = replace(qos, **{key: value[key]})
    if "depth" in value:
        if qos.history != "keep_last":
            raise ValueError(f"leave out the qos depth, or keep history keep_last: depth applies to it, not to "
                             f"{qos.history}")
        qos = replace(qos, depth=_depth(value["depth"]))
    return _named(qos)


def mismatch(publisher: Qos, subscriber: Qos) -> str | None:
    """Why a subscription never gets this publisher's messages (ROS 2's request-offer rule), or None.

    Reliable subscriptions need reliable publishers, transient-local ones transient-local
    publishers; the middleware's defaults (system_default) are not known here, so they pass.
    """
    if subscriber.reliability == "reliable" and publisher.reliability == "best_effort":
        return "it subscribes reliable and the publisher is best_effort"
    if subscriber.durability == "transient_local" and publisher.durability == "volatile":
        return "it subscribes transient_local and the publisher is volatile"
    return None


def incompatible_pairs(publishers: Iterable[tuple[str, Qos]],
                       subscribers: Iterable[tuple[str, Qos]]) -> list[tuple[str, str, str]]:
    """(publisher, subscriber, why) for each named pair on one topic that would not connect."""
    publishers = list(publishers)
    return [(who, reader, why) for reader, wanted in subscribers for who, offered in publishers
            if (why := mismatch(offered, wanted))]
