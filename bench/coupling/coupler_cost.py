#!/usr/bin/python3
"""What the couplers cost (issue #10, "Speed"): the coupler's overhead in a run's wall time, and
what Jacobi's two threads give when a participant is expensive.

Each run's summary.json splits the run's wall time into the statics, the time inside each
participant's advance (measured by the engine around every call) and the recording (the step
callback: result files, checks, heartbeat); what is left is the coupler's own work with the
host's table between them, the coupler overhead. Runs:
  cheap:  bench/whole_run/clm_100_sleepers.json (100 sleepers, CLM soil, 1 s) with gauss_seidel,
          jacobi on 1 and 2 threads, gauss_seidel with an adaptive step, implicit (IQN-ILS);
  FEM:    scenarios/paper/study/track_on_fem_soil.json (medium soil, about 3.5e4 DOFs) for
          FEM_END s with gauss_seidel, jacobi on 1 and 2 threads and implicit (IQN-ILS; its
          iterations per macro step are reported for every run);
  both:   both participants expensive and alike: scenarios/examples/half_train_two_cars.json
          (two 10-DOF cars, 8 wheels, 120 sleepers) on the medium FEM soil meshed as a box at
          20 Hz (3.7e4 DOFs), BOTH_END s, gauss_seidel and jacobi on 1 and 2 threads.
Jacobi's speed-up is the wall time of its 1-thread run over its 2-thread run, whole and without
the statics (the stepping, where the threads work). While the two sides advance at once the host
gives the soil one thread fewer, and every core where the track is cheap beside it or the sides
do not overlap (engine/run/include/run/core_share.hpp). The machine's load average is recorded
with the figures. Jacobi on two threads against Gauss-Seidel, alternately and repeated, on a
balanced case: bench/coupling/jacobi_speedup.py.

usage: bench/coupling/coupler_cost.py [RUMBLE] [WORKDIR]
       (defaults: build/release/bin/rumble, or build/dev/bin/rumble if there is none (the dev
       preset is optimised too: -O2); /tmp/rumble_coupler_cost)
Writes results/bench/coupler_cost.json and prints a table.
"""
import copy
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FEM_END = 0.1  # s
ADAPTIVE = {"min_step": 1e-4, "max_step": 2e-3, "tolerance": 0.05}

CHEAP = ("bench/whole_run/clm_100_sleepers.json", [
    ("gauss_seidel", {"type": "gauss_seidel", "params": {}}),
    ("jacobi, 1 thread", {"type": "jacobi", "params": {"threads": 1}}),
    ("jacobi, 2 threads", {"type": "jacobi", "params": {"threads": 2}}),
    ("gauss_seidel adaptive", {"type": "gauss_seidel", "params": {"adaptive": ADAPTIVE}}),
    ("implicit iqn_ils", {"type": "implicit", "params": {"acceleration": "iqn_ils"}}),
])
FEM = ("scenarios/paper/study/track_on_fem_soil.json", [
    ("gauss_seidel", {"type": "gauss_seidel", "params": {}}),
    ("jacobi, 1 thread", {"type": "jacobi", "params": {"threads": 1}}),
    ("jacobi, 2 threads", {"type": "jacobi", "params": {"threads": 2}}),
    ("implicit iqn_ils", {"type": "implicit", "params": {"acceleration": "iqn_ils"}}),
])
BOTH_END = 0.5  # s
BOTH = ("scenarios/examples/half_train_two_cars.json", [
    ("gauss_seidel", {"type": "gauss_seidel", "params": {}}),
    ("jacobi, 1 thread", {"type": "jacobi", "params": {"threads": 1}}),
    ("jacobi, 2 threads", {"type": "jacobi", "params": {"threads": 2}}),
])


def fem_box_soil(scenario):
    """The medium FEM soil of the paper study, meshed as a box around the long track."""
    soil = json.loads((ROOT / FEM[0]).read_text())["soil"]
    soil["params"]["mesh"].update({"shape": "box", "f_max": 20.0})
    scenario["soil"] = soil


