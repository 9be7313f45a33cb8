"""The documentation site's build, shared by tests/test_docs.py (strict, offline) and tests/test_site.py (browser)."""

from __future__ import annotations

from support.generation import ROOT

DOCS = ROOT / "docs"
CONFIG = DOCS / "mkdocs.yml"
# Nothing may be fetched while building: any HTTP(S) request through Python's usual clients goes to
# a closed port and fails the build.
NO_NETWORK = {"HTTP_PROXY": "http://127.0.0.1:9", "HTTPS_PROXY": "http://127.0.0.1:9",
              "http_proxy": "http://127.0.0.1:9", "https_proxy": "http://127.0.0.1:9", "NO_PROXY": "", "no_proxy": ""}
