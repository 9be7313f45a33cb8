"""Line breaking by length: a template marks where a line may change; it changes only if too long.

Templates write each statement, comment or docstring on one line with markers:

- `{{ br }}` (BREAK) where the linters of the generated package accept a line break;
- `{{ sbr }}` (SPLIT) inside a string literal, where it may be cut in two;
- `{{ opt }}...{{ endopt }}` (OPTIONAL) around words a comment or docstring can do
  without, such as a long topic name, or `{{ opt }}long{{ alt }}short{{ endopt }}` to give
  the words that replace them;
- `{{ wrap }}` (WRAP) after the `=` of an assignment whose own start is too long for a
  line with the call that follows (a long member name): Python puts what follows in
  parentheses on the next lines, C++ just continues it there;
- NESTED_BREAK and NESTED_SPLIT, which the dialects put in a list literal (an array
  parameter's default) after its opening bracket, after each comma and in its strings:
  the places it may break once its line, broken at its own markers, is still too long.

`fit()` leaves a line that fits as it is, markers removed. A line that does not fit loses
its optional words first; if it still does not fit it breaks at its first marker, then
takes as many pieces per line as fit, each continuation line indented by the language's
continuation indent (ROS's uncrustify: 2, flake8's hanging indent: 4) from the line's own.
"""

from __future__ import annotations

import re
import textwrap
import unicodedata
from collections.abc import Iterable

# Private-use characters: no text reaches the output raw with them (rna.names refuses
# them in free text and the dialects escape them in literals), and unlike the ASCII
# separators neither str.split() nor str.splitlines() treats them as white space.
BREAK = "\ue000"
SPLIT = "\ue001"
OPTIONAL = "\ue002"
OPTIONAL_END = "\ue003"
ALTERNATIVE = "\ue004"
WRAP = "\ue007"
NESTED_BREAK = "\ue005"
NESTED_SPLIT = "\ue006"
_NESTED = NESTED_BREAK + NESTED_SPLIT

# Columns of a word without spaces (a URL, a path) between the places a literal may be cut.
WORD_PIECE = 30

# (column limit, continuation indent) of the linters each language is checked with:
# ament_cpplint / ament_uncrustify (100 columns) and ament_flake8 (99).
LIMITS = {"cpp": (100, 2), "python": (99, 4)}

# Any marker at all: a line without one is left as it is, whatever its length.
_ANY_MARKER = re.compile(f"[{BREAK}{SPLIT}{OPTIONAL}{OPTIONAL_END}{ALTERNATIVE}{WRAP}{_NESTED}]")
# A line without brackets leaves the parenthesis depth as it was.
_BRACKETS = re.compile(r"[()\[\]]")
_DEPTH_TOKENS = re.compile(r"""[()\[\]'"#\\]|//""")  # what _depth looks at

_OPTIONAL_WORDS = re.compile(
    f"{OPTIONAL}[^{OPTIONAL_END}{ALTERNATIVE}]*(?:{ALTERNATIVE}([^{OPTIONAL_END}]*))?{OPTIONAL_END}")
_PREFIX = re.compile(r"[A-Za-z]*$")


def columns(line: str, language: str) -> int:
    """The width of a line as its linter counts it: flake8 counts characters; cpplint counts
    East Asian wide characters twice and combining marks not at all."""
    if language != "cpp" or line.isascii():
        return len(line)
    return sum(2 if unicodedata.east_asian_width(char) in "WF" else 0 if unicodedata.combining(char) else 1
               for char in line)


def _wrapped(line: str, language: str, inside: bool) -> list[str]:
    """A line with WRAP: broken there only if what comes before its first break does not fit."""
    width, step = LIMITS[language]
    before, _, after = line.partition(WRAP)
    plain = before + after
    if language == "python":
        # Python breaks a line only inside brackets: without the parentheses, not outside them.
        plain = before + "".join(char for index, char in enumerate(after)
                                 if char != BREAK or _depth(after[:index]) > 0)
    start = re.split(f"[{BREAK}{SPLIT}]", plain)[0]
    if columns(_plain(start), language) <= width or columns(_plain(plain), language) <= width:
        return fit_line(plain, language, inside)
    own = len(line) - len(line.lstrip(" "))
    if language == "python":
        return [before.rstrip() + " ("] + fit_line(" " * (own + step) + after.lstrip() + ")", language, True)
    return [before.rstrip()] + fit_line(" " * (own + step) + after.lstrip(), language, True)


def splittable(spelled: Iterable[tuple[str, str]]) -> str:
    """A string literal's inside from (character, its escaped spelling) pairs, with a SPLIT
    after each space and, in a longer word, every WORD_PIECE columns (never inside an escape)."""
    out, run = [], 0
    for char, spelling in spelled:
        out.append(spelling)
        run = 0 if char == " " else run + len(spelling)
        if char == " " or run >= WORD_PIECE:
            out.append(SPLIT)
            run = 0
    return "".join(out).removesuffix(SPLIT)


