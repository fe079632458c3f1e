"""The limits of a scene, checked before it is parsed or run (docs/limits.md).

A scene is a small text file; these bounds keep a hostile or broken one from taking
unbounded time or memory (a file that never ends, tables nested a thousand deep, dotted
keys that make the TOML parser quadratic, lists of 10⁵ reductions). Each refusal names the
limit.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

__all__ = [
    "MAX_SCENE_BYTES",
    "MAX_LINE_CHARS",
    "MAX_NESTING",
    "MAX_LIST",
    "MAX_CASES",
    "MAX_NAME_CHARS",
    "MAX_TITLE_CHARS",
    "read_scene_bytes",
    "check_text",
    "show",
]

#: the largest scene file [bytes]
MAX_SCENE_BYTES = 64 * 1024
#: the longest line of a scene [characters] (bounds the depth of a dotted key)
MAX_LINE_CHARS = 4096
#: the deepest nesting of arrays, inline tables and table headers
MAX_NESTING = 16
#: the most values in a list ([surface] mu, [loading] reduced_normal_load)
MAX_LIST = 100
#: the most cases (listed mu times listed reduced_normal_load)
MAX_CASES = 100
#: the longest [scene] name [characters] (it names the output directory)
MAX_NAME_CHARS = 100
#: the longest [scene] title [characters]
MAX_TITLE_CHARS = 500


def show(value: object, width: int = 60) -> str:
    """``repr(value)``, cut to ``width`` characters (a value in a one-line message)."""
    if isinstance(value, list) and len(value) > 8:
        text = f"[{', '.join(show(v, 20) for v in value[:3])}, ... ({len(value)} values)]"
    else:
        try:
            text = repr(value)
        except (RecursionError, ValueError):  # nested too deep, or an int too long to print
            text = f"<{type(value).__name__}>"
    return text if len(text) <= width else text[: width - 3] + "..."


def read_scene_bytes(path: Path) -> bytes:
    """The bytes of a scene file: a regular file of at most MAX_SCENE_BYTES (a FIFO, a
    device such as /dev/zero or a socket is refused before it is opened). Raises OSError
    or ValueError (a message without the path)."""
    st = os.stat(path)
    if stat.S_ISDIR(st.st_mode):
        raise IsADirectoryError(path)
    if not stat.S_ISREG(st.st_mode):
        raise ValueError("not a regular file (a FIFO, device or socket); a scene is a text file")
    with open(path, "rb") as fh:
        raw = fh.read(MAX_SCENE_BYTES + 1)
    if len(raw) > MAX_SCENE_BYTES:
        raise ValueError(f"larger than the limit of {MAX_SCENE_BYTES} bytes for a scene file")
    return raw


def check_text(text: str) -> str | None:
    """What is wrong with scene text before it is parsed (None: nothing): its size, its
    longest line, its deepest nesting (brackets and braces outside strings and comments)."""
    if len(text.encode("utf-8", "surrogatepass")) > MAX_SCENE_BYTES:
        return f"larger than the limit of {MAX_SCENE_BYTES} bytes for a scene"
    for i, line in enumerate(text.splitlines(), 1):
        if len(line) > MAX_LINE_CHARS:
            return f"line {i} has {len(line)} characters; the limit is {MAX_LINE_CHARS}"
    depth, deepest, i, n = 0, 0, 0, len(text)
    while i < n:
        ch = text[i]
        if ch == "#":
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif ch in "\"'":
            quote = ch * 3 if text.startswith(ch * 3, i) else ch
            i = _string_end(text, i + len(quote), quote)
            continue
        elif ch in "[{":
            depth += 1
            deepest = max(deepest, depth)
            if deepest > MAX_NESTING:
                lineno = text.count("\n", 0, i) + 1
                return f"nesting deeper than the limit of {MAX_NESTING} (line {lineno})"
        elif ch in "]}":
            depth = max(depth - 1, 0)
        i += 1
    return None


def _string_end(text: str, i: int, quote: str) -> int:
    """The index just past the string that opened with ``quote`` before ``i``."""
    basic = quote[0] == '"'
    while i < len(text):
        if basic and text[i] == "\\":
            i += 2
            continue
        if text.startswith(quote, i):
            return i + len(quote)
        if len(quote) == 1 and text[i] == "\n":  # unterminated: the parser reports it
            return i
        i += 1
    return i
