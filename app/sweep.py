"""``cusp sweep SCENE --out DIR [--workers N] [--chunk-size N] [--scheduler ADDRESS]``:
run every case of a scene's ``[sweep]`` section (:mod:`cusp.app._sweep_spec`) into a
Parquet dataset.

Each case is the scene with its fields replaced, run as ``cusp run --no-plots`` runs a
scene (the path and energies; the loci with ``[manifold]``), without writing its files:
one row of ``DIR/results.parquet`` (:mod:`cusp.app._sweep_case` names the columns), the
loci in ``DIR/loci.parquet``. A case that is refused or fails is a row with its status and
message; it never stops the sweep. The cases run in chunks, on ``--workers`` local
processes (default: one per CPU; 0: in this process) or, with ``--scheduler``, as tasks
of an existing Dask distributed cluster (``pip install 'cusp[dask]'``); each finished
chunk is written atomically (:mod:`cusp.app._sweep_store`), so a rerun after a kill
computes only the missing cases. ``DIR/sweep.json`` records the scene, the fields and the
number of cases. Exit status: 0 every case has its row, 2 a bad scene, ``[sweep]`` or
option (one line naming it), 1 the run was interrupted or a worker died (the finished
chunks are kept: run the same command again to resume).
"""

from __future__ import annotations

import json
import math
import os
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from ._sweep_case import STATUSES, run_chunk
from ._sweep_spec import Sweep, case_key
from ._sweep_store import (
    LOCI,
    RESULTS,
    StoreError,
    done_cases,
    prune_loci,
    require_pyarrow,
    results_schema,
    write_part,
)
from .output import OutDirError, check_out_dir
from .run import resolve_scene
from .scene import SceneError, load_scene

__all__ = ["add_arguments", "main", "sweep", "chunk_size"]

#: chunks per worker when the size is chosen automatically (balances the load at the end)
CHUNKS_PER_WORKER = 4
#: what a local worker process imports before it forks (paid once, not once a worker)
PRELOAD = ("cusp.app._sweep_case", "cusp.app.run", "cusp.models.contact_loss", "numpy", "scipy")
#: the largest automatic chunk (a resumed run loses at most this many cases a worker)
MAX_CHUNK = 100


def add_arguments(parser) -> None:
    parser.add_argument("scene", help="scene file (TOML) with a [sweep] section, or its name")
    parser.add_argument(
        "--out", default=None, metavar="DIR", help="output directory (default: cusp-out/NAME-sweep)"
    )
    parser.add_argument(
        "--workers",
        default=None,
        metavar="N",
        help="local worker processes (default: one per CPU; 0: run in this process)",
    )
    parser.add_argument(
        "--chunk-size",
        default=None,
        metavar="N",
        help=f"cases per chunk (default: about {CHUNKS_PER_WORKER} chunks a worker, at most "
        f"{MAX_CHUNK})",
    )
    parser.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="run the chunks on this Dask distributed scheduler (tcp://host:port) instead",
    )
    parser.add_argument("--quiet", action="store_true", help="print only errors")


def _count(flag: str, text: str | None, low: int, default: int) -> int:
    if text is None:
        return default
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < low:
        raise SceneError(f"{flag} = {text!r}; allowed: an integer >= {low}")
    return value


def chunk_size(todo: int, parallel: int) -> int:
    """The automatic chunk size: about CHUNKS_PER_WORKER chunks a worker, at most
    MAX_CHUNK cases (start-up and scheduling costs are paid once a chunk)."""
    return max(1, min(MAX_CHUNK, math.ceil(todo / (CHUNKS_PER_WORKER * max(parallel, 1)))))


def _in_process(chunks: list, source: str) -> Iterator[tuple[list, list]]:
    for chunk in chunks:
        yield run_chunk(chunk, source)


