"""Render every example answers file (docs/examples/*.yml) into a folder, one package each.

    tests/env python tests/tools/render_examples.py OUT [--template PATH]

The template is the working tree (committed into a scratch repository first, so uncommitted
changes count). Comparing two such folders with `diff -r` shows what a change does to the
generated output.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import copier
import yaml

ROOT = Path(__file__).resolve().parents[2]
FIXED_ANSWERS = {"maintainer": "Ada Lovelace", "maintainer_email": "ada@example.com",
                 "copyright_holder": "Ada Lovelace", "copyright_year": 2026}


def snapshot(source: Path, destination: Path) -> Path:
    for item in ("copier.yml", "template", "extensions"):
        if (source / item).is_dir():
            shutil.copytree(source / item, destination / item, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            shutil.copy2(source / item, destination / item)
    for args in (["init", "-q", "-b", "main"], ["add", "-A"],
                 ["-c", "user.name=rna", "-c", "user.email=rna@example.com", "commit", "-q", "-m", "snapshot"]):
        subprocess.run(["git", *args], cwd=destination, check=True)
    return destination


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--template", type=Path, default=ROOT)
    parser.add_argument("--examples", type=Path, default=ROOT / "docs" / "examples")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="rna-examples-") as scratch:
        template = snapshot(args.template, Path(scratch))
        for example in sorted(Path(args.examples).glob("*.yml")):
            answers = {**FIXED_ANSWERS, **yaml.safe_load(example.read_text())}
            copier.run_copy(str(template), str(args.out / example.stem), data=answers, defaults=True,
                            unsafe=True, quiet=True, vcs_ref="HEAD")
    return 0


if __name__ == "__main__":
    sys.exit(main())
