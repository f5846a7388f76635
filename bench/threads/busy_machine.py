#!/usr/bin/python3
"""What a busy machine costs a FEM run (issue #32, "Threads on a busy machine").

One run of the stiff FEM example (scenarios/examples/stiff_soil_fem.json, 0.1 s) on all the
usable cores and pinned to one core (taskset), on a quiet machine and next to BUSY processes
that spin (as a compile or another run would), under each OpenMP waiting setting:
  rumble:   nothing set: what rumble chooses itself (docs/toolchain.md section 8);
  spinning: GOMP_SPINCOUNT=300000, libgomp's own default when OMP_WAIT_POLICY is unset (threads
            spin on a barrier before they sleep): rumble before it chose.
The figure is the stepping time (summary.json's wall time less the statics) on all cores over
the same on one core, measured in one go: a loaded machine should cost a run at most its fair
share, so with a competing process that ratio must stay at most 1.3 (issue #32).

usage: bench/threads/busy_machine.py [RUMBLE] [WORKDIR] [--busy N] [--repeat N]
       (defaults: the newer of build/release/bin/rumble and build/dev/bin/rumble (both are
       optimised; a stale one would measure old code); /tmp/rumble_busy_machine; 1 busy process;
       the best of 2 runs each)
Writes results/bench/busy_machine.json and prints a table.
"""
import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "scenarios/examples/stiff_soil_fem.json"
END = 0.1  # s of simulated time
WAITS = {
    "rumble": {},
    "spinning": {"GOMP_SPINCOUNT": "300000"},
}
LIMIT = 1.3  # all cores over one core, next to a busy process (issue #32)


def arguments():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    built = [b for b in (ROOT / "build/release/bin/rumble", ROOT / "build/dev/bin/rumble")
             if b.exists()]
    default = max(built, key=lambda b: b.stat().st_mtime) if built else "rumble"
    p.add_argument("rumble", nargs="?", default=str(default))
    p.add_argument("workdir", nargs="?", default="/tmp/rumble_busy_machine")
    p.add_argument("--busy", type=int, default=1, help="spinning processes beside the run")
    p.add_argument("--repeat", type=int, default=2, help="runs per case; the fastest counts")
    return p.parse_args()


def scenario_file(workdir):
    scenario = json.loads(SCENARIO.read_text())
    scenario["time"]["end"] = END
    scenario.setdefault("outputs", {})["directory"] = "results"
    scenario["outputs"].pop("fields", None)
    path = workdir / "stiff_soil_fem_busy.json"
    path.write_text(json.dumps(scenario, indent=2))
    return path


def stepping_seconds(rumble, scenario, env, one_core, folder):
    """The run's wall time less its statics [s], from summary.json."""
    command = [rumble, "run", str(scenario), "--output", str(folder), "--overwrite"]
    if one_core:
        command = ["taskset", "-c", str(sorted(os.sched_getaffinity(0))[0])] + command
    full_env = {k: v for k, v in os.environ.items()
                if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    full_env.update(env)
    done = subprocess.run(command, env=full_env, capture_output=True, text=True)
    (folder.parent / (folder.name + ".log")).write_text(done.stderr + done.stdout)
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} failed ({done.returncode}):\n{done.stderr[-2000:]}")
    wall = json.loads((folder / "summary.json").read_text())["wall_time_s"]
    return wall["total"] - wall.get("statics", 0.0)


def spinners(count):
    spin = "while True:\n    pass\n"
    return [subprocess.Popen([sys.executable, "-c", spin]) for _ in range(count)]


def measure(args, scenario, workdir, busy):
    out = {}
    for wait, env in WAITS.items():
        row = {}
        for cores, one_core in (("one core", True), ("all cores", False)):
            folder = workdir / f"{wait}_{cores.replace(' ', '_')}_{busy}"
            row[cores] = min(stepping_seconds(args.rumble, scenario, env, one_core, folder)
                             for _ in range(args.repeat))
        row["ratio"] = row["all cores"] / row["one core"]
        out[wait] = row
    return out


def main():
    args = arguments()
    workdir = Path(args.workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    scenario = scenario_file(workdir)
    print(f"measuring {args.rumble}")
    results = {"rumble": str(args.rumble), "cores": len(os.sched_getaffinity(0)), "end_s": END,
               "load_average_before": os.getloadavg()[0]}
    results["quiet"] = measure(args, scenario, workdir, 0)
    procs = spinners(args.busy)
    try:
        time.sleep(1.0)  # let them take their cores
        results[f"busy ({args.busy} spinning)"] = measure(args, scenario, workdir, args.busy)
    finally:
        for p in procs:
            p.kill()
    out = ROOT / "results/bench/busy_machine.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(results, indent=2) + "\n")
    print(f"{'machine':<22}{'waiting':<10}{'one core [s]':>14}{'all cores [s]':>15}{'ratio':>8}")
    for machine, rows in results.items():
        if not isinstance(rows, dict):
            continue
        for wait, r in rows.items():
            print(f"{machine:<22}{wait:<10}{r['one core']:>14.2f}{r['all cores']:>15.2f}"
                  f"{r['ratio']:>8.2f}")
    busy = results[f"busy ({args.busy} spinning)"]["rumble"]["ratio"]
    print(f"written to {out}; busy machine, rumble's choice: all cores / one core = {busy:.2f} "
          f"(at most {LIMIT})")
    return 0 if busy <= LIMIT else 1


if __name__ == "__main__":
    sys.exit(main())
