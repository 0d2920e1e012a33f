"""Discovery of the modules that register themselves (materials, SPH smoothing kernels):
importing every module of a package folder, so that adding one is adding a file."""
import importlib
import pkgutil
from pathlib import Path


def import_all(package, init_file, machinery=()):
    """Import every module of `package` (whose `__init__.py` is `init_file`) but the names
    in `machinery` and the private ones; idempotent (imports are cached)."""
    for info in pkgutil.iter_modules([str(Path(init_file).parent)]):
        if info.name not in machinery and not info.name.startswith("_"):
            importlib.import_module(f"{package}.{info.name}")
