#!/usr/bin/python3
"""Jacobi's two threads against Gauss-Seidel at the same H (issue #32): one invocation runs
gauss_seidel, jacobi on 1 thread and jacobi on 2 threads alternately (one of each in turn, REPEATS
rounds, medians reported), so that a change in the machine's load falls on all three alike.

Cases:
  balanced: bench/coupling/balanced_train_on_fem.json: the track's and the soil's advance alike
            (within about 20 % on one thread each): one 10-DOF car (4 wheels) on a long track over the
            medium FEM soil meshed as a box. Where Jacobi's second thread can pay most.
  heavy:    bench/coupling/heavy_train_on_fem.json: the issue's "FEM soil with a heavy vehicle":
            two such cars (8 wheels) over the same track and soil meshed finer (f_max 29 Hz), the
            two sides alike again at about 5 ms per macro step each, twice the balanced case's.
  soil:     scenarios/paper/study/track_on_fem_soil.json (one wheel, 40 sleepers, the medium FEM
            soil, 3.5e4 DOFs) for SOIL_END s: the soil is nearly the whole step.

Per run, from summary.json's wall_time_s and the log: the wall time, the statics, the stepping
(wall minus statics), each side's time inside its advance, the recording, the rest (the coupler,
the handoff between threads, the soil's checkpoint on the worker), the soil's threads (the
engine's grant, the FEM soil's team sizes), the load average before and after (our own runs add
to it: up to 2 for a run on two threads), and the CPU the machine's other processes used during
the run, in cores (/proc/stat's busy time less the run's own CPU time, over the run's wall
time): the figure that says whether the run had the cores to itself. Per case: the medians, gauss_seidel / jacobi-2 and
jacobi-1 / jacobi-2 (whole and stepping), each side's share of gauss_seidel's stepping and the
ceiling of overlapping them, 1 / (1 - p) with p the smaller side's share (Amdahl: the larger side
and the serial rest remain).

Every run has OMP_WAIT_POLICY=PASSIVE (the engine's own choice, docs/toolchain.md section 8).
--busy K starts K processes that spin for the runs' duration: a loaded machine made on purpose.

usage: bench/coupling/jacobi_speedup.py [--repeats N] [--cases balanced,heavy,soil] [--busy K]
           [--rumble PATH] [--workdir DIR] [--output FILE]
       (defaults: 3 rounds, the balanced and soil cases, no load of our own, build/release/bin/rumble or else
       build/dev/bin/rumble (-O2), /tmp/rumble_jacobi_speedup, results/bench/jacobi_speedup.json)
"""
import argparse
import copy
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SOIL_END = 0.2  # s
CASES = {
    "balanced": ("bench/coupling/balanced_train_on_fem.json", None),
    "heavy": ("bench/coupling/heavy_train_on_fem.json", None),
    "soil": ("scenarios/paper/study/track_on_fem_soil.json", SOIL_END),
}
COUPLINGS = [
    ("gauss_seidel", {"type": "gauss_seidel", "params": {}}),
    ("jacobi-1", {"type": "jacobi", "params": {"threads": 1}}),
    ("jacobi-2", {"type": "jacobi", "params": {"threads": 2}}),
]
NOT_SIDES = ("total", "statics", "recording")


def scenario_for(base, end, coupling, folder):
    scenario = json.loads((ROOT / base).read_text())
    for v in scenario.get("vehicles", []):  # files named relative to the base scenario
        if "file" in v.get("params", {}):
            v["params"]["file"] = str(((ROOT / base).parent / v["params"]["file"]).resolve())
    scenario["coupling"] = copy.deepcopy(coupling)
    if end is not None:
        scenario["time"]["end"] = end
    scenario.setdefault("outputs", {})["directory"] = "results"
    scenario["outputs"].pop("fields", None)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "scenario.json"
    path.write_text(json.dumps(scenario, indent=1))
    return path


def soil_threads(log):
    """What the log says of the soil's threads: the engine's change of grant, the FEM soil's
    team sizes over the stepping."""
    said = [m.group(0) for m in re.finditer(r"the soil steps on \d+ thread\(s\)[^\n]*", log)]
    said += [m.group(1) for m in re.finditer(r"explicit steps on ([^\n]*) of the stepping", log)]
    return "; ".join(said)


def busy_seconds():
    """CPU time of the whole machine so far [s]: /proc/stat's first line less idle and iowait."""
    fields = [int(x) for x in Path("/proc/stat").read_text().split("\n")[0].split()[1:]]
    return (sum(fields[:8]) - fields[3] - fields[4]) / os.sysconf("SC_CLK_TCK")


def children_seconds():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(rumble, case, name, coupling, workdir):
    base, end = CASES[case]
    folder = workdir / f"{case}_{name}"
    path = scenario_for(base, end, coupling, folder)
    env = dict(os.environ, OMP_WAIT_POLICY="PASSIVE")
    env.pop("GOMP_SPINCOUNT", None)
    load_before = os.getloadavg()[0]
    busy, ours, start = busy_seconds(), children_seconds(), time.monotonic()
    done = subprocess.run([rumble, "run", str(path), "--no-progress", "--no-plots", "--log-level",
                           "info", "--overwrite"], env=env, capture_output=True, text=True)
    others = ((busy_seconds() - busy) - (children_seconds() - ours)) / (time.monotonic() - start)
    if done.returncode != 0:
        sys.exit(f"{case} {name} failed:\n{done.stdout}\n{done.stderr}")
    summary = json.loads((folder / "results" / "summary.json").read_text())
    wall = summary["wall_time_s"]
    sides = {k: v for k, v in wall.items() if k not in NOT_SIDES}
    track = next(v for k, v in sides.items() if k.startswith("vehicle"))
    soil = next(v for k, v in sides.items() if k.startswith("soil"))
    stepping = wall["total"] - wall["statics"]
    # Two threads: the sides advance at the same time and the longer one is what the step waits
    # for; one thread: one after the other.
    inside = max(track, soil) if coupling["params"].get("threads") == 2 else track + soil
    return {"case": case, "coupling": name, "wall_s": wall["total"], "statics_s": wall["statics"],
            "stepping_s": stepping, "track_s": track, "soil_s": soil,
            "recording_s": wall["recording"], "rest_s": stepping - wall["recording"] - inside,
            "macro_steps": summary["time"]["macro_steps"],
            "soil_threads": soil_threads(done.stdout + done.stderr),
            "load_before": load_before, "load_after": os.getloadavg()[0],
            "others_cores": max(0.0, others)}


