"""The documentation site (docs/mkdocs.yml) builds cleanly, offline, and shows every example answers file."""

from __future__ import annotations

import os
import re
import subprocess
import sys

from support.docs_site import CONFIG, DOCS, NO_NETWORK

PAGES = DOCS / "pages"
EXAMPLES = DOCS / "examples"
SNIPPET = re.compile(r'^--8<-- "examples/([^"]+)"$', re.MULTILINE)


def test_site_builds_strict_and_offline(tmp_path):
    site = tmp_path / "site"
    # NO_MKDOCS_2_WARNING: material's notice about its successor, printed on every build.
    env = {**os.environ, **NO_NETWORK, "NO_MKDOCS_2_WARNING": "1"}
    result = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--config-file", str(CONFIG), "--site-dir", str(site)],
        capture_output=True, text=True, timeout=120, env=env, cwd=tmp_path, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "WARNING" not in result.stderr, result.stderr
    # The snippets were expanded, not shown as their --8<-- lines.
    examples_page = (site / "reference" / "examples" / "index.html").read_text()
    assert "package_name" in examples_page and "--8&lt;--" not in examples_page


def test_every_example_is_shown_by_a_page():
    shown = {name for page in PAGES.rglob("*.md") for name in SNIPPET.findall(page.read_text())}
    examples = {path.name for path in EXAMPLES.glob("*.yml")}
    assert examples, EXAMPLES
    assert examples <= shown, f"not included by any page in docs/pages: {sorted(examples - shown)}"
