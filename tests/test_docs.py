"""The documentation runs: every ```python block of the Markdown pages and the README, every
tutorial and gallery script (the ones the site executes at build time), and the generated
references list exactly what the code defines.

The scripts and snippets run in-process with matplotlib's Agg backend, from a scratch
working directory (anything they write lands there), with ``plt.show`` a no-op (the gallery
shows figures by scraping them; Agg would warn).
"""

from __future__ import annotations

import importlib
import importlib.util
import math
import re
import runpy
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
PAGES = sorted([ROOT / "README.md", *DOCS.glob("*.md"), *DOCS.glob("benchmarks/*.md")])
SCRIPTS = sorted([*DOCS.glob("tutorials/*.py"), *DOCS.glob("examples/*.py")])
_FENCE = re.compile(r"^```python\n(.*?)^```", re.MULTILINE | re.DOTALL)


def python_blocks(path: Path) -> list[str]:
    """The ```python blocks of a Markdown page, in order."""
    return _FENCE.findall(path.read_text(encoding="utf-8"))


@pytest.fixture
def quiet_matplotlib(tmp_path, monkeypatch):
    """Agg, ``plt.show`` a no-op, a scratch working directory, every figure closed after."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    monkeypatch.setattr(plt, "show", lambda *a, **k: None)
    monkeypatch.chdir(tmp_path)
    yield
    plt.close("all")


def test_the_pages_have_snippets():
    """The pages do hold python blocks (a broken pattern would otherwise run nothing)."""
    counted = {p.name: len(python_blocks(p)) for p in PAGES}
    assert counted["README.md"] >= 4 and counted["continuation.md"] >= 5, counted
    assert sum(counted.values()) >= 15, counted


@pytest.mark.parametrize(
    "page", [p for p in PAGES if python_blocks(p)], ids=lambda p: str(p.relative_to(ROOT))
)
def test_snippets_run(page, quiet_matplotlib):
    """Each page's python blocks run in order, in one namespace (a later block may use what
    an earlier one defined, as a reader would)."""
    from cusp.models import registry

    bodies = dict(registry._REGISTRY)  # a snippet may register a body: put the list back
    namespace: dict = {"__name__": "__doc_snippet__"}
    try:
        for i, block in enumerate(python_blocks(page)):
            code = compile(block, f"{page.name}[python block {i}]", "exec")
            exec(code, namespace)  # noqa: S102 (the project's own documentation)
    finally:
        registry._REGISTRY.clear()
        registry._REGISTRY.update(bodies)


def test_toml_snippets_are_scenes():
    """The README's ```toml blocks are valid scenes: a block with [surface] on its own, a
    block of further sections (the [manifold] example) added to the scene before it."""
    from cusp.app.scene import parse_scene

    blocks = re.findall(r"^```toml\n(.*?)^```", (ROOT / "README.md").read_text(), re.M | re.S)
    assert len(blocks) >= 2
    base = ""
    for i, block in enumerate(blocks):
        text = block if "[surface]" in block else base + block
        scene = parse_scene(text, source=f"README.md[toml block {i}]")
        base = text if "[surface]" in block else base
        if "[manifold]" in block:
            assert scene.manifold is not None


def test_the_scripts_are_found():
    """At least five tutorials and ten gallery examples."""
    assert len(list(DOCS.glob("tutorials/tutorial_*.py"))) >= 5
    assert len(list(DOCS.glob("examples/plot_*.py"))) >= 10


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_script_runs(script, quiet_matplotlib):
    """Each tutorial and gallery script runs to its end, as the site build runs it."""
    runpy.run_path(str(script), run_name="__main__")


def _schema_module():
    path = DOCS / "_ext" / "scene_schema.py"
    spec = importlib.util.spec_from_file_location("cusp_docs_scene_schema", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_scene_schema_reference_lists_every_key():
    """The generated schema reference names every section, key, body (with each of its
    parameters and their ranges), figure and reading the scene parser accepts."""
    from cusp.app import scene
    from cusp.models import registry

    text = "\n".join(_schema_module().schema_rst())
    for section in (*scene._SECTIONS, "surface"):
        assert f"``[{section}]``" in text, section
        for key in scene._section_keys(section):
            assert f"``{key}``" in text or f"] {key}``" in text, (section, key)
    for name in registry.body_names():
        entry = registry.body_entry(name)
        assert f"``{name}``" in text, name
        if entry.has_path:
            table = text.split(f'of model = "{name}"')[1].split(".. list-table::")[0]
            for p in entry.parameters.values():
                assert f"``{p.name}``" in table and p.range_text() in table, (name, p.name)
        else:
            assert entry.refusal in text
    for word in (*scene.FIGURES, *scene.AREA_READINGS, *scene.MANIFOLD_PARAMETERS):
        assert word in text, word


def _autosummary_names(page: Path) -> list[str]:
    names = []
    for block in re.findall(
        r"\.\. autosummary::\n(?:   :.*\n)*\n((?:   \S.*\n)+)", page.read_text()
    ):
        names += block.split()
    return names


@pytest.mark.parametrize("module", ["cusp.continuation", "cusp.models"])
def test_api_reference_lists_every_public_name(module):
    """docs/api/<name>.rst documents each name of the module's ``__all__`` exactly once."""
    page = DOCS / "api" / f"{module.split('.')[1]}.rst"
    listed = _autosummary_names(page)
    public = importlib.import_module(module).__all__
    assert sorted(listed) == sorted(public)


