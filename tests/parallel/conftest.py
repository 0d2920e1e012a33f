import os
import sys

sys.path.insert(0, os.path.dirname(__file__))

import pytest  # noqa: E402


@pytest.fixture
def shared_dir(request):
    """Rank 0's tmp_path on every rank (only rank 0 asks pytest for one)."""
    from mpi_util import world

    dist = world()
    local = str(request.getfixturevalue("tmp_path")) if dist.is_root else None
    path = dist.bcast(local)
    dist.barrier()
    return path
