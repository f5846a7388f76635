#!/usr/bin/python3
"""The spectral radius of one macro step of gauss_seidel and jacobi (`rumble stability`) against
the macro step H, on the paper's soft soil (CLM, E = 10 MPa) with the participating mass per
footprint varied, and the measured runs of the same cases on the same axes (issue #10).

Measured runs come from results/bench/scheme_errors.json (bench/coupling/scheme_errors.py, its
"soft_mass_sweep": 1 and 0.1 ms, 0.5 s): a filled marker where the run completed, a cross where
the engine stopped it as diverged, drawn at the radius the analysis gives for that case.

usage: bench/coupling/stability_plot.py [RUMBLE] [WORKDIR]
       (defaults: build/release/bin/rumble, /tmp/rumble_stability_plot)
Writes results/bench/stability.json and results/bench/stability.png (and .svg).
"""
import json
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
MASSES = [25.0, 50.0, 100.0, 200.0, 608.0]  # kg per footprint
STEPS = [1e-3, 7e-4, 5e-4, 3e-4, 2e-4, 1e-4]  # s
SCHEMES = {"gauss_seidel": "-", "jacobi": "--"}


def main(rumble, workdir):
    base = json.loads((ROOT / "scenarios/paper/soft_soil_gauss_seidel.json").read_text())
    workdir.mkdir(parents=True, exist_ok=True)
    radii = {}
    for mass in MASSES:
        s = json.loads(json.dumps(base))
        s["soil"]["params"]["m_f"] = mass
        path = workdir / f"soft_{mass:g}kg.json"
        path.write_text(json.dumps(s, indent=2))
        out = workdir / f"soft_{mass:g}kg_stability.json"
        subprocess.run([rumble, "stability", str(path), "--macro-steps",
                        ",".join(f"{h:g}" for h in STEPS), "--output", str(out)],
                       check=True, capture_output=True, text=True)
        for p in json.loads(out.read_text()):
            radii[(mass, p["scheme"], round(p["macro_step_s"], 9))] = p["spectral_radius"]
        print(f"m_f = {mass:g} kg: done", flush=True)
    runs = []
    measured = ROOT / "results/bench/scheme_errors.json"
    if measured.exists():
        runs = json.loads(measured.read_text()).get("soft_mass_sweep", [])

    fig, ax = plt.subplots(figsize=(8, 5))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, mass in enumerate(MASSES):
        for scheme, style in SCHEMES.items():
            rho = [radii[(mass, scheme, round(h, 9))] for h in STEPS]
            ax.semilogx([h * 1e3 for h in STEPS], rho, style, color=colours[i % len(colours)],
                        label=f"{scheme}, {mass:g} kg")
    for r in runs:
        key = (r["m_f_kg"], r["scheme"], round(r["H_s"], 9))
        if key not in radii:
            continue
        i = MASSES.index(r["m_f_kg"])
        ax.plot(r["H_s"] * 1e3, radii[key], "o" if r["completed"] else "x",
                color=colours[i % len(colours)], ms=8, mfc="none" if r["completed"] else None)
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set(xlabel="macro step H [ms]", ylabel="spectral radius of one macro step [-]",
           title="soft soil (CLM, E = 10 MPa): > 1 diverges; o run completed, x run diverged")
    ax.grid(True, which="both", alpha=0.4)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    out_dir = ROOT / "results/bench"
    out_dir.mkdir(parents=True, exist_ok=True)
    for ext in ("png", "svg"):
        fig.savefig(out_dir / f"stability.{ext}", dpi=120)
    (out_dir / "stability.json").write_text(json.dumps(
        [{"m_f_kg": m, "scheme": s, "H_s": h, "spectral_radius": v} for (m, s, h), v in radii.items()],
        indent=2))
    print(f"wrote {out_dir / 'stability.png'}")


if __name__ == "__main__":
    rumble = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "build/release/bin/rumble")
    workdir = Path(sys.argv[2] if len(sys.argv) > 2 else "/tmp/rumble_stability_plot")
    main(rumble, workdir)
