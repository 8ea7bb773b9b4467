"""The output-directory policy of every command that writes files (``--out``).

One policy, applied by :func:`gearcontact.cli.main` around each such command:

1. **Checked before any work.** ``--out`` must be a non-empty path that is a directory
   or does not exist yet (missing parents are created); writability is proven by
   creating the lock file. A refusal is bad input (exit 2) naming ``--out``, the value
   and the reason.
2. **One run owns the directory.** The directory must be empty or hold the files of a
   previous run of the same command (listed in its ``run.json``, which names the
   command). Anything else (files gearcontact did not write, a run of another command,
   a directory named like an output file) makes the command refuse before any work,
   unless ``--force`` is given: foreign entries (and another command's files) then stay
   untouched and same-named files are replaced. A file of the previous run whose
   content is no longer the SHA-256 its ``run.json`` lists (edited since, as a written
   settings TOML is meant to be) is not the run's to replace either: refused the same
   way. A refused directory is left as it was (no lock file remains).
3. **Atomic files, no stale files.** The command writes into a hidden staging directory
   inside ``--out``; when it finishes, every file is moved into place with
   :func:`os.replace` (atomic per file), the previous run's files that this run did not
   write are removed, and ``run.json`` is written last (temporary file + replace). A
   run that finished with a datapath flag (exit 3) or a failed check (exit 4) is
   committed the same way, its exit code in ``run.json``. When the command fails (bad
   input, a bug, an interrupt), the staging directory is removed and the previous run
   stays as it was (a directory this run created is removed again). Commands whose generated files embed their own absolute paths (``rtl soc``,
   ``rtl synth``: LiteX/Yosys scripts) write in place instead (``staged=False``): the
   previous run's files are removed before the work starts, and a failed run's
   ``run.json`` lists what it left (so that the next run removes it; a failed run that
   left nothing in a directory it created leaves no directory). A resumable
   command (``sweep``) names the entries it continues (``resume=("sweep.zarr",)``):
   they count as its own even without a ``run.json`` (a killed run) and are kept.
4. **A lock.** An exclusive :func:`fcntl.flock` on ``.gearcontact.lock`` is held for the
   whole run; a second run into the same directory is refused (exit 2) while the first
   one holds it, so two runs cannot interleave their files.

``run.json`` (the run manifest) lists the files of the run (path, bytes, SHA-256), the
command line, the package and library versions, the start time (UTC), the wall time,
the stage timings the command reported and its exit code. Timings live only here, so
that the result files of two identical runs are byte-identical.
"""

from __future__ import annotations

import fcntl
import hashlib
import json
import os
import shutil
import sys
import tempfile
import time
from datetime import datetime, timezone
from importlib import metadata
from pathlib import Path

from ..validation import InputRangeError
from . import EXIT_CHECK_FAILED, EXIT_FLAGGED, EXIT_OK, exit_code_of

__all__ = ["MANIFEST", "LOCK_NAME", "OutputDirectoryError", "RunDirectory",
           "add_out_argument", "final_path", "write_atomic"]

#: Name of the run manifest inside ``--out``.
MANIFEST = "run.json"
#: Name of the lock file inside ``--out`` (kept; it is empty).
LOCK_NAME = ".gearcontact.lock"
#: Prefix of the staging directories inside ``--out``.
STAGING_PREFIX = ".gearcontact-staging-"
#: Distributions whose versions run.json records (when installed).
_VERSIONED = ("gearcontact", "numpy", "scipy", "numba", "matplotlib", "amaranth")


class OutputDirectoryError(InputRangeError):
    """``--out`` cannot be used (bad input, exit 2): names the path and the reason."""

    def __init__(self, path, reason: str):
        super().__init__("--out", str(path), reason)
        self.args = (f"--out = {str(path)!r}: {reason}",)

    def __str__(self) -> str:
        return self.args[0]


def add_out_argument(p, *, help: str = "output directory", required: bool = True) -> None:
    """Add ``--out DIR`` and ``--force`` to a sub-parser and mark it as writing files
    (``required=False``: the command's ``check`` demands it where it writes)."""
    p.add_argument("--out", required=required, metavar="DIR",
                   help=f"{help} (created if missing; must be empty or hold a previous "
                        f"gearcontact run, whose files are replaced; see run.json)")
    p.add_argument("--force", action="store_true",
                   help="write into --out even if it holds files gearcontact did not write "
                        "(they are kept; same-named files are replaced)")
    p.set_defaults(writes_files=True)


def final_path(args, path) -> Path:
    """Where ``path`` (written by a command into ``args.out``) ends up after the run:
    the staging prefix replaced by the real ``--out`` (unchanged outside a run)."""
    run = getattr(args, "run", None)
    return Path(path) if run is None else run.final(path)


