"""benchmarks/landing_speed.py runs each solver configuration once: for the paper landings the
benchmark step is the scenario's own 5e-5 s, and the "scenario step" row used to repeat the
"h=5e-05" row. The landings are replaced by a stub (a real benchmark takes minutes)."""

import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))


def _fake_runs(monkeypatch):
    import landing_speed

    jobs = []

    def run_job(job):
        jobs.append(job)
        return {"wall_s": 1.0, "wall_s_per_simulated_s": 1.0, "load_1min": 0.0, "peak_rss_mb": 100.0,
                "steps": 10, "newton_iterations": 20, "jacobians": 5, "step_s": job.get("step"),
                "user_function_share": 0.5, "user_function_s": {}, "user_function_calls": {}}

    monkeypatch.setattr(landing_speed, "run_job", run_job)
    return landing_speed, jobs


def test_scenario_step_row_skipped_when_it_is_the_benchmark_step(monkeypatch, tmp_path, capsys):
    landing_speed, jobs = _fake_runs(monkeypatch)
    out = tmp_path / "bench.json"
    # case 2: backward landing, benchmark step 5e-5 s = its [solver] step
    landing_speed.main(["--cases", "2", "--repeat", "1", "--no-lsoda", "--json", str(out)])
    case = json.loads(out.read_text())["cases"][0]
    assert list(case["runs"]) == ["exudyn h=5e-05"]
    assert "exudyn scenario step" in case["skipped"]
    # one timed run and one instrumented run, both at the benchmark step: no second configuration
    assert [j.get("step") for j in jobs] == [5e-5, 5e-5]
    printed = capsys.readouterr().out
    assert "exudyn scenario step" in printed and "skipped" in printed


def test_scenario_step_row_kept_when_it_differs(monkeypatch, tmp_path):
    landing_speed, jobs = _fake_runs(monkeypatch)
    out = tmp_path / "bench.json"
    # case 0: forward landing, benchmark step 2e-4 s, scenario step 5e-5 s
    landing_speed.main(["--cases", "0", "--repeat", "1", "--no-lsoda", "--json", str(out)])
    case = json.loads(out.read_text())["cases"][0]
    assert list(case["runs"]) == ["exudyn h=0.0002", "exudyn scenario step"]
    assert "skipped" not in case
    assert [j.get("step") for j in jobs] == [2e-4, 2e-4, None, None]
    # --step at the scenario's own step: the duplicate is skipped here too
    jobs.clear()
    landing_speed.main(["--cases", "0", "--step", "5e-5", "--repeat", "1", "--no-lsoda", "--json", str(out)])
    assert list(json.loads(out.read_text())["cases"][0]["runs"]) == ["exudyn h=5e-05"]
