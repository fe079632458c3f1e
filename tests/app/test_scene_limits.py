"""Scenes at and beyond the limits (docs/limits.md): each refusal names the field or the
limit, nothing hangs, no traceback, no warning on stderr; and a property-based fuzzer over
the schema (valid-but-extreme and invalid values)."""

from __future__ import annotations

import os
import time
import warnings
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cusp.app import cli
from cusp.app.limits import MAX_LIST, MAX_NESTING, MAX_SCENE_BYTES
from cusp.app.scene import SceneError, parse_scene

ROOT = Path(__file__).resolve().parents[2]
FIG6 = (ROOT / "scenes" / "fig6.toml").read_text(encoding="utf-8")


def _run(capsys, scene: Path | str, out: Path, *extra: str) -> tuple[int, str]:
    status = cli.main(["run", str(scene), "--out", str(out), "--no-plots", "--quiet", *extra])
    return status, capsys.readouterr().err


def _refused(capsys, tmp_path, text: str | bytes, *expect: str) -> None:
    path = tmp_path / "s.toml"
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    t0 = time.perf_counter()
    status, err = _run(capsys, path, tmp_path / "o")
    assert time.perf_counter() - t0 < 5.0
    assert status == 2, err
    assert err.count("\n") == 1 and err.startswith("cusp run: error: "), err
    for word in expect:
        assert word in err, err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(
    "text, expect",
    [
        (FIG6.replace("850.0 ", "1" + "0" * 400), ["reduced_normal_load", "float range"]),
        (FIG6 + "\n[scene]\nx = " + "[" * 1000 + "]" * 1000, [f"limit of {MAX_NESTING}"]),
        (FIG6 + "\n" + ".".join(["a"] * 50_000) + " = 1\n", ["65536 bytes"]),
        (FIG6 + "\n" + ".".join(["a"] * 10_000) + " = 1\n", ["line", "limit is 4096"]),
        (FIG6.replace("850.0 ", "[" + ", ".join(["900.0"] * 100_000) + "]"), ["bytes"]),
        (
            FIG6.replace("850.0 ", "[" + ", ".join(["900.0"] * (MAX_LIST + 1)) + "]"),
            ["reduced_normal_load", f"at most {MAX_LIST} values"],
        ),
        (FIG6 + "\n" + "# " + "x" * 4000 + "\n" * 70_000, [f"{MAX_SCENE_BYTES} bytes"]),
        (FIG6.replace('"fig6"', '"' + "n" * 300 + '"'), ["[scene] name", "100 characters"]),
        (FIG6.replace('"fig6"', '"a\\u0007b"'), ["[scene] name", "control"]),
        (FIG6 + "\n[solver]\nds_max = 1e-11\n", ["[solver] ds_max = 1e-11", "[1e-10, 1]"]),
    ],
    ids=[
        "int",
        "nesting",
        "dotted-50000",
        "dotted",
        "huge-list",
        "list",
        "size",
        "long-name",
        "bell",
        "ds_max",
    ],
)
def test_limits_are_refused_naming_the_limit(tmp_path, capsys, text, expect):
    _refused(capsys, tmp_path, text, *expect)


def test_weibull_refusals_name_shape(tmp_path, capsys):
    text = (ROOT / "scenes" / "gaussian.toml").read_text(encoding="utf-8")
    text = text.replace("rough-gaussian", "rough-weibull").replace(
        "nominal_area = 1.0e6", "nominal_area = 1.0e6\nshape = 1e-3"
    )
    _refused(capsys, tmp_path, text, "shape = 0.001")


@pytest.mark.parametrize("special", ["/dev/zero", "fifo"])
def test_devices_and_fifos_are_refused_without_reading(tmp_path, capsys, special):
    path = Path(special)
    if special == "fifo":
        path = tmp_path / "fifo.toml"
        os.mkfifo(path)
    status, err = _run(capsys, path, tmp_path / "o")
    assert status == 2 and "not a regular file" in err and err.count("\n") == 1


def test_a_byte_order_mark_is_accepted(tmp_path, capsys):
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + FIG6.encode())
    assert _run(capsys, path, tmp_path / "o") == (0, "")


def test_names_are_checked_before_any_work(tmp_path, capsys, monkeypatch):
    from cusp.models import contact_loss

    def never(self, options=None):
        raise AssertionError("computed before the names were checked")

    monkeypatch.setattr(contact_loss.ContactLoss, "run", never)
    status, err = _run(capsys, ROOT / "scenes" / "fig6.toml", tmp_path / ("d" * 300))
    assert status == 2 and "--out" in err and "bytes" in err
    (tmp_path / "file").write_text("x")
    status, err = _run(capsys, ROOT / "scenes" / "fig6.toml", tmp_path / "file")
    assert status == 2 and "not a directory" in err


