"""The installed console script ``gearcontact`` run as a user runs it: a real process,
its return code, stdout and stderr (this checkout's package first on its path)."""

import os
import shutil
import subprocess
import sys

import pytest

#: This checkout's package first, for the child processes.
ENV = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}


def run_console(*argv, timeout: float = 300.0, cwd=None):
    """Run ``gearcontact *argv`` (in the directory ``cwd``, default this process's);
    (return code, stdout, stderr). Skips the test when the console script is not on
    PATH (``pip install -e .``)."""
    exe = shutil.which("gearcontact")
    if exe is None:
        pytest.skip("the gearcontact console script is not on PATH (pip install -e .)")
    p = subprocess.run([exe, *map(str, argv)], capture_output=True, text=True, env=ENV,
                       timeout=timeout, cwd=cwd)
    return p.returncode, p.stdout, p.stderr
