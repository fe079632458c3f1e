"""``cusp run [SCENE] [--out DIR] [--no-plots] [--rtol RTOL]``: trace the contact-loss path
of a scene.

``SCENE`` is a scene file or the name of a bundled scene (``fig9``; none: ``fig6``);
``--rtol`` overrides the scene's ``[solver] rtol`` (the relative accuracy of everything
computed, in [1e-13, 1e-2], default 1e-3; summary.json records it). Writes
``DIR/summary.json``, ``DIR/branch.csv``, for a scene with a ``[manifold]`` section
``DIR/loci.csv`` (:mod:`cusp.app.loci`) and, unless ``--no-plots``, the scene's figures as
PNG and SVG. Everything is computed and rendered in memory first, then committed as one
set (:mod:`cusp.app.output`), so a failure leaves ``DIR`` as it was. Exit status: 0
success, 2 bad scene or ``--out`` (one line on stderr naming the field), 1 a numerical
failure (one line naming the cause); never a traceback, and warnings go to summary.json,
not stderr (docs/limits.md).

Only what the scene needs is imported: an exponential scene loads no Gaussian or quadrature
code, ``--no-plots`` loads no matplotlib, and sympy is never loaded.
"""

from __future__ import annotations

import csv
import io
import json
import platform
import sys
import time
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .cases import Case, build_body, length_notes, make_model, solver_options
from .output import OutDirError, check_out_dir, write_outputs
from .progress import ImportClock, Tasks, on_terminal
from .scene import MANIFOLD_FIGURES, Scene, SceneError, check_title, load_scene, with_rtol

__all__ = [
    "run_scene",
    "SceneRun",
    "Case",
    "summary",
    "branch_csv",
    "write_outputs",
    "DEFAULT_SCENE",
    "bundled_names",
    "resolve_scene",
]

#: the scene ``cusp run`` runs without an argument (the paper's Fig 6)
DEFAULT_SCENE = "fig6.toml"

#: units of the path columns; the two levels of every body are lengths [µm]
#: (cusp.models.protocol.ContactLevels.scale)
_UNITS = {"g_T": "µm", "F_T": "N", "F_N": "N", "A_SL": "1", "energy": "N·µm (= µJ)"}
_LEVEL_UNIT = "µm"


def add_arguments(parser) -> None:
    parser.add_argument(
        "scene",
        nargs="?",
        default=None,
        help="scene file (TOML) or the name of a bundled scene (fig6, fig8, ...); default: "
        f"the bundled {DEFAULT_SCENE} (the paper's Fig 6)",
    )
    parser.add_argument(
        "--out",
        default=None,
        metavar="DIR",
        help="output directory (default: cusp-out/<scene name>)",
    )
    parser.add_argument("--no-plots", action="store_true", help="write no figures")
    parser.add_argument(
        "--rtol",
        default=None,
        metavar="RTOL",
        help="relative accuracy of the paths, loci and energies, in [1e-13, 1e-2] (overrides "
        "the scene's [solver] rtol; default 1e-3)",
    )
    parser.add_argument("--quiet", action="store_true", help="print only errors")


def bundled_scene(name: str = DEFAULT_SCENE) -> Path:
    """Path of a scene shipped with the package (the ``scenes`` directory)."""
    from importlib import resources

    return Path(str(resources.files("cusp.scenes") / name))


def bundled_names() -> list[str]:
    """The names of the bundled scenes (``fig6``, ...), sorted."""
    from importlib import resources

    files = resources.files("cusp.scenes").iterdir()
    return sorted(f.name[: -len(".toml")] for f in files if f.name.endswith(".toml"))


def resolve_scene(arg: str | None) -> tuple[Path, str | None]:
    """The scene file ``cusp run ARG`` reads, and how messages name it (None: as given): an
    existing file, else a bundled scene by name (``fig8`` or ``fig8.toml``; also when a
    directory of that name is in the way, e.g. an earlier ``--out fig8``)."""
    if arg is None:
        return bundled_scene(), f"scenes/{DEFAULT_SCENE} (bundled)"
    path = Path(arg)
    if path.is_file():
        return path, None
    names = bundled_names()
    name = arg.removesuffix(".toml")
    if name in names:
        return bundled_scene(f"{name}.toml"), f"scenes/{name}.toml (bundled)"
    if path.exists():  # a directory, say: load_scene names the problem
        return path, None
    raise SceneError(
        f"{arg}: no such scene file, nor a bundled scene of that name; allowed: a scene file "
        f"(TOML) or a bundled scene: {', '.join(names)}"
    )


