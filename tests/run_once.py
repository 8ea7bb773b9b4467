"""Work done once per test run and shared by the pytest-xdist workers.

A session fixture is per *worker* under xdist (``-n 2`` in pyproject.toml): two workers
that both run tests using ``quick_report`` each ran ``gearcontact reproduce --quick``
(about 2 min CPU). :func:`run_once` makes such a fixture's files once per run: the
first worker to ask builds them, the other waits on a file lock and reads them (the
pytest-xdist documentation's recipe for "session fixtures once").
"""

import fcntl
import json
import os
import shutil


def run_once(tmp_path_factory, name: str, build):
    """``(directory, result)``: ``build(directory)`` called once per test run.

    Parameters
    ----------
    tmp_path_factory : pytest.TempPathFactory
        The session's factory; under xdist the parent of a worker's base directory is
        the run's, shared by the workers (a plain run uses its own base directory).
    name : str
        Name of the shared directory (and of its lock and result files).
    build : callable
        ``build(directory) -> JSON-able result``: writes its files into ``directory``
        (new and empty). It runs under an exclusive lock; a build that raises records
        nothing, so the next worker that asks builds again (and fails the same way).

    Returns
    -------
    tuple
        The directory and ``build``'s result as read back from JSON.
    """
    root = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = root.parent
    directory, done = root / name, root / f"{name}.json"
    with open(root / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)        # released when the file closes
        if not done.exists():
            if directory.exists():              # the files of a build that failed
                shutil.rmtree(directory)
            directory.mkdir()
            done.write_text(json.dumps(build(directory)))
    return directory, json.loads(done.read_text())
