"""The JSON Schema of the answers: made from the rules, up to date, and it accepts the examples."""

from __future__ import annotations

import json
import subprocess
import sys

import jsonschema
import pytest
import yaml

from support.generation import EXAMPLES, ROOT, example, examples

SCHEMA_FILE = ROOT / "docs" / "pages" / "schema" / "answers.json"
SCHEMA_LINE = "# yaml-language-server: $schema=../pages/schema/answers.json"


@pytest.fixture(scope="module")
def validator():
    schema = json.loads(SCHEMA_FILE.read_text())
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


def test_the_schema_file_is_made_from_the_current_rules():
    result = subprocess.run([sys.executable, str(ROOT / "tests" / "tools" / "make_schema.py"), "--check"],
                            capture_output=True, text=True, check=False)
    assert result.returncode == 0, result.stdout + result.stderr


@pytest.mark.parametrize("name", examples())
def test_every_example_follows_the_schema_and_says_so(validator, name):
    assert (EXAMPLES / f"{name}.yml").read_text().splitlines()[0] == SCHEMA_LINE
    errors = [error.message for error in validator.iter_errors(example(name))]
    assert not errors


@pytest.mark.parametrize("changes", [
    {"package_name": "My-Bad Pkg"}, {"package_name": "p" * 40}, {"package_name": "class"},
    {"ros_distro": "foxy"}, {"license": "WTFPL"}, {"maintainer_email": "ada@localhost"},
    {"nodes": [{"name": "talker_base"}]}, {"nodes": [{"name": "Talker"}]}, {"nodes": []},
    {"nodes": [{"name": "a", "publishers": ["cmd vel:geometry_msgs/msg/Twist"]}]},
    {"nodes": [{"name": "a", "publisher": []}]},
    {"nodes": [{"name": "a", "timers": [0]}]},
    {"nodes": [{"name": "a", "autostart": True}]},
    {"nodes": [{"name": "a", "executor": "parallel"}]}, {"nodes": [{"name": "a", "threads": 2}]},
    {"nodes": [{"name": "a", "executor": "multi_threaded", "threads": 0}]},
    {"nodes": [{"name": "a", "callback_groups": [{"name": "g", "members": []}]}]},
    {"nodes": [{"name": "a", "callback_groups": [{"name": "g", "type": "shared", "members": ["x"]}]}]},
    {"nodes": [{"name": "a", "remappings": {"cmd vel": "x"}}]}, {"nodes": [{"name": "a", "remappings": ["a:=b"]}]},
    {"interfaces": {"messages": [{"name": "target", "fields": ["float64 x"]}]}},
    {"unknown_question": 1},
])
def test_the_schema_refuses_what_the_rules_refuse(validator, changes):
    answers = {**yaml.safe_load((EXAMPLES / "talker_listener.yml").read_text()), **changes}
    assert list(validator.iter_errors(answers))
