"""Scenarios of the conformance corpus that are not built-in scenarios (see :mod:`acphys.corpus`)."""
