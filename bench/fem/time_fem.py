#!/usr/bin/python3
"""Whole-run timings of the FEM soil (issue #9): the stiff-soil example
(scenarios/examples/stiff_soil_fem.json) with meshes of growing size (mesh.f_max), 0.1 s
simulated. For each size: the mesh time and DOFs (`rumble mesh` into an empty cache, which the
runs then read: meshed once), then the run's wall time in the soil per simulated second and the
DOF-updates per second, with 1 and 2 threads
(taskset to 1 or 2 cores: the engine grants the soil every core it may use). Results go to
results/bench/fem_whole_run.json with the machine's load average, since a loaded machine makes
every figure larger and threads worse.

usage: bench/fem/time_fem.py [--E PA] [RUMBLE] [F_MAX ...]
       (default build/release/bin/rumble; 50 80 120; --E: the soil's Young's modulus instead of
       the example's 750 MPa: the soft soil's 1e7 has 8.7x slower waves, so the same mesh
       resolves 8.7x lower frequencies and steps 8.7x longer)
"""
import json
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SIMULATED = 0.1  # s
YOUNG = None  # Pa: --E, or the example's


def scenario(f_max, out_dir):
    s = json.loads((ROOT / "scenarios/examples/stiff_soil_fem.json").read_text())
    if YOUNG is not None:
        s["soil"]["params"]["E"] = YOUNG
    s["time"]["end"] = SIMULATED
    s["soil"]["params"]["mesh"]["f_max"] = f_max
    s["outputs"] = {"directory": out_dir.name, "receivers": [2.5, 5.0, 10.0]}  # next to it
    return s


def measure(rumble, f_max, work):
    path = work / f"fem_{f_max:g}.json"
    out_dir = work / f"out_{f_max:g}"
    path.write_text(json.dumps(scenario(f_max, out_dir)))
    # Into the runs' (empty) cache: meshed once, timed here, reused by the runs below.
    mesh_log = subprocess.run([rumble, "mesh", str(path), "--log-level", "info"],
                              env=dict(os.environ, RUMBLE_MESH_CACHE=str(work / "cache")),
                              check=True, capture_output=True, text=True)
    text = mesh_log.stdout + mesh_log.stderr
    dofs = int(re.search(r"(\d+) DOFs, \d+ footprints", text).group(1))
    # (the soil is built twice, to validate and to mesh: the first meshes, the second reads it)
    mesh_s = max(float(x) for x in re.findall(r"meshed in ([0-9.e+-]+) s", text))
    bytes_per_dof = float(re.search(r"\(([0-9.e+]+) B per DOF\)", text).group(1))
    row = {"f_max_hz": f_max, "dofs": dofs, "mesh_s": mesh_s, "bytes_per_dof": bytes_per_dof,
           "runs": []}
    available = sorted(os.sched_getaffinity(0))
    for threads in (1, 2):
        if threads > len(available):
            break
        ran = subprocess.run(["taskset", "-c", ",".join(map(str, available[:threads])), rumble,
                              "run", str(path), "--no-progress", "--no-plots", "--overwrite",
                              "--log-level", "info"],
                             env=dict(os.environ, RUMBLE_MESH_CACHE=str(work / "cache")),
                             check=True, capture_output=True, text=True)
        summary = json.loads((out_dir / "summary.json").read_text())
        soil_s = summary["wall_time_s"]["soil/fem"]
        sub_steps = int(re.search(r"fem: (\d+) explicit sub-step", ran.stdout + ran.stderr)
                        .group(1))
        steps = summary["time"]["macro_steps"] * sub_steps
        row["runs"].append({"threads": threads, "soil_wall_s": soil_s,
                            "soil_wall_per_simulated_s": soil_s / summary["time"]["reached"],
                            "explicit_steps": steps,
                            "mdof_updates_per_s": steps * dofs / soil_s * 1e-6})
    return row


def main(rumble, sizes):
    with tempfile.TemporaryDirectory() as tmp:
        rows = [measure(rumble, f, Path(tmp)) for f in sizes]
    out = {"load_average_1_5_15": list(os.getloadavg()), "simulated_s": SIMULATED,
           "young_modulus_pa": scenario(0.0, Path("."))["soil"]["params"]["E"], "sizes": rows}
    target = ROOT / "results/bench/fem_whole_run.json"
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(out, indent=2) + "\n")
    for r in rows:
        runs = ", ".join(f"{x['threads']} thread(s): {x['soil_wall_per_simulated_s']:.1f} s per "
                         f"simulated s, {x['mdof_updates_per_s']:.0f} MDOF/s" for x in r["runs"])
        print(f"f_max {r['f_max_hz']:g} Hz: {r['dofs']} DOFs meshed in {r['mesh_s']:.1f} s, "
              f"{r['bytes_per_dof']:.0f} B/DOF; {runs}")
    print(f"load average {out['load_average_1_5_15']}; written to {target}")


if __name__ == "__main__":
    args = sys.argv[1:]
    if args and args[0] == "--E":
        YOUNG = float(args[1])
        args = args[2:]
    rumble = args.pop(0) if args and not args[0].replace(".", "").isdigit() else str(
        ROOT / "build/release/bin/rumble")
    main(rumble, [float(a) for a in args] or [50.0, 80.0, 120.0])