@dataclass
class SceneRun:
    """The computed cases of a scene (:class:`Case`, one per listed μ or F'_N), the loci of
    a ``[manifold]`` scene (a :class:`cusp.models.manifold.Loci`, else None); ``timing``
    holds the compute and render wall times [s]; ``options``: the continuation options of
    the paths (:func:`~cusp.app.cases.solver_options`)."""

    scene: Scene
    cases: list[Case]
    timing: dict[str, float]
    loci: Any = None
    #: the warnings raised while computing (kept off stderr; listed in summary.json)
    warnings: list[str] = field(default_factory=list)
    options: Any = None
    #: notes on the scene itself (lengths that look like the wrong unit), in every case's
    #: messages (:func:`~cusp.app.cases.length_notes`)
    notes: list[str] = field(default_factory=list)


def run_scene(
    scene: Scene, *, plots: bool = True, progress: bool = False, clock: ImportClock | None = None
) -> tuple[SceneRun, dict]:
    """Trace every case of a scene (and the loci of a [manifold] scene); returns the run and
    the rendered figures (bytes). ``progress``: a bar over the cases on a terminal
    (:class:`~.progress.Tasks`); ``clock``: an installed :class:`~.progress.ImportClock`,
    whose import time ``timing`` then reports apart (``imports_s``) from the compute and
    render times."""
    t0, i0 = time.perf_counter(), clock.seconds if clock else 0.0
    options = solver_options(scene)
    notes = length_notes(scene)
    cases = []
    if plots and scene.title and scene.figures:
        check_title(scene)
    several = len(scene.cases) > 1
    tasks = Tasks(len(scene.cases) + (scene.manifold is not None), progress)
    try:
        for mu, load in scene.cases:
            where = f"case mu = {mu!r}, F'_N = {load!r} N: " if several else ""
            with _failures(where, notes), tasks.task(f"mu = {mu:g}, F'_N = {load:g} N"):
                model = make_model(scene, build_body(scene, mu), load)
                cases.append(Case(model.mu0, load, model.run(options)))
        loci = None
        if scene.manifold is not None:
            from .loci import trace_loci

            with _failures(f"the loci in {scene.manifold['parameter']}: ", notes):
                with tasks.task(f"loci in {scene.manifold['parameter']}"):
                    loci = trace_loci(scene)
    finally:
        tasks.close()
    t1, i1 = time.perf_counter(), clock.seconds if clock else 0.0
    run = SceneRun(scene, cases, {}, loci, options=options, notes=notes)
    figures = {}
    path_figures = [f for f in scene.figures if f not in MANIFOLD_FIGURES]
    loci_figures = [f for f in scene.figures if f in MANIFOLD_FIGURES]
    if plots and path_figures:
        from .figures import render

        with _failures("drawing the figures: "):
            figures = render(cases, path_figures, title=scene.title)
    if plots and loci_figures:
        from .manifold_figures import render_manifold

        with _failures("drawing the loci figures: "):
            figures.update(render_manifold(run, loci_figures))
    t2, i2 = time.perf_counter(), clock.seconds if clock else 0.0
    run.timing = {
        "compute_s": (t1 - t0) - (i1 - i0),
        "render_s": (t2 - t1) - (i2 - i1),
        "imports_s": i2 - i0,
    }
    return run, figures


def _case_summary(mu: float, load: float, res, notes: list[str]) -> dict[str, Any]:
    energy = dict(res.energy)
    return {
        "mu": {"value": mu, "unit": ""},
        "reduced_normal_load": {"value": load, "unit": "N"},
        "points": res.points,
        "energy": {**energy, "unit": _UNITS["energy"], "error_estimate": dict(res.energy_error)},
        "folds": res.folds,
        "gross_sliding": res.gross_sliding,
        "messages": [*notes, *res.messages],
        "solver": res.stats,
    }


