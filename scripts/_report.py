"""Shared by the figure and benchmark scripts: reports and figures written atomically, figures
byte-for-byte reproducible."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path


def write_bytes(path, data: bytes) -> Path:
    """Write ``data`` to ``path`` through a temporary file beside it and an atomic rename: an
    interrupted run leaves the previous file intact, never half of a new one."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    try:
        tmp.write_bytes(data)
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path


def write_report(path, text: str) -> Path:
    """Write ``text`` to ``path`` (UTF-8) atomically (see :func:`write_bytes`)."""
    return write_bytes(path, text.encode("utf-8"))


def save_figure(fig, path, **savefig_kw) -> Path:
    """Save a matplotlib figure atomically, in the format of ``path``'s suffix, as the same
    bytes on every run (:func:`cusp.app.figures.figure_bytes`)."""
    from cusp.app.figures import figure_bytes

    path = Path(path)
    return write_bytes(path, figure_bytes(fig, path.suffix.lstrip(".").lower(), **savefig_kw))


def commit_and_load() -> tuple[str, float]:
    """The short commit of the repository holding this script ("unknown" outside git) and
    the machine's 1-minute load average (NaN where the OS does not report it): the
    provenance line of a benchmark report."""
    root = Path(__file__).resolve().parents[1]
    commit = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], cwd=root, capture_output=True, text=True
    ).stdout.strip()
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return commit or "unknown", load
