"""Write the JSON Schema of the answers (docs/pages/schema/answers.json) from the template's rules.

    tests/env python tests/tools/make_schema.py [--check]

The fast tier checks that the file is up to date (--check does the same here).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "extensions"))

from rna import lab, schema  # noqa: E402 - the template's own package

TARGET = ROOT / "docs" / "pages" / "schema" / "answers.json"


def text() -> str:
    return json.dumps(schema.answers_schema(lab.DOCS_URL), indent=2, ensure_ascii=False) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="fail if the file is not up to date")
    args = parser.parse_args()
    if args.check:
        if not TARGET.is_file() or TARGET.read_text() != text():
            print(f"{TARGET.relative_to(ROOT)} is out of date: run tests/env python tests/tools/make_schema.py")
            return 1
        return 0
    TARGET.parent.mkdir(parents=True, exist_ok=True)
    TARGET.write_text(text())
    return 0


if __name__ == "__main__":
    sys.exit(main())
