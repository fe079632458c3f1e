"""Where the pleat closes: the order of contact of the two fold loci (A and B) of the
contact-loss path, measured on the exponential, Gaussian and sphere scenes (issue 16, point 4).

The pleat of one path is the range over which it is folded: g_T ∈ [g_B, g_A] under
displacement control, F_T ∈ [F_B, F_A] under force control. Its edges, as the reduction
d = ΔF_N/F_N0 (or μ) varies, are the loci of the corners A and B. Measured here, with
``ContactLoss`` single runs at d = 10⁻¹ … 10⁻¹², each against an independent reference:

* the widths g_A − g_B and F_A − F_B, the snap-back drop F_A − F_D, the snap-through jump
  g_C − g_A, and the released energies ABD (snap-back) and ABC (snap-through);
* the exponents by least squares on log-log data over d ∈ [10⁻⁸, 10⁻²], only at the d where
  the measured value agrees with the reference to ``TRUST`` (with the spread: the standard
  error of the slope and the range of the local slopes between neighbouring d);
* references: for exponential heights the sympy closed forms of
  :func:`cusp.verification.contact_loss_path` (and their series in d, the exact exponents);
  for the Gaussian surface and the sphere, the path written out from the physics with
  mpmath (the frozen stick level of AB, the energies as loop integrals of F_T dg_T); both in
  ``scripts/_shared/pleat_reference.py`` (``cusp._scripts.pleat_reference``);
* the slopes of the loci of A, B and D at the closure (d = 0), from the tangent of the locus
  in F'_N (:func:`cusp.models.manifold.point_loci`), traced through F'_N = F_N0;
* μ → 0 at the scene's F'_N: the same quantities over μ = 0.1 … 10⁻⁴ (as far as each body
  goes) and the events of the locus in μ.

Usage (from the repository root, with the test extra installed)::

    python scripts/pleat_closure.py [--md PATH] [--png PATH] [--no-figure]

writes ``docs/benchmarks/pleat-closure.md`` and ``docs/figures/pleat-closure.png`` (the
defaults) and prints the fitted exponents. Runs in about a minute.
"""

from __future__ import annotations

import argparse
import math
import platform
import time
from pathlib import Path

import numpy as np

from cusp._scripts.pleat_reference import REF_DPS, exponential_series, reference, rel_error
from cusp._scripts.report import commit_and_load, save_figure, write_report
from cusp.app.run import bundled_scene
from cusp.app.scene import load_scene
from cusp.continuation import ChainPoint, ContinuationError, PointChain
from cusp.models import ContactLoss, ModelParameterError
from cusp.models.manifold import point_loci
from cusp.models.registry import build_body

ROOT = Path(__file__).resolve().parents[1]
#: the bodies: label -> bundled scene
SCENES = {"exponential": "fig6.toml", "Gaussian": "gaussian.toml", "sphere": "sphere.toml"}
#: distances to closure d = ΔF_N/F_N0 (half decades)
D_VALUES = tuple(10.0 ** (-k / 2) for k in range(2, 25))
#: the fit window in d
FIT_RANGE = (1e-8, 1e-2)
#: a value enters a fit only if it agrees with its reference to this (relative)
TRUST = 1e-6
#: friction coefficients of the μ sweep (μ0 = 0.1 down to 10⁻⁴, eighth decades)
MU_VALUES = tuple(0.1 * 10.0 ** (-k / 8) for k in range(0, 25))
MU_FIT_MAX = 1e-2
#: the measured quantities: key -> (what, unit)
QUANTITIES = {
    "dg": ("g_A − g_B (width in g_T)", "µm"),
    "dF": ("F_A − F_B (width in F_T)", "N"),
    "drop": ("F_A − F_D (snap-back drop)", "N"),
    "jump": ("g_C − g_A (snap-through jump)", "µm"),
    "ABD": ("area ABD (snap-back energy)", "N·µm"),
    "ABC": ("area ABC (snap-through energy)", "N·µm"),
}


# ------------------------------------------------------------------------------------------
# the bodies and the measurement


def scene_case(label: str) -> dict:
    """The body's model name, surface parameters and loading from its bundled scene."""
    scene = load_scene(bundled_scene(SCENES[label]))
    params = dict(scene.surface)
    model = params.pop("model")
    return {
        "label": label,
        "model": model,
        "params": params,
        "F_N0": scene.loading["normal_load"],
        "g_A": scene.loading["max_slip"],
        "F_Np": scene.reduced_normal_loads[0],
    }


