#!/usr/bin/python3
"""The paper's finding on the FEM soil (issue #10): with the soft soil (E = 10 MPa), does Jacobi
at H = 1 ms diverge while it is stable at 0.1 ms and Gauss-Seidel is stable at both?

On the reduced CLM soil the answer depends on the participating mass per footprint (docs/
couplers.md, bench/coupling/scheme_errors.py); the FEM soil has no such parameter, its footprint
dynamics come from the mesh. Runs scenarios/paper/study/track_on_fem_soil.json with E = 10 MPa
for END s with gauss_seidel and jacobi at H = 1 and 0.1 ms on meshes resolving F_MAX Hz (a
coarser mesh lumps more soil into the footprint's elements: the verdict is reported per mesh),
the divergence monitor set to stop. Per run: completed, or diverged at t; the peak footprint
velocity; the soil's DOFs; wall time.

usage: bench/coupling/paper_finding_fem.py [RUMBLE] [WORKDIR] [F_MAX ...]
       (defaults: build/release/bin/rumble, or build/dev/bin/rumble if there is none;
       /tmp/rumble_paper_finding_fem; 8 12)
Writes results/bench/paper_finding_fem.json and prints a table.
"""
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
END = 0.5  # s: the CLM runs that diverge do so before 0.45 s
SCHEMES = ["gauss_seidel", "jacobi"]
MACRO_STEPS = [1e-3, 1e-4]  # s


def run(rumble, workdir, f_max, scheme, H):
    scenario = json.loads((ROOT / "scenarios/paper/study/track_on_fem_soil.json").read_text())
    scenario["time"] = {"end": END, "macro_step": H}
    scenario["soil"]["params"]["E"] = 1e7
    scenario["soil"]["params"]["mesh"]["f_max"] = f_max
    scenario["coupling"] = {"type": scheme, "params": {},
                            "divergence": {"action": "stop"}}
    scenario["outputs"] = {"directory": "results", "receivers": [2.5, 5.0]}
    folder = workdir / f"soft_{f_max:g}Hz_{scheme}_{H * 1e3:g}ms"
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "scenario.json"
    path.write_text(json.dumps(scenario, indent=1))
    done = subprocess.run([rumble, "run", str(path), "--no-progress", "--no-plots",
                           "--log-level", "warn", "--overwrite"], capture_output=True, text=True)
    summary = json.loads((folder / "results" / "summary.json").read_text())
    divergence = summary.get("divergence", {})
    return {
        "f_max_Hz": f_max,
        "scheme": scheme,
        "macro_step_s": H,
        "exit_code": done.returncode,
        "status": summary.get("status"),
        "diverged": bool(divergence.get("detected")),
        "t_diverged_s": divergence.get("t_detected_s"),
        "reached_s": summary.get("time", {}).get("reached"),
        "peak_footprint_velocity_m_s": max(summary.get("peak_footprint_velocity_m_s") or [0.0]),
        "wall_s": summary.get("wall_time_s", {}).get("total"),
        "message": done.stderr.strip().splitlines()[-1] if done.returncode else "",
    }


def main(rumble, workdir, meshes):
    workdir.mkdir(parents=True, exist_ok=True)
    runs = [run(rumble, workdir, f, s, H) for f in meshes for s in SCHEMES for H in MACRO_STEPS]
    out = {"load_average_1_5_15": list(os.getloadavg()), "end_s": END, "runs": runs}
    target = ROOT / "results/bench/paper_finding_fem.json"
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(out, indent=2) + "\n")
    for r in runs:
        verdict = (f"diverged at {r['t_diverged_s']:.3f} s" if r["diverged"] else
                   f"{r['status']} to {r['reached_s']} s")
        print(f"f_max {r['f_max_Hz']:4g} Hz  {r['scheme']:13} H {r['macro_step_s'] * 1e3:4g} ms: "
              f"{verdict:28} peak footprint v {r['peak_footprint_velocity_m_s']:.3g} m/s, "
              f"{r['wall_s']:.0f} s wall")
    print(f"load average {out['load_average_1_5_15']}; written to {target}")


if __name__ == "__main__":
    default = ROOT / "build/release/bin/rumble"
    if not default.exists():
        default = ROOT / "build/dev/bin/rumble"
    args = sys.argv[1:]
    main(args[0] if args else str(default),
         Path(args[1]) if len(args) > 1 else Path("/tmp/rumble_paper_finding_fem"),
         [float(f) for f in args[2:]] or [8.0, 12.0])
