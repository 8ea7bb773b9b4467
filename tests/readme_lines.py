"""The README's shell commands, shared by the tests that run them as written."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def readme_commands(prefix: str = "gearcontact ") -> list[str]:
    """Lines of the README's sh blocks that start with ``prefix`` (default: every
    ``gearcontact ...`` line), comments stripped."""
    text = (ROOT / "README.md").read_text()
    lines = []
    for block in re.findall(r"```sh\n(.*?)```", text, re.S):
        for line in block.splitlines():
            line = line.split(" #", 1)[0].strip()
            if line.startswith(prefix):
                lines.append(line)
    return lines


def readme_argv(prefix: str, out) -> list[str]:
    """The argv (without ``gearcontact``) of the README's one line starting with
    ``prefix``, its ``--out`` redirected to ``out``."""
    import shlex

    lines = [c for c in readme_commands() if c.startswith(prefix)]
    assert len(lines) == 1, f"README has {len(lines)} lines starting with {prefix!r}"
    argv = shlex.split(lines[0])[1:]
    argv[argv.index("--out") + 1] = str(out)
    return argv