def run(rumble, base, name, coupling, workdir, end=None, patch=None):
    scenario = json.loads((ROOT / base).read_text())
    for v in scenario.get("vehicles", []):  # files named relative to the base scenario
        if "file" in v.get("params", {}):
            v["params"]["file"] = str((ROOT / base).parent / v["params"]["file"])
    if patch is not None:
        patch(scenario)
    scenario["coupling"] = copy.deepcopy(coupling)
    if end is not None:
        scenario["time"]["end"] = end
    scenario.setdefault("outputs", {})["directory"] = "results"
    scenario["outputs"].pop("fields", None)
    stem = Path(base).stem + ("_fem" if patch is not None else "")
    folder = workdir / (stem + "_" + name.replace(" ", "_").replace(",", ""))
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "scenario.json"
    path.write_text(json.dumps(scenario, indent=1))
    subprocess.run([rumble, "run", str(path), "--no-progress", "--no-plots", "--log-level",
                    "warn", "--overwrite"], check=True)
    summary = json.loads((folder / "results" / "summary.json").read_text())
    wall = summary["wall_time_s"]
    inside = [v for k, v in wall.items() if k not in ("total", "statics", "recording")]
    # Two threads: the participants advance at the same time, the longer one is the wall time.
    inside = max(inside) if coupling.get("params", {}).get("threads") == 2 else sum(inside)
    coupler = wall["total"] - wall["statics"] - wall["recording"] - inside
    return {
        "scenario": base,
        "coupling": name,
        "simulated_s": summary["time"]["reached"],
        "macro_steps": summary["time"]["macro_steps"],
        "iterations_per_step": summary["coupling"]["iterations"]["mean_per_step"],
        "wall_s": wall["total"],
        "statics_s": wall["statics"],
        "recording_s": wall["recording"],
        "participants_s": {k: v for k, v in wall.items()
                           if k not in ("total", "statics", "recording")},
        "coupler_s": coupler,
        "coupler_fraction": coupler / wall["total"],
        "recording_fraction": wall["recording"] / wall["total"],
    }


def main(rumble, workdir):
    workdir.mkdir(parents=True, exist_ok=True)
    runs = [run(rumble, CHEAP[0], n, c, workdir) for n, c in CHEAP[1]]
    runs += [run(rumble, FEM[0], n, c, workdir, FEM_END) for n, c in FEM[1]]
    both = [run(rumble, BOTH[0], n, c, workdir, BOTH_END, fem_box_soil) for n, c in BOTH[1]]
    for r in both:
        r["scenario"] += " (fem box)"
    runs += both
    by = {(r["scenario"], r["coupling"]): r for r in runs}
    speedups = {}
    for base in (CHEAP[0], FEM[0], BOTH[0] + " (fem box)"):
        one, two = by[(base, "jacobi, 1 thread")], by[(base, "jacobi, 2 threads")]
        speedups[base] = {"whole": one["wall_s"] / two["wall_s"],
                          "stepping": (one["wall_s"] - one["statics_s"]) /
                                      (two["wall_s"] - two["statics_s"])}
    out = {"load_average_1_5_15": list(os.getloadavg()), "cpus": os.cpu_count(),
           "rumble": rumble, "runs": runs, "jacobi_two_thread_speedup": speedups}
    target = ROOT / "results/bench/coupler_cost.json"
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(out, indent=2) + "\n")
    print(f"{'scenario':56} {'coupling':24} {'steps':>6} {'iter':>5} {'wall s':>8} "
          f"{'coupler':>8} {'recording':>9}")
    for r in runs:
        print(f"{r['scenario']:56} {r['coupling']:24} {r['macro_steps']:6d} "
              f"{r['iterations_per_step']:5.2f} {r['wall_s']:8.2f} "
              f"{100 * r['coupler_fraction']:7.2f}% {100 * r['recording_fraction']:8.2f}%")
    for base, s in speedups.items():
        print(f"jacobi 1 thread / 2 threads on {base}: {s['whole']:.2f}x whole, "
              f"{s['stepping']:.2f}x without the statics")
    print(f"load average {out['load_average_1_5_15']}; written to {target}")


if __name__ == "__main__":
    default = ROOT / "build/release/bin/rumble"
    if not default.exists():
        default = ROOT / "build/dev/bin/rumble"
    main(sys.argv[1] if len(sys.argv) > 1 else str(default),
         Path(sys.argv[2]) if len(sys.argv) > 2 else Path("/tmp/rumble_coupler_cost"))
