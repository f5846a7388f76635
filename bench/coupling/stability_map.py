#!/usr/bin/python3
"""Which soil/macro-step pairs an explicit coupling survives (docs/decisions/0004).

Runs scenarios/paper/soft_soil_gauss_seidel.json for 0.3 s with the soil (winkler, clm), its
participating mass (none or 608 kg per footprint) and the macro step H (1 ms, 0.1 ms, 20 us)
varied, and prints one line per run: "completes" or the time the engine stopped it as diverged.

usage: bench/coupling/stability_map.py [RUMBLE] [WORKDIR]
       (defaults: build/release/bin/rumble, /tmp/rumble_stability_map)
"""
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SOIL = {"E": 1e7, "nu": 0.3, "rho": 1800.0}  # the paper's soft soil [Pa, -, kg/m^3]
CASES = [
    ("winkler", {}),
    ("winkler", {"m": 608.0}),
    ("clm", {}),
    ("clm", {"m_f": 608.0}),
]
MACRO_STEPS = [1e-3, 1e-4, 2e-5]  # s


def main(rumble, workdir):
    base = json.loads((ROOT / "scenarios/paper/soft_soil_gauss_seidel.json").read_text())
    workdir.mkdir(parents=True, exist_ok=True)
    for soil, mass in CASES:
        for h in MACRO_STEPS:
            label = f"{soil}{'+' + str(next(iter(mass.values()))) + ' kg' if mass else ', massless'}"
            s = json.loads(json.dumps(base))
            s["soil"] = {"type": soil, "params": {**SOIL, **mass}}
            s["time"].update({"macro_step": h, "end": 0.3})
            # Beside its scenario file: inside the scenario's folder, as rumble requires.
            s["outputs"] = {"directory": f"{soil}_{len(mass)}_{h:g}"}
            path = workdir / f"{soil}_{len(mass)}_{h:g}.json"
            path.write_text(json.dumps(s, indent=2))
            r = subprocess.run([rumble, "run", str(path), "--no-progress", "--no-plots"],
                               capture_output=True, text=True)
            diverged = [ln for ln in (r.stdout + r.stderr).splitlines() if "diverged at" in ln]
            what = "completes" if r.returncode == 0 else (diverged[0] if diverged else r.stderr)
            print(f"{label:22s} H = {h * 1e3:g} ms: {what}", flush=True)


if __name__ == "__main__":
    rumble = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "build/release/bin/rumble")
    workdir = Path(sys.argv[2] if len(sys.argv) > 2 else "/tmp/rumble_stability_map")
    main(rumble, workdir)
