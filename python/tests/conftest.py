import os

import pytest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture
def repo():
    """The egw repository root (reference data under test/data)."""
    return REPO
