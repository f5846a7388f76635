#!/usr/bin/python3
"""Whole-run timings (issue #3): each scenario in bench/whole_run/ run by the release `rumble`
pinned to one core (taskset, the first core this process may use), three times; the best wall time, the micro-step and the cost
per micro-step go to results/bench/whole_run.json and are printed. The machine's load average
is recorded with them, since a loaded machine makes every figure larger.

usage: bench/whole_run/time_runs.py [RUMBLE]   (default: build/release/bin/rumble)
"""
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
REPEATS = 3


def time_one(rumble, scenario):
    core = str(min(os.sched_getaffinity(0)))
    best = None
    for _ in range(REPEATS):
        subprocess.run(["taskset", "-c", core, rumble, "run", str(scenario), "--no-progress",
                        "--no-plots", "--log-level", "warn"], check=True)
        doc = json.loads((scenario.parent / "results" / scenario.stem / "summary.json")
                         .read_text())
        if best is None or doc["wall_time_s"]["total"] < best["wall_time_s"]["total"]:
            best = doc
    t = best["time"]
    micro_steps = t["macro_steps"] * round(t["macro_step"] / t["micro_step"])
    wall = best["wall_time_s"]  # measured inside rumble: the run, not loading and validation
    return {
        "scenario": str(scenario.relative_to(ROOT)),
        "simulated_s": t["reached"],
        "wall_s": wall["total"],
        "wall_per_participant_s": {k: v for k, v in wall.items() if k != "total"},
        "micro_step_s": t["micro_step"],
        "micro_steps": micro_steps,
        "vehicle_track_us_per_micro_step": 1e6 * wall["vehicle/track"] / micro_steps,
    }


def main(rumble):
    runs = [time_one(rumble, s) for s in sorted((ROOT / "bench/whole_run").glob("*.json"))]
    out = {"load_average_1_5_15": list(os.getloadavg()), "cores_used": 1, "runs": runs}
    target = ROOT / "results/bench/whole_run.json"
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(out, indent=2) + "\n")
    for r in runs:
        print(f"{r['scenario']}: {r['simulated_s']:g} s simulated in {r['wall_s']:.2f} s wall "
              f"(one core); micro-step {r['micro_step_s'] * 1e6:.1f} us, "
              f"{r['vehicle_track_us_per_micro_step']:.1f} us per vehicle/track micro-step")
    print(f"load average {out['load_average_1_5_15']}; written to {target}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "build/release/bin/rumble"))
