"""Figure and benchmark scripts (run from the repository root: ``python scripts/<name>.py``)."""
