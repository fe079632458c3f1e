"""The mathtext parses kept across renderers (:func:`cusp.app.figures.shared_mathtext`): the
same bytes as matplotlib's own parsing, each string parsed once across figures and formats,
and matplotlib left as it was found."""

from __future__ import annotations

import threading

import pytest

matplotlib = pytest.importorskip("matplotlib")

from cusp.app import figures  # noqa: E402

LABELS = (r"friction coefficient $\mu$", r"$F'_T = 0$", r"$\sigma^* = 2$ µm")


def _figure():
    fig = figures.new_figure((3.0, 2.0))
    ax = fig.add_subplot()
    ax.plot([0.05, 0.5], [1.0, 2.0])
    ax.set_xscale("log")  # tick labels $\mathdefault{10^{-1}}$: mathtext too
    ax.set_xlabel(LABELS[0])
    ax.set_ylabel(LABELS[1])
    fig.suptitle(LABELS[2])
    return fig


def _plain_bytes(fig) -> dict[str, bytes]:
    """What :func:`figures.encode` does, with matplotlib's own parsing."""
    fig.get_layout_engine().execute(fig)
    fig.set_layout_engine("none")
    return {fmt: figures.figure_bytes(fig, fmt, dpi=150) for fmt in ("png", "svg")}


def _parse_method():
    from matplotlib.mathtext import MathTextParser

    return MathTextParser.__dict__["_parse_cached"]


def test_same_bytes_as_matplotlibs_own_parsing():
    plain = _plain_bytes(_figure())
    figures._parsed.cache_clear()
    shared = figures.encode(_figure())
    assert shared == plain  # PNG and SVG, bit for bit
    again = figures.encode(_figure())  # every string now from the kept parses
    assert again == plain


def test_each_string_parsed_once_across_figures_and_formats():
    figures._parsed.cache_clear()
    figures.encode(_figure())
    first = figures._parsed.cache_info()
    # parsed for the Agg canvas (layout and PNG) and for the SVG's paths: once per output
    # type, dpi and font size, however often the figure asks
    assert first.hits > 0
    figures.encode(_figure())  # a second figure, new canvas and new SVG renderer
    second = figures._parsed.cache_info()
    assert second.misses == first.misses
    assert second.hits > first.hits


def test_matplotlib_left_as_found_nested_and_from_threads():
    before = _parse_method()
    with figures.shared_mathtext():
        inside = _parse_method()
        assert inside is not before
        with figures.shared_mathtext():
            assert _parse_method() is inside
        assert _parse_method() is inside  # the outer context still open

        # threads entering and leaving while this context is open, in every order
        barrier = threading.Barrier(4)
        seen = []

        def enter_and_leave(k: int):
            barrier.wait()
            with figures.shared_mathtext():
                seen.append(_parse_method())
                barrier.wait()
            for _ in range(k):
                with figures.shared_mathtext():
                    seen.append(_parse_method())

        threads = [threading.Thread(target=enter_and_leave, args=(k,)) for k in range(3)]
        for t in threads:
            t.start()
        barrier.wait()
        barrier.wait()
        for t in threads:
            t.join()
        assert seen and all(m is inside for m in seen)
        assert _parse_method() is inside
    assert _parse_method() is before


def test_restored_when_drawing_fails():
    before = _parse_method()
    with pytest.raises(RuntimeError, match="boom"), figures.shared_mathtext():
        raise RuntimeError("boom")
    assert _parse_method() is before


def test_a_kept_parse_is_not_reused_under_other_mathtext_settings():
    """The same strings under another ``mathtext.*`` setting (the roman font of a custom
    fontset) give the bytes matplotlib's own parsing gives under it, not the kept ones."""
    figures._parsed.cache_clear()
    sans = {"mathtext.fontset": "custom", "mathtext.rm": "sans", "mathtext.it": "sans:italic"}
    with matplotlib.rc_context(sans):
        figures.encode(_figure())  # kept under the sans-serif fonts
    serif = {"mathtext.fontset": "custom", "mathtext.rm": "serif", "mathtext.it": "serif:italic"}
    with matplotlib.rc_context(serif):  # the same fontset name, other fonts
        plain = _plain_bytes(_figure())
        shared = figures.encode(_figure())
    assert shared == plain