def write_atomic(path, data: bytes | str) -> Path:
    """Write ``data`` to ``path`` through a temporary file in the same directory and
    :func:`os.replace` (readers see the old or the new file, never a partial one)."""
    path = Path(path)
    raw = data.encode() if isinstance(data, str) else data
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(raw)
        os.chmod(tmp, 0o666 & ~_umask())    # mkstemp makes 0600; a result file is 0644
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _versions() -> dict:
    out = {"python": sys.version.split()[0]}
    for name in _VERSIONED:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            pass
    return out


def _ours(name: str) -> bool:
    return name in (MANIFEST, LOCK_NAME) or name.startswith(STAGING_PREFIX)


def _tree(root: Path) -> tuple[list[str], list[str]]:
    """Relative file paths and relative directory paths under ``root`` (ours skipped)."""
    files, dirs = [], []
    for here, dnames, fnames in os.walk(root):
        rel = Path(here).relative_to(root)
        if rel == Path("."):
            dnames[:] = [d for d in dnames if not _ours(d)]
            fnames = [f for f in fnames if not _ours(f)]
        dirs += [(rel / d).as_posix() for d in dnames]
        files += [(rel / f).as_posix() for f in fnames]
    return sorted(files), sorted(dirs)


def _previous_files(root: Path) -> dict[str, str | None] | None:
    """Files listed by the previous run's manifest, each with its SHA-256 as listed
    (None where the entry has none); None when there is no manifest (or it is not a
    gearcontact manifest)."""
    path = root / MANIFEST
    if not path.is_file():
        return None
    try:
        doc = json.loads(path.read_text(encoding="utf-8"))
        return {str(f["path"]): f.get("sha256") for f in doc["files"]}
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None


def _edited(root: Path, previous: dict) -> list[str]:
    """The files of ``previous`` (``{path: SHA-256}``, the manifest's) whose content is
    no longer what the run wrote: edited by the user since (a settings TOML is written
    to be edited), not the run's to replace."""
    return [f for f, sha in previous.items() if sha is not None and
            hashlib.sha256((root / f).read_bytes()).hexdigest() != sha]


def _inside(rel: str) -> bool:
    """A manifest path that stays inside the directory (relative, no ``..``)."""
    p = Path(rel)
    return not p.is_absolute() and ".." not in p.parts and rel not in ("", ".")


def _remove_empty_dirs(root: Path, rel_files) -> None:
    parents = sorted({p for f in rel_files for p in Path(f).parents if p != Path(".")},
                     key=lambda p: len(p.parts), reverse=True)
    for d in parents:
        try:
            (root / d).rmdir()
        except OSError:
            pass  # not empty (foreign or new files) or already gone


#: Exit codes of a run whose computation finished: its files replace the previous run's
#: (a flagged or failed-check result is kept for inspection; run.json says which).
_FINISHED = (EXIT_OK, EXIT_FLAGGED, EXIT_CHECK_FAILED)


