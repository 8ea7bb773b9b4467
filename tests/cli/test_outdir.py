"""The output-directory policy (:mod:`gearcontact.cli.outdir`) through the real entry point.

Truths: a refused ``--out`` exits 2 naming ``--out`` *before any work* (the command's
writer is never called and nothing is created); a re-run leaves exactly the files of
the new run, listed in run.json with their true sizes and SHA-256; a failed run leaves
the previous run byte for byte; a held lock refuses a second run. The cheap ``vectors``
command (a few ms of golden model) stands for every command with ``--out``.
"""

import fcntl
import hashlib
import json
import os

import pytest

import gearcontact.cli.vectors as cli_vectors
from gearcontact.cli import main
from gearcontact.cli.outdir import (LOCK_NAME, MANIFEST, OutputDirectoryError, RunDirectory,
                                    write_atomic)


def _vectors(out, *extra, cores="hertz"):
    return main(["vectors", "--out", str(out), "--count", "1", "--cores", cores, *extra])


@pytest.fixture
def no_work(monkeypatch):
    """Fail the test if the command's writer runs (the work must not start)."""
    calls = []
    monkeypatch.setattr(cli_vectors, "export_vectors",
                        lambda *a, **k: calls.append(a) or [])
    return calls


def _files(d):
    return sorted(p.relative_to(d).as_posix() for p in d.rglob("*") if p.is_file()
                  and p.name != LOCK_NAME)


@pytest.mark.parametrize("make, sub, needle", [
    (lambda t: (t / "f").write_text("x"), "f", "is an existing file"),
    (lambda t: (t / "f").write_text("x"), "f/sub", "lies under"),
])
def test_out_not_a_directory_is_refused_before_work(tmp_path, capsys, no_work, make, sub,
                                                   needle):
    make(tmp_path)
    assert _vectors(tmp_path / sub) == 2
    err = capsys.readouterr().err
    assert "--out" in err and needle in err and "Traceback" not in err
    assert no_work == [] and (tmp_path / "f").read_text() == "x"


def test_empty_out_is_refused(tmp_path, capsys, no_work, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert _vectors("") == 2
    assert "--out = ''" in capsys.readouterr().err
    assert no_work == [] and list(tmp_path.iterdir()) == []   # nothing in the cwd


def test_unwritable_out_is_refused(tmp_path, capsys, no_work, monkeypatch):
    # root may write anywhere, so the refusal of the OS is simulated on the lock file,
    # the first thing the policy creates
    real_open = os.open

    def deny(path, *a, **k):
        if str(path).endswith(LOCK_NAME):
            raise PermissionError(13, "Permission denied")
        return real_open(path, *a, **k)

    monkeypatch.setattr(os, "open", deny)
    assert _vectors(tmp_path / "ro") == 2
    err = capsys.readouterr().err
    assert "--out" in err and "Permission denied" in err and no_work == []


@pytest.mark.skipif(os.geteuid() == 0, reason="root ignores directory permissions")
def test_read_only_directory_is_refused(tmp_path, capsys, no_work):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        assert _vectors(ro) == 2
    finally:
        ro.chmod(0o755)
    assert "cannot be created or written" in capsys.readouterr().err and no_work == []


def test_directory_named_like_an_output_file_is_refused_before_work(tmp_path, capsys,
                                                                    no_work):
    (tmp_path / "README.md").mkdir()
    assert _vectors(tmp_path) == 2
    err = capsys.readouterr().err
    assert "not written by a gearcontact run" in err and "README.md" in err
    assert no_work == []


def test_directory_named_like_an_output_file_with_force(tmp_path, capsys):
    (tmp_path / "README.md").mkdir()
    assert _vectors(tmp_path, "--force") == 2      # named, not IsADirectoryError
    assert "'README.md' is a directory" in capsys.readouterr().err
    assert not (tmp_path / MANIFEST).exists()


def test_manifest_lists_exactly_the_files(tmp_path):
    assert _vectors(tmp_path, cores="hertz,fit") == 0
    doc = json.loads((tmp_path / MANIFEST).read_text())
    listed = {f["path"]: f for f in doc["files"]}
    assert sorted(listed) == [f for f in _files(tmp_path) if f != MANIFEST]
    for name, entry in listed.items():
        data = (tmp_path / name).read_bytes()
        assert entry["bytes"] == len(data)
        assert entry["sha256"] == hashlib.sha256(data).hexdigest()
    assert doc["command"][:2] == ["gearcontact", "vectors"] and doc["exit_code"] == 0
    assert {"python", "gearcontact", "numpy"} <= set(doc["versions"])
    assert doc["wall_s"] >= 0
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".gearcontact-staging")]
    assert oct((tmp_path / MANIFEST).stat().st_mode & 0o777) == oct(0o666 & ~_umask())


