"""Scene files (TOML) for ``cusp run``, one per figure of the paper; see ``models.scene``."""
