"""Scene files (TOML) bundled with cusp, one per figure of the paper; see :mod:`cusp.app.scene`."""
