"""The built-in motion tables, in the scenario format (``[motion_table]``)."""
