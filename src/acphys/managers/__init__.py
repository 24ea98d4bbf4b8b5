"""The per-tick managers a body carries (retail ``cpmanager`` and friends).

One module per manager: ``position`` (with ``interpolation``, ``sticky`` and
``constraint``), ``target``, ``detection``, ``scripts`` and ``particles``.
Import the classes from their modules; this package imports nothing itself,
so a module can be loaded by the body without pulling in the others.
"""
