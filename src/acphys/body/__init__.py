"""The parts of :class:`acphys.physics_obj.PhysicsObj`, one module per concern."""