def measure(case: dict, F_Np: float, mu: float | None = None) -> dict[str, float]:
    """One traced path: the quantities of :data:`QUANTITIES` (NaN where C or D is missing)."""
    params = dict(case["params"], **({} if mu is None else {"mu": mu}))
    body = build_body(case["model"], **params)
    res = ContactLoss(body, case["F_N0"], case["g_A"], F_Np).run()
    P, E = res.points, res.energy
    A, B, C, D = (P[k] for k in "ABCD")
    nan = math.nan
    return {
        "dg": A["g_T"] - B["g_T"],
        "dF": A["F_T"] - B["F_T"],
        "drop": A["F_T"] - D["F_T"] if D else nan,
        "jump": C["g_T"] - A["g_T"] if C else nan,
        "ABD": E["snap_back"] if E["snap_back"] is not None else nan,
        "ABC": E["snap_through"] if E["snap_through"] is not None else nan,
    }


# ------------------------------------------------------------------------------------------
# fits


def fit(x, y) -> dict[str, float]:
    """Least-squares slope of log y against log x, its standard error, the local slopes
    between neighbouring points (the one at the smallest x, their range) and the count."""
    order = np.argsort(x)
    lx, ly = np.log10(np.asarray(x)[order]), np.log10(np.asarray(y)[order])
    n = lx.size
    if n < 3:
        return {"p": math.nan, "se": math.nan, "lo": math.nan, "hi": math.nan, "n": n}
    slope, icpt = np.polyfit(lx, ly, 1)
    resid = ly - (slope * lx + icpt)
    se = math.sqrt(float(resid @ resid) / (n - 2) / float(((lx - lx.mean()) ** 2).sum()))
    local = np.diff(ly) / np.diff(lx)
    return {
        "p": float(slope),
        "se": se,
        "lo": float(local.min()),
        "hi": float(local.max()),
        "first": float(local[0]),
        "n": n,
    }


def fits(x, rows, refs, window) -> dict[str, dict[str, float]]:
    """Fit every quantity over ``window`` of x, at the trusted points only."""
    out = {}
    for key in QUANTITIES:
        pts = [
            (xi, r[key])
            for xi, r, f in zip(x, rows, refs)
            if window[0] * (1 - 1e-9) <= xi <= window[1] * (1 + 1e-9)
            and r[key] > 0.0
            and rel_error(r[key], f[key]) <= TRUST
        ]
        out[key] = fit([p[0] for p in pts], [p[1] for p in pts]) if pts else fit([], [])
    return out


# ------------------------------------------------------------------------------------------
# sweeps


def sweep_d(case: dict) -> dict:
    """Single runs at every d of :data:`D_VALUES`, references, errors and fits."""
    F_N0 = case["F_N0"]
    ds, rows, refs = [], [], []
    t0 = time.perf_counter()
    failures: dict[float, str] = {}
    for d in D_VALUES:
        F_Np = F_N0 * (1.0 - d)
        ds.append((F_N0 - F_Np) / F_N0)  # the reduction actually applied
        try:
            rows.append(measure(case, F_Np))
        except (ValueError, ContinuationError) as exc:  # the run itself fails (reported)
            rows.append(dict.fromkeys(QUANTITIES, math.nan))
            failures[ds[-1]] = f"{type(exc).__name__}: {exc}"
        refs.append(reference(case, F_Np))
    seconds = time.perf_counter() - t0
    return {
        "d": ds,
        "rows": rows,
        "refs": refs,
        "fits": fits(ds, rows, refs, FIT_RANGE),
        "seconds": seconds,
        "failures": failures,
    }


def sweep_mu(case: dict) -> dict:
    """Single runs at the scene's F'_N for μ of :data:`MU_VALUES`, down to where the body
    stops (A slides, or its levels fail), with references and fits over μ ≤ MU_FIT_MAX."""
    mus, rows, refs, stop = [], [], [], ""
    floor = None  # where a locus in μ can be sent: it ends at its own events before that
    for mu in MU_VALUES:
        try:
            row = measure(case, case["F_Np"], mu)
        except ModelParameterError as exc:  # g_A beyond the slip at which A slides
            stop, floor = f"μ = {mu:.3g}: refused ({str(exc).split(',')[0]})", mu
            break
        except ContinuationError as exc:
            stop = f"μ = {mu:.3g}: {type(exc).__name__} ({str(exc).split(';')[0]})"
            break
        mus.append(mu)
        rows.append(row)
        refs.append(reference(case, case["F_Np"], mu))
    return {
        "mu": mus,
        "rows": rows,
        "refs": refs,
        "stop": stop,
        "F_Np": case["F_Np"],
        "floor": floor if floor is not None else min(mus),
        "mu_slides": _mu_slides(case),
        "fits": fits(mus, rows, refs, (0.0, MU_FIT_MAX)),
    }


