"""Old names kept for one release: a module ``__getattr__`` that warns.

A name that moved (or a result type merged into another, issue 24) stays importable from
its old module for one release through :func:`moved_names`, which emits a
:class:`DeprecationWarning` naming the new home. This module imports nothing of the
package: every module may use it.
"""

from __future__ import annotations

import importlib
import warnings

__all__ = ["warn_deprecated", "moved_names"]


def warn_deprecated(old: str, new: str, *, stacklevel: int = 3) -> None:
    """Emit the :class:`DeprecationWarning` of ``old`` (to go in the next release)."""
    warnings.warn(f"{old} is deprecated and goes in the next release; use {new}",
                  DeprecationWarning, stacklevel=stacklevel)


def moved_names(module: str, aliases: dict[str, str]):
    """A module ``__getattr__`` serving moved names with a :class:`DeprecationWarning`.

    Parameters
    ----------
    module : str
        The old module's ``__name__``.
    aliases : dict of str to str
        Old name -> new home ``"package.module:name"`` (imported on first use, so the
        old module does not import its new home at import time).

    Returns
    -------
    callable
        To assign to the module's ``__getattr__`` (PEP 562).
    """
    def __getattr__(name: str):
        if name not in aliases:
            raise AttributeError(f"module {module!r} has no attribute {name!r}")
        home, _, new_name = aliases[name].partition(":")
        warn_deprecated(f"{module}.{name}", f"{home}.{new_name}")
        return getattr(importlib.import_module(home), new_name)
    return __getattr__
