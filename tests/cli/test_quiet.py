"""``--quiet`` on every computing command (issue 26 audit: ``ltca`` and ``bending``
refused it while the others took it).

Truth: argparse's own option table for the accepting commands; for ``ltca`` and
``bending``, which show no progress bar, the run without ``--quiet`` (identical result
files and result line, the house rule that identical runs write identical files)."""

import argparse

import pytest

from gearcontact.cli import build_parser, main
from gearcontact.cli.warm_up import COMPILING_COMMANDS

SPUR = "examples/spur_20x40_m3.toml"


def test_every_computing_command_takes_quiet():
    """Every command that compiles kernels (the long-running ones) has ``--quiet``."""
    sub = next(a for a in build_parser([])._actions
               if isinstance(a, argparse._SubParsersAction))
    for name in sorted(COMPILING_COMMANDS):
        options = {o for a in sub.choices[name]._actions for o in a.option_strings}
        assert "--quiet" in options, name


@pytest.mark.parametrize("argv, result", [
    (["ltca", "--pair", SPUR, "--rigid", "--cells", "16", "--phases", "3"], "ltca.json"),
    (["bending", "--pair", SPUR, "--points", "2", "2"], "compliance.json"),
])
def test_quiet_changes_nothing_but_bars(tmp_path, capsys, argv, result):
    """With and without ``--quiet``: exit 0, the same stdout line (but the output path)
    and byte-identical result files."""
    lines, files = [], []
    for k, quiet in enumerate(([], ["--quiet"])):
        out = tmp_path / f"run{k}"
        assert main(argv + quiet + ["--no-figures", "--out", str(out)]) == 0
        lines.append(capsys.readouterr().out.replace(str(out), "OUT"))
        files.append((out / result).read_bytes())
    assert lines[0] == lines[1] and lines[0].strip()
    assert files[0] == files[1]