# --- numbers in the prose: each quoted as the page prints it, from a run of the code --------


def _page(name: str) -> str:
    """A page with its whitespace collapsed (a phrase may break across lines)."""
    return " ".join((DOCS / name).read_text(encoding="utf-8").split())


def _exponential(mu: float, load: float):
    from cusp.models import ContactLoss, ExponentialRoughSurface

    return ContactLoss(ExponentialRoughSurface(2.0, 0.3, mu), 1000.0, 0.34, load).run()


def test_the_figures_numbers_are_the_codes():
    """docs/contact_loss.md's reading of Figs 6, 8 and 9 quotes the points and energies the
    model computes (the Fig 6 scene: σ* = 2 µm, ν = 0.3, F_N0 = 1000 N, g_A = 0.34 µm),
    rounded as printed."""
    text = _page("contact_loss.md")
    fig6 = _exponential(0.1, 850.0)
    A, B, C, D = (fig6.points[k] for k in "ABCD")
    high = _exponential(0.5, 850.0)
    deep = _exponential(0.1, 400.0)
    quoted = [
        f"up to {A['F_T']:.1f} N at {A['g_T']:.2f} µm",
        f"B ({B['g_T']:.4f} µm, {B['F_T']:.1f} N)",
        f"D ({D['g_T']:.2f} µm, {D['F_T']:.1f} N)",
        f"C ({C['g_T']:.3f} µm, {C['F_T']:.1f} N)",
        f"B drops to {high.points['B']['g_T']:.3f} µm, {high.points['B']['F_T']:.1f} N",
        f"grows from {fig6.energy['snap_back']:.3f} to {high.energy['snap_back']:.3f} N·µm",
        f"(snap-through {fig6.energy['snap_through']:.3f} to "
        f"{high.energy['snap_through']:.3f} N·µm)",
        # the floor F'_N = F_N0 − F_A/μ, where F'_T = F_A − μΔF_N reaches 0
        f"near the floor {1000.0 - A['F_T'] / 0.1:.1f} N",
        f"F'_N = 400 N (Fig 8) it reaches {deep.points['D']['A_SL']:.2f} at D",
    ]
    missing = [q for q in quoted if q not in text]
    assert not missing, missing