def _umask():
    m = os.umask(0o022)
    os.umask(m)
    return m


def test_rerun_removes_the_previous_runs_files(tmp_path, capsys):
    assert _vectors(tmp_path, cores="hertz,fit") == 0
    assert "fit.jsonl" in _files(tmp_path)
    assert _vectors(tmp_path, cores="hertz") == 0
    files = _files(tmp_path)
    assert "fit.jsonl" not in files and "hertz.jsonl" in files
    listed = [f["path"] for f in json.loads((tmp_path / MANIFEST).read_text())["files"]]
    assert sorted(listed + [MANIFEST]) == files
    assert str(tmp_path / "hertz.jsonl") in capsys.readouterr().out  # final, not staging


def test_foreign_files_refused_then_kept_with_force(tmp_path, capsys):
    (tmp_path / "notes.txt").write_text("mine")
    assert _vectors(tmp_path) == 2
    assert "--force" in capsys.readouterr().err
    assert _vectors(tmp_path, "--force") == 0
    assert (tmp_path / "notes.txt").read_text() == "mine"
    listed = [f["path"] for f in json.loads((tmp_path / MANIFEST).read_text())["files"]]
    assert "notes.txt" not in listed
    # a later run (with --force again, notes.txt is still foreign) never removes it
    assert _vectors(tmp_path, "--force", cores="fit") == 0
    assert (tmp_path / "notes.txt").read_text() == "mine"
    assert "hertz.jsonl" not in _files(tmp_path)


def test_failed_run_leaves_the_previous_run(tmp_path, capsys, monkeypatch):
    assert _vectors(tmp_path) == 0
    before = {f: (tmp_path / f).read_bytes() for f in _files(tmp_path)}

    def half_then_crash(out, **kw):
        (out / "hertz.jsonl").write_text("half")
        raise RuntimeError("boom")

    monkeypatch.setattr(cli_vectors, "export_vectors", half_then_crash)
    assert _vectors(tmp_path) == 1
    assert "internal error, please report" in capsys.readouterr().err
    assert {f: (tmp_path / f).read_bytes() for f in _files(tmp_path)} == before
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".gearcontact-staging")]


def test_second_run_into_a_locked_directory_is_refused(tmp_path, capsys, no_work):
    tmp_path.joinpath(LOCK_NAME).touch()
    fd = os.open(tmp_path / LOCK_NAME, os.O_RDWR)
    fcntl.flock(fd, fcntl.LOCK_EX)        # another run holds the directory
    try:
        assert _vectors(tmp_path) == 2
    finally:
        os.close(fd)
    assert "another gearcontact run" in capsys.readouterr().err and no_work == []
    assert _vectors(tmp_path) == 0         # released: the next run proceeds


def test_in_place_mode_records_and_replaces(tmp_path):
    # staged=False (rtl soc / synth): previous files removed before the work starts
    with RunDirectory(str(tmp_path), ["x"], staged=False) as run:
        (run.work / "a.txt").write_text("1")
        (run.work / "sub").mkdir()
        (run.work / "sub" / "b.txt").write_text("2")
    with RunDirectory(str(tmp_path), ["x"], staged=False) as run:
        assert not (tmp_path / "a.txt").exists()
        (run.work / "c.txt").write_text("3")
    assert _files(tmp_path) == ["c.txt", MANIFEST]
    # a failed in-place run lists what it left, and the next run removes it
    with pytest.raises(RuntimeError):
        with RunDirectory(str(tmp_path), ["x"], staged=False) as run:
            (run.work / "half.txt").write_text("h")
            raise RuntimeError("tool crashed")
    doc = json.loads((tmp_path / MANIFEST).read_text())
    assert doc["exit_code"] == 1 and [f["path"] for f in doc["files"]] == ["half.txt"]
    with RunDirectory(str(tmp_path), ["x"], staged=False) as run:
        (run.work / "d.txt").write_text("4")
    assert _files(tmp_path) == ["d.txt", MANIFEST]


