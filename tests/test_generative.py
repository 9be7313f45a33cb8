"""Any valid answer set gives a package whose files read back right; any invalid one a one-line error (issue 8).

Property-based: Hypothesis draws the answer sets (tests/support/strategies.py) and each
one goes through Copier in-process, from a YAML data file as `copier copy --data-file`
reads it. The profile (tests/conftest.py) keeps the fast tier to a few seconds and
reproducible; HYPOTHESIS_PROFILE=thorough draws many more.
"""

from __future__ import annotations

import ast
import re
import subprocess
import sys
import tempfile
import unicodedata
import xml.etree.ElementTree as ET
from pathlib import Path

import copier
import pytest
import yaml
from catkin_pkg.package import parse_package
from copier.errors import UserMessageError
from hypothesis import example, given
from rna import build_package, distros
from rna.parameters import INT_RANGES
from rna.update import resolve
from support.launch_files import description, expected_description
from support.packages import table_rows_of_wrong_width
from support.strategies import invalid_answers, read_data_file, valid_answers, write_data_file


def copy(template: Path, destination: Path, answers: dict) -> None:
    """`copier copy --data-file answers.yml --defaults --trust`, in-process."""
    data = read_data_file(write_data_file(answers, destination.parent / "answers.yml"))
    copier.run_copy(str(template), str(destination), data=data, defaults=True, unsafe=True, quiet=True)


# ----------------------------------------------------------------------------- invalid answers

@given(invalid_answers())
def test_an_invalid_answer_set_is_refused_with_one_line_naming_the_question(template_folder, case):
    answers, question = case
    with tempfile.TemporaryDirectory() as scratch:
        destination = Path(scratch) / "out"
        with pytest.raises(UserMessageError) as refused:
            copy(template_folder, destination, answers)
        message = str(refused.value)
        assert "\n" not in message
        assert message.startswith(f"rna-template: invalid answer to '{question}': "), message
        assert not destination.exists()


# ----------------------------------------------------------------------------- valid answers

def extreme_numbers(distro: str, language: str) -> tuple[dict, dict]:
    """A node with numbers at the edges; `1e+308` in a config file is a string to YAML 1.1 (PyYAML, rosparam)."""
    parameters = {"huge": ("double", 1e308), "tiny": ("double", 1e-06), "gains": ("double[]", [1e16, -5e-324]),
                  "lowest": ("int", INT_RANGES[distros.generation(distro)][0]), "ranged": ("double", 1e300)}
    answers = [{"name": name, "type": ptype, "default": default} for name, (ptype, default) in parameters.items()]
    answers[-1]["range"] = [-1e308, 1e308]
    answers[-2]["range"] = [parameters["lowest"][1], 0]
    return {"name": "edge", "language": language, "parameters": answers}, parameters


def edges(distro: str, build_type: str, language: str) -> dict:
    """Names at their longest, a description with a long word, extreme numbers: what broke files before."""
    url = "https://example.com/" + "a-very-long-path/" * 6
    node = {"name": "n" * 39, "language": language, "description": f"See {url}", "timers": [1e-9],
            "service_servers": [{"name": "/" + "s" * 79, "type": "std_srvs/srv/Trigger", "id": "reset"}],
            "action_clients": [{"name": "a" * 80, "type": "test_msgs/action/Fibonacci", "id": "fib"}],
            "publishers": ["p" * 40 + ":std_msgs/msg/String", "q" * 40 + ":std_msgs/msg/String"],
            "parameters": [{"name": "x" * 40, "default": 1.0, "description": url,
                            "range": [-1.7976931348623157e308, 1.7976931348623157e308, 1e-300]},
                           # NEL read back as a space from the answers file (PyYAML).
                           {"name": "greeting", "type": "string", "default": "a\x85b\u2028c"}]}
    numbers, extremes = extreme_numbers(distro, language)
    return {"package_name": "p" * 33 if language == "cpp" else "p" * 39, "description": url,
            "maintainer": "Ada", "maintainer_email": "a" * 60 + "@" + "b" * 60 + ".org", "license": "MIT",
            "copyright_holder": "Ada", "copyright_year": 2026, "ros_distro": distro, "build_type": build_type,
            "nodes": [node, numbers], "_expected": {
                node["name"]: {"x" * 40: ("double", 1.0), "greeting": ("string", "a\x85b\u2028c")},
                numbers["name"]: extremes}}


