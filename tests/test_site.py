"""The documentation site in a real browser: headless Chromium (Debian's chromium and
chromium-driver, driven by selenium) opens every page of the built site, served on the
loopback address, and checks that the node graphs rendered (Mermaid drew an SVG from the
site's own mermaid.js) and that no link leads nowhere (every page linked loads, every
anchor exists).

The browser tier (`pytest -m browser`): run as root, it installs Chromium first, as the
ROS 1 tier installs its Debian packages; outside CI it is skipped where Chromium cannot
be had, and with CI=true that is a failure.
"""

from __future__ import annotations

import functools
import http.server
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path
from urllib.parse import urldefrag, urlparse

import pytest
from support.docs_site import CONFIG, NO_NETWORK
from support.tiers import unavailable

pytestmark = pytest.mark.browser

CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
# Flags that work in a container as root, with nothing fetched in the background.
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-dev-shm-usage")


def ensure_chromium() -> None:
    if Path(CHROMIUM).exists() and Path(CHROMEDRIVER).exists():
        return
    if os.geteuid() != 0 or shutil.which("apt-get") is None:
        unavailable("Debian's chromium and chromium-driver are not installed (install them as root)")
    env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
    for command in (["apt-get", "update", "-qq"], ["apt-get", "install", "-y", "-qq", "chromium", "chromium-driver"]):
        result = subprocess.run(command, capture_output=True, text=True, env=env, timeout=900, check=False)
        if result.returncode != 0:
            unavailable(f"{' '.join(command)} failed: {result.stderr.strip()[-500:]}")


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The site built as the fast tier builds it, served on 127.0.0.1 (a free port)."""
    folder = tmp_path_factory.mktemp("site")
    env = {**os.environ, **NO_NETWORK, "NO_MKDOCS_2_WARNING": "1"}
    result = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--config-file", str(CONFIG),
                             "--site-dir", str(folder)], capture_output=True, text=True, timeout=300, env=env,
                            cwd=folder, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    handler = functools.partial(QuietHandler, directory=str(folder))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format, *args):  # noqa: A002 - the base class's name
        pass


@pytest.fixture(scope="module")
def browser():
    ensure_chromium()
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    profile = tempfile.mkdtemp(prefix="rna-chromium-")
    for flag in (*FLAGS, f"--user-data-dir={profile}"):
        options.add_argument(flag)
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    driver.set_page_load_timeout(60)
    try:
        yield driver
    finally:
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)


def wait_for(check, timeout: float = 20.0):
    """`check()` once it is truthy, or its last value after `timeout` seconds."""
    deadline = time.monotonic() + timeout
    while True:
        value = check()
        if value or time.monotonic() > deadline:
            return value
        time.sleep(0.1)


def diagrams(browser) -> list[bool]:
    """For each diagram on the page, whether Mermaid drew it: an SVG with nodes inside it.

    Material draws into a closed shadow root, which page scripts cannot see into: the
    document is read through the browser's DevTools, which can.
    """
    document = browser.execute_cdp_cmd("DOM.getDocument", {"depth": -1, "pierce": True})["root"]

    def attributes(node) -> dict:
        flat = node.get("attributes", [])
        return dict(zip(flat[::2], flat[1::2], strict=False))

    def drawn(node) -> bool:
        if node.get("nodeName", "").lower() == "svg" and any(
                "node" in attributes(child).get("class", "").split() for child in descendants(node)):
            return True
        return any(drawn(child) for child in (*node.get("children", ()), *node.get("shadowRoots", ())))

    def descendants(node):
        for child in (*node.get("children", ()), *node.get("shadowRoots", ())):
            yield child
            yield from descendants(child)

    return [drawn(node) for node in descendants(document)
            if node.get("nodeName") == "DIV" and "mermaid" in attributes(node).get("class", "").split()]


@pytest.mark.parametrize("page", ["", "tutorial/"])
def test_the_node_graphs_render_as_diagrams(site, browser, page):
    browser.get(site + page)
    drawn = wait_for(lambda: (found := diagrams(browser)) and all(found) and found)
    assert drawn, f"{page or 'home'}: no Mermaid diagram drawn ({diagrams(browser)})"
    # Drawn by the site's own script: nothing came from elsewhere.
    scripts = browser.execute_script("return [...document.scripts].map(s => s.src).filter(Boolean)")
    assert all(src.startswith(site) for src in scripts), scripts


def test_no_page_has_a_broken_link(site, browser):
    """Every page reachable from the home page loads, and every link within the site leads to a page
    that loads and to an anchor that is on it."""
    pages: dict[str, set[str] | None] = {}  # each page: the ids on it, or None when it does not load
    links: list[tuple[str, str, str]] = []  # (on page, to page, anchor)
    queue = [site]
    while queue:
        url = queue.pop()
        if url in pages:
            continue
        try:
            urllib.request.urlopen(url, timeout=10).close()
        except urllib.error.HTTPError:
            pages[url] = None
            continue
        browser.get(url)
        pages[url] = set(browser.execute_script("return [...document.querySelectorAll('[id]')].map(e => e.id)"))
        for href in browser.execute_script("return [...document.querySelectorAll('a[href]')].map(a => a.href)"):
            target, anchor = urldefrag(href)
            if urlparse(target).netloc != urlparse(site).netloc or "/assets/" in target or (
                    Path(urlparse(target).path).suffix not in ("", ".html")):
                continue
            links.append((url, target, anchor))
            queue.append(target)
    broken = [(page, target + (f"#{anchor}" if anchor else "")) for page, target, anchor in links
              if pages.get(target) is None or (anchor and anchor not in pages[target])]
    assert len(pages) > 30, sorted(pages)
    assert not broken, broken
