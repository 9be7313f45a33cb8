"""A lab's choices (extensions/lab.yml): checked with one-line errors, and used by every package."""

from __future__ import annotations

import copier
import pytest
import yaml
from catkin_pkg.package import parse_package

from rna import Answers, lab
from support.generation import VALID, git, snapshot_template
from support.packages import package_dir

CHOICES = {
    "maintainer": "Grace Hopper", "maintainer_email": "grace@lab.example.org",
    "copyright_holder": "The Robotics Lab", "license": "BSD-3-Clause", "ros_distro": "humble",
    "build_type": "ament_cmake", "qos": "sensor_data",
    "dependencies": {"exec_depend": ["lab_bringup", "rclcpp"], "test_depend": ["lab_lint_config"]},
    "header": "Part of the Robotics Lab's robot software.\n",
    "files": {"CODEOWNERS": "* @robotics-lab/maintainers"},
    "docs_url": "https://robotics-lab.github.io/rna-template/",
}


def load(tmp_path, text: str) -> dict:
    path = tmp_path / "lab.yml"
    path.write_text(text)
    return lab.load.__wrapped__(path)


def test_the_docs_address_is_the_labs_or_the_templates():
    expected = lab.load().get("docs_url", lab.DOCS_URL).rstrip("/")
    assert lab.docs_url("reference/answers/") == f"{expected}/reference/answers/"


def test_every_choice_is_read(tmp_path):
    assert load(tmp_path, yaml.safe_dump(CHOICES)) == CHOICES


@pytest.mark.parametrize(("text", "rule"), [
    ("licence: MIT\n", "did you mean 'license'"),
    ("license: WTFPL\n", "is not one of"),
    ("ros_distro: foxy\n", "is not one of"),
    ("build_type: catkin\n", "is not one of"),
    ("maintainer_email: ada@localhost\n", "catkin_pkg"),
    ("dependencies: [a]\n", "a mapping of tag to package names"),
    ("dependencies: {run_depend: [a]}\n", "did you mean"),
    ("dependencies: {exec_depend: [Bad-Name]}\n", "REP 144"),
    ("files: {/etc/passwd: x}\n", "not a path within the package"),
    ("files: {../up: x}\n", "not a path within the package"),
    ("header: [a]\n", "as text"),
    ("- a\n", "a mapping"),
    ("license: [\n", "not valid YAML"),
])
def test_a_broken_choice_is_one_line_naming_the_file(tmp_path, text, rule):
    with pytest.raises(lab.LabError) as caught:
        load(tmp_path, text)
    assert str(caught.value).startswith("lab.yml: ") and rule in str(caught.value)
    assert "\n" not in str(caught.value)


def test_the_labs_qos_is_the_default_of_every_endpoint():
    answers = {**VALID, "nodes": [{"name": "a", "publishers": ["x:std_msgs/msg/String", "y:std_msgs/msg/String:3"]}]}
    publishers = Answers(answers, lab={"qos": "sensor_data"}).package.nodes[0].publishers
    assert [(p.qos.profile, p.qos.depth) for p in publishers] == [("sensor_data", 5), (None, 3)]


def test_a_package_from_a_customised_template_has_the_labs_choices(tmp_path):
    template = snapshot_template(tmp_path / "template")
    (template / "extensions" / "lab.yml").write_text(yaml.safe_dump(CHOICES))
    git("commit", "-qam", "our lab's choices", cwd=template)
    destination = tmp_path / "lab_pkg"
    copier.run_copy(str(template), str(destination), defaults=True, unsafe=True, quiet=True, vcs_ref="HEAD",
                    data={"copyright_year": 2026, "nodes": [{"name": "a", "publishers": ["x:std_msgs/msg/String"]}]})
    package = package_dir(destination)
    manifest = parse_package(str(package / "package.xml"))
    manifest.validate()
    assert manifest.licenses == ["BSD-3-Clause"]
    assert manifest.maintainers[0].name == "Grace Hopper"
    depends = {d.name for d in manifest.exec_depends} | {d.name for d in manifest.test_depends}
    assert {"lab_bringup", "lab_lint_config"} <= depends
    assert (package / "CODEOWNERS").read_text() == "* @robotics-lab/maintainers\n"
    assert "// Part of the Robotics Lab's robot software." in (package / "src" / "a.cpp").read_text()
    assert "rclcpp::SensorDataQoS()" in (package / "include" / "lab_pkg" / "a_base.hpp").read_text()
    assert CHOICES["docs_url"] in (destination / "README.md").read_text()
