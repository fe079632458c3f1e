"""What ``cusp`` shows while it works and how it accounts for its time: a progress bar over
a run's tasks on a terminal (tqdm, when installed), the ``-v`` logging of the ``cusp``
loggers, and a clock of the time spent importing modules (so that the printed compute time
is the computation's alone).

Loggers (the standard library's :mod:`logging`; ``cusp -v`` shows INFO, ``-vv`` DEBUG, on
standard error): ``cusp.continuation`` (the engine: steps that stop, special points dropped,
checkpoints; its modules log under it), ``cusp.models`` (the physics), ``cusp.app`` (the
scene runner: each task and its time).
"""

from __future__ import annotations

import logging
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

logger = logging.getLogger("cusp.app")


def configure_logging(verbose: int) -> None:
    """Send the ``cusp`` loggers' records to standard error: INFO and above for
    ``verbose`` = 1, DEBUG for 2 or more (0: nothing is configured)."""
    root = logging.getLogger("cusp")
    for old in [h for h in root.handlers if getattr(h, "cusp_cli", False)]:
        root.removeHandler(old)  # (a command run again in one process: one handler)
        root.setLevel(logging.NOTSET)
    if verbose <= 0:
        return
    handler = logging.StreamHandler(sys.stderr)
    handler.cusp_cli = True  # type: ignore[attr-defined]
    handler.setFormatter(logging.Formatter("%(levelname)s %(name)s: %(message)s"))
    root.addHandler(handler)
    root.setLevel(logging.INFO if verbose == 1 else logging.DEBUG)


def on_terminal() -> bool:
    """Whether standard error is a terminal (a progress bar is shown only there)."""
    isatty = getattr(sys.stderr, "isatty", None)
    return bool(isatty is not None and isatty())


class Tasks:
    """A progress bar over ``total`` tasks (tqdm on standard error, shown after a second;
    nothing when not wanted, not on a terminal or without tqdm), and their log lines."""

    def __init__(self, total: int, wanted: bool) -> None:
        self.bar: Any = None
        if wanted and on_terminal():
            try:
                from tqdm import tqdm
            except ImportError:  # (an optional extra: cusp[progress])
                logger.debug("no progress bar: tqdm is not installed (cusp[progress])")
            else:
                self.bar = tqdm(total=total, unit=" task", delay=1.0, leave=False, file=sys.stderr)

    @contextmanager
    def task(self, name: str) -> Iterator[None]:
        if self.bar is not None:
            self.bar.set_description_str(name, refresh=False)
        t0 = time.perf_counter()
        yield
        logger.info("%s: %.1f ms", name, 1e3 * (time.perf_counter() - t0))
        if self.bar is not None:
            self.bar.update(1)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


class ImportClock:
    """The wall time spent importing modules while it is installed (a finder first on
    :data:`sys.meta_path` that times each module's execution, nested imports once)."""

    def __init__(self) -> None:
        self.seconds = 0.0
        self._depth = 0

    def __enter__(self) -> ImportClock:
        sys.meta_path.insert(0, self)
        return self

    def __exit__(self, *exc: object) -> None:
        sys.meta_path.remove(self)

    def find_spec(self, name: str, path: Any = None, target: Any = None) -> Any:
        for finder in sys.meta_path:
            find = getattr(finder, "find_spec", None)
            if finder is self or find is None:
                continue
            spec = find(name, path, target)
            if spec is not None:
                if spec.loader is not None and hasattr(spec.loader, "exec_module"):
                    spec.loader = _TimedLoader(spec.loader, self)
                return spec
        return None

    def timed(self, run: Any, module: Any) -> None:
        t0 = time.perf_counter()
        self._depth += 1
        try:
            run(module)
        finally:
            self._depth -= 1
            if self._depth == 0:
                self.seconds += time.perf_counter() - t0


class _TimedLoader:
    """A module's loader whose ``exec_module`` the clock times (all else passed through)."""

    def __init__(self, loader: Any, clock: ImportClock) -> None:
        self._loader, self._clock = loader, clock

    def create_module(self, spec: Any) -> Any:
        return self._loader.create_module(spec)

    def exec_module(self, module: Any) -> None:
        spec = getattr(module, "__spec__", None)
        if spec is not None and spec.loader is self:  # the module keeps its own loader
            spec.loader = self._loader
        if getattr(module, "__loader__", None) is self:
            module.__loader__ = self._loader
        self._clock.timed(self._loader.exec_module, module)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._loader, name)


__all__ = ["ImportClock", "Tasks", "configure_logging", "on_terminal"]