def test_the_manifold_events_quoted_are_the_codes():
    """The events of the Fig 9 loci (C boundary μ_C, F'_T = 0 at μ_0) as docs/contact_loss.md
    and docs/manifold.md quote them, from a trace of the loci; and the snap-through energy
    is least inside the range (contact_loss.md's reading of loci-energies)."""
    import numpy as np

    from cusp.models import ContactLoss, ExponentialRoughSurface, point_loci

    model = ContactLoss(ExponentialRoughSurface(2.0, 0.3, 0.1), 1000.0, 0.34, 850.0)
    loci = point_loci(model, "mu", (0.01, 1.0))
    events = {e["event"]: e["mu"] for e in loci.events}
    mu_c, mu_0 = events["C boundary"], events["F'_T = 0"]
    contact_loss, manifold = _page("contact_loss.md"), _page("manifold.md")
    for phrase in (f"μ_C = {mu_c:.4f}", f"μ_0 = {mu_0:.4f}"):
        assert phrase in contact_loss, phrase
    assert f"C boundary {mu_c:.10f}, F'_T = 0 {mu_0:.10f}" in manifold
    through = loci.columns["snap_through_energy"]
    finite = through[np.isfinite(through)]
    assert 0 < int(np.argmin(finite)) < len(finite) - 1


def test_the_frictionless_limit_numbers_are_the_codes():
    """docs/manifold.md, "μ → 0 does not close the pleat": the widths over μ at every μ from
    0.1 to 1e-4, the limit of ABD/μ² (closed form λ[ΔF_N − F'_N ln(F_N0/F'_N)],
    λ = σ*(2 − ν)/(2(1 − ν))), and the C boundary of each body and the sphere's loss of D and
    sliding of A (where F_A = μF'_N, where g_A is the sliding slip under F'_N and under F_N0:
    the slip limit of a sphere is proportional to μ), as the page rounds them."""
    from scipy.optimize import brentq

    from cusp.app.cases import build_body
    from cusp.app.run import resolve_scene
    from cusp.app.scene import load_scene

    text = _page("manifold.md")
    widths = set()
    for mu in (0.1, 1e-2, 1e-4):
        res = _exponential(mu, 850.0)
        A, B = res.points["A"], res.points["B"]
        widths.add(f"(g_A − g_B)/μ = {(A['g_T'] - B['g_T']) / mu:.12f} µm")
        widths.add(f"(F_A − F_B)/μ = {(A['F_T'] - B['F_T']) / mu:.0f} N")
    assert len(widths) == 2 and all(w in text for w in widths), widths
    lam = 2.0 * (2.0 - 0.3) / (2.0 * (1.0 - 0.3))
    limit = lam * (150.0 - 850.0 * math.log(1000.0 / 850.0))
    assert f"= {limit:.8f} N·µm" in text
    assert abs(res.energy["snap_back"] / 1e-4**2 - limit) < 1e-3 * limit  # at μ = 1e-4

    def scene(name):
        path, source = resolve_scene(name)
        return load_scene(path, source=source)

    def c_boundary(sc):  # F_A(μ) = μ F'_N at the scene's g_A, F_N0 and F'_N = 850 N
        g_A, F_N0 = sc.loading["max_slip"], sc.loading["normal_load"]

        def gap(mu):
            return build_body(sc, mu).tangential_force(g_A, F_N0) - mu * 850.0

        return brentq(gap, 0.02, 0.5, xtol=1e-12)

    bounds = [c_boundary(scene(n)) for n in ("fig6", "gaussian", "sphere")]
    phrase = "μ = {:.4f} exponential, {:.4f} Gaussian, {:.4f} sphere".format(*bounds)
    assert phrase in text, phrase
    sph = scene("sphere")
    per_mu = build_body(sph, 1.0).slip_limit  # sliding slip at μ = 1, ∝ μ
    g_A = sph.loading["max_slip"]
    d_lost, a_slides = g_A / per_mu(850.0), g_A / per_mu(sph.loading["normal_load"])
    assert f"loses D at μ = {d_lost:.4f} and A slides at μ = {a_slides:.4f}" in text