def _mu_slides(case: dict) -> float | None:
    """The μ below which A slides at g_A (a body with a finite slip limit ∝ μ), else None."""
    body = build_body(case["model"], **case["params"])
    limit = getattr(body, "slip_limit", None)
    if limit is None:
        return None
    return case["params"]["mu"] * case["g_A"] / float(limit(case["F_N0"]))


def closure_slopes(case: dict) -> dict[str, float]:
    """The loci of A, B and D at the closure (m_B = 1 − F'_N/F_N0 = 0, where B = D = A).

    The locus in F'_N (:func:`point_loci`) is traced from F'_N = 0.999 F_N0 through
    F'_N = F_N0; ``gap`` is the largest difference between B, D and A at its end (0 if the
    locus closes there). Its slopes at d = 0 (d/dd of g_A − g_B [µm], F_A − F_B, F_A − F_D
    [N], and of g_A) are those of the same chain of points (A: g_T = g_A on OA; B: F_N = F'_N
    on AB with A's stick level; D: g_T = g_A on BC at B's load) by the implicit function
    theorem at the closure point, −J⁻¹ ∂R/∂m_B with J the chain's Jacobian: exact, where the
    tangent the tracer stores at a bound-hit end carries an O(h²) error of the last step."""
    F_N0 = case["F_N0"]
    body = build_body(case["model"], **case["params"])
    model = ContactLoss(body, F_N0, case["g_A"], 0.999 * F_N0)
    loci = point_loci(model, "reduced_normal_load", (0.99 * F_N0, F_N0))
    main = loci.branches["A-B-D"]
    end = main.point(int(np.argmin(main["m_B"])))
    at_a = {v: end[f"A.{v}"] for v in ("g", "t", "m", "A_SL", "p", "q")}
    s = model.scales
    chain = PointChain(
        [
            ChainPoint("A", model.problem("OA", start=1.0), "g", ("g", 1.0)),
            ChainPoint(
                "B",
                model.problem("AB", start=0.0, constant=at_a["q"]),
                "m",
                ("m", "m_B"),
                links={"q_A": ("A", "q")},
            ),
            ChainPoint(
                "D",
                model.problem("BC", start=1.0, constant=0.0),
                "g",
                ("g", 1.0),
                links={"m_B": ("B", "m")},
            ),
        ],
        {"mu": model.mu0, "m_B": 0.0},
    )
    u = chain.start({"A": at_a, "B": at_a, "D": at_a})
    du = np.linalg.solve(
        chain.jacobian(u, chain.params), chain.param_jacobian(u, chain.params, "m_B")
    )
    rate = dict(zip(chain.unknowns, du))  # −d/dm_B = d/dn_B, n_B = 1 − m_B, d = m_B
    return {
        "n_B": 1.0 - end["m_B"],
        "gap": max(abs(end[f"{x}.{v}"] - end[f"A.{v}"]) for x in "BD" for v in ("g", "t")),
        "residual": float(np.max(np.abs(chain.residual(u, chain.params)))),
        "dg": rate["B.g"] * s["g"],
        "dF": rate["B.t"] * s["t"],
        "drop": rate["D.t"] * s["t"],
        "A.g": rate["A.g"] * s["g"],
    }


def mu_events(case: dict, lo: float) -> list[tuple[str, float]]:
    """The events of the locus in μ ∈ [lo, μ0] at the scene's F'_N (C boundary, D
    disappears, A slides)."""
    body = build_body(case["model"], **case["params"])
    model = ContactLoss(body, case["F_N0"], case["g_A"], case["F_Np"])
    loci = point_loci(model, "mu", (lo, model.mu0))
    return [(e["event"], e["mu"]) for e in loci.events]


# ------------------------------------------------------------------------------------------
# report


def _g(v: float) -> str:
    return "—" if not math.isfinite(v) else f"{v:.4e}"


def _g10(v: float) -> str:
    return "—" if not math.isfinite(v) else f"{v:.10g}"