def test_command_reporting_bad_input_keeps_nothing(tmp_path, capsys, monkeypatch):
    """A handler that returns exit 2 itself (e.g. a missing optional tool) commits
    nothing: the previous run stays, a new directory is removed."""
    assert _vectors(tmp_path / "v") == 0
    before = {f: (tmp_path / "v" / f).read_bytes() for f in _files(tmp_path / "v")}

    def refuse(out, **kw):
        (out / "partial.txt").write_text("p")
        return []

    monkeypatch.setattr(cli_vectors, "export_vectors", refuse)
    monkeypatch.setattr(cli_vectors, "run", lambda args: (refuse(args.out), 2)[1])
    assert main(["vectors", "--out", str(tmp_path / "v"), "--count", "1"]) == 2
    assert {f: (tmp_path / "v" / f).read_bytes() for f in _files(tmp_path / "v")} == before
    assert main(["vectors", "--out", str(tmp_path / "new"), "--count", "1"]) == 2
    assert not (tmp_path / "new").exists()


def test_write_atomic_replaces_whole_files(tmp_path):
    p = write_atomic(tmp_path / "x.json", "old")
    write_atomic(p, b"new")
    assert p.read_bytes() == b"new" and [q.name for q in tmp_path.iterdir()] == ["x.json"]


def test_two_processes_cannot_interleave(tmp_path, capsys):
    """A second process's run is refused while another process holds the directory."""
    import subprocess
    import sys

    holder = subprocess.Popen(
        [sys.executable, "-c",
         "import sys\nfrom gearcontact.cli.outdir import RunDirectory\n"
         f"with RunDirectory({str(tmp_path)!r}, ['vectors']) as run:\n"
         "    (run.work / 'a.txt').write_text('first')\n"
         "    print('held', flush=True)\n"
         "    sys.stdin.readline()\n"],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
        env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)})
    try:
        assert holder.stdout.readline().strip() == "held"
        assert _vectors(tmp_path) == 2
        assert "another gearcontact run" in capsys.readouterr().err
    finally:
        holder.communicate("\n", timeout=60)
    assert holder.returncode == 0
    assert (tmp_path / "a.txt").read_text() == "first"
    assert _vectors(tmp_path) == 0 and not (tmp_path / "a.txt").exists()


