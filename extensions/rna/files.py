"""A file of the user's project, read and written so that nothing in it is lost.

Packages hold more than UTF-8 text: images, meshes and bags, sources written in Latin-1
or with Windows line ends, symbolic links to shared data, files of gigabytes. Every step
that reads or writes a file of the project (the after-update step and its merges and
renames, adding a node to a package, the ports) does it here, and nowhere else
(tests/test_user_files.py holds the other modules to it):

- a file is read as bytes, and has a text view only when it is text. Binary (a NUL byte
  in its first 8000 bytes, git's rule, or control characters in bytes that are not
  UTF-8) has none: it is never parsed and never rewritten;
- text is UTF-8 (with or without a byte order mark) or, failing that, an 8-bit encoding,
  read as Latin-1: one character per byte, so that writing the text back unchanged gives
  the same bytes;
- line ends that are all CRLF read as LF and are written back as CRLF; a file that mixes
  them keeps its carriage returns in its text;
- a symbolic link is read as a link (its target), never followed; nothing is written
  through a link, nor into a folder that leads out of the project;
- a file larger than LARGE bytes is not read at all, unless the template owns it.

Writing a text back keeps its file's encoding, byte order mark and line ends; text its
encoding cannot hold is refused (NotWritable), never written in another encoding.
"""

from __future__ import annotations

import os
import re
import subprocess
from dataclasses import dataclass
from pathlib import Path

LARGE = 1 << 20  # bytes: larger files of the user's (bags, meshes, maps) are not read
BINARY_PROBE = 8000  # git's: a NUL byte in the first 8000 bytes makes a file binary
BOM = b"\xef\xbb\xbf"
# Bytes no text file holds (C0 controls but tab, line ends, form feed and escape; DEL).
_CONTROLS = re.compile(rb"[\x00-\x08\x0b\x0e-\x1a\x1c-\x1f\x7f]")


class NotWritable(ValueError):
    """Why a text cannot be written to a file of the project: one line for the user."""


@dataclass(frozen=True)
class Content:
    """What one file holds: its kind, its bytes, and a text view when it is text."""

    kind: str  # "text", "binary", "link" or "large" (not read)
    data: bytes | None = None  # the bytes (a link: its target's name; a large file: None)
    text: str | None = None  # text only: lines end in "\n" (a mixed file keeps its "\r"s)
    encoding: str = "utf-8"  # text only: "utf-8" or "latin-1"
    bom: bool = False  # text only: UTF-8 with a byte order mark
    newline: str = "\n"  # text only: "\r\n" when every line ended so
    size: int = 0

    @property
    def target(self) -> str | None:
        """A link's target, as the link names it."""
        return os.fsdecode(self.data) if self.kind == "link" and self.data is not None else None

    def encode(self, text: str) -> bytes:
        """`text` as this file would hold it: its encoding, byte order mark and line ends."""
        if self.newline != "\n":
            text = text.replace("\n", self.newline)
        try:
            data = text.encode(self.encoding)
        except UnicodeEncodeError as error:
            raise NotWritable(f"it is {self.encoding.upper()} text and the update's text holds "
                              f"{text[error.start:error.end]!r}, which {self.encoding.upper()} cannot hold") from None
        return BOM + data if self.bom else data


UTF8 = Content("text", b"", "", size=0)  # how a new file is written


def of_bytes(data: bytes) -> Content:
    """The content of a file that holds `data`."""
    if b"\0" in data[:BINARY_PROBE]:
        return Content("binary", data, size=len(data))
    bom = data.startswith(BOM)
    body = data[len(BOM):] if bom else data
    try:
        text, encoding = body.decode("utf-8"), "utf-8"
    except UnicodeDecodeError:
        if _CONTROLS.search(body):
            return Content("binary", data, size=len(data))
        text, encoding, bom = data.decode("latin-1"), "latin-1", False
    newline = "\n"
    if "\r\n" in text and text.count("\r\n") == text.count("\n") and "\r" not in text.replace("\r\n", ""):
        text, newline = text.replace("\r\n", "\n"), "\r\n"
    return Content("text", data, text, encoding, bom, newline, len(data))


def link(target: bytes | str) -> Content:
    data = os.fsencode(target)
    return Content("link", data, size=len(data))


def inside(root: Path, path: str) -> bool:
    """Whether the folder `path` is in stays inside `root` once its links are followed."""
    folder = (Path(root) / path).parent
    try:
        return folder.resolve().is_relative_to(Path(root).resolve())
    except (OSError, RuntimeError):  # a loop of links
        return False


def read(root: Path, path: str, owned: bool = False) -> Content | None:
    """The file `path` of the project in `root`, or None when there is none (or no file:
    a folder, a socket; or one reached through a folder that leads out of the project).

    `owned`: the template makes this file, so it is read whatever its size."""
    file = Path(root) / path
    if not inside(root, path):
        return None
    try:
        stat = file.lstat()
    except OSError:
        return None
    if file.is_symlink():
        return link(os.readlink(file))
    if not file.is_file():
        return None
    if stat.st_size > LARGE and not owned:
        return Content("large", size=stat.st_size)
    try:
        return of_bytes(file.read_bytes())
    except OSError:
        return None


def text(root: Path, path: str, owned: bool = False) -> str | None:
    """The text of the file `path`, or None (no file, binary, a link, too large)."""
    content = read(root, path, owned)
    return content.text if content is not None else None