def _fit_text(f: dict) -> tuple[str, str, str, str]:
    if not math.isfinite(f["p"]):
        return ("—", "—", "—", str(f["n"]))
    return (
        f"{f['p']:.6f}",
        f"{f['se']:.1e}",
        f"[{f['lo']:.6f}, {f['hi']:.6f}]; {f['first']:.6f} at the smallest",
        str(f["n"]),
    )


def d_table(label: str, sw: dict) -> list[str]:
    """The measured quantities against d, with the worst relative error against the
    reference (values outside the fit window or untrusted are marked)."""
    keys = list(QUANTITIES)
    head = "| d | " + " | ".join(f"{QUANTITIES[k][0]} [{QUANTITIES[k][1]}]" for k in keys)
    lines = [f"### {label}: single runs", "", head + " | max rel. error | fitted |"]
    lines.append("|" + "---:|" * (len(keys) + 3))
    for d, r, f in zip(sw["d"], sw["rows"], sw["refs"]):
        err = max(rel_error(r[k], f[k]) for k in keys)
        inside = FIT_RANGE[0] * (1 - 1e-9) <= d <= FIT_RANGE[1] * (1 + 1e-9)
        used = "yes" if inside and err <= TRUST else ("no (error)" if inside else "no")
        cells = " | ".join(_g(r[k]) for k in keys)
        if d in sw["failures"]:
            err_text, used = "run failed", "no"
        else:
            err_text = f"{err:.1e}"
        lines.append(f"| {d:.3g} | {cells} | {err_text} | {used} |")
    for d, why in sw["failures"].items():
        lines.append(f"\nAt d = {d:.3g} `ContactLoss.run()` raised {why}")
    return lines + [""]


def fit_table(results: dict, what: str, key: str = "sweep") -> list[str]:
    lines = [
        f"| body | quantity | exponent ({what}) | std. error | local slopes [min, max]; the "
        f"one at the smallest {what[3:]} | points |",
        "|---|---|---:|---:|---|---:|",
    ]
    for label, res in results.items():
        for k, f in res[key]["fits"].items():
            p, se, local, n = _fit_text(f)
            lines.append(f"| {label} | {QUANTITIES[k][0]} | {p} | {se} | {local} | {n} |")
    return lines + [""]


def series_table(series: dict, fitted: dict, smallest: dict) -> list[str]:
    lines = [
        "| quantity | series in d (sympy, x_A = g_A/(μλ)) | exact exponent | fitted | "
        "leading coeff. (scene) | measured value/d^p at the smallest fitted d |",
        "|---|---|---:|---:|---:|---:|",
    ]
    for k, s in series.items():
        lines.append(
            f"| {QUANTITIES[k][0]} | {s['terms']} + … | {s['exponent']} | "
            f"{fitted[k]['p']:.6f} | {s['leading']:.10g} | {smallest[k]:.10g} |"
        )
    return lines + [""]


def smallest_ratio(sw: dict, key: str, power: float) -> float:
    """value/d^power at the smallest trusted d of the fit window."""
    for d, r, f in zip(sw["d"][::-1], sw["rows"][::-1], sw["refs"][::-1]):
        ok = FIT_RANGE[0] * (1 - 1e-9) <= d and rel_error(r[key], f[key]) <= TRUST
        if ok and math.isfinite(r[key]):
            return r[key] / d**power
    return math.nan


