"""Files of ``gearcontact design``: the synthesized ease-off.

:func:`write_easeoff_toml` writes ``easeoff.toml``
(:func:`~gearcontact.tca.synthesis.easeoff_toml`).
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["write_easeoff_toml"]


def write_easeoff_toml(text: str, out) -> Path:
    """Write the ease-off tables ``text`` as ``easeoff.toml`` into the directory ``out``
    (created if missing); returns its path."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "easeoff.toml"
    path.write_text(text)
    return path