def summary(run: SceneRun) -> dict[str, Any]:
    """The content of ``summary.json``: the first case at the top level, all in ``cases``."""
    import numpy
    import scipy

    cases = [_case_summary(*case, run.notes) for case in run.cases]
    first = cases[0]
    level_names = run.cases[0].result.level_names
    out = {
        "scene": run.scene.echo(),
        "points": first["points"],
        "energy": first["energy"],
        "folds": first["folds"],
        "gross_sliding": first["gross_sliding"],
        "messages": first["messages"],
        "solver": first["solver"],
        "accuracy": accuracy(run),
        "warnings": list(run.warnings),
        "cases": cases,
        "units": {
            **{k: _UNITS[k] for k in ("g_T", "F_T", "F_N", "A_SL")},
            **dict.fromkeys(level_names, _LEVEL_UNIT),
            "energy": _UNITS["energy"],
        },
        "software": {
            "python": platform.python_version(),
            "numpy": numpy.__version__,
            "scipy": scipy.__version__,
            "cusp": _version(),
        },
    }
    if run.loci is not None:
        from .loci import manifold_summary

        out["manifold"] = manifold_summary(run.scene, run.loci)
    return out


def accuracy(run: SceneRun) -> dict[str, float]:
    """The ``accuracy`` entry of ``summary.json``: the ``rtol`` the scene was computed at
    (``[solver] rtol`` or ``--rtol``, else the default) and the tolerances of the paths it
    set or [solver] gave (Newton ``tol`` and ``step_tol``, ``locate_tol`` of the special
    points, ``quad_tol`` of the energies)."""
    o = run.options if run.options is not None else solver_options(run.scene)
    return {k: float(getattr(o, k)) for k in ("rtol", "tol", "step_tol", "locate_tol", "quad_tol")}


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("cusp")
    except PackageNotFoundError:  # run from a source tree without installing
        return "unknown"


def branch_csv(run: SceneRun) -> str:
    """The traced branches as CSV: one row per traced point, all cases and legs."""
    buf = io.StringIO()
    first = run.cases[0].result
    p_name, q_name = first.level_names
    cols = [
        "case",
        "mu",
        "reduced_normal_load",
        "leg",
        "point",
        "g_T",
        "F_T",
        "F_N",
        "A_SL",
        p_name,
        q_name,
    ]
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(cols)
    for i, (mu, load, res) in enumerate(run.cases):
        labels = {row: key for key, row in res.point_rows.items()}
        for leg in res.legs:
            path = res.path(leg)
            for j in range(len(path["g_T"])):
                key = labels.get((leg, j), "")
                # a named point's row holds the polished point, as summary.json does (the
                # traced row is only within the step tolerance of it)
                point = res.points.get(key) if key else None
                values = [point[c] if point else path[c][j] for c in cols[5:]]
                w.writerow([i, repr(mu), repr(load), leg, key, *(repr(float(v)) for v in values)])
    return buf.getvalue()


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip()
    return text.splitlines()[0] if text else type(exc).__name__


class NumericalFailure(RuntimeError):
    """A case or the loci failed numerically (one-line message); ``internal``: the cause
    was an untyped exception (a bug in the models, named in the message)."""

    def __init__(self, message: str, internal: bool = False) -> None:
        super().__init__(message)
        self.internal = internal


@contextmanager
def _failures(where: str, notes: list[str] | None = None) -> Iterator[None]:
    """Turn what the library raises while computing ``where`` into NumericalFailure (a
    SceneError passes through), with the scene's ``notes`` (a length in the wrong unit is
    the likelier cause) after the cause."""
    try:
        with _typed_failures(where):
            yield
    except NumericalFailure as exc:
        if not notes:
            raise
        raise NumericalFailure(f"{exc}; note: {' '.join(notes)}", exc.internal) from exc


