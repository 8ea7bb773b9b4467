"""Public names of a package that load on first use: a package ``__getattr__`` (PEP 562).

A package that re-exported the names of all its modules imported all of them, and so
numpy, scipy.optimize and numba, whenever any one module was imported: ``import
gearcontact.geometry.pair`` cost the whole geometry (0.4 s of CPU in every process of
the command line that only reads a pair). With :func:`lazy_names` the package imports
nothing at import time and each public name imports its own module when first read
(docs/performance.md, "Test suite budget"). This module imports nothing of the package:
every module may use it.
"""

from __future__ import annotations

import importlib
import sys

__all__ = ["lazy_names"]


def lazy_names(package: str, homes: dict[str, tuple[str, ...]], *, fallback=None):
    """A package ``__getattr__`` serving public names from their modules on first use.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    homes : dict of str to tuple of str
        Module (relative to ``package``, e.g. ``"pair"``) -> the public names it defines.
        No name may be that of a submodule of the package: importing the submodule
        binds its name on the package to the module, which ``__getattr__`` never sees
        (``gearcontact.tca`` re-exports the function ``phase_table`` of the module
        ``tca.phase_table`` and therefore imports its names at once).
    fallback : callable, optional
        The ``__getattr__`` to ask for any other name (e.g.
        :func:`gearcontact.deprecation.moved_names`); without it, ``AttributeError``.

    Returns
    -------
    callable
        To assign to the package's ``__getattr__``. A name read once is stored in the
        package's namespace, so the next read is an ordinary attribute.
    """
    home_of = {name: module for module, names in homes.items() for name in names}

    def __getattr__(name: str):
        module = home_of.get(name)
        if module is None:
            if fallback is not None:
                return fallback(name)
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f".{module}", package), name)
        setattr(sys.modules[package], name, value)
        return value
    return __getattr__
