"""The catalogues of standard interface types (extensions/rna/catalogue) and the check built on them.

The fast tests check the function and the shape of every catalogue; the ros and ros1 tests
check the kilted, jazzy and noetic catalogues against the packages those tiers install.
"""

from __future__ import annotations

import datetime
import os
from pathlib import Path

import pytest
from rna.catalogue import FOLDER, load, unknown_type_error
from rna.distros import DISTROS, ROS2_DISTROS
from rna.interfaces import KINDS
from rna.names import is_camel_case
from support import ros1 as ros1_support
from support import ros2 as ros2_support
from support.tiers import unavailable


@pytest.mark.parametrize("distro", ROS2_DISTROS)
@pytest.mark.parametrize("package, kind, name", [
    ("std_msgs", "msg", "String"), ("geometry_msgs", "msg", "Twist"), ("std_srvs", "srv", "Trigger"),
    ("sensor_msgs", "msg", "PointCloud2"), ("action_msgs", "msg", "GoalStatus"),
    ("lifecycle_msgs", "srv", "ChangeState"), ("test_msgs", "action", "Fibonacci"),
])
def test_known_ros2_types_pass(package, kind, name, distro):
    assert unknown_type_error(package, kind, name, distro) is None


@pytest.mark.parametrize("package, kind, name", [
    ("std_msgs", "msg", "String"), ("geometry_msgs", "msg", "Twist"), ("std_srvs", "srv", "Trigger"),
    ("actionlib_msgs", "msg", "GoalStatus"), ("nav_msgs", "action", "GetMap"),
    ("nav_msgs", "msg", "GetMapGoal"),  # the messages actionlib derives from an action
])
def test_known_noetic_types_pass(package, kind, name):
    assert unknown_type_error(package, kind, name, "noetic") is None


def test_misspelt_type_gets_the_closest_name():
    assert unknown_type_error("geometry_msgs", "msg", "Twst", "jazzy") == (
        "did you mean geometry_msgs/msg/Twist? 'geometry_msgs/msg/Twst' is not a message of geometry_msgs in jazzy")
    assert unknown_type_error("example_interfaces", "srv", "AddTwoInt", "humble") == (
        "did you mean example_interfaces/srv/AddTwoInts? 'example_interfaces/srv/AddTwoInt' is not a service of "
        "example_interfaces in humble")


def test_noetic_spells_types_the_ros1_way():
    assert unknown_type_error("geometry_msgs", "msg", "Twst", "noetic") == (
        "did you mean geometry_msgs/Twist? 'geometry_msgs/Twst' is not a message of geometry_msgs in noetic")


def test_a_name_differing_in_case_is_suggested():
    assert unknown_type_error("geometry_msgs", "msg", "POSESTAMPED", "kilted").startswith(
        "did you mean geometry_msgs/msg/PoseStamped? ")


def test_a_type_of_another_kind_is_named_as_such():
    assert unknown_type_error("std_srvs", "msg", "Trigger", "kilted") == (
        "'std_srvs/msg/Trigger' is not a message of std_srvs in kilted: it is a service")
    assert unknown_type_error("test_msgs", "srv", "Fibonacci", "rolling") == (
        "'test_msgs/srv/Fibonacci' is not a service of test_msgs in rolling: it is an action")
    assert unknown_type_error("nav_msgs", "msg", "GetMap", "noetic") == (
        "'nav_msgs/GetMap' is not a message of nav_msgs in noetic: it is a service and an action")


def test_without_a_close_name_a_short_package_lists_what_it_has():
    assert unknown_type_error("std_srvs", "srv", "Reboot", "humble") == (
        "use one of Empty, SetBool and Trigger: 'std_srvs/srv/Reboot' is not a service of std_srvs in humble")
    assert unknown_type_error("std_srvs", "msg", "Reboot", "jazzy") == (
        "'std_srvs/msg/Reboot' is not a message of std_srvs in jazzy: std_srvs has no messages")
    assert unknown_type_error("sensor_msgs", "msg", "Zzzzzz", "jazzy") == (
        "'sensor_msgs/msg/Zzzzzz' is not a message of sensor_msgs in jazzy")


@pytest.mark.parametrize("package, distro", [
    ("nav2_msgs", "jazzy"), ("my_robot_interfaces", "humble"), ("control_msgs", "noetic"),
    ("std_msgs", "foxy"),  # no catalogue for the distro: nothing to tell
])
def test_other_packages_stay_allowed(package, distro):
    assert unknown_type_error(package, "msg", "Anything", distro) is None


def test_each_catalogue_is_loaded_once():
    assert load("jazzy") is load("jazzy")


def test_there_is_one_catalogue_per_distro():
    assert sorted(path.stem for path in FOLDER.glob("*.json")) == sorted(DISTROS)


@pytest.mark.parametrize("distro", DISTROS)
def test_catalogue_is_well_formed(distro):
    catalogue = load(distro)
    assert catalogue["distro"] == distro
    datetime.date.fromisoformat(catalogue["generated"])
    packages = catalogue["packages"]
    assert sorted(catalogue["sources"]) == sorted(packages)
    assert all(isinstance(source, str) and source for source in catalogue["sources"].values())
    for package, types in packages.items():
        assert sorted(types) == sorted(KINDS), package
        for kind, names in types.items():
            assert names == sorted(set(names)), (package, kind)
            assert all(is_camel_case(name) for name in names), (package, kind)
        assert any(types.values()), f"{package} has no types"
    common = {"std_msgs", "std_srvs", "geometry_msgs", "sensor_msgs", "nav_msgs"}
    assert common | ({"actionlib_msgs"} if distro == "noetic" else {"action_msgs", "lifecycle_msgs"}) <= set(packages)
    assert "String" in packages["std_msgs"]["msg"] and "Twist" in packages["geometry_msgs"]["msg"]


def installed_types(share: Path, package: str) -> dict[str, list[str]]:
    """What an installed package's share folder defines per kind, read independently of the script."""
    return {kind: sorted({path.stem for path in (share / package / kind).glob("*")
                          if path.suffix in (f".{kind}", ".idl")}) for kind in KINDS}


def assert_catalogue_matches(distro: str, share: Path) -> None:
    packages = load(distro)["packages"]
    present = [package for package in packages if (share / package).is_dir()]
    assert "std_msgs" in present and "geometry_msgs" in present, f"{share} lacks the common packages"
    for package in present:
        assert packages[package] == installed_types(share, package), f"{distro} {package} differs from {share}"


@pytest.mark.ros
@pytest.mark.parametrize("distro", ros2_support.DISTROS)
def test_ros2_catalogue_matches_the_installed_wheels(ros2_of, distro):
    assert_catalogue_matches(distro, ros2_of(distro).venv / "share")


@pytest.mark.ros1
def test_noetic_catalogue_matches_the_debian_packages():
    try:
        ros1_support.ensure_environment(install=os.geteuid() == 0)
    except ros1_support.Ros1Unavailable as error:
        unavailable(f"ROS 1 from Debian's packages is not available: {error}")
    assert_catalogue_matches("noetic", Path("/usr/share"))
