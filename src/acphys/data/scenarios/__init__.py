"""Built-in scenario files; ``acphys run`` uses ``default.toml``."""