def closure_table(results: dict) -> list[str]:
    """Slopes at the closure (the locus tangent) against value/d at the smallest fitted d,
    and the triangle ratios of the energies."""
    lines = [
        "| body | locus end: max abs(B, D − A) | d(g_A)/dd | d(g_A − g_B)/dd at d = 0 [µm] | "
        "(g_A − g_B)/d [µm] (runs) | d(F_A − F_B)/dd [N] | (F_A − F_B)/d [N] (runs) | "
        "d(F_A − F_D)/dd [N] | (F_A − F_D)/d [N] (runs) | ABD/(½·Δg·ΔF_D) | "
        "ABC/(½·(Δg + Δg_C)·ΔF_D) |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for label, res in results.items():
        sl, sw = res["slopes"], res["sweep"]
        tri = triangles(sw)
        lines.append(
            f"| {label} | {sl['gap']:.1e} | {sl['A.g']:.1e} | {sl['dg']:.10g} | "
            f"{smallest_ratio(sw, 'dg', 1):.10g} | {sl['dF']:.10g} | "
            f"{smallest_ratio(sw, 'dF', 1):.10g} | {sl['drop']:.10g} | "
            f"{smallest_ratio(sw, 'drop', 1):.10g} | {tri[0]:.8f} | {tri[1]:.8f} |"
        )
    return lines + [""]


def triangles(sw: dict) -> tuple[float, float]:
    """ABD and ABC over the areas of the straight-sided triangles ABD and ABC at the
    smallest fitted d (→ 1 if the pleat closes as a corner)."""
    for d, r, f in zip(sw["d"][::-1], sw["rows"][::-1], sw["refs"][::-1]):
        errs = [rel_error(r[k], f[k]) for k in QUANTITIES]
        if FIT_RANGE[0] * (1 - 1e-9) <= d and max(errs) <= TRUST:
            abd = r["ABD"] / (0.5 * r["dg"] * r["drop"])
            abc = r["ABC"] / (0.5 * (r["dg"] + r["jump"]) * r["drop"])
            return abd, abc
    return math.nan, math.nan


def mu_table(label: str, sw: dict, events) -> list[str]:
    lines = [
        f"### {label}: μ → 0 at F'_N = {sw['F_Np']:g} N",
        "",
        "| μ | (g_A − g_B)/μ [µm] | (F_A − F_B)/μ [N] | (F_A − F_D)/μ [N] | ABD/μ² [N·µm] | "
        "ABC/μ² [N·µm] | max rel. error |",
        "|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for mu, r, f in zip(sw["mu"], sw["rows"], sw["refs"]):
        err = max(rel_error(r[k], f[k]) for k in QUANTITIES)
        lines.append(
            f"| {mu:.4g} | {r['dg'] / mu:.12g} | {r['dF'] / mu:.12g} | {r['drop'] / mu:.10g} | "
            f"{r['ABD'] / mu**2:.10g} | {_g10(r['ABC'] / mu**2)} | {err:.1e} |"
        )
    events = list(events)
    if sw.get("mu_slides") is not None:
        events.append(("A slides (g_A = slip limit under F_N0, closed form)", sw["mu_slides"]))
    ev = "; ".join(f"{name} at μ = {mu:.10g}" for name, mu in events) or "none"
    lines += ["", f"Events of the locus in μ (point_loci): {ev}."]
    lines += [f"The sweep stops at {sw['stop']}." if sw["stop"] else "The sweep reaches μ = 1e-4."]
    return lines + [""]


def figure(results: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.6), constrained_layout=True)
    colors = {"exponential": "C0", "Gaussian": "C1", "sphere": "C2"}
    for label, res in results.items():
        sw, sm, c = res["sweep"], res["mu_sweep"], colors[label]
        case = res["case"]
        d = np.array(sw["d"])
        g_s, e_s = case["g_A"], case["params"]["mu"] * case["F_N0"] * case["g_A"]
        ax.loglog(
            d,
            [r["dg"] / g_s for r in sw["rows"]],
            "o-",
            color=c,
            ms=3,
            label=f"{label}: (g_A − g_B)/g_A",
        )
        ax.loglog(
            d,
            [r["ABD"] / e_s for r in sw["rows"]],
            "s--",
            color=c,
            ms=3,
            label=f"{label}: ABD/(μF_N0 g_A)",
        )
        mu = np.array(sm["mu"])
        bx.loglog(
            mu,
            [r["dg"] / g_s for r in sm["rows"]],
            "o-",
            color=c,
            ms=3,
            label=f"{label}: (g_A − g_B)/g_A",
        )
        bx.loglog(
            mu,
            [r["ABD"] / e_s for r in sm["rows"]],
            "s--",
            color=c,
            ms=3,
            label=f"{label}: ABD/(μ0F_N0 g_A)",
        )
    dd = np.array([1e-12, 1e-1])
    for p, ls in ((1.0, ":"), (1.5, "-."), (2.0, ":")):
        ax.loglog(dd, 0.3 * dd**p, ls, color="0.5", lw=0.8)
        ax.annotate(rf"$\propto d^{{{p:g}}}$", (dd[0], 0.3 * dd[0] ** p), fontsize=9, color="0.4")
    ax.axvspan(*FIT_RANGE, color="0.93", zorder=0)
    ax.set(
        xlabel="d = ΔF_N / F_N0",
        ylabel="width, energy (scaled)",
        title="closure d → 0 (shaded: fit window)",
    )
    mm = np.array([1e-4, 1e-1])
    for p in (1.0, 2.0):
        bx.loglog(mm, 3.0 * mm**p, ":", color="0.5", lw=0.8)
        bx.annotate(rf"$\propto \mu^{{{p:g}}}$", (mm[0], 3.0 * mm[0] ** p), fontsize=9, color="0.4")
    bx.set(
        xlabel="μ",
        ylabel="width, energy (scaled by the μ0 = 0.1 scales)",
        title="μ → 0 at the scene's F'_N (= 850 N)",
    )
    ax.legend(fontsize=7, loc="lower right")
    bx.legend(fontsize=7, loc="lower right")
    save_figure(fig, path, dpi=110)
    plt.close(fig)


def report(results: dict, series: dict, seconds: float) -> str:
    commit = commit_and_load()[0]
    exp = results["exponential"]
    smallest = {k: smallest_ratio(exp["sweep"], k, s["exponent"]) for k, s in series.items()}
    lines = [
        "# Where the pleat closes: widths and energies against the distance to closure",
        "",
        "Generated by `python scripts/pleat_closure.py` (issue 16, point 4); what it means: the",
        "section on the closure of the pleat in the manifold docs. Bodies: the bundled scenes",
        "`fig6.toml` (exponential), `gaussian.toml` and `sphere.toml`; d = ΔF_N/F_N0 with",
        "F'_N = F_N0(1 − d) (d as applied, in floating point). Each row is one `ContactLoss` run;",
        "its error is the largest relative difference, over the six quantities, from the",
        "reference (exponential: the sympy closed forms of `contact_loss_path()`, evaluated at",
        "the exact binary inputs; Gaussian and sphere: the path written out with mpmath at",
        f"{REF_DPS} digits; both in `scripts/_shared/pleat_reference.py`). Fits: least squares of",
        f"log y on log d over d ∈ [{FIT_RANGE[0]:g}, {FIT_RANGE[1]:g}], at rows with error ≤",
        f"{TRUST:g}.",
        "",
        f"Commit `{commit}`; Python {platform.python_version()}, numpy {np.__version__}; "
        f"{seconds:.0f} s in all.",
        "",
        "## Fitted exponents, d → 0",
        "",
        *fit_table(results, "in d"),
        "## Exact exponents (exponential heights): series of the closed forms",
        "",
        *series_table(series, exp["sweep"]["fits"], smallest),
        "## Slopes at the closure",
        "",
        "The loci of A, B and D in F'_N (`point_loci(model, 'reduced_normal_load')`) are",
        "traced through F'_N = F_N0, where B and D reach A (nondimensional g and t: the first",
        "column). The slopes at d = 0 are those of the same chain of points at the closure by",
        "the implicit function theorem (the chain's Jacobian; A does not move with F'_N), set",
        "beside value/d of the runs at the smallest fitted d. The triangle ratios divide the",
        "energies by the areas of the straight-sided triangles ABD and ABC at that d.",
        "",
        *closure_table(results),
        "## μ → 0 at fixed F'_N",
        "",
        "Fits over the rows with μ ≤ 0.01 (error ≤ the trust level; none for the sphere,",
        "which at g_A = 2 µm loses D, then A, well above μ = 0.01):",
        "",
        *fit_table(results, "in μ", "mu_sweep"),
    ]
    for label, res in results.items():
        lines += mu_table(label, res["mu_sweep"], res["mu_events"])
    lines += ["## The runs", ""]
    for label, res in results.items():
        lines += d_table(label, res["sweep"])
    return "\n".join(lines).rstrip() + "\n"


def run_body(label: str) -> dict:
    case = scene_case(label)
    sweep = sweep_d(case)
    mu_sweep = sweep_mu(case)
    return {
        "case": case,
        "sweep": sweep,
        "slopes": closure_slopes(case),
        "mu_sweep": mu_sweep,
        "mu_events": mu_events(case, mu_sweep["floor"]),
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--md", type=Path, default=ROOT / "docs/benchmarks/pleat-closure.md")
    parser.add_argument("--png", type=Path, default=ROOT / "docs/figures/pleat-closure.png")
    parser.add_argument("--no-figure", action="store_true")
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    results = {label: run_body(label) for label in SCENES}
    series = exponential_series(results["exponential"]["case"])
    seconds = time.perf_counter() - t0
    write_report(args.md, report(results, series, seconds))
    if not args.no_figure:
        figure(results, args.png)
    for label, res in results.items():
        for k, f in res["sweep"]["fits"].items():
            print(f"{label:12s} {k:5s} p = {f['p']:.6f} ± {f['se']:.1e} (n = {f['n']})")
    print(f"wrote {args.md}" + ("" if args.no_figure else f" and {args.png}"))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
