"""The example answers files of docs/examples, which the docs show and the tiers use, stay valid."""

from __future__ import annotations

import pytest

from support.generation import example, examples, generate
from support.packages import dependencies, model_of, package_dir


@pytest.mark.parametrize("name", examples())
def test_example_generates_a_package(template_folder, tmp_path, name):
    destination = tmp_path / name
    generate(template_folder, destination, example(name))
    model = model_of(destination)
    assert dependencies(package_dir(destination) / "package.xml")
    for node in model.nodes:
        assert (package_dir(destination) / node.user_file).is_file()
        assert (package_dir(destination) / node.base_file).is_file()