def test_an_untyped_exception_in_the_models_is_one_line_naming_it(tmp_path, capsys, monkeypatch):
    from cusp.models import contact_loss

    def broken(self, options=None):
        return 1.0 / 0.0

    monkeypatch.setattr(contact_loss.ContactLoss, "run", broken)
    status, err = _run(capsys, ROOT / "scenes" / "fig6.toml", tmp_path / "o")
    assert status == 1 and err.count("\n") == 1
    assert err.startswith("cusp run: numerical failure: unexpected ZeroDivisionError")


def test_warnings_stay_off_stderr_and_are_listed_in_the_summary(tmp_path, capsys, monkeypatch):
    import json

    import numpy as np

    from cusp.models import contact_loss

    real = contact_loss.ContactLoss.run

    def noisy(self, options=None):
        np.log(np.zeros(1))  # a numpy RuntimeWarning (and errstate is not 'raise')
        warnings.warn("engine note", UserWarning, stacklevel=1)
        return real(self, options)

    monkeypatch.setattr(contact_loss.ContactLoss, "run", noisy)
    assert _run(capsys, ROOT / "scenes" / "fig6.toml", tmp_path / "o") == (0, "")
    listed = json.loads((tmp_path / "o" / "summary.json").read_text())["warnings"]
    assert listed == ["UserWarning: engine note"]


def test_broken_mathtext_in_the_title_is_a_scene_error(tmp_path, capsys):
    path = tmp_path / "t.toml"
    path.write_text(FIG6.replace('title = "', 'title = "$\\\\nocommand$ '), encoding="utf-8")
    status = cli.main(["run", str(path), "--out", str(tmp_path / "o"), "--quiet"])
    err = capsys.readouterr().err
    assert status == 2 and "[scene] title" in err and err.count("\n") == 1


# ------------------------------------------------------------------ property-based fuzzing
_NUMBERS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=5e-324, max_value=1e308),
    st.integers(min_value=-(10**400), max_value=10**400),
    st.sampled_from([0, 1, -1, 5e-324, 1e-300, 1e300, 999.999999999, 0.5, 1e15]),
)
_VALUES = st.one_of(
    _NUMBERS,
    st.text(max_size=20),
    st.booleans(),
    st.lists(_NUMBERS, max_size=4),
    st.lists(st.lists(_NUMBERS, max_size=2), max_size=2),
)
_FIELDS = {
    "surface": ["model", "sigma", "nu", "mu", "E", "radius", "density", "nominal_area", "shape"],
    "loading": ["normal_load", "max_slip", "reduced_normal_load"],
    "solver": ["ds_max", "tol", "rtol"],
    "options": ["area_reading"],
    "scene": ["name", "title"],
    "manifold": ["parameter", "range"],
    "output": ["figures"],
    "bogus": ["x"],
}


def _toml(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return {"inf": "inf", "-inf": "-inf", "nan": "nan"}.get(repr(value), repr(value))
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return '"' + "".join(c if c.isalnum() or c in " .-_$" else "" for c in value) + '"'
    return "[" + ", ".join(_toml(v) for v in value) + "]"


@st.composite
def scenes(draw) -> str:
    """fig6 with a few fields set to drawn values (extreme, wrong type) or removed."""
    lines = {"surface": {}, "loading": {}}
    for _ in range(draw(st.integers(1, 4))):
        section = draw(st.sampled_from(sorted(_FIELDS)))
        key = draw(st.sampled_from(_FIELDS[section]))
        lines.setdefault(section, {})[key] = draw(st.one_of(st.none(), _VALUES))
    text = FIG6
    for section, keys in lines.items():
        for key, value in keys.items():
            old = [ln for ln in text.splitlines() if ln.startswith(f"{key} =")]
            new = "" if value is None else f"{key} = {_toml(value)}"
            text = text.replace(old[0], new) if old else f"{text}\n[{section}]\n{new}\n"
    return text


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(scenes())
def test_parsing_any_scene_gives_a_scene_or_one_line_scene_error(text):
    try:
        parse_scene(text)
    except SceneError as exc:
        assert "\n" not in str(exc) and len(str(exc)) < 2000


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(scenes())
def test_running_any_scene_ends_with_a_right_exit_status(tmp_path_factory, text):
    tmp = tmp_path_factory.mktemp("fuzz")
    path = tmp / "s.toml"
    path.write_text(text, encoding="utf-8")
    from contextlib import redirect_stderr, redirect_stdout
    from io import StringIO

    err = StringIO()
    with redirect_stderr(err), redirect_stdout(StringIO()):
        status = cli.main(["run", str(path), "--out", str(tmp / "o"), "--no-plots", "--quiet"])
    lines = err.getvalue().splitlines()
    head = {0: None, 1: "cusp run: numerical failure: ", 2: "cusp run: error: "}[status]
    assert lines == [] if head is None else (len(lines) == 1 and lines[0].startswith(head))
    assert sorted(p.name for p in tmp.iterdir()) == (["o", "s.toml"] if status == 0 else ["s.toml"])
