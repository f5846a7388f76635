#!/usr/bin/python3
"""The co-simulation error of gauss_seidel and jacobi against the monolithic reference, on the
paper's three soils (issue #10, "the paper's finding"; docs/couplers.md).

Runs scenarios/paper/soft_soil_gauss_seidel.json (70 sleepers, one wheel at 25 m/s) for END
seconds on a CLM soil with a participating mass (608 kg per footprint; decision 0004 explains why
a massless soil diverges under every explicit scheme) with E = 10, 155 and 750 MPa, once with
`monolithic` and then with each scheme at each macro step H, the track's micro-step fixed (the
default one depends on H and would hide the coupling's order). Per run: "diverged at t" or the
largest footprint displacement error relative to the reference's dynamic motion, the peak
footprint velocity against the reference's, and the energy residual at the cut relative to the
energy the reference put into the soil. Then, on the soft soil, the participating mass swept
(MASS_SWEEP) with both schemes at 1 and 0.1 ms: which runs diverge (the paper's finding: Jacobi
unstable at 1 ms and stable at 0.1 ms while Gauss-Seidel is stable at both).

usage: bench/coupling/scheme_errors.py [RUMBLE] [WORKDIR]
       (defaults: build/release/bin/rumble, /tmp/rumble_scheme_errors)
Writes results/bench/scheme_errors.json and prints a table.
"""
import csv
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SOILS = {"soft": 1e7, "medium": 1.55e8, "stiff": 7.5e8}  # E [Pa]; nu 0.3, rho 1800 kg/m^3
MASS = 608.0  # kg per footprint
SCHEMES = ["gauss_seidel", "jacobi"]
MACRO_STEPS = [1e-3, 5e-4, 2e-4, 1e-4]  # s
MICRO_STEP = 2e-5  # s, divides every H above
END = 0.5  # s
MASS_SWEEP = [25.0, 50.0, 100.0, 200.0, 400.0]  # kg per footprint, soft soil


def footprint_displacements(results):
    with open(results / "footprint_displacement.csv") as f:
        rows = list(csv.reader(f))[1:]
    return {round(float(r[0]) * 1e9): [float(x) for x in r[1:]] for r in rows}


def run(workdir, name, scenario, rumble):
    scenario["outputs"] = {"directory": name, "plots": False}
    path = workdir / f"{name}.json"
    path.write_text(json.dumps(scenario, indent=2))
    r = subprocess.run([rumble, "run", str(path), "--no-progress", "--overwrite"],
                       capture_output=True, text=True)
    summary = json.loads((workdir / name / "summary.json").read_text())
    return r.returncode, summary, workdir / name


def main(rumble, workdir):
    base = json.loads((ROOT / "scenarios/paper/soft_soil_gauss_seidel.json").read_text())
    workdir.mkdir(parents=True, exist_ok=True)
    table = []
    for soil, E in SOILS.items():
        s = json.loads(json.dumps(base))
        s["soil"] = {"type": "clm", "params": {"E": E, "nu": 0.3, "rho": 1800.0, "m_f": MASS}}
        s["track"]["integrator"] = {"micro_step": MICRO_STEP}
        s["time"] = {"end": END, "macro_step": MACRO_STEPS[0]}
        s["coupling"] = {"type": "monolithic", "params": {}}
        code, ref_summary, ref_dir = run(workdir, f"{soil}_monolithic", s, rumble)
        if code != 0:
            sys.exit(f"{soil}: the monolithic reference failed: {ref_summary.get('message')}")
        ref = footprint_displacements(ref_dir)
        first = ref[0]
        scale = max(abs(u - u0) for row in ref.values() for u, u0 in zip(row, first))
        ref_peak = max(ref_summary["peak_footprint_velocity_m_s"])
        ref_energy = ref_summary["interface"]["energy_exchanged_J"]
        for scheme in SCHEMES:
            for h in MACRO_STEPS:
                s["coupling"] = {"type": scheme, "params": {}}
                s["time"]["macro_step"] = h
                name = f"{soil}_{scheme}_{h * 1e6:g}us"
                code, summary, run_dir = run(workdir, name, s, rumble)
                entry = {"soil": soil, "E_Pa": E, "scheme": scheme, "H_s": h}
                if code != 0:
                    entry["diverged_at_s"] = summary["divergence"].get("t_detected_s")
                    entry["message"] = summary.get("message", "")
                else:
                    got = footprint_displacements(run_dir)
                    error = max(abs(a - b) for t, row in ref.items() if t in got
                                for a, b in zip(got[t], row))
                    entry["displacement_error"] = error / scale
                    entry["peak_velocity_ratio"] = max(summary["peak_footprint_velocity_m_s"]) / ref_peak
                    entry["energy_residual"] = summary["interface"]["energy_residual_J"] / ref_energy
                table.append(entry)
                if "diverged_at_s" in entry:
                    what = f"diverged at t = {entry['diverged_at_s']} s"
                else:
                    what = (f"error {entry['displacement_error']:.3g}, peak v x{entry['peak_velocity_ratio']:.3f}, "
                            f"energy residual {entry['energy_residual']:.3g}")
                print(f"{soil:6s} {scheme:12s} H = {h * 1e3:5.2f} ms: {what}", flush=True)
    sweep = []
    for mass in MASS_SWEEP:
        for scheme in SCHEMES:
            for h in (1e-3, 1e-4):
                s = json.loads(json.dumps(base))
                s["soil"] = {"type": "clm",
                             "params": {"E": SOILS["soft"], "nu": 0.3, "rho": 1800.0, "m_f": mass}}
                s["time"] = {"end": END, "macro_step": h}
                s["coupling"] = {"type": scheme, "params": {}}
                code, summary, _ = run(workdir, f"soft_{mass:g}kg_{scheme}_{h * 1e6:g}us", s, rumble)
                t = summary["divergence"].get("t_detected_s") if code != 0 else None
                sweep.append({"m_f_kg": mass, "scheme": scheme, "H_s": h, "completed": code == 0,
                              "diverged_at_s": t})
                what = "completes" if code == 0 else f"diverged at t = {t} s"
                print(f"soft m_f = {mass:5g} kg {scheme:12s} H = {h * 1e3:4.1f} ms: {what}",
                      flush=True)
    out = ROOT / "results/bench/scheme_errors.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps({"end_s": END, "micro_step_s": MICRO_STEP, "m_f_kg": MASS,
                               "runs": table, "soft_mass_sweep": sweep}, indent=2))
    print(f"wrote {out}")


if __name__ == "__main__":
    rumble = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "build/release/bin/rumble")
    workdir = Path(sys.argv[2] if len(sys.argv) > 2 else "/tmp/rumble_scheme_errors")
    main(rumble, workdir)
