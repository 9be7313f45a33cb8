"""The ROS tiers' rule: outside CI a tier that cannot set itself up is skipped, in CI it fails."""

from __future__ import annotations

import os

import pytest


def in_ci() -> bool:
    return os.environ.get("CI", "").lower() == "true"


def unavailable(reason: str):
    """Skip a ROS tier that cannot run here, except in CI, where that is a failure."""
    if in_ci():
        pytest.fail(f"CI=true and this tier cannot run: {reason}", pytrace=False)
    pytest.skip(reason)
