"""pmpmsph: MPI-parallel coupled Material Point Method and SPH solver with Numba kernels."""
__version__ = "0.1.0"

from .config import case_from_dict, load_case_file, load_case_text  # noqa: E402
from .errors import ConfigError, RunError  # noqa: E402
from .io.results import Run, read  # noqa: E402
from .scene_api import Scene  # noqa: E402

__all__ = ["Scene", "ConfigError", "RunError", "Run", "read", "case_from_dict", "load_case_file",
           "load_case_text", "__version__"]