def test_the_readmes_numbers_are_the_codes():
    """README.md's comments quote C of the Fig 6 path, the CO-oxidation cusp, the range of
    ``rtol`` and the point and energy accuracy of its default as the code computes and
    allows them."""
    from cusp.continuation import (
        RTOL_DEFAULT,
        RTOL_MAX,
        RTOL_MIN,
        fold_curve,
        point_tol,
        quadrature_tol,
    )
    from cusp.examples import co_oxidation

    def cut(x: float, digits: int) -> str:  # "0.528..." : the digits shown, then "..."
        return f"{math.floor(x * 10**digits) / 10**digits:.{digits}f}..."

    text = " ".join((ROOT / "README.md").read_text(encoding="utf-8").split())
    C = _exponential(0.1, 850.0).points["C"]
    assert f"{{'g_T': {cut(C['g_T'], 3)}, 'F_T': {cut(C['F_T'], 2)}, ...}}" in text
    ex = co_oxidation()
    br = ex.trace(ds_max=0.01)
    assert len(br.special("fold")) == 2  # "two folds"
    fc = fold_curve(ex.problem, br.special("fold")[0], free=("q2", "k"), bounds={"k": (0, 2.2)})
    k = fc.special("cusp")[0].values["k"]
    assert f"k = {cut(k, 14)}" in text, k

    def e(x: float) -> str:  # 1e-3 as the README writes it
        return f"{x:.0e}".replace("e-0", "e-")

    assert f"(default {e(RTOL_DEFAULT)}; [{e(RTOL_MIN)}, {e(RTOL_MAX)}])" in text
    points, energies = point_tol(RTOL_DEFAULT), quadrature_tol(RTOL_DEFAULT)
    assert f"(the default: points to {e(points)}, energies to {e(energies)};" in text


def test_the_limits_table_is_the_codes():
    """docs/limits.md's table of limits quotes the constants the code enforces."""
    from cusp.app import limits, output, scene
    from cusp.continuation import RTOL_MAX, RTOL_MIN
    from cusp.models import manifold

    text = _page("limits.md")
    ds_max, tol = scene._NUMBERS["ds_max"], scene._NUMBERS["tol"]
    quoted = [
        f"at most {limits.MAX_SCENE_BYTES:,} bytes",
        f'"limit of {limits.MAX_SCENE_BYTES} bytes"',
        f"at most {limits.MAX_LINE_CHARS:,} characters",
        f"at most {limits.MAX_NESTING} levels",
        f"1 to {limits.MAX_LIST} values",
        f"at most {limits.MAX_CASES} (listed μ times listed F'_N)",
        f"1 to {limits.MAX_NAME_CHARS} printable characters",
        f"at most {limits.MAX_TITLE_CHARS} characters",
        f"at most {output.MAX_NAME_BYTES} bytes (UTF-8; the staging names add "
        f"{output.NAME_MAX - output.MAX_NAME_BYTES})",
        f"`[solver] ds_max` | [{ds_max.lower:g}, {ds_max.upper:g}]",
        f"`[solver] tol` | ({tol.lower:g}, {tol.upper:.0e}]".replace("e-0", "e-"),
        f"[{RTOL_MIN:.0e}, {RTOL_MAX:.0e}]".replace("e-0", "e-"),
        f"`LOCUS_STEPS` = {manifold.LOCUS_STEPS} steps",
        f"`ENERGY_ROWS` = {manifold.ENERGY_ROWS} rows",
    ]
    missing = [q for q in quoted if q not in text]
    assert not missing, missing


