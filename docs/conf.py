"""Sphinx configuration of the cusp documentation site.

Build it (with the ``docs`` extra installed, ``pip install -e ".[docs]"``), from the
repository root::

    python -m sphinx -W --keep-going -b html docs docs/_build/html

The Markdown pages are read by myst-parser; the API reference is autosummary/autodoc with
numpydoc; the tutorials and the gallery are sphinx-gallery scripts (``docs/tutorials/``,
``docs/examples/``), executed at every build and run by ``tests/test_docs.py``; the scene
schema reference is generated from :mod:`cusp.app.scene` and the body registry by the
``cusp-scene-schema`` directive (``docs/_ext/scene_schema.py``).
"""

from __future__ import annotations

import importlib.util
import os
from pathlib import Path

import cusp

os.environ.setdefault("MPLBACKEND", "Agg")

HERE = Path(__file__).resolve().parent

project = "cusp"
author = "the cusp authors"
copyright = "the cusp authors"  # noqa: A001 (Sphinx's name)
version = release = cusp.__version__

extensions = [
    "myst_parser",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
templates_path = ["_templates"]
exclude_patterns = [
    "_build",
    "_templates",
    "**/README.md",
    "tutorials/README.txt",
    "examples/README.txt",
    "auto_*/**/*.ipynb",
    "auto_*/**/*.py",
    "auto_*/**/*.zip",
    "auto_*/**/*.md5",
    "auto_*/**/*.codeobj.json",
]

# Markdown: heading anchors for the pages' "page.md#section" links
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]

# autodoc / autosummary / numpydoc: the reference is generated at build time from the
# package; numpydoc's validation is a test of its own, not switched on here
autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

sphinx_gallery_conf = {
    "examples_dirs": ["tutorials", "examples"],
    "gallery_dirs": ["auto_tutorials", "auto_examples"],
    "filename_pattern": r"/(plot|tutorial)_",
    "within_subsection_order": "FileNameSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "show_memory": False,
}

html_theme = "pydata_sphinx_theme"
html_title = f"cusp {release}"
html_theme_options = {"navigation_depth": 2, "show_toc_level": 2}
html_static_path: list[str] = []


def setup(app):
    """Register the scene-schema directive (loaded from its file: the docs edit no import
    path)."""
    path = HERE / "_ext" / "scene_schema.py"
    spec = importlib.util.spec_from_file_location("cusp_docs_scene_schema", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.setup(app)
