"""The message, service and action types of the standard interface packages, per distro.

Each `<distro>.json` beside this file is written by tests/tools/make_catalogue.py from the
packages' own definition files and says where they came from and when (docs/pages/reference/catalogue.md).
Only the packages a catalogue lists are checked: types of any other package stay allowed.
"""

from __future__ import annotations

import difflib
import functools
import json
from pathlib import Path

from ..distros import generation
from ..interfaces import KIND_NAMES, InterfaceType
from ..wording import english_list, with_article

FOLDER = Path(__file__).resolve().parent
ROLLING_FALLBACKS = ("kilted", "jazzy")
SHORT_LIST = 6  # a package with this many types of a kind or fewer has them all named in the error


@functools.cache
def load(distro: str) -> dict | None:
    """The catalogue of `distro` as written by make_catalogue.py, None if there is none."""
    path = FOLDER / f"{distro}.json"
    # not through rna/files.py: the template's
    return json.loads(path.read_text(encoding="utf-8")) if path.is_file() else None


def known_types(package: str, distro: str) -> dict[str, list[str]] | None:
    """{kind: sorted type names} of a catalogued package, None when it is not catalogued."""
    catalogue = load(distro)
    return catalogue["packages"].get(package) if catalogue else None


ROS1_CATALOGUE = "noetic"
# ROS 1 packages of interface types that ROS 2 does not have, and what it has instead.
ROS1_TYPE_PACKAGES = {
    "actionlib_msgs": "action_msgs",
    "actionlib": "test_msgs, whose test_msgs/action/Fibonacci is ROS 2's test action",
    "tf": "tf2_msgs",
    "roscpp": "rcl_interfaces",
    "rosgraph_msgs": "rosgraph_msgs (Clock only; Log is rcl_interfaces/msg/Log)",
}


def _ros1_package_error(package: str, kind: str, name: str, distro: str) -> str | None:
    """Why a type of a ROS 1 package (catalogued for ROS 1, not for this ROS 2 distro) does not exist there."""
    if generation(distro) == 1 or load(distro) is None or package == "rosgraph_msgs":
        return None
    if package not in ROS1_TYPE_PACKAGES and known_types(package, ROS1_CATALOGUE) is None:
        return None
    given = InterfaceType(package, kind, name, generation(distro)).full_name
    instead = f": ROS 2 has {ROS1_TYPE_PACKAGES[package]}" if package in ROS1_TYPE_PACKAGES else ""
    return f"'{given}': {package} is a ROS 1 package, which {distro} does not have{instead}"


def unknown_type_error(package: str, kind: str, name: str, distro: str) -> str | None:
    """Why `package/kind/name` does not exist in `distro`, or None when it does or cannot be told.

    A type named under another kind is said so; a misspelt one gets the closest name.
    """
    types = known_types(package, distro)
    if types is None:
        return _ros1_package_error(package, kind, name, distro)
    if name in types[kind]:
        return None
    # Rolling moves on faster than its catalogue: a type the released distros have stays allowed.
    if distro == "rolling" and any(name in (known_types(package, released) or {}).get(kind, ())
                                   for released in ROLLING_FALLBACKS):
        return None
    ros = generation(distro)
    given = InterfaceType(package, kind, name, ros).full_name
    problem = f"'{given}' is not {with_article(KIND_NAMES[kind])} of {package} in {distro}"
    others = [with_article(KIND_NAMES[other]) for other in KIND_NAMES if name in types[other]]
    if others:  # ROS 1's nav_msgs/GetMap is both a service and an action
        return f"{problem}: it is {english_list(others)}"
    # A name differing only in case is the one meant, however far apart difflib finds them.
    close = [known for known in types[kind] if known.lower() == name.lower()]
    close = close or difflib.get_close_matches(name, types[kind], n=1)
    if close:  # the whole corrected type first, ready to type
        return f"did you mean {InterfaceType(package, kind, close[0], ros).full_name}? {problem}"
    if not types[kind]:
        return f"{problem}: {package} has no {KIND_NAMES[kind]}s"
    if len(types[kind]) <= SHORT_LIST:
        return f"use one of {english_list(types[kind])}: {problem}"
    return problem
