"""Shared by the benchmark scripts: write a report file atomically."""

from __future__ import annotations

import os
from pathlib import Path


def write_report(path, text: str) -> Path:
    """Write ``text`` to ``path`` (UTF-8) through a temporary file beside it and an atomic
    rename: an interrupted run leaves the previous report intact, never half of a new one."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    try:
        tmp.write_text(text, encoding="utf-8")
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path
