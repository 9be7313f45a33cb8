"""The template's own Python (extensions/ and tests/) stays clean under ruff.

The rules live here rather than in a config file because the design card fixes the
repository's top level; generated code is linted by the ROS linters instead.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RULES = "E,F,W,B,UP"  # pycodestyle, pyflakes, bugbear, pyupgrade
LINE_LENGTH = 120


def test_own_python_is_lint_clean():
    result = subprocess.run(
        [sys.executable, "-m", "ruff", "check", "--isolated", "--no-cache", "--output-format", "concise",
         "--select", RULES, "--line-length", str(LINE_LENGTH), "--target-version", "py311",
         # ros2/examples' nodes as they are published, the runtime benchmark's reference.
         "--extend-exclude", "tests/tools/reference_pair",
         str(ROOT / "extensions"), str(ROOT / "tests")],
        capture_output=True, text=True, timeout=120, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