def _local(chunks: list, source: str, workers: int) -> Iterator[tuple[list, list]]:
    """The chunks on a pool of ``workers`` processes (forkserver where there is one)."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed

    method = "forkserver" if "forkserver" in mp.get_all_start_methods() else "spawn"
    ctx = mp.get_context(method)
    if method == "forkserver":  # the workers fork from a server that imported these once
        ctx.set_forkserver_preload(list(PRELOAD))
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=ctx)
    try:
        futures = [pool.submit(run_chunk, chunk, source) for chunk in chunks]
        for fut in as_completed(futures):
            yield fut.result()
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _dask_client(address: str) -> Any:
    try:
        from dask.distributed import Client
    except ImportError as exc:
        raise ImportError(
            "--scheduler runs on Dask, which is not installed; install it with "
            "pip install 'cusp[dask]'"
        ) from exc
    try:
        return Client(address, timeout="10s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise SceneError(f"--scheduler {address}: cannot connect ({exc})") from None


def _dask(chunks: list, source: str, client: Any) -> Iterator[tuple[list, list]]:
    """The chunks as tasks of a Dask distributed cluster, in the order they finish."""
    from dask.distributed import as_completed

    futures = [client.submit(run_chunk, chunk, source, pure=False) for chunk in chunks]
    try:
        for fut in as_completed(futures):
            yield fut.result()
    finally:
        client.cancel(futures)


def _progress(total: int, quiet: bool) -> Any:
    """A tqdm bar on a terminal (when tqdm is installed), else None."""
    if quiet or total == 0 or not sys.stderr.isatty():
        return None
    try:
        from tqdm import tqdm
    except ImportError:
        return None
    return tqdm(total=total, unit="case", file=sys.stderr, dynamic_ncols=True)


def _write_manifest(out: Path, scene: Any, sweep: Sweep) -> None:
    """``DIR/sweep.json``: the scene, the fields, where the cases came from, their number."""
    from .run import _version

    doc = {
        "scene": scene.echo(),
        "fields": list(sweep.fields),
        "cases": len(sweep),
        "origin": sweep.origin,
        "results": RESULTS,
        "loci": LOCI if scene.manifold is not None else None,
        "cusp": _version(),
    }
    tmp = out / f".sweep.json.{os.getpid()}.tmp"
    tmp.write_text(json.dumps(doc, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
    os.replace(tmp, out / "sweep.json")


@contextmanager
def _exclusive(out: Path) -> Iterator[None]:
    """Hold ``out/.lock`` (flock) for the whole run: a second sweep into ``out`` is refused,
    not run beside the first (both would compute the same missing cases)."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not POSIX: no lock
        yield
        return
    fd = os.open(out / ".lock", os.O_RDWR | os.O_CREAT, 0o644)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise StoreError(
                f"{out}: another cusp sweep is writing into it; allowed: one sweep at a time "
                "into a directory (wait for it, or use another --out)"
            ) from None
        yield
    finally:
        os.close(fd)  # releases the lock


def sweep(
    scene: Any,
    out: Path,
    *,
    workers: int = 0,
    chunk: int | None = None,
    client: Any = None,
    quiet: bool = True,
) -> dict[str, Any]:
    """Run the missing cases of ``scene``'s sweep into ``out`` (see the module docstring):
    in this process (``workers`` 0), on local processes, or on a Dask ``client``. Returns
    ``{"cases", "done_before", "computed", "chunks", "chunk_size", "statuses",
    "seconds"}``."""
    sw: Sweep = scene.sweep
    t0 = time.perf_counter()
    keys = [case_key(sw.case_data(i)) for i in range(len(sw))]
    out.mkdir(parents=True, exist_ok=True)
    with _exclusive(out):
        return _sweep(scene, out, keys, workers, chunk, client, quiet, t0)


