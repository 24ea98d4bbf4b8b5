"""Fixtures for the conformance tests."""

from __future__ import annotations

import pytest

from acphys.world.world import World


@pytest.fixture
def world() -> World:
    return World()
