"""Files of ``gearcontact design``: the synthesized ease-off, the machine settings.

:func:`write_easeoff_toml` writes ``easeoff.toml``
(:func:`~gearcontact.tca.synthesis.easeoff_toml`); :func:`write_machine_settings_toml`
writes ``machine_settings.toml`` (:func:`~gearcontact.geometry.pair.pair_to_toml` of
the pair with its standard machine settings, docs/machine_settings.md).
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["write_easeoff_toml", "write_machine_settings_toml"]


def write_easeoff_toml(text: str, out) -> Path:
    """Write the ease-off tables ``text`` as ``easeoff.toml`` into the directory ``out``
    (created if missing); returns its path."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "easeoff.toml"
    path.write_text(text)
    return path


def write_machine_settings_toml(text: str, out) -> Path:
    """Write the pair TOML ``text`` (with its machine and blade tables) as
    ``machine_settings.toml`` into the directory ``out`` (created if missing); returns
    its path."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "machine_settings.toml"
    path.write_text(text)
    return path
