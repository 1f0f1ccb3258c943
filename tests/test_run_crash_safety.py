"""`rotorlanding run` crash safety (issue 16): a killed run never leaves an earlier `complete:
true`, --out is checked before the solve, a full disk is one line with exit 3."""

import json
from pathlib import Path

import pytest

from rotorlanding.cli import main

ROOT = Path(__file__).resolve().parents[1]
SCEN = ROOT / "scenarios" / "landing_7000rpm.toml"


def _cli(args, **kw):
    import os
    import subprocess
    import sys

    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    env.pop("ROTORLANDING_FAULT", None)
    env.update(kw.pop("env", {}))
    return subprocess.Popen([sys.executable, "-m", "rotorlanding", "run", str(SCEN)] + args, env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, **kw)


def _claims(out):
    """Everything in the folder that says `complete` (summary.json, results.h5's attribute)."""
    import h5py

    out_ = {}
    if (out / "summary.json").exists():
        out_["summary.json"] = json.loads((out / "summary.json").read_text()).get("complete")
    try:
        with h5py.File(out / "results.h5", "r") as h5:
            out_["results.h5"] = bool(h5.attrs["complete"])
    except OSError:
        # absent, or removed between a check and the open while the new run starts (a poll of a
        # running run raced the run's own removal of the earlier results once in CI, session 13;
        # h5py reports the removal mid-open as a plain OSError "can't retrieve stat info", session
        # 16). A file that is still there and does not open is a real failure.
        if (out / "results.h5").exists():
            raise
    return out_


def test_killed_run_never_leaves_an_earlier_complete(tmp_path):
    """A finished run's folder, then a run killed mid-solve (from outside) and one killed right
    after it started (a fault point): no `complete: true` remains, the summary says running."""
    import signal
    import time

    out = tmp_path / "run"
    assert main(["run", str(SCEN), "--out", str(out), "--t-end", "0.01", "--quiet", "--no-plots"]) == 0
    assert _claims(out) == {"summary.json": True, "results.h5": True}
    proc = _cli(["--out", str(out), "--t-end", "2.0", "--quiet", "--no-plots"])
    deadline = time.time() + 60
    while _claims(out).get("summary.json") is not False and time.time() < deadline:
        time.sleep(0.02)
    time.sleep(0.3)  # into the solve (2 s of landing take far longer)
    assert proc.poll() is None, "the run ended before it was killed"
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert _claims(out) == {"summary.json": False}
    assert json.loads((out / "summary.json").read_text())["status"] == "running"
    assert sorted(p.name for p in out.iterdir()) == ["summary.json"]  # no temporary file left either
    # again after a finished run, killed by the write path's own hook just after the start marker
    assert main(["run", str(SCEN), "--out", str(out), "--t-end", "0.01", "--quiet", "--no-plots"]) == 0
    proc = _cli(["--out", str(out), "--t-end", "0.01", "--quiet", "--no-plots"],
                env={"ROTORLANDING_FAULT": "run-started"})
    assert proc.wait() == -signal.SIGKILL
    assert _claims(out) == {"summary.json": False}


def test_killed_while_renaming_results_leaves_no_complete(tmp_path):
    import signal

    out = tmp_path / "run"
    assert main(["run", str(SCEN), "--out", str(out), "--t-end", "0.01", "--quiet", "--no-plots"]) == 0
    proc = _cli(["--out", str(out), "--t-end", "0.01", "--quiet", "--no-plots"],
                env={"ROTORLANDING_FAULT": "results-written"})  # results written, not yet renamed
    assert proc.wait() == -signal.SIGKILL
    assert _claims(out) == {"summary.json": False}


@pytest.mark.parametrize("target", ["file", "devnull", "under-a-file"])
def test_bad_out_is_refused_before_the_solve(tmp_path, capsys, target):
    import time

    path = {"file": tmp_path / "results.txt", "devnull": Path("/dev/null"),
            "under-a-file": tmp_path / "results.txt" / "run"}[target]
    (tmp_path / "results.txt").write_text("keep me\n")
    t0 = time.perf_counter()
    assert main(["run", str(SCEN), "--out", str(path), "--quiet", "--no-plots"]) == 2  # the full 0.5 s landing
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--out" in err and "Traceback" not in err
    assert time.perf_counter() - t0 < 2.0  # refused before solving (the landing takes longer)
    assert (tmp_path / "results.txt").read_text() == "keep me\n"


def test_disk_full_is_one_line_exit_3_and_leaves_no_complete(tmp_path):
    """RLIMIT_FSIZE (portable stand-in for a full disk): results.h5 cannot be written."""
    import resource
    import signal

    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # writes past the limit fail with EFBIG instead
        resource.setrlimit(resource.RLIMIT_FSIZE, (100_000, 100_000))

    out = tmp_path / "run"
    assert main(["run", str(SCEN), "--out", str(out), "--t-end", "0.01", "--quiet", "--no-plots"]) == 0
    proc = _cli(["--out", str(out), "--t-end", "0.05", "--quiet", "--no-plots"], preexec_fn=limit)
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 3, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "results.h5" in lines[0] and "File too large" in lines[0], err
    assert _claims(out) == {"summary.json": False}
    assert sorted(p.name for p in out.iterdir()) == ["summary.json"]


def test_write_failing_inside_hdf5_is_still_one_line_and_no_crash(tmp_path):
    """Without the space reservation the write of results.h5 fails inside the HDF5 library
    (before: 'Exception ignored' pages and a segfault, exit 139): exit 3, one line."""
    import subprocess
    import sys

    code = ("import resource, signal, sys\n"
            "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
            "resource.setrlimit(resource.RLIMIT_FSIZE, (100000, 100000))\n"
            "import rotorlanding.safeio as S, rotorlanding.results as R\n"
            "S.reserve = lambda *a, **k: None\n"
            "from rotorlanding.cli import main\n"
            "sys.exit(main(sys.argv[1:]))\n")
    import os

    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    out = tmp_path / "run"
    proc = subprocess.run([sys.executable, "-c", code, "run", str(SCEN), "--out", str(out), "--t-end", "0.05",
                           "--quiet", "--no-plots"], env=env, capture_output=True, text=True)
    assert proc.returncode == 3, proc.stderr[-2000:]
    assert proc.stderr.strip().splitlines() == [f"rotorlanding: error: cannot write {out / 'results.h5'}: File too large"]
    assert _claims(out) == {"summary.json": False}
