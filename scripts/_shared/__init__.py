"""What the scripts of ``scripts/`` share (private: no API, no stability promise).

The benchmark, figure and measurement scripts run as ``python scripts/NAME.py`` from the
repository root; the code more than one of them uses lives here, installed with the package
as ``cusp._scripts`` (folder ``scripts/_shared/``), so that a script or a test imports it by
name, without adding ``scripts/`` to the import path. The top layer: it may import every other
layer of ``cusp``, and nothing imports it. Its optional dependencies (contique, pacopy,
mpmath) are imported where they are used, never when a module is imported.

* :mod:`~cusp._scripts.report`: reports and figures written atomically, figures byte for
  byte reproducible; the provenance of a measurement (commit, load average, machine);
* :mod:`~cusp._scripts.tools`: the continuation tools the benchmarks compare (ours,
  contique, pacopy, a SciPy loop) run on one problem and counted; timing helpers; the
  problems of ``scripts/bench_trace.py`` (:func:`~cusp._scripts.tools.trace_problems`);
* :mod:`~cusp._scripts.wp_problems`, :mod:`~cusp._scripts.wp_contact`,
  :mod:`~cusp._scripts.wp_figures`, :mod:`~cusp._scripts.wp_report`: the tasks, figures and
  report of ``scripts/bench_work_precision.py``;
* :mod:`~cusp._scripts.pleat_reference`: the independent references of
  ``scripts/pleat_closure.py``.
"""