def test_a_forged_manifest_removes_nothing_outside(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("keep")
    out = tmp_path / "out"
    out.mkdir()
    (out / MANIFEST).write_text(json.dumps({"files": [{"path": "../victim.txt"},
                                                      {"path": str(victim)}]}))
    assert _vectors(out) == 0
    assert victim.read_text() == "keep"


def test_in_place_command_checks_its_tool_before_removing_anything(tmp_path, capsys,
                                                                   monkeypatch):
    """``rtl soc`` writes in place, so a missing LiteX must be found before the previous
    run's files are removed: exit 2 naming the pip command, previous run intact."""
    import sys

    with RunDirectory(str(tmp_path), ["rtl", "soc"], staged=False) as run:
        (run.work / "csr.csv").write_text("previous")
    monkeypatch.setitem(sys.modules, "litex", None)
    assert main(["rtl", "soc", "--out", str(tmp_path)]) == 2
    assert "pip install litex" in capsys.readouterr().err
    assert (tmp_path / "csr.csv").read_text() == "previous"


def test_soc_lanes_checked_before_the_directory_is_touched(tmp_path, capsys):
    """``rtl soc --lanes 4`` failed inside LiteX generation (exit 1) after creating
    ``amaranth/``, and the rerun was then refused as foreign: now exit 2 at once."""
    out = tmp_path / "soc"
    assert main(["rtl", "soc", "--out", str(out), "--lanes", "4"]) == 2
    err = capsys.readouterr().err
    assert "--lanes = 4" in err and "power of two in [8, 64]" in err
    assert not out.exists()


def test_failed_in_place_run_leaves_no_unlisted_directory(tmp_path):
    """An in-place run that made an empty directory and then failed on bad input: the
    directory is removed and, as the run left nothing, so are its run.json and lock
    (the directory is as before: empty); the next run is not refused."""
    from gearcontact.validation import InputRangeError

    with pytest.raises(InputRangeError):
        with RunDirectory(str(tmp_path), ["rtl", "soc"], staged=False) as run:
            (run.work / "amaranth" / "deep").mkdir(parents=True)
            raise InputRangeError("lanes", 4, "a power of two in [8, 64]")
    assert not (tmp_path / "amaranth").exists()
    assert list(tmp_path.iterdir()) == []
    with RunDirectory(str(tmp_path), ["rtl", "soc"], staged=False) as run:
        (run.work / "csr.csv").write_text("ok")
    assert json.loads((tmp_path / MANIFEST).read_text())["files"][0]["path"] == "csr.csv"


def test_refused_foreign_directory_keeps_no_lock(tmp_path, capsys, no_work):
    """Issue 28 probe: a refused foreign --out kept an empty .gearcontact.lock; the
    directory is now left exactly as it was."""
    (tmp_path / "notes.txt").write_text("mine")
    assert _vectors(tmp_path) == 2
    assert "--force" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.txt"]
    assert not no_work


def test_run_of_another_command_is_refused_without_force(tmp_path, capsys):
    """Issue 28 probe: `tca --out DIR` where DIR held an `analyze` run deleted the
    analyze files (the policy replaced "the previous run"). A run of another command is
    refused (run.json names the command); with --force its files stay beside ours."""
    with RunDirectory(str(tmp_path), ["analyze", "--pair", "s0003"]) as run:
        (run.work / "summary.md").write_text("analyze result")
    assert json.loads((tmp_path / MANIFEST).read_text())["command_name"] == "analyze"
    assert _vectors(tmp_path) == 2
    err = capsys.readouterr().err
    assert "holds a run of `gearcontact analyze`" in err and "--force" in err
    assert (tmp_path / "summary.md").read_text() == "analyze result"
    assert _vectors(tmp_path, "--force") == 0
    assert (tmp_path / "summary.md").read_text() == "analyze result"
    doc = json.loads((tmp_path / MANIFEST).read_text())
    assert doc["command_name"] == "vectors"
    assert "summary.md" not in [f["path"] for f in doc["files"]]
    assert _vectors(tmp_path, "--force", cores="fit") == 0     # a rerun keeps it too
    assert (tmp_path / "summary.md").read_text() == "analyze result"


def test_same_command_replaces_its_run_and_old_manifests_name_theirs(tmp_path):
    """A rerun of the same command needs no --force; a run.json written before it named
    the command (no command_name) is read from its command line ("rtl soc": two
    words)."""
    assert _vectors(tmp_path) == 0
    assert _vectors(tmp_path, cores="fit") == 0
    doc = json.loads((tmp_path / MANIFEST).read_text())
    del doc["command_name"]
    doc["command"] = ["gearcontact", "rtl", "soc", "--out", str(tmp_path)]
    (tmp_path / MANIFEST).write_text(json.dumps(doc))
    with pytest.raises(OutputDirectoryError, match="gearcontact rtl soc"):
        with RunDirectory(str(tmp_path), ["rtl", "verilog", "--core", "fit"]):
            pass
    with RunDirectory(str(tmp_path), ["rtl", "soc"], staged=False):
        pass                                                     # same command: accepted


def test_finished_run_with_a_failed_check_keeps_its_files(tmp_path, capsys, monkeypatch):
    """A computation that ends in CheckFailed (exit 4) or DatapathFlagged (exit 3)
    keeps what it wrote, run.json recording the code; bad input keeps nothing."""
    from gearcontact.errors import CheckFailed

    def written_then_failed(out, **kw):
        (out / "hertz.jsonl").write_text("result")
        raise CheckFailed("LCP not converged")

    monkeypatch.setattr(cli_vectors, "export_vectors", written_then_failed)
    assert _vectors(tmp_path / "o") == 4
    assert capsys.readouterr().err == ("gearcontact vectors: check failed: LCP not "
                                       "converged\n")
    doc = json.loads((tmp_path / "o" / MANIFEST).read_text())
    assert doc["exit_code"] == 4 and [f["path"] for f in doc["files"]] == ["hertz.jsonl"]
