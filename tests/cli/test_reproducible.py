"""Identical runs write byte-identical result files; timings live only in run.json.

Truth: two runs of the same command into two directories give files with equal bytes
(figures included), and the run manifests list the same files with the same SHA-256 —
so every difference between the manifests is a timing, a time stamp or the path.
"""

import json

import pytest

from gearcontact.cli import main
from gearcontact.cli.outdir import MANIFEST


@pytest.mark.parametrize("argv", [
    ["tca", "--pair", "s0003-centred", "--phases", "5", "--quiet"],
    ["ltca", "--pair", "s0003-centred", "--phases", "5", "--cells", "24", "--export-problem"],
])
def test_identical_runs_identical_files(tmp_path, argv):
    outs = [tmp_path / "a", tmp_path / "b"]
    for out in outs:
        assert main(argv + ["--out", str(out)]) == 0
    manifests = [json.loads((d / MANIFEST).read_text()) for d in outs]
    files = [{f["path"]: f["sha256"] for f in m["files"]} for m in manifests]
    assert files[0] == files[1] and files[0]
    for name in files[0]:
        assert (outs[0] / name).read_bytes() == (outs[1] / name).read_bytes(), name
    # the timings are in the manifest, and nowhere in the result files
    assert manifests[0]["timings_s"]
    for name in files[0]:
        if name.endswith((".json", ".csv", ".md")):
            text = (outs[0] / name).read_text()
            assert "timings_s" not in text and "solve_ms" not in text, name