def writable(root: Path, path: str) -> None:
    """NotWritable when `path` is a link or lies through a folder that leads out of the project."""
    if not inside(root, path):
        raise NotWritable("its folder leads out of the project (a symbolic link)")
    if (Path(root) / path).is_symlink():
        raise NotWritable("it is a symbolic link (the update writes no file through one)")


def write(root: Path, path: str, text: str, like: Content | None = None) -> None:
    """Write `text` to the file `path` as `like` holds text (by default, as the file there
    does now, or UTF-8 with LF line ends for a new one); NotWritable says why not."""
    writable(root, path)
    if like is None or like.kind != "text":
        current = read(root, path, owned=True)
        like = current if current is not None and current.kind == "text" else UTF8
    data = like.encode(text)
    file = Path(root) / path
    file.parent.mkdir(parents=True, exist_ok=True)
    file.write_bytes(data)


def put(root: Path, path: str, content: Content, executable: bool = False) -> None:
    """Put `content` back at `path` as it was: the same bytes, or the same link."""
    writable(root, path)
    file = Path(root) / path
    file.parent.mkdir(parents=True, exist_ok=True)
    if content.kind == "link":
        if file.exists() or file.is_symlink():
            file.unlink()
        os.symlink(content.data, file)
        return
    if content.data is None:
        raise NotWritable(f"it is {content.size} bytes, more than the update reads")
    file.write_bytes(content.data)
    if executable:
        file.chmod(file.stat().st_mode | 0o111)


# --- files as git committed them (the project's last commit, the user's files before an update)


def blobs(root: Path, objects: list[str]) -> dict[str, bytes]:
    """The bytes of git blobs, by object name, from one git process (those git could not give are left out)."""
    output = subprocess.run(["git", "cat-file", "--batch"], cwd=root, input="".join(f"{o}\n" for o in objects).encode(),
                            capture_output=True, check=False).stdout
    found, start = {}, 0
    for name in objects:
        end = output.find(b"\n", start)
        if end < 0:  # git stopped short
            break
        header = output[start:end].split()
        start = end + 1
        if len(header) != 3 or not header[2].isdigit():  # "<object> missing": no content follows
            continue
        size = int(header[2])
        found[name] = output[start:start + size]
        start += size + 1
    return found


def blob(root: Path, name: str) -> bytes:
    return subprocess.run(["git", "cat-file", "blob", name], cwd=root, capture_output=True, check=True).stdout


def put_blob(root: Path, path: str, name: str, executable: bool = False) -> None:
    """Write the git blob `name` at `path`, streamed (a large file is never held in memory)."""
    writable(root, path)
    file = Path(root) / path
    file.parent.mkdir(parents=True, exist_ok=True)
    with file.open("wb") as out:
        subprocess.run(["git", "cat-file", "blob", name], cwd=root, stdout=out, check=True)
    if executable:
        file.chmod(file.stat().st_mode | 0o111)


# --- line ends as git writes files out (a .gitattributes `eol=crlf`, core.autocrlf on Windows)


def _git_setting(root: Path, key: str) -> str:
    return subprocess.run(["git", "config", "--get", key], cwd=root, capture_output=True, text=True,
                          check=False).stdout.strip().lower()


def crlf_on_checkout(root: Path, paths: list[str]) -> set[str]:
    """Those of `paths` (text files) git writes with CRLF line ends when it checks them out:
    the `eol` and `text` attributes, then core.autocrlf and core.eol (gitattributes(5)). In such
    a checkout git holds the files with LF line ends, so Copier's new version of a file comes
    with LF line ends; the update writes them as git would have."""
    if not paths:
        return set()
    autocrlf = _git_setting(root, "core.autocrlf")
    autocrlf = "true" if autocrlf in ("true", "yes", "on", "1") else autocrlf
    text_eol = "crlf" if autocrlf == "true" else "lf" if autocrlf == "input" else _git_setting(root, "core.eol")
    listed = subprocess.run(["git", "check-attr", "-z", "--stdin", "text", "eol"], cwd=root, capture_output=True,
                            input=b"".join(os.fsencode(path) + b"\0" for path in paths), check=False).stdout
    fields = [os.fsdecode(field) for field in listed.split(b"\0")]
    attributes: dict[str, dict[str, str]] = {}
    for path, attribute, value in zip(fields[0::3], fields[1::3], fields[2::3], strict=False):
        attributes.setdefault(path, {})[attribute] = value
    crlf = set()
    for path in paths:
        text, eol = attributes.get(path, {}).get("text", "unspecified"), attributes.get(path, {}).get("eol")
        if text == "unset":  # -text, binary: written as it is
            continue
        if eol in ("crlf", "lf"):  # an eol attribute makes the file text, whatever the settings
            wanted = eol
        elif text in ("set", "auto") or autocrlf == "true":
            wanted = text_eol
        else:
            continue
        if wanted == "crlf":
            crlf.add(path)
    return crlf


def as_checked_out(root: Path, paths: list[str]) -> list[str]:
    """Give the text files among `paths` that hold only LF line ends the CRLF ones git would
    check them out with (crlf_on_checkout); the files rewritten."""
    rewritten = []
    for path in sorted(crlf_on_checkout(root, paths)):
        content = read(root, path)
        if content is None or content.kind != "text" or "\r" in content.text or "\n" not in content.text \
                or content.newline != "\n":
            continue
        try:
            write(root, path, content.text, like=Content("text", encoding=content.encoding, bom=content.bom,
                                                         newline="\r\n"))
        except NotWritable:
            continue
        rewritten.append(path)
    return rewritten