def medians(runs):
    keys = ("wall_s", "statics_s", "stepping_s", "track_s", "soil_s", "recording_s", "rest_s",
            "load_before", "load_after", "others_cores")
    return {k: statistics.median(r[k] for r in runs) for k in keys}


def summarize(case, runs):
    by = {name: medians([r for r in runs if r["coupling"] == name]) for name, _ in COUPLINGS}
    gs, j1, j2 = by["gauss_seidel"], by["jacobi-1"], by["jacobi-2"]
    shares = {side: gs[f"{side}_s"] / gs["stepping_s"] for side in ("track", "soil")}
    shares["rest"] = 1.0 - shares["track"] - shares["soil"]
    p = min(shares["track"], shares["soil"])
    return {"case": case, "scenario": CASES[case][0], "medians": by,
            "gs_over_jacobi2": {"whole": gs["wall_s"] / j2["wall_s"],
                                "stepping": gs["stepping_s"] / j2["stepping_s"]},
            "jacobi1_over_jacobi2": {"whole": j1["wall_s"] / j2["wall_s"],
                                     "stepping": j1["stepping_s"] / j2["stepping_s"]},
            "gauss_seidel_shares": shares, "overlap_ceiling": 1.0 / (1.0 - p)}


def print_table(results):
    print(f"{'case':9} {'coupling':13} {'wall s':>7} {'statics':>7} {'stepping':>8} "
          f"{'track':>6} {'soil':>6} {'record':>6} {'rest':>6} {'load':>9} {'others':>6}")
    for s in results["cases"]:
        for name, m in s["medians"].items():
            print(f"{s['case']:9} {name:13} {m['wall_s']:7.2f} {m['statics_s']:7.2f} "
                  f"{m['stepping_s']:8.2f} {m['track_s']:6.2f} {m['soil_s']:6.2f} "
                  f"{m['recording_s']:6.2f} {m['rest_s']:6.2f} "
                  f"{m['load_before']:4.2f}-{m['load_after']:4.2f} {m['others_cores']:6.2f}")
    for s in results["cases"]:
        r, q, sh = s["gs_over_jacobi2"], s["jacobi1_over_jacobi2"], s["gauss_seidel_shares"]
        print(f"{s['case']}: gauss_seidel / jacobi-2 = {r['whole']:.2f}x whole, "
              f"{r['stepping']:.2f}x stepping; jacobi-1 / jacobi-2 = {q['whole']:.2f}x whole, "
              f"{q['stepping']:.2f}x stepping; gauss_seidel's stepping: track "
              f"{100 * sh['track']:.0f} %, soil {100 * sh['soil']:.0f} %, rest "
              f"{100 * sh['rest']:.0f} %; ceiling of overlapping them {s['overlap_ceiling']:.2f}x")
    for r in results["runs"]:
        if r["soil_threads"]:
            print(f"  {r['case']} {r['coupling']} (round {r['round']}): {r['soil_threads']}")


def main():
    default = ROOT / "build/release/bin/rumble"
    if not default.exists():
        default = ROOT / "build/dev/bin/rumble"
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cases", default="balanced,soil")
    ap.add_argument("--busy", type=int, default=0)
    ap.add_argument("--rumble", default=str(default))
    ap.add_argument("--workdir", type=Path, default=Path("/tmp/rumble_jacobi_speedup"))
    ap.add_argument("--output", type=Path, default=ROOT / "results/bench/jacobi_speedup.json")
    args = ap.parse_args()
    cases = args.cases.split(",")
    load_at_start = list(os.getloadavg())
    busy = [subprocess.Popen([sys.executable, "-c", "while True: pass"])
            for _ in range(args.busy)]
    start = time.time()
    try:
        runs = []
        for k in range(args.repeats):
            for case in cases:
                for name, coupling in COUPLINGS:
                    runs.append(dict(run(args.rumble, case, name, coupling, args.workdir),
                                     round=k))
    finally:
        for p in busy:
            p.kill()
            p.wait()
    results = {"load_average_1_5_15_at_start": load_at_start,
               "load_average_1_5_15_at_end": list(os.getloadavg()), "cpus": os.cpu_count(),
               "busy_processes": args.busy, "repeats": args.repeats, "rumble": args.rumble,
               "minutes": (time.time() - start) / 60.0,
               "command": " ".join([Path(sys.argv[0]).name] + sys.argv[1:]),
               "cases": [summarize(c, [r for r in runs if r["case"] == c]) for c in cases],
               "runs": runs}
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(results, indent=2) + "\n")
    print_table(results)
    print(f"load average at the start {load_at_start}, at the end "
          f"{results['load_average_1_5_15_at_end']}; {args.busy} busy process(es) of ours; "
          f"'others': the cores the machine's other processes used during each run; written to "
          f"{args.output}")


if __name__ == "__main__":
    main()
