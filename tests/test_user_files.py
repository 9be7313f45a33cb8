"""Files of the user's project are read and written through rna/files.py alone, and come through whole.

A package holds images, meshes, bags, sources in Latin-1 or with CRLF line ends, links to
shared data: every step of an update, adding a node, merging and renaming reads them as
bytes with a text view only for text, and writes text back as the file held it.
"""

from __future__ import annotations

import ast
import os
import subprocess
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st
from rna import files
from rna.update.project import Project
from support.generation import ROOT

EXTENSIONS = ROOT / "extensions"
MARKER = "# not through rna/files.py:"
# What reads or writes a file, or a file as git committed it.
FILE_CALLS = {"read_text", "read_bytes", "write_text", "write_bytes", "open", "copy", "copy2", "copyfile", "copytree"}
XML_READS = {"parse", "iterparse"}  # ElementTree's, which open a file by its name
GIT_READS = {"cat-file", "show"}


def raw_file_access(path: Path) -> list[tuple[int, str]]:
    """(line, what) of each call in a module that reads or writes a file, or reads one from git."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Call):
            function = node.func
            name = function.attr if isinstance(function, ast.Attribute) else getattr(function, "id", None)
            receiver = getattr(getattr(function, "value", None), "id", None)
            if name in FILE_CALLS or (name in XML_READS and receiver in ("ET", "ElementTree", "minidom")):
                found.append((node.lineno, f"{name}()"))
        elif isinstance(node, ast.Constant) and node.value in GIT_READS:
            found.append((node.lineno, f"git {node.value}"))
    return found


def test_every_module_reads_and_writes_project_files_through_rna_files():
    """So that no step, now or later, can read a user's file another way (and crash on a PNG,
    rewrite a CRLF file as LF, follow a link out of the project, or read a bag of gigabytes):
    every other file access says on its line, or the line above, why it is not a project file."""
    unmarked = []
    for path in sorted(EXTENSIONS.rglob("*.py")):
        if path == EXTENSIONS / "rna" / "files.py":
            continue
        lines = path.read_text().split("\n")
        for number, what in raw_file_access(path):
            if not any(MARKER in line for line in lines[max(0, number - 2):number]):
                unmarked.append(f"{path.relative_to(ROOT)}:{number}: {what}: {lines[number - 1].strip()}")
    assert not unmarked, ("read or write the project's files with rna.files (or say why the file is not one: "
                          f"'{MARKER} <why>'):\n" + "\n".join(unmarked))


def test_the_guard_finds_what_it_must():
    probe = ROOT / "extensions" / "rna" / "files.py"
    assert {what for _, what in raw_file_access(probe)} >= {"read_bytes()", "write_bytes()", "git cat-file"}


# ─── Contents ─────────────────────────────────────────────────────────────────


def test_text_binary_and_other_encodings():
    assert files.of_bytes("café\n".encode()).text == "café\n"
    latin = files.of_bytes("# café\n".encode("latin-1"))
    assert (latin.kind, latin.encoding, latin.text) == ("text", "latin-1", "# café\n")
    assert latin.encode(latin.text + "x = 1\n") == "# café\nx = 1\n".encode("latin-1")
    with pytest.raises(files.NotWritable, match="LATIN-1 cannot hold"):
        latin.encode("Łukasz\n")
    png = files.of_bytes(b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR")
    assert (png.kind, png.text) == ("binary", None)
    assert files.of_bytes(b"\xff\xfe\x01\x02\x03").kind == "binary"  # no NUL, not UTF-8, controls
    stl = files.of_bytes(b"binary STL header" + b"\x00" * 63 + (12).to_bytes(4, "little"))
    assert stl.kind == "binary"
    bom = files.of_bytes(files.BOM + b"<a/>\n")
    assert (bom.text, bom.bom) == ("<a/>\n", True) and bom.encode(bom.text) == files.BOM + b"<a/>\n"


def test_line_ends():
    crlf = files.of_bytes(b"a\r\nb\r\n")
    assert (crlf.text, crlf.newline) == ("a\nb\n", "\r\n")
    assert crlf.encode("a\nb\nc\n") == b"a\r\nb\r\nc\r\n"
    mixed = files.of_bytes(b"a\r\nb\n")
    assert (mixed.text, mixed.newline) == ("a\r\nb\n", "\n")  # the carriage return stays in the text
    assert files.of_bytes(b"no final newline").encode("no final newline") == b"no final newline"
    assert files.of_bytes(b"").text == ""


@given(st.binary(max_size=300) | st.text(max_size=100).map(lambda text: text.replace("\n", "\r\n").encode())
       | st.text(st.characters(max_codepoint=255), max_size=100).map(lambda text: text.encode("latin-1")))
def test_text_written_back_unchanged_is_the_same_bytes(data):
    content = files.of_bytes(data)
    if content.kind == "text":
        assert content.encode(content.text) == data
    else:
        assert content.kind == "binary" and content.text is None and content.data == data


# ─── The disk ─────────────────────────────────────────────────────────────────


def test_links_are_read_as_links_and_never_written_through(tmp_path):
    project, outside = tmp_path / "project", tmp_path / "outside"
    project.mkdir()
    outside.mkdir()
    (outside / "shared.yaml").write_text("secret: 1\n")
    os.symlink(outside / "shared.yaml", project / "config.yaml")
    os.symlink(outside, project / "data")
    link = files.read(project, "config.yaml")
    assert (link.kind, link.target, link.text) == ("link", str(outside / "shared.yaml"), None)
    assert files.read(project, "data/shared.yaml") is None  # through a folder that leads out
    with pytest.raises(files.NotWritable, match="symbolic link"):
        files.write(project, "config.yaml", "mine: 2\n")
    with pytest.raises(files.NotWritable, match="leads out of the project"):
        files.write(project, "data/new.yaml", "mine: 2\n")
    assert (outside / "shared.yaml").read_text() == "secret: 1\n" and not (outside / "new.yaml").exists()
    files.put(project, "again.yaml", link)
    assert os.readlink(project / "again.yaml") == str(outside / "shared.yaml")


def test_large_files_are_read_only_when_the_template_owns_them(tmp_path):
    (tmp_path / "big.bag").write_bytes(b"x" * (files.LARGE + 1))
    assert files.read(tmp_path, "big.bag") == files.Content("large", size=files.LARGE + 1)
    assert files.read(tmp_path, "big.bag", owned=True).text == "x" * (files.LARGE + 1)


def test_a_write_keeps_the_files_encoding_and_line_ends(tmp_path):
    (tmp_path / "CMakeLists.txt").write_bytes("# Grüße\r\nproject(x)\r\n".encode("latin-1"))
    content = files.read(tmp_path, "CMakeLists.txt")
    files.write(tmp_path, "CMakeLists.txt", content.text + "add_executable(y y.cpp)\n")
    assert (tmp_path / "CMakeLists.txt").read_bytes() == "# Grüße\r\nproject(x)\r\nadd_executable(y y.cpp)\r\n".encode(
        "latin-1")
    files.write(tmp_path, "new/file.txt", "ü\n")
    assert (tmp_path / "new" / "file.txt").read_bytes() == "ü\n".encode()


def _git(root: Path, *args: str) -> None:
    subprocess.run(["git", "-c", "user.name=t", "-c", "user.email=t@example.com", *args], cwd=root, check=True,
                   capture_output=True)


def test_the_last_commit_comes_back_byte_for_byte(tmp_path):
    root = tmp_path / "repo"
    (root / "pkg" / "meshes").mkdir(parents=True)
    png, latin = b"\x89PNG\r\n\x1a\n\x00\x01\x02", "# café\r\n".encode("latin-1")
    (root / "pkg" / "doc.png").write_bytes(png)
    (root / "pkg" / "old.py").write_bytes(latin)
    (root / "pkg" / "meshes" / "base.stl").write_bytes(b"\x00" * (files.LARGE + 10))
    (root / "pkg" / "run.sh").write_text("#!/bin/sh\n")
    (root / "pkg" / "run.sh").chmod(0o755)
    os.symlink("doc.png", root / "pkg" / "picture.png")
    latin_name = os.fsdecode(b"caf\xe9.txt")  # a file name that is not UTF-8
    (root / "pkg" / latin_name).write_bytes(b"old name\n")
    _git(root, "init", "-q")
    _git(root, "add", "-A")
    _git(root, "commit", "-qm", "mine")
    project = Project(root / "pkg", ".copier-answers.yml")
    assert project.committed_files == {"doc.png", "old.py", "meshes/base.stl", "run.sh", "picture.png", latin_name}
    assert project.committed_content("doc.png").data == png and project.committed("doc.png") is None
    assert project.committed("old.py") == "# café\n"
    assert project.committed_content("meshes/base.stl").kind == "large"
    assert project.committed_content("picture.png").target == "doc.png"
    for path in project.committed_files:
        (root / "pkg" / path).unlink()
    for path in project.committed_files:
        project.restore(path)
    assert (root / "pkg" / "doc.png").read_bytes() == png and (root / "pkg" / "old.py").read_bytes() == latin
    assert (root / "pkg" / "meshes" / "base.stl").stat().st_size == files.LARGE + 10
    assert os.readlink(root / "pkg" / "picture.png") == "doc.png" and os.access(root / "pkg" / "run.sh", os.X_OK)
    assert project.write("old.py", "# café\nx = 1\n")
    assert (root / "pkg" / "old.py").read_bytes() == "# café\r\nx = 1\r\n".encode("latin-1")
    assert not project.write("picture.png", "text") and project.unwritable[0][0] == "picture.png"
    assert project.changed_files() == (set(), {"old.py"}, set())


@pytest.mark.parametrize(("settings", "crlf"), [
    ({}, {"a.txt", "sub dir/b.auto"}),
    ({"core.eol": "crlf"}, {"a.txt", "sub dir/b.auto", "c.text"}),
    ({"core.autocrlf": "true"}, {"a.txt", "sub dir/b.auto", "c.text", "d.md"}),
    ({"core.autocrlf": "input"}, {"a.txt", "sub dir/b.auto"}),
])
def test_line_ends_as_git_checks_files_out(tmp_path, settings, crlf):
    """The eol and text attributes first, then core.autocrlf, then core.eol (gitattributes(5))."""
    _git(tmp_path, "init", "-q")
    for key, value in settings.items():
        _git(tmp_path, "config", key, value)
    (tmp_path / ".gitattributes").write_text("*.txt eol=crlf\n*.auto text=auto eol=crlf\n*.text text\n"
                                             "*.lf text eol=lf\n*.bin -text\n*.png binary\n")
    names = ["a.txt", "sub dir/b.auto", "c.text", "d.md", "e.lf", "f.bin", "g.png"]
    assert files.crlf_on_checkout(tmp_path, names) == crlf
    for name in names:
        (tmp_path / name).parent.mkdir(exist_ok=True)
        (tmp_path / name).write_bytes(b"one\ntwo\n")
    (tmp_path / "a mixed.txt").write_bytes(b"one\r\ntwo\n")
    os.symlink("c.text", tmp_path / "link.txt")
    assert files.as_checked_out(tmp_path, [*names, "a mixed.txt", "link.txt"]) == sorted(crlf)
    assert {name for name in names if (tmp_path / name).read_bytes() == b"one\r\ntwo\r\n"} == crlf
    assert (tmp_path / "a mixed.txt").read_bytes() == b"one\r\ntwo\n" and os.readlink(tmp_path / "link.txt") == "c.text"