def _sweep(scene, out, keys, workers, chunk, client, quiet, t0) -> dict[str, Any]:
    """:func:`sweep` with the directory locked."""
    sw: Sweep = scene.sweep
    prune_loci(out)
    done = done_cases(out, keys)
    _write_manifest(out, scene, sw)
    todo = [i for i in range(len(sw)) if i not in done]
    parallel = len(client.nthreads()) if client is not None else workers  # (one case at a
    # time in a process: a Dask worker's threads do not add to it)
    size = chunk if chunk is not None else chunk_size(len(todo), parallel)
    groups = [todo[k : k + size] for k in range(0, len(todo), size)]
    chunks = [[(i, keys[i], sw.case_data(i)) for i in g] for g in groups]
    numeric = {f: sw.numeric(f) for f in sw.fields}  # once: each call reads every case
    schema = results_schema(list(numeric.items()))
    if client is not None:
        results = _dask(chunks, scene.source, client)
    elif workers > 0 and chunks:
        results = _local(chunks, scene.source, min(workers, len(chunks)))
    else:
        results = _in_process(chunks, scene.source)
    statuses = dict.fromkeys(STATUSES, 0)
    bar = _progress(len(todo), quiet)
    try:
        for rows, loci in results:
            for row in rows:
                for name, value in zip(sw.fields, sw.values[row["index"]]):
                    row[name] = float(value) if numeric[name] else str(value)
                statuses[row["status"]] += 1
            write_part(out, schema, rows, loci if scene.manifold is not None else None)
            if bar is not None:
                bar.update(len(rows))
    finally:
        if bar is not None:
            bar.close()
    return {
        "cases": len(sw),
        "done_before": len(done),
        "computed": len(todo),
        "chunks": len(chunks),
        "chunk_size": size,
        "statuses": statuses,
        "seconds": time.perf_counter() - t0,
    }


def _fail(kind: str, message: str, status: int) -> int:
    print(f"cusp sweep: {kind}: {' '.join(message.split())}", file=sys.stderr)
    return status


def main(args) -> int:
    client = None
    try:
        require_pyarrow()
        path, source = resolve_scene(args.scene)
        scene = load_scene(path, source=source)
        if scene.sweep is None:
            raise SceneError(
                f"{scene.source}: no [sweep] section; allowed: a scene with a [sweep] section "
                "naming the fields to vary (docs/sweeps.md)"
            )
        workers = _count("--workers", args.workers, 0, os.cpu_count() or 1)
        chunk = None if args.chunk_size is None else _count("--chunk-size", args.chunk_size, 1, 1)
        out = Path(args.out) if args.out is not None else Path("cusp-out") / f"{scene.name}-sweep"
        out = check_out_dir(out)
        if args.scheduler is not None:
            client = _dask_client(args.scheduler)
        where = (
            f"the Dask scheduler {args.scheduler}"
            if client is not None
            else f"{workers} worker process{'es' if workers != 1 else ''}"
            if workers
            else "this process"
        )
        if not args.quiet:
            print(f"sweep {scene.name} ({scene.source}): {len(scene.sweep)} cases on {where}")
        info = sweep(scene, out, workers=workers, chunk=chunk, client=client, quiet=args.quiet)
    except (SceneError, OutDirError, StoreError, ImportError) as exc:
        return _fail("error", str(exc), 2)
    except KeyboardInterrupt:
        return _fail("interrupted", "the finished chunks are kept; rerun to resume", 1)
    except Exception as exc:  # a worker died (BrokenProcessPool), the cluster went away, ...
        return _fail("failed", f"{type(exc).__name__}: {exc}; rerun to resume", 1)
    finally:
        if client is not None:
            client.close()
    if not args.quiet:
        _report(info, out)
    return 0


def _report(info: dict[str, Any], out: Path) -> None:
    counts = ", ".join(f"{k} {v}" for k, v in info["statuses"].items() if v)
    rate = info["computed"] / info["seconds"] if info["seconds"] > 0 else math.inf
    print(
        f"  {info['done_before']} cases already in {out}; computed {info['computed']} in "
        f"{info['chunks']} chunks of up to {info['chunk_size']}: {counts or 'none'}"
    )
    print(f"  {info['seconds']:.2f} s, {rate:.1f} cases/s (after imports)")
    print(f"wrote {out / RESULTS}")
