"""Registers the hardware preview backends with :mod:`gearcontact.preview.engine`.

``preview.engine`` defines the backend protocol and the ``reference`` and ``golden``
backends and knows nothing of the hardware; importing this module adds

* ``rtl`` -- :class:`.rtl_engine.RtlEngine`, the RTL cores in simulation (both Hertz
  forms);
* ``rtl-soc`` -- :class:`.soc_engine.SocEngine`, the SoCs in simulation behind the host
  driver, returning the register values it reads back (both Hertz forms: the
  simulated SoC is built with the requested tables).

Both through lazy factories: nothing here imports Amaranth or builds a model until a
backend is created. ``preview.engine.get_engine`` imports this module through the
``gearcontact.preview_backends`` entry point (pyproject.toml) the first time it is asked
for a backend it does not know.
"""

from __future__ import annotations

from ..preview.engine import PreviewEngine, register_backend
from ..preview.hertz.formats import HERTZ_FORMS

__all__ = ["HARDWARE_BACKENDS"]

#: Names registered by this module.
HARDWARE_BACKENDS = ("rtl", "rtl-soc")


def _rtl(**kwargs) -> PreviewEngine:
    from .rtl_engine import RtlEngine
    return RtlEngine(**kwargs)


def _rtl_soc(**kwargs) -> PreviewEngine:
    from .soc_engine import SocEngine
    return SocEngine(**kwargs)


register_backend("rtl", _rtl, hertz_forms=HERTZ_FORMS)
register_backend("rtl-soc", _rtl_soc, hertz_forms=HERTZ_FORMS)
