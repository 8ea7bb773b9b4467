"""F.2's machine-settings example (examples/machine_settings/) with keys of one table
retyped: the careless-user pairs of docs/machine_settings.md sec. 5, "Ordinary pairs,
measured" (a helper of the tests, no test here)."""

from __future__ import annotations

import re
from pathlib import Path

EXAMPLE = Path(__file__).parents[2] / "examples" / "machine_settings" / "iso23509_f2_machine.toml"


def retyped(tmp_path: Path, table: str, changes: dict) -> Path:
    """A copy of the example with ``changes`` ({key: TOML text}) typed in ``[table]``
    (a key the table does not type is added), written under ``tmp_path``."""
    head, rest = EXAMPLE.read_text().split(f"[{table}]\n", 1)
    body, tail = rest.split("\n[", 1)
    for key, text in changes.items():
        body, n = re.subn(rf"^{key} = .*$", f"{key} = {text}", body, flags=re.M)
        body += "" if n else f"\n{key} = {text}"
    path = tmp_path / "pair.toml"
    path.write_text(f"{head}[{table}]\n{body}\n[{tail}")
    return path