@given(valid_answers(interfaces=True))
@example(edges("jazzy", "ament_python", "python"))
@example(edges("jazzy", "ament_cmake", "cpp"))
@example(edges("noetic", "catkin", "python"))
@example(edges("noetic", "catkin", "cpp"))
def test_a_valid_answer_set_gives_files_that_read_back(template_folder, answers):
    answers = dict(answers)
    expected = answers.pop("_expected")
    model = build_package(answers)
    with tempfile.TemporaryDirectory() as scratch:
        destination = Path(scratch) / "out"
        copy(template_folder, destination, answers)
        package = destination / model.name
        files = [path for path in destination.rglob("*") if path.is_file()]
        # The answers file is what `copier update` starts from: it must give the same package.
        recorded = (destination / ".copier-answers.yml").read_text(encoding="utf-8")
        assert build_package(yaml.safe_load(recorded)) == model
        assert resolve.edited_by_hand(recorded) is False, "its checksum does not match the answers it holds"

        python = []
        for path in files:
            if path.suffix == ".py" or path.parent.name == "scripts":
                source = path.read_text(encoding="utf-8")
                compile(source, str(path), "exec")
                check_python_parameters(ast.parse(source), expected, path)
                python.append(path)
            elif path.suffix in (".xml", ".launch"):
                ET.parse(path)
            elif path.suffix in (".yaml", ".yml"):
                yaml.safe_load(path.read_text(encoding="utf-8"))
            elif path.suffix in (".cpp", ".hpp", ".h"):
                check_cpp_lines(path)
        parse_package(str(package / "package.xml")).validate()
        manifest = ET.parse(package / "package.xml").getroot()  # catkin_pkg gives the description as XML
        assert (manifest.findtext("description"), manifest.findtext("maintainer"),
                manifest.find("maintainer").get("email")) == (model.description, model.maintainer,
                                                              model.maintainer_email)
        lint_python(python)
        if model.ros == 2:  # in any format, the launch file starts every node as the answers say
            assert description(package / model.launch_file, model.ros_distro) == expected_description(model)
        assert not table_rows_of_wrong_width((destination / "README.md").read_text(encoding="utf-8"))

        for node in model.nodes:
            config = yaml.safe_load((package / node.config_file).read_text(encoding="utf-8"))
            loaded = config if model.ros == 1 else config["/**"]["ros__parameters"]
            assert set(loaded or {}) == set(expected[node.name]), node.config_file
            for name, (ptype, default) in expected[node.name].items():
                assert_same_value(loaded[name], default, f"{node.config_file}: {name} ({ptype})")



def assert_same_value(loaded: object, default: object, where: str) -> None:
    """The value read back has the default's type, element by element: int stays int, double float."""
    if isinstance(default, list):
        assert isinstance(loaded, list) and len(loaded) == len(default), where
        for item, wanted in zip(loaded, default, strict=True):
            assert_same_value(item, wanted, where)
        return
    assert type(loaded) is type(default), f"{where}: {loaded!r} read back as {type(loaded).__name__}"
    assert loaded == default, f"{where}: {loaded!r} != {default!r}"


def check_python_parameters(tree: ast.AST, expected: dict, path: Path) -> None:
    """Each default in declare_parameter() (ROS 2) or rospy.get_param() (ROS 1) reads back as the answer's."""
    wanted = expected.get(path.stem.removesuffix("_base"), {})
    for call in ast.walk(tree):
        if (isinstance(call, ast.Call) and isinstance(call.func, ast.Attribute)
                and call.func.attr in ("declare_parameter", "get_param") and len(call.args) >= 2):
            name = ast.literal_eval(call.args[0]).lstrip("~")
            assert_same_value(ast.literal_eval(call.args[1]), wanted[name][1], f"{path.name}: {name}")


def lint_python(files: list[Path]) -> None:
    """ruff's pyflakes rules, syntax errors, blank lines, invalid escapes, flake8-quotes with ament_flake8's
    single quotes, and ament_flake8's 99 columns.

    flake8 counts characters where ruff counts a wide character as two columns: E501 is
    checked here as flake8 checks it.
    """
    if not files:
        return
    for path in files:
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            assert len(line) <= 99, f"{path.name}:{number}: {line}"
    result = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "--isolated", "--preview",
                             "--select", "F,E3,E9,W291,W293,W391,W6,Q",
                             "--config", "lint.flake8-quotes.inline-quotes = 'single'", *map(str, files)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr


def check_cpp_lines(path: Path) -> None:
    """What ament_cpplint and GCC's -Wall see line by line: 100 columns, and comments that end where they seem to."""
    lines = path.read_text(encoding="utf-8").splitlines()
    for number, line in enumerate(lines, 1):
        where = f"{path.name}:{number}: {line}"
        # cpplint counts East Asian wide characters as two columns, combining ones as none.
        width = sum(2 if unicodedata.east_asian_width(c) in "WF" else 0 if unicodedata.combining(c) else 1
                    for c in line)
        assert width <= 100, where
        assert line == line.rstrip(), where
        comment = line.partition("//")[2] if line.lstrip().startswith("//") else ""
        assert not comment.endswith(("\\", "??/")), where  # a comment continued onto the next line
        # A literal whose magnitude does not fit int64_t, and timers that would never wait
        # (but a lifecycle component's autostart timer, which fires once: it cancels itself).
        assert "-9223372036854775808" not in line, where
        if number > 1 and lines[number - 2].endswith("autostart_timer_ = create_wall_timer("):
            assert "autostart_timer_->cancel();" in lines[number + 1], where
            continue
        assert not re.search(r"std::chrono::\w+\(0\)|ros::Duration\(0(\.0)?\)", line), where
