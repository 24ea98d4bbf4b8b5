"""The fast engine: the reference engine's tick over arrays, compiled with Numba.

``Simulation(engine="fast")`` (``load_scenario(..., engine="fast")``, ``acphys run --engine fast``)
runs bodies through :class:`acphys.fast.engine.FastPhysics`: records in retail's object-table
order (:mod:`acphys.fast.layout`), stepped by compiled kernels (:mod:`acphys.fast.kernels`) that
perform the reference's float64 operations in its order and narrow to float32 where it does, so
the traces are byte for byte the reference's (:mod:`acphys.fast.differential`). A body-step the
kernels do not cover runs on the reference path in its place in the order
(:mod:`acphys.fast.coverage`); the engine counts how many do.
"""