def _open_literal(text: str) -> tuple[str, str]:
    """(prefix, quote) of the string literal left open at the end of `text`, or ("", "")."""
    quote, prefix, escaped = "", "", False
    for index, char in enumerate(text):
        if escaped:
            escaped = False
        elif char == "\\" and quote:
            escaped = True
        elif quote and char == quote:
            quote = ""
        elif not quote and char in "'\"":
            quote, prefix = char, _PREFIX.search(text[:index])[0]
    return (prefix, quote) if quote else ("", "")


def _pieces(line: str) -> list[tuple[str, str]]:
    """(marker before it, text) of each piece of the line; a piece cut inside a string
    literal closes it, and the next one reopens it with the same prefix (f'...')."""
    pieces, current, marker = [], "", ""
    for char in line:
        if char in (BREAK, SPLIT):
            prefix, quote = _open_literal("".join(text for _, text in pieces) + current) if char == SPLIT else ("", "")
            pieces.append((marker, current + quote))
            current, marker = prefix + quote, char
        else:
            current += char
    pieces.append((marker, current))
    return pieces


_PYTHON_STRING = re.compile(r"""([A-Za-z]*)('(?:[^'\\]|\\.)*'|"(?:[^"\\]|\\.)*")""")


def _requote(line: str, first: bool, last: bool) -> str:
    """A Python line whose first or last string literal is a piece of a cut one, each piece in
    the quotes flake8-quotes wants for it alone: single ones, unless it holds a single quote and
    no double one (a piece of "it's ..." may hold none; one of 'both \\' and " ...' no double)."""
    literals = list(_PYTHON_STRING.finditer(line))
    pieces = {literals[0]} if first and literals else set()
    pieces |= {literals[-1]} if last and literals else set()
    for match in sorted(pieces, key=lambda match: -match.start()):  # from the end: offsets stay right
        prefix, spelled = match[1], match[2]
        if set(prefix.lower()) & {"f", "r"}:
            continue  # an f-string's expressions, a raw string's backslashes: kept as they are
        text = re.sub(r"\\(.)", lambda escape: escape[1] if escape[1] in "'\"" else escape[0], spelled[1:-1])
        quote = '"' if "'" in text and '"' not in text else "'"
        inside = re.sub(r"(\\.)|" + quote, lambda char, quote=quote: char[1] or "\\" + quote, text)
        line = line[:match.start(2)] + quote + inside + quote + line[match.end(2):]
    return line


def _join(current: str, marker: str, piece: str) -> str:
    """A piece appended to the same line: a cut string literal is mended."""
    if marker == SPLIT:
        reopened = len(piece) - len(piece.lstrip("bBfFrRuU")) + 1
        return current[:-1] + piece[reopened:]
    return current + piece


def _plain(text: str) -> str:
    """The text without the nested markers (a list literal whole)."""
    return text.replace(NESTED_BREAK, "").replace(NESTED_SPLIT, "")


def _head(text: str) -> str:
    """What must fit on the line itself: a list literal can break later, after its bracket."""
    cut = min((text.index(marker) for marker in _NESTED if marker in text), default=len(text))
    return text[:cut]


def _nested(line: str, language: str, inside: bool) -> list[str]:
    """A line broken at its own markers, then each line still too long at its list literal's markers."""
    width = LIMITS[language][0]
    out = []
    for index, broken in enumerate(line):
        if columns(_plain(broken), language) > width and any(marker in broken for marker in _NESTED):
            deeper = broken.replace(NESTED_BREAK, BREAK).replace(NESTED_SPLIT, SPLIT)
            out += fit_line(deeper, language, inside=inside or index > 0, listing=True)
        else:
            out.append(_plain(broken))
    return out


def _depth(text: str, depth: int = 0) -> int:
    """The parenthesis depth after `text` (strings and comments skipped), starting at `depth`.

    Only the characters that matter are visited (every generated line passes here)."""
    if not _BRACKETS.search(text):
        return depth
    quote, escaped = "", -1  # escaped: the index of the character a backslash escapes
    for token in _DEPTH_TOKENS.finditer(text):
        char = token[0]
        if token.start() == escaped:
            continue
        if quote:
            if char == "\\":
                escaped = token.start() + 1
            elif char == quote:
                quote = ""
        elif char in ("'", '"'):
            quote = char
        elif char in ("#", "//"):
            break
        elif char in "([":
            depth += 1
        elif char in ")]":
            depth -= 1
    return depth


# A Python statement whose continuation lines would line up with the block that follows it.
_CONDITION = re.compile(r"\s*(if|elif|while) ")
# The end of a C++ type before the name it declares: a template's '>' or a reference's '&'.
_TYPE_END = re.compile(r"(?<![->&])>$|(?<!&) &$")


