"""Registries of the entries that register themselves (materials, SPH smoothing kernels, MPM
shape functions): discovery imports every module of the entries' package folder, so that
adding an entry is adding a file."""
import importlib
import pkgutil
from pathlib import Path


def import_all(package, init_file, machinery=()):
    """Import every module of `package` (whose `__init__.py` is `init_file`) but the names
    in `machinery` and the private ones; idempotent (imports are cached)."""
    for info in pkgutil.iter_modules([str(Path(init_file).parent)]):
        if info.name not in machinery and not info.name.startswith("_"):
            importlib.import_module(f"{package}.{info.name}")


class Registry:
    """Entries with a stable integer `code` and the names `names(entry)` (default: its
    `name`), from the modules of `package` (`import_all`)."""

    def __init__(self, what, package, init_file, machinery=("registry",),
                 names=lambda entry: (entry.name,)):
        self.what = what
        self.package = package
        self.init_file = init_file
        self.machinery = machinery
        self.names = names
        self.by_code = {}

    def register(self, entry):
        """Add `entry`; its code and names must be new (registering it again is a no-op)."""
        old = self.by_code.get(entry.code)
        if old is not None and old != entry:
            raise ValueError(f"{self.what} code {entry.code} of {self.names(entry)[0]!r} is "
                             f"taken by {self.names(old)[0]!r}")
        taken = {n: self.names(e)[0] for e in self.by_code.values()
                 if e.code != entry.code for n in self.names(e)}
        for n in self.names(entry):
            if n in taken:
                raise ValueError(f"{self.what} name {n!r} of {self.names(entry)[0]!r} is taken "
                                 f"by {taken[n]!r}")
        self.by_code[entry.code] = entry
        return entry

    def entries(self):
        """Every registered entry, in code order."""
        import_all(self.package, self.init_file, self.machinery)
        return [self.by_code[c] for c in sorted(self.by_code)]

    def of_code(self, code):
        self.entries()
        return self.by_code[code]

    def named(self, name):
        """The entry called `name` (KeyError if none is)."""
        return {n: e for e in self.entries() for n in self.names(e)}[name]