def test_the_physics_pages_fig6_values_are_the_codes():
    """docs/physics.md's Fig 6 table (the closed forms evaluated to 16 digits) and the values
    around it, against the traced model: to 1e-13 relative (the table's 16 digits and the
    model's rounding), and the rounded ones as printed."""
    text = _page("physics.md")
    res = _exponential(0.1, 850.0)
    rows = re.findall(r"\| ([ABCD]) \| ([0-9.]+) \| ([0-9.]+) \| ([0-9.]+) \|", text)
    assert [r[0] for r in rows] == list("ABCD"), rows
    for name, g, f, a in rows:
        point = res.points[name]
        for key, quoted in (("g_T", g), ("F_T", f), ("A_SL", a)):
            assert abs(point[key] - float(quoted)) <= 1e-13 * abs(point[key]), (name, key)
    for kind, label in (("snap_back", "(area ABD)"), ("snap_through", "(area ABC)")):
        quoted = re.search(re.escape(label) + r" ([0-9.]+) N·µm", text)
        assert quoted is not None, label
        assert abs(res.energy[kind] - float(quoted.group(1))) <= 1e-13 * res.energy[kind]
    F_A = res.points["A"]["F_T"]
    assert f"= {1000.0 - F_A / 0.1:.3f} N" in text and f"F'_N > {F_A / 0.1:.3f} N" in text
    deep = _exponential(0.1, 400.0).points["D"]["A_SL"]
    assert f"= {deep:.4f} (`docs/gallery/fig8/summary.json`)" in text
    energies = [_exponential(mu, 850.0).energy["snap_back"] for mu in (0.5, 0.1, 0.01)]
    assert "{:.6g}, {:.6g} and {:.6g} N·µm for μ = 0.5, 0.1 and 0.01".format(*energies) in text


def test_the_verification_pages_numbers_are_the_codes():
    """docs/verification.md quotes the comparison's points and tolerances as
    ``cusp.verification`` defines them, and the value of Eq 12's reading b at F̂_T = 0.0217
    against the derived F̂_ST = F̂_T − P(5/2, x), x = −ln(1 − F̂_T) (mpmath, 40 digits)."""
    import inspect

    import mpmath

    from cusp.verification import FT_HAT_EXTREMES, FT_HAT_INTERIOR, IMPLEMENTATION_RTOL
    from cusp.verification.printed import check_printed

    text = _page("verification.md")
    kw = inspect.signature(check_printed).parameters
    points, dps = kw["points"].default, kw["dps"].default
    # printed.py's numeric verdict: tolerance 10^-(dps - 10)
    assert f"{points} points at {dps} digits" in text and f"below 1e-{dps - 10} relative" in text
    interior = "{" + ", ".join(f"{v:g}" for v in FT_HAT_INTERIOR) + "}"
    assert f"at F̂_T ∈ {interior}" in text, interior
    shown = {1e-300: "1e-300", 1e-100: "1e-100", 1e-14: "1e-14", 1e-9: "1e-9",
             1 - 1e-9: "1 − 1e-9", 1 - 2.0**-40: "1 − 2⁻⁴⁰", 1 - 2.0**-52: "1 − 2⁻⁵²"}  # fmt: skip
    assert "extremes {" + ", ".join(shown[v] for v in FT_HAT_EXTREMES) + "}" in text
    assert f"a fixed **{IMPLEMENTATION_RTOL:.0e} relative**" in text
    with mpmath.workdps(40):
        F = mpmath.mpf("0.0217")
        X = mpmath.sqrt(-mpmath.log(1 - F))
        poly = (4 * X**3 + 6 * X) / (3 * mpmath.sqrt(mpmath.pi))
        derived = F + (1 - F) * poly - mpmath.erf(X)  # = F − P(5/2, X²)
        assert abs(derived - (F - mpmath.gammainc(2.5, 0, X**2, regularized=True))) < 1e-35
        reading_b = F + (1 - F) * poly + mpmath.erf(X)  # the brace opened after "F̂_T −"
    quoted = f"{float(reading_b):.3f} instead of {float(derived):.4f} at F̂_T = 0.0217"
    assert quoted in text, quoted


