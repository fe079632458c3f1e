"""The outputs of ``cusp run``, written as one set.

A run owns the files any run may write into its output directory ``DIR`` (:func:`owned`:
``summary.json``, ``branch.csv``, ``loci.csv`` and every figure as PNG and SVG); every
other entry of ``DIR`` (a file or a directory) is foreign and is kept, untouched.

The set is committed as a whole or not at all:

1. every file is written into a staging directory ``.DIR.partial-*`` beside ``DIR``, which
   is renamed ``.DIR.ready-*`` once complete;
2. under an exclusive lock (``flock`` on the parent directory), the foreign entries of an
   existing ``DIR`` are moved into the ready directory, ``DIR`` is renamed
   ``.DIR.old-*``, the ready directory is renamed ``DIR``, and the old one is removed.

So ``DIR`` holds either the previous set or the new one, never a mix; the owned files of
the previous set that the new run does not write (the figures of an earlier run, after a
run with ``--no-plots``) are gone with it. Between the two renames of step 2 ``DIR`` is
absent for a moment. On a failure the steps are undone. A run killed midway leaves hidden
directories beside ``DIR``; the next run into ``DIR`` (while holding the lock, so no other
run is using them) puts ``DIR`` back as it was and removes them. Concurrent runs into one
``DIR`` are serialised by the lock: each commits a complete set, the last to commit wins.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

__all__ = ["owned", "write_outputs", "check_out_dir", "OutDirError", "MAX_NAME_BYTES"]

#: the longest file name most file systems allow [bytes]
NAME_MAX = 255
#: the longest name of an output directory [bytes] (its staging names add 30 bytes)
MAX_NAME_BYTES = NAME_MAX - 32
_KINDS = ("partial", "ready", "old")


class OutDirError(ValueError):
    """``--out`` names a directory that cannot hold the outputs (one-line message)."""


def owned(name: str) -> bool:
    """Is ``name`` a file that ``cusp run`` writes (and so replaces as part of a set)?"""
    from .scene import FIGURES

    if name in ("summary.json", "branch.csv", "loci.csv"):
        return True
    stem, dot, ext = name.rpartition(".")
    return bool(dot) and ext in ("png", "svg") and stem in FIGURES


def check_out_dir(out: Path) -> Path:
    """The output directory to write (a symbolic link resolved to its target), checked
    before any work; raises :class:`OutDirError` naming the problem."""
    out = Path(os.path.abspath(out))
    for name in (out.name, out.resolve().name):
        if len(name.encode("utf-8", "surrogateescape")) > MAX_NAME_BYTES:
            raise OutDirError(
                f"--out {name[:40]}...: a name of {len(name.encode())} bytes; allowed: at "
                f"most {MAX_NAME_BYTES} bytes (UTF-8)"
            )
    try:
        return _check_existing(out.resolve() if out.is_symlink() else out)
    except OSError as exc:
        raise OutDirError(f"--out {out}: {exc.strerror or exc}") from None


def _check_existing(out: Path) -> Path:
    if not out.name or out == out.parent:
        raise OutDirError(f"--out {out}: the root directory; allowed: a directory of its own")
    if out.exists() and not out.is_dir():
        raise OutDirError(f"--out {out} exists and is not a directory; allowed: a directory")
    cwd = Path.cwd().resolve()
    if out.exists() and (cwd == out.resolve() or out.resolve() in cwd.parents):
        raise OutDirError(
            f"--out {out} holds the working directory; allowed: a directory of its own "
            "(it is replaced as a whole)"
        )
    return out


@contextmanager
def _locked(parent: Path) -> Iterator[None]:
    """An exclusive lock on ``parent`` (released when the process ends, even if killed)."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not POSIX: no lock
        yield
        return
    fd = os.open(parent, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)  # releases the lock


def _hidden(out: Path, kind: str) -> list[Path]:
    prefix = f".{out.name}.{kind}-"
    return sorted(p for p in out.parent.iterdir() if p.name.startswith(prefix))


def _move_foreign(src: Path, dst: Path) -> None:
    for entry in sorted(src.iterdir()):
        if not owned(entry.name) and not (dst / entry.name).exists():
            os.rename(entry, dst / entry.name)


def recover(out: Path) -> None:
    """Undo what killed runs left beside ``out`` (call with the lock held): a missing
    ``out`` comes back from ``.out.old-*``, foreign entries go back from ``.out.ready-*``,
    and every staging directory is removed."""
    if not out.exists():
        olds = _hidden(out, "old")
        if olds and _hidden(out, "ready"):
            os.rename(olds[-1], out)
    for ready in _hidden(out, "ready"):
        if out.is_dir():
            _move_foreign(ready, out)
    for kind in _KINDS:
        for path in _hidden(out, kind):
            shutil.rmtree(path, ignore_errors=True)


def _stage(out: Path, files: dict[str, bytes]) -> Path:
    """Write ``files`` into ``.out.partial-*``, then rename it ``.out.ready-*``."""
    stage = Path(tempfile.mkdtemp(prefix=f".{out.name}.partial-", dir=out.parent))
    try:
        for name, data in files.items():
            with open(stage / name, "wb") as fh:
                fh.write(data)
                fh.flush()
                os.fsync(fh.fileno())
        mode = out.stat().st_mode & 0o7777 if out.is_dir() else 0o777 & ~_umask()
        os.chmod(stage, mode)
        ready = out.parent / stage.name.replace(".partial-", ".ready-", 1)
        os.rename(stage, ready)
        return ready
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _commit(out: Path, ready: Path) -> None:
    """Swap ``ready`` in as ``out`` (see the module docstring), undoing on failure."""
    if not out.exists():
        os.rename(ready, out)
        return
    old = out.parent / ready.name.replace(".ready-", ".old-", 1)
    try:
        _move_foreign(out, ready)
        os.rename(out, old)
    except BaseException:
        _move_foreign(ready, out)
        raise
    try:
        os.rename(ready, out)
    except BaseException:
        os.rename(old, out)
        _move_foreign(ready, out)
        raise
    shutil.rmtree(old, ignore_errors=True)


def write_outputs(
    out: Path, files: dict[str, bytes], *, before_commit: Callable[[], None] | None = None
) -> None:
    """Write ``files`` (name -> bytes, owned names only) into ``out`` as one set (see the
    module docstring). On failure ``out`` is left as it was and nothing is left beside it."""
    out = Path(os.path.abspath(out))
    bad = [name for name in files if not owned(name)]
    if bad:
        raise ValueError(f"not an output file name: {bad[0]!r}")
    out.parent.mkdir(parents=True, exist_ok=True)
    if out.exists() and not out.is_dir():
        raise OSError(f"--out {out} exists and is not a directory")
    with _locked(out.parent):
        recover(out)
        ready = _stage(out, files)
        try:
            if before_commit is not None:
                before_commit()
            _commit(out, ready)
        finally:
            if ready.exists():
                shutil.rmtree(ready, ignore_errors=True)
