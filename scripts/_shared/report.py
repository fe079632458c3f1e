"""Shared by the figure and benchmark scripts: reports and figures written atomically, figures
byte-for-byte reproducible; the provenance of a measurement (commit, load, machine)."""

from __future__ import annotations

import contextlib
import os
import platform
import subprocess
from pathlib import Path

#: the repository this package runs from (installed in development mode, ``pip install -e``,
#: as the scripts expect): ``scripts/_shared/`` -> the root
ROOT = Path(__file__).resolve().parents[2]


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


def commit() -> str:
    """The short commit of the repository the scripts run from; "unknown" where that is not a
    git checkout (or the package is not installed from one)."""
    if not (ROOT / "scripts" / "_shared").is_dir():
        return "unknown"
    try:
        done = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True
        )
    except OSError:  # no git
        return "unknown"
    return done.stdout.strip() or "unknown"


def commit_and_load() -> tuple[str, float]:
    """The short commit (:func:`commit`) and the machine's 1-minute load average (NaN where
    the OS does not report it): the provenance line of a benchmark report."""
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return commit(), load


def machine() -> str:
    """The CPU, its logical count, the OS and the versions of Python, NumPy and SciPy."""
    import numpy as np
    import scipy

    cpu = platform.processor() or platform.machine()
    with contextlib.suppress(OSError):
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    return (
        f"{cpu}, {os.cpu_count()} logical CPUs (shared with other jobs); "
        f"{platform.system()} {platform.release()}; Python {platform.python_version()}, "
        f"NumPy {np.__version__}, SciPy {scipy.__version__}"
    )