def test_the_sweep_pages_numbers_are_the_codes():
    """docs/sweeps.md's table of limits, the chunk size and the case key, as ``cusp.app``
    defines them."""
    from cusp.app import _sweep_spec, sweep

    text = _page("sweeps.md")

    def spaced(n: int) -> str:  # 100 000 as the page writes it
        return f"{n:,}".replace(",", " ")

    assert f"a list | 1 to {spaced(_sweep_spec.MAX_VALUES)} finite numbers" in text
    assert f"an integer, 1 to {spaced(_sweep_spec.MAX_VALUES)})" in text
    assert f"at most {spaced(_sweep_spec.MAX_SWEEP_CASES)} cases" in text
    assert (
        f"default about {['', 'one', 'two', 'three', 'four', 'five'][sweep.CHUNKS_PER_WORKER]}"
        f" chunks a worker, at most {sweep.MAX_CHUNK} cases" in text
    )
    key = _sweep_spec.case_key({"surface": {"mu": 0.1}})
    assert re.fullmatch("[0-9a-f]{16}", key) and "16 hex digits of a SHA-256" in text


def _sci(x: float, digits: int) -> str:
    """1.36·10⁻²⁰ as docs/physics.md writes it (the mantissa to ``digits`` decimals)."""
    mantissa, exponent = f"{x:.{digits}e}".split("e")
    sup = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")
    return f"{mantissa.replace('-', '−')}·10{str(int(exponent)).translate(sup)}"


