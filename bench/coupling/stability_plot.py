#!/usr/bin/python3
"""The spectral radius of one macro step of gauss_seidel and jacobi (`rumble stability`) against
the macro step H on the paper's track over a CLM soil (issue #10), in two panels:
(a) the soft soil (E = 10 MPa) with the participating mass per footprint varied;
(b) the soil's stiffness varied (E = 5 to 750 MPa, nu 0.3, rho 1800 kg/m^3) at 50 kg per
    footprint, the mass that gives the paper's finding on the soft soil.
The measured runs of the same cases go on the same axes, drawn at the radius the analysis gives
for them: a circle where the run completed, a cross where the engine stopped it as diverged.
Panel (a)'s runs come from results/bench/scheme_errors.json (bench/coupling/scheme_errors.py,
its "soft_mass_sweep": 1 and 0.1 ms, 0.5 s); panel (b)'s are run here (0.5 s each, about 2
minutes in all).

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
STIFFNESSES = [5e6, 1e7, 2e7, 4e7, 1.55e8, 7.5e8]  # E [Pa]
SWEEP_MASS = 50.0  # kg per footprint in panel (b)
RUN_STEPS = [1e-3, 1e-4]  # s: the measured runs of panel (b)
RUN_END = 0.5  # s
STEPS = [1e-3, 7e-4, 5e-4, 3e-4, 2e-4, 1e-4]  # s
SCHEMES = {"gauss_seidel": "-", "jacobi": "--"}


def soil_case(base, E, mass):
    s = json.loads(json.dumps(base))
    s["soil"] = {"type": "clm", "params": {"E": E, "nu": 0.3, "rho": 1800.0, "m_f": mass}}
    return s


def spectral_radii(rumble, workdir, name, scenario):
    """{(scheme, H): radius} from `rumble stability`."""
    path = workdir / f"{name}.json"
    path.write_text(json.dumps(scenario, indent=2))
    out = workdir / f"{name}_stability.json"
    subprocess.run([rumble, "stability", str(path), "--macro-steps",
                    ",".join(f"{h:g}" for h in STEPS), "--output", str(out)],
                   check=True, capture_output=True, text=True)
    return {(p["scheme"], round(p["macro_step_s"], 9)): p["spectral_radius"]
            for p in json.loads(out.read_text())}


def measured_run(rumble, workdir, name, scenario, scheme, H):
    """True when the run completes, False when the engine stops it as diverged."""
    s = json.loads(json.dumps(scenario))
    s["time"] = {"end": RUN_END, "macro_step": H}
    s["coupling"] = {"type": scheme, "params": {}}
    s["outputs"] = {"directory": name, "plots": False}
    path = workdir / f"{name}.json"
    path.write_text(json.dumps(s, indent=2))
    done = subprocess.run([rumble, "run", str(path), "--no-progress", "--overwrite"],
                          capture_output=True, text=True)
    if done.returncode not in (0, 3):
        sys.exit(f"{name}: rumble run failed: {done.stderr.strip().splitlines()[-1]}")
    return done.returncode == 0


def draw(ax, keys, radii, runs, label, title):
    """One line per key and scheme; runs: [(key, scheme, H, completed)]."""
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, key in enumerate(keys):
        for scheme, style in SCHEMES.items():
            rho = [radii[(key, scheme, round(h, 9))] for h in STEPS]
            ax.semilogx([h * 1e3 for h in STEPS], rho, style, color=colours[i % len(colours)],
                        label=f"{scheme}, {label(key)}")
    for key, scheme, H, completed in runs:
        if (key, scheme, round(H, 9)) not in radii:
            continue
        ax.plot(H * 1e3, radii[(key, scheme, round(H, 9))], "o" if completed else "x",
                color=colours[keys.index(key) % len(colours)], ms=8,
                mfc="none" if completed else None)
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set(xlabel="macro step H [ms]", ylabel="spectral radius of one macro step [-]", title=title)
    ax.grid(True, which="both", alpha=0.4)
    ax.legend(fontsize=7, ncol=2)


def main(rumble, workdir):
    base = json.loads((ROOT / "scenarios/paper/soft_soil_gauss_seidel.json").read_text())
    workdir.mkdir(parents=True, exist_ok=True)
    by_mass, by_stiffness = {}, {}
    for mass in MASSES:
        for (scheme, h), v in spectral_radii(rumble, workdir, f"soft_{mass:g}kg",
                                             soil_case(base, 1e7, mass)).items():
            by_mass[(mass, scheme, h)] = v
        print(f"m_f = {mass:g} kg: done", flush=True)
    mass_runs = []
    measured = ROOT / "results/bench/scheme_errors.json"
    if measured.exists():
        mass_runs = [(r["m_f_kg"], r["scheme"], r["H_s"], r["completed"])
                     for r in json.loads(measured.read_text()).get("soft_mass_sweep", [])]
    stiffness_runs = []
    for E in STIFFNESSES:
        case = soil_case(base, E, SWEEP_MASS)
        for (scheme, h), v in spectral_radii(rumble, workdir, f"E{E:g}", case).items():
            by_stiffness[(E, scheme, h)] = v
        for scheme in SCHEMES:
            for H in RUN_STEPS:
                completed = measured_run(rumble, workdir, f"E{E:g}_{scheme}_{H * 1e6:g}us",
                                         case, scheme, H)
                stiffness_runs.append((E, scheme, H, completed))
                print(f"E = {E / 1e6:g} MPa, {scheme}, H = {H * 1e3:g} ms: radius "
                      f"{by_stiffness[(E, scheme, round(H, 9))]:.4f}, run "
                      f"{'completes' if completed else 'diverges'}", flush=True)

    fig, (ax_mass, ax_stiffness) = plt.subplots(1, 2, figsize=(14, 5.5))
    draw(ax_mass, MASSES, by_mass, mass_runs, lambda m: f"{m:g} kg",
         "(a) soft soil (CLM, E = 10 MPa), mass per footprint varied")
    draw(ax_stiffness, STIFFNESSES, by_stiffness, stiffness_runs, lambda E: f"{E / 1e6:g} MPa",
         f"(b) stiffness varied, {SWEEP_MASS:g} kg per footprint")
    fig.suptitle("> 1 diverges; o run completed, x run diverged (0.5 s)")
    fig.tight_layout()
    out_dir = ROOT / "results/bench"
    out_dir.mkdir(parents=True, exist_ok=True)
    for ext in ("png", "svg"):
        fig.savefig(out_dir / f"stability.{ext}", dpi=120)
    (out_dir / "stability.json").write_text(json.dumps({
        "mass_sweep": [{"E_Pa": 1e7, "m_f_kg": m, "scheme": s, "H_s": h, "spectral_radius": v}
                       for (m, s, h), v in by_mass.items()],
        "stiffness_sweep": [{"E_Pa": E, "m_f_kg": SWEEP_MASS, "scheme": s, "H_s": h,
                             "spectral_radius": v} for (E, s, h), v in by_stiffness.items()],
        "stiffness_runs": [{"E_Pa": E, "scheme": s, "H_s": H, "completed": c}
                           for E, s, H, c in stiffness_runs]}, indent=2))
    print(f"wrote {out_dir / 'stability.png'}")


if __name__ == "__main__":
    rumble = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "build/release/bin/rumble")
    workdir = Path(sys.argv[2] if len(sys.argv) > 2 else "/tmp/rumble_stability_plot")
    main(rumble, workdir)