def fit_line(line: str, language: str, inside: bool = False, listing: bool = False) -> list[str]:
    """One line, or the lines it is broken into; `inside`: the line continues an open bracket;
    `listing`: its markers are those of a list literal (see _nested)."""
    if not _ANY_MARKER.search(line):
        return [line]  # no place to break it at, nor words to drop
    if WRAP in line:
        return _wrapped(line, language, inside)
    width, step = LIMITS[language]
    whole = re.sub(f"{ALTERNATIVE}[^{OPTIONAL_END}]*", "", line).replace(OPTIONAL, "").replace(OPTIONAL_END, "")
    pieces = _pieces(whole)
    joined = pieces[0][1]
    for marker, piece in pieces[1:]:
        joined = _join(joined, marker, piece)
    if columns(_plain(joined), language) <= width:
        return [_plain(joined)]
    if OPTIONAL in line:
        return fit_line(_OPTIONAL_WORDS.sub(lambda match: match[1] or "", line), language, inside)
    if len(pieces) == 1:
        return _nested([joined], language, inside)
    # Broken, a line always breaks at its first BREAK (a hanging indent, which flake8
    # and uncrustify both accept after an opening parenthesis), then fills each line.
    # A line that itself continues an open bracket keeps its indent for what follows,
    # unless it opens another one (or, for uncrustify, continues an expression, not a list).
    own = len(line) - len(line.lstrip(" "))
    head = pieces[0][1].rstrip()
    keep = inside and _depth(head) <= 0 and (language == "python" or head.endswith(","))
    # uncrustify does not indent a declaration's name that follows its type on a line of its
    # own: after a template's closing '>', or a member function's return type.
    # A qualified type broken after its '::' in a declaration (not in a call's arguments) too.
    declaration = bool(_TYPE_END.search(head)) or (head.lstrip().startswith("virtual ") and "(" not in head)
    declaration = declaration or (head.endswith("::") and not inside)
    keep = keep or (language == "cpp" and declaration)
    indent = own if keep else own + step
    if language == "python" and not keep and _CONDITION.match(head):
        indent += step  # pycodestyle: a condition's continuation stands apart from its block (E125)
    lines, current, cut = [], head, False
    reopened = False  # the current line starts with a piece of a cut string literal
    rest = pieces[1:]
    for index, (marker, piece) in enumerate(rest):
        longer = _join(current, marker, piece)
        if listing and marker == BREAK:
            # An element that does not fit the rest of the line starts the next one whole,
            # and one cut in pieces has its lines to itself.
            for following, more in rest[index + 1:]:
                if following != SPLIT:
                    break
                longer = _join(longer, following, more)
            fits = index > 0 and not cut and columns(_head(longer), language) <= width
            longer = _join(current, marker, piece)
        else:
            fits = (index > 0 or marker == SPLIT) and columns(_head(longer), language) <= width
        if fits:
            current = longer
            continue
        lines.append(current.rstrip())
        if language == "python" and (reopened or marker == SPLIT):
            lines[-1] = _requote(lines[-1], reopened, marker == SPLIT)
        cut = reopened = marker == SPLIT
        # uncrustify indents what continues an expression (after '<<', '&&'...) once more
        # than what continues a list (after '(' or ',') or a qualified name (after '::');
        # in a list literal, a string cut in two is not indented again, nor a declaration's
        # name after its type, nor a string literal cut after an assignment's `=`.
        continues_list = _plain(lines[-1]).endswith((",", "(", "::"))
        if language == "cpp" and not listing and index > 0 and marker != SPLIT and not continues_list:
            indent += 0 if _TYPE_END.search(_plain(lines[-1])) else step
        current = " " * indent + piece.lstrip()
    lines.append(_requote(current, True, False) if language == "python" and reopened else current)
    # uncrustify puts the brace of a condition that spans lines on a line of its own.
    if language == "cpp" and re.match(r"\s*(if|while|for) \(", head) and _plain(current).endswith(") {"):
        lines[-1] = current.rstrip().removesuffix(" {")
        lines.append(" " * own + "{")
    return _nested(lines, language, inside)


def fit(text: str, language: str) -> str:
    """Every line of `text` that is too long shortened or broken at its markers; markers removed."""
    lines, depth = [], 0
    for line in text.split("\n"):
        lines += fit_line(line, language, inside=depth > 0)
        depth = max(_depth(line, depth), 0)
    return "\n".join(lines)


def reflow(text: str, prefix: str = "", width: int = 99) -> str:
    """Prose re-wrapped to `width` columns, each line starting with `prefix` ('// ', '# ' or '').

    Paragraphs are separated by blank lines; a word longer than a line stays whole.
    """
    paragraphs = [" ".join(block.split()) for block in re.split(r"\n\s*\n", text.strip())]
    wrapped = [textwrap.wrap(paragraph, width - len(prefix), break_long_words=False, break_on_hyphens=False)
               for paragraph in paragraphs]
    blank = prefix.rstrip()
    return f"\n{blank}\n".join("\n".join(prefix + line for line in lines) for lines in wrapped)