def test_the_physics_pages_numerical_traps_are_the_codes():
    """docs/physics.md outside its Fig 6 table: the traps of §4 (the erf form of P(5/2, x)
    at x = 1e-8 in double precision against mpmath; 1 − gammainc at x = 50 against
    Q(5/2, 50); the bracket of Q(5/2, x) − e^{−x} for F̂_T > 1/2, least at x = ln 2 and
    growing), the Fig 5 crossings (closed forms Eqs 12, 15, 28, 29 with mpmath root finding
    at 40 digits), d0 − d at g_A = 1e-9 µm on the Gaussian scene (Eq 5) and ε/f of §7."""
    import mpmath
    from scipy.special import gammainc

    from cusp.app.cases import build_body
    from cusp.app.run import resolve_scene
    from cusp.app.scene import load_scene
    from cusp.models import GaussianRoughSurface

    text = _page("physics.md")
    # 1 − F̂_T rounds to 1 at F̂_T ≤ 2⁻⁵⁴ (half the spacing 2⁻⁵³ of the doubles below 1)
    assert 1.0 - 2.0**-54 == 1.0 and 1.0 - math.nextafter(2.0**-54, 1.0) < 1.0
    assert f"at or below 2⁻⁵⁴ ≈ {_sci(2.0**-54, 1)} it rounds to 1" in text
    x = 1e-8  # the erf form, as double-precision code would write it
    erf_form = math.erf(math.sqrt(x)) - math.exp(-x) * (4 * x**1.5 + 6 * math.sqrt(x)) / (
        3 * math.sqrt(math.pi)
    )
    with mpmath.workdps(40):
        exact = float(mpmath.gammainc(2.5, 0, x, regularized=True))
        q50 = float(mpmath.gammainc(2.5, 50, mpmath.inf, regularized=True))
    assert erf_form < 0 < exact
    percent = round(abs(erf_form - exact) / exact * 100, -1)
    assert (
        f"gives {_sci(erf_form, 2)} instead of {_sci(exact, 3)} (error {percent:.0f} %, wrong sign)"
        in text
    )
    assert 1.0 - gammainc(2.5, 50.0) == 0.0
    assert f"(at x = 50 it returns 0; Q(5/2, 50) = {_sci(q50, 2)})" in text
    with mpmath.workdps(40):

        def bracket(x):  # e^x Q(5/2, x) − 1 = erfcx(√x) + (4x^{3/2} + 6x^{1/2})/(3√π) − 1
            return mpmath.exp(x) * mpmath.gammainc(2.5, x, mpmath.inf, regularized=True) - 1

        grid = [mpmath.log(2) * (1 + k / 10) for k in range(0, 200)]
        values = [bracket(v) for v in grid]
        assert values == sorted(values) and values[0] >= 0.85 > values[0] - 0.01
    assert "a bracket ≥ 0.85" in text  # 0.8516... at x = ln 2

    with mpmath.workdps(40):

        def x_of(F):
            return -mpmath.log(1 - F)

        def cyl_force(F):  # Eq 28
            return (
                2 / mpmath.pi * (mpmath.sqrt((1 - F) * F) + mpmath.atan(mpmath.sqrt((1 - F) / F)))
                + F
                - 1
            )

        def exp_force(F):  # Eq 12: F̂_T − P(5/2, x)
            return F - mpmath.gammainc(2.5, 0, x_of(F), regularized=True)

        xf = float(
            mpmath.findroot(lambda F: cyl_force(F) - exp_force(F), (0.96, 0.98), solver="illinois")
        )
        xa = float(
            mpmath.findroot(
                lambda F: mpmath.sqrt(1 - F) - (1 - F) * (1 + x_of(F)),
                (0.9, 0.94),
                solver="illinois",
            )
        )  # Eq 29 against Eq 15
    assert f"mpmath root finding ({xf:.7f}…, {xa:.7f}…)" in text, (xf, xa)
    assert f"F̂_ST on 0 < F̂_T < {xf:.5f} and for Â_ST on 0 < F̂_T < {xa:.5f};" in text

    path, source = resolve_scene("gaussian")
    gaussian = load_scene(path, source=source)
    surface = build_body(gaussian, gaussian.surface["mu"])
    assert isinstance(surface, GaussianRoughSurface)
    d0_d = surface.stick_threshold(1e-9) / surface.sigma  # g_N0 = 2(1 − ν)g_A/(μ(2 − ν))
    d0_d = f"{d0_d:.1e}".replace("e-0", "e-")
    assert f"is {d0_d} σ* (Eq 5;" in text, d0_d
    eps_f = f"{2.0**-52 / 1e-8:.1e}".replace("e-0", "e-")
    assert f"(ε/f ≈ {eps_f} at f = 1e-8)" in text, eps_f


def test_the_rtol_table_is_the_codes():
    """docs/continuation.md's table of what ``rtol`` sets: the default column and the
    bounds, as ``ContinuationOptions`` derives them (at the default, at the loosest and at
    the tightest ``rtol``)."""
    from cusp.continuation import RTOL_DEFAULT, RTOL_MAX, RTOL_MIN, ContinuationOptions

    def e(x: float) -> str:  # 1e-3 as the page writes it
        return f"{x:.0e}".replace("e-0", "e-")

    text = _page("continuation.md")
    d, loose, tight = (ContinuationOptions(rtol=r) for r in (RTOL_DEFAULT, RTOL_MAX, RTOL_MIN))
    assert f"(in `[{e(RTOL_MIN)}, {e(RTOL_MAX)}]`, default {e(RTOL_DEFAULT)})" in text
    rows = {
        "within `rtol` of the curve": d.rtol,
        "(`step_tol`)": d.step_tol,
        f"within [{e(tight.tol)}, {e(loose.tol)}]": d.tol,
        f"at least {e(tight.locate_tol)}": d.locate_tol,
        f"at least {e(tight.quad_tol)}": d.quad_tol,
    }
    for phrase, value in rows.items():
        assert f"{phrase} | {e(value)} |" in text, (phrase, value)
    assert d.step_tol == (d.rtol / 1000) ** 2 and d.tol == 100 * d.step_tol