class RunDirectory:
    """Context manager applying the policy above to one command run.

    Parameters
    ----------
    out : str
        The ``--out`` value as given.
    argv : list of str
        The command line (recorded in run.json).
    force : bool, keyword-only
        Accept foreign entries in ``out`` (kept; same-named files replaced).
    staged : bool, keyword-only
        Write through a staging directory (default); False writes in place.
    resume : tuple of str, keyword-only
        Top-level entries an in-place command continues from run to run: never foreign,
        never removed before the work.
    command : str, keyword-only
        The command's name (``"tca"``, ``"rtl verilog"``; default: from ``argv``): a
        directory holding a run of another command is refused without ``force``.

    Attributes
    ----------
    path : Path
        The output directory.
    work : Path
        Where the command writes: the staging directory, or ``path`` when not staged.
    timings_s : dict
        Stage timings (s) the command reports; written only into run.json.
    input_checks : dict
        Findings of the input checks run before the work (``{"blank_check": {...}}``),
        written into run.json as top-level entries; empty: nothing written (the
        manifest of a run without such a check keeps its fields).
    exit_code : int
        Recorded in run.json (set by the caller before leaving the context).
    """

    def __init__(self, out, argv, *, force: bool = False, staged: bool = True,
                 resume: tuple[str, ...] = (), command: str | None = None):
        self.given = out
        self.command = command if command is not None else _command_name(argv)
        self.resume = tuple(resume)
        self.argv = list(argv)
        self.force = force
        self.staged = staged
        self.timings_s: dict = {}
        self.input_checks: dict = {}
        self.exit_code = 0
        self.path = self._check_path(out)
        self.work = self.path
        self._lock_fd = None
        self._created = False
        self._discard = False
        self._started = time.perf_counter()
        self._started_wall = time.time()
        self._started_utc = datetime.now(timezone.utc).isoformat(timespec="seconds")
        self._previous: list[str] = []
        self._foreign: set[str] = set()

    # -- checks before any work ------------------------------------------------------
    @staticmethod
    def _check_path(out) -> Path:
        text = "" if out is None else str(out)
        if not text.strip():
            raise OutputDirectoryError(text, "an output directory path is required "
                                             "(empty path given)")
        path = Path(text)
        for p in [path, *path.parents]:
            if p.exists() and not p.is_dir():
                what = "is" if p == path else f"lies under {str(p)!r}, which is"
                raise OutputDirectoryError(text, f"{what} an existing file, not a directory")
            if p.exists():
                break
        return path

    def _lock(self) -> None:
        self._created = not self.path.exists()
        self._lock_created = self._created or not (self.path / LOCK_NAME).exists()
        try:
            self.path.mkdir(parents=True, exist_ok=True)
            fd = os.open(self.path / LOCK_NAME, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise OutputDirectoryError(self.given, f"cannot be created or written "
                                                   f"({exc.strerror or exc})") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            raise OutputDirectoryError(self.given, "another gearcontact run is writing "
                                                   f"into it (lock {LOCK_NAME} held); wait "
                                                   "for it or use another directory") from None
        self._lock_fd = fd

    def _check_contents(self) -> None:
        for entry in self.path.iterdir():   # staging left by a crashed run: ours, unlocked
            if entry.name.startswith(STAGING_PREFIX):
                shutil.rmtree(entry, ignore_errors=True)
        previous = _previous_files(self.path)
        other = _previous_command(self.path)
        if previous is not None and other not in (None, self.command):
            if not self.force:              # its files are not this command's to replace
                raise OutputDirectoryError(
                    self.given, f"holds a run of `gearcontact {other}` (run.json), not of "
                    f"`gearcontact {self.command}`; use another directory, or --force to "
                    "write beside its files (they are kept)")
            previous = None                 # --force: its files stay, as foreign ones
        if previous is None:                # not a gearcontact run: refuse at a glance
            top = sorted(e.name for e in self.path.iterdir()
                         if not _ours(e.name) and e.name not in self.resume)
            top += [MANIFEST] if (self.path / MANIFEST).exists() and other is None else []
            if top and not self.force:
                self._refuse(top)
            previous = {}
        # only listed files that are really inside the directory are ever removed
        previous = {f: sha for f, sha in previous.items()
                    if _inside(f) and (self.path / f).is_file()}
        self._previous = list(previous)
        edited = [] if self.force else _edited(self.path, previous)
        if edited:
            raise OutputDirectoryError(
                self.given, f"holds {edited[0]!r} changed since the run that wrote it (its "
                f"SHA-256 is not the one {MANIFEST} lists: edited?); copy it elsewhere, use "
                "another directory, or --force to replace it")
        if self.force and self.staged:
            return                          # nothing below matters: no walk of a big tree
        files, dirs = _tree(self.path)
        owned = set(self._previous)
        owned_dirs = {p.as_posix() for f in owned for p in Path(f).parents}
        foreign = [f for f in files if f not in owned] + [d for d in dirs
                                                           if d not in owned_dirs]
        foreign = [f for f in foreign if Path(f).parts[0] not in self.resume]
        if foreign and not self.force:
            self._refuse(foreign)
        self._foreign = set(foreign)

    def _refuse(self, foreign) -> None:
        raise OutputDirectoryError(
            self.given, f"holds entries not written by a gearcontact run (e.g. "
            f"{sorted(foreign)[0]!r}); use an empty or new directory, or --force to write "
            "beside them")

    def __enter__(self) -> "RunDirectory":
        self._lock()
        try:
            self._check_contents()
            if self.staged:
                self.work = Path(tempfile.mkdtemp(prefix=STAGING_PREFIX, dir=self.path))
            else:
                self._remove_previous(keep=[f for f in self._previous
                                            if Path(f).parts[0] in self.resume])
        except BaseException:
            self._release(remove=self._lock_created)
            raise
        return self

    # -- after the work ---------------------------------------------------------------
    def final(self, path) -> Path:
        """Final location of ``path`` written under :attr:`work`."""
        path = Path(path)
        try:
            return self.path / path.relative_to(self.work)
        except ValueError:
            return path

    def _remove_previous(self, *, keep) -> None:
        keep = set(keep)
        gone = [f for f in self._previous if f not in keep and f not in self._foreign]
        for f in gone:
            (self.path / f).unlink(missing_ok=True)
        _remove_empty_dirs(self.path, gone)

    def _commit(self) -> list[str]:
        if self.staged:
            files, _ = _tree(self.work)
            for f in files:
                target = self.path / f
                if target.is_dir():
                    raise OutputDirectoryError(self.given, f"{f!r} is a directory where "
                                                           "this run writes a file")
            for f in files:
                target = self.path / f
                target.parent.mkdir(parents=True, exist_ok=True)
                os.replace(self.work / f, target)
            self._remove_previous(keep=files)
        else:
            self._remove_empty_dirs_left()
            files = [f for f in _tree(self.path)[0] if f not in self._foreign
                     or (self.path / f).stat().st_mtime >= self._started_wall]
        return files

    def _remove_empty_dirs_left(self) -> None:
        """In place: directories this run left empty (e.g. made before it failed) are
        listed nowhere, so the next run would take them for foreign: remove them."""
        for here, _dnames, _fnames in os.walk(self.path, topdown=False):
            rel = Path(here).relative_to(self.path)
            if (rel == Path(".") or _ours(rel.parts[0]) or rel.parts[0] in self.resume
                    or rel.as_posix() in self._foreign):
                continue                    # ours, a resumed store (zarr), or foreign
            try:
                os.rmdir(here)
            except OSError:
                pass                        # not empty

    def _manifest(self, files) -> dict:
        entries = []
        for f in files:
            data = (self.path / f).read_bytes()
            entries.append({"path": f, "bytes": len(data),
                            "sha256": hashlib.sha256(data).hexdigest()})
        return {"manifest": "gearcontact run", "command": ["gearcontact", *self.argv],
                "command_name": self.command,
                "exit_code": self.exit_code, "versions": _versions(),
                "started_utc": self._started_utc,
                "wall_s": round(time.perf_counter() - self._started, 3),
                "timings_s": self.timings_s, **self.input_checks, "files": entries}

    def discard(self) -> None:
        """Keep nothing of this run (the command reported bad input or a failure
        itself): on leaving, the staging directory is removed as after an exception."""
        self._discard = True

    def _unlock(self) -> None:
        if self._lock_fd is not None:
            fcntl.flock(self._lock_fd, fcntl.LOCK_UN)
            os.close(self._lock_fd)
            self._lock_fd = None

    def _release(self, *, remove: bool) -> None:
        """Unlock; with ``remove`` also delete the lock file this run created (while
        still holding it: a run opening it meanwhile is refused, not let in twice) and
        the directory when this run created it and it is empty again."""
        if remove:
            (self.path / LOCK_NAME).unlink(missing_ok=True)
        self._unlock()
        if remove and self._created:
            try:
                self.path.rmdir()
            except OSError:
                pass                        # not empty

    def __exit__(self, exc_type, exc, tb) -> bool:
        if exc_type is not None:
            self.exit_code = exit_code_of(exc_type)     # as gearcontact.cli.main reports it
        failed = self._discard or self.exit_code not in _FINISHED
        left_nothing = False
        try:
            # in place, the previous run is gone already: a failed run still lists what
            # it left (exit code 1 when it raised), so that the next run removes it
            if not failed or not self.staged:
                files = self._commit()
                left_nothing = failed and not files and not self._previous
                if not left_nothing:        # a failed run that wrote nothing: no run.json
                    write_atomic(self.path / MANIFEST,
                                 json.dumps(self._manifest(files), indent=2) + "\n")
        finally:
            if self.staged and self.work != self.path:
                shutil.rmtree(self.work, ignore_errors=True)
            # a failed first run leaves nothing (staged, or in place with nothing written)
            self._release(remove=failed and self._lock_created
                          and (self.staged or left_nothing))
        return False


def _previous_command(root: Path) -> str | None:
    """The command name of the run recorded in ``root``'s run.json (None: no readable
    gearcontact manifest)."""
    try:
        doc = json.loads((root / MANIFEST).read_text(encoding="utf-8"))
        if "command_name" in doc:
            return str(doc["command_name"])
        return _command_name([str(w) for w in doc["command"][1:]]) or None
    except (OSError, ValueError, KeyError, TypeError, IndexError):
        return None


def _command_name(argv) -> str:
    """``"tca"`` of ``["tca", "--pair", ...]``, ``"rtl soc"`` of ``["rtl", "soc", ...]``
    (the rtl and export actions are commands of their own)."""
    n = 2 if list(argv[:1]) in (["rtl"], ["export"]) else 1
    return " ".join(w for w in argv[:n] if not w.startswith("-"))