@contextmanager
def _typed_failures(where: str) -> Iterator[None]:
    """:func:`_failures` without the notes."""
    from cusp.continuation import ContinuationError, OptionsError, ProblemDefinitionError
    from cusp.models.contact_loss import PathError
    from cusp.models.errors import ModelParameterError

    typed = (ContinuationError, PathError, ModelParameterError, ProblemDefinitionError)
    try:
        yield
    except SceneError:
        raise
    except (*typed, OptionsError) as exc:
        raise NumericalFailure(f"{where}{_first_line(exc)}") from exc
    except Exception as exc:  # last resort: an untyped exception is a bug in the models
        raise NumericalFailure(
            f"{where}unexpected {type(exc).__name__} in the models ({_first_line(exc)}); "
            "this is a bug, please report it with the scene",
            internal=True,
        ) from exc


def _output_files(run: SceneRun, figures: dict) -> dict[str, bytes]:
    """Every output file of a run: name -> bytes."""
    text = json.dumps(summary(run), indent=2, ensure_ascii=False, allow_nan=False)
    files = {"summary.json": (text + "\n").encode(), "branch.csv": branch_csv(run).encode()}
    if run.loci is not None:
        from .loci import loci_csv

        files["loci.csv"] = loci_csv(run.loci).encode()
    for name, blobs in figures.items():
        for fmt, data in blobs.items():
            files[f"{name}.{fmt}"] = data
    return files


def _fail(kind: str, message: str, status: int) -> int:
    text = " ".join(message.split())  # one line, whatever the message held
    print(f"cusp run: {kind}: {text}", file=sys.stderr)
    return status


def main(args) -> int:
    t_start = time.perf_counter()
    try:
        path, source = resolve_scene(args.scene)
        scene = load_scene(path, source=source)
        if getattr(args, "rtol", None) is not None:
            scene = with_rtol(scene, args.rtol)
        out = Path(args.out) if args.out is not None else Path("cusp-out") / scene.name
        out = check_out_dir(out)
        show = not args.quiet and on_terminal()
        with warnings.catch_warnings(record=True) as caught, np.errstate(all="ignore"):
            warnings.simplefilter("always")
            with ImportClock() as clock:
                run, figures = run_scene(scene, plots=not args.no_plots, progress=show, clock=clock)

            with _failures("writing the outputs: "):
                run.warnings = sorted({f"{w.category.__name__}: {w.message}" for w in caught})
                files = _output_files(run, figures)
    except SceneError as exc:
        return _fail("error", str(exc), 2)
    except OutDirError as exc:
        return _fail("error", str(exc), 2)
    except NumericalFailure as exc:
        return _fail("numerical failure", str(exc), 1)
    try:
        write_outputs(out, files)
    except OSError as exc:
        return _fail("error", f"cannot write the output to {out}: {exc}", 1)
    if not args.quiet:
        _report(run, out, sorted(files), time.perf_counter() - t_start)
    return 0


def _report(run: SceneRun, out: Path, files: list[str], total: float) -> None:
    sc = run.scene
    print(
        f"scene {sc.name} ({sc.source}): {sc.surface['model']}, F_N0 = "
        f"{sc.loading['normal_load']:g} N, g_A = {sc.loading['max_slip']:g} µm"
    )
    for mu, load, res in run.cases:
        print(f"  mu = {mu:g}, F'_N = {load:g} N")
        for key in "OABCD":
            pt = res.points[key]
            if pt is None:
                print(f"    {key}: none")
                continue
            print(
                f"    {key}: g_T = {pt['g_T']:.10g} µm, F_T = {pt['F_T']:.10g} N, "
                f"F_N = {pt['F_N']:.10g} N, A_SL = {pt['A_SL']:.10g}"
            )
        for kind in ("snap_back", "snap_through"):
            val = res.energy[kind]
            text = "none (gross sliding)" if val is None else f"{val:.10g} N·µm"
            print(f"    energy {kind}: {text}")
        for msg in [*run.notes, *res.messages]:
            print(f"    note: {msg}")
    if run.loci is not None:
        from .loci import report

        report(run.scene, run.loci)
    t = run.timing
    print(
        f"time: compute {t['compute_s'] * 1e3:.1f} ms, figures {t['render_s'] * 1e3:.1f} ms, "
        f"imports on the way {t.get('imports_s', 0.0) * 1e3:.1f} ms; total {total * 1e3:.1f} "
        f"ms from the command's start (Python's start-up and cusp.app's import before it "
        f"not counted)"
    )
    print(f"wrote {out}/: {', '.join(files)}")
