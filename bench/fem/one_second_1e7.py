#!/usr/bin/python3
"""1e7 DOFs, 1 s simulated, on one process and on 2 ranks (issue #33; docs/fem-soil.md §8,
"1e7 DOFs, one simulated second"), checked against the performance model of rank_model.py.

The run: the paper's study base (scenarios/paper/study/track_on_fem_soil.json) on its soft soil
(E = 10 MPa, near_distance 3 m, as paper.study.json's "soft"), meshed for f_max 62 Hz with
`mesh.refine` 1 (about 1e7 DOFs), the track lengthened to 50 sleepers so the wheel stays on the
rail for 1 s. The soft soil reaches 1e7 DOFs at a low f_max (its wave speeds are 1/8.7 of the
stiff soil's, so a wavelength spans as many elements at 1/8.7 of the frequency), and its stable
step at that size is 17x the stiff example's (2.74e-4 against about 1.6e-5 s, where the stiff
mesh's smallest elements are set by the footprints' width, not by the wavelength); the
coupling's step of 0.1 ms (Gauss-Seidel diverges at 1 ms here) then sets the sub-step: 1 s is
1e4 sub-steps, not 7e4.

For each rank count (one process on its default threads; 2 ranks of one thread, bound to cores),
first a calibration run (the same at f_max 31 Hz, 1.3e6 DOFs, 30 ms) whose rate predicts the
1e7 run's seconds per sub-step (rank_model.py's model); then the 1e7 run. Written to --out: each
run's DOFs, largest rank, ghosts, sub-steps, seconds per sub-step (measured and predicted),
DOF-updates per second, wall time (the process's, and summary.json's phases), peak resident
memory per rank and per phase, the first static solve's CG iterations. Run on an idle machine;
about 28 minutes per rank count (the first call also meshes with gmsh, a few minutes more):

    bench/fem/one_second_1e7.py [--build build/release] [--ranks 2,1] [--end 1] [--reuse]
                                [--workdir /tmp/rumble_1e7] [--out results/bench/fem_1e7.json]

Exit code 1 if a prediction is off by more than 20 % (the issue's bar for the model).
"""
import argparse
import json
import os
import re
import sys

import rank_model

ROOT = rank_model.ROOT
BASE = os.path.join(ROOT, "scenarios", "paper", "study", "track_on_fem_soil.json")
F_MAX = 62.0  # Hz: 1.0e7 DOFs with mesh.refine 1 (HXT: 8.88e6 at 59 Hz, DOFs ~ f_max^3)
# The model's rate (rank_model.py) is calibrated on the same run at an eighth of the size: f_max
# 31 Hz, 1.3e6 DOFs (a working set of about 250 MB, far beyond the 32 MiB L3 here), 30 ms. The
# stiff example as calibration, as rank_model.py's own check, predicted 0.72 / 0.96 (one process
# / 2 ranks) of the measured sub-step from 2.6e5 DOFs (partly in the cache: one process stepped
# 1.4x as fast per DOF) and 0.84 / 0.77 from 1.0e6 DOFs: it steps 11-19 sub-steps per macro
# step, this run one, and the work once per macro step (the far field's traction, the force's
# jump) cost about a quarter of a sub-step at 1e6 DOFs (one run each, docs/fem-soil.md §8).
CALIBRATION_F, CALIBRATION_END = 31.0, 0.03  # Hz, s
SOFT = ["/soil/params/E=1e7", "/soil/params/mesh/near_distance=3",  # paper.study.json's "soft"
        "/soil/params/mesh/refine=1", "/soil/params/mesh/max_dofs=2e7",
        "/soil/params/mesh/threads=2", "/track/sleepers/count=50", "/track/unevenness/position=15",
        "/outputs/post/f_max=%g" % F_MAX,
        # Gauss-Seidel at the paper's 1 ms diverges on this mesh (growth 1.17 per macro step
        # from 0.03 s, measured): the paper's remedy for the soft soil, H = 0.1 ms (Figure 5b)
        "/time/macro_step=1e-4"]


def details(out, ranks):
    """What summary.json and the log add: memory per rank and phase, phases' wall times, CG."""
    summary = json.load(open(os.path.join(out, "summary.json")))
    log = open(out + ".log").read()
    memory = summary["memory"]
    per_rank = memory.get("ranks", {})
    return {
        "status": summary["status"],
        "simulated_s": summary["time"]["reached"],
        "wall_time_s": summary["wall_time_s"],
        "peak_resident_bytes": memory["peak_resident_bytes"],
        "run_peak_bytes_per_rank": per_rank.get("run_peak_bytes",
                                                [max(memory["peak_resident_bytes"].values())]),
        "estimate_over_peak": memory["estimate_over_peak"],
        "static_cg_iterations": [int(n) for n in re.findall(r"(\d+) CG iterations", log)],
        "sub_step_s": float(re.search(r"explicit sub-step\(s\) of ([0-9.e+-]+) s", log).group(1)),
        "threads": "default" if ranks == 1 else "1 per rank",
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build", "release"))
    parser.add_argument("--ranks", default="2,1")
    parser.add_argument("--end", type=float, default=1.0, help="simulated seconds")
    parser.add_argument("--workdir", default="/tmp/rumble_1e7")
    parser.add_argument("--out", default=os.path.join(ROOT, "results", "bench", "fem_1e7.json"))
    parser.add_argument("--reuse", action="store_true",
                        help="take the 1e7 runs already in --workdir (calibrate again only)")
    args = parser.parse_args()
    runs, ratios = [], []
    for ranks in (int(n) for n in args.ranks.split(",")):
        calibration = rank_model.run(
            args.build, CALIBRATION_F, ranks,
            os.path.join(args.workdir, "calibration_%d_%g" % (ranks, CALIBRATION_F)),
            scenario=BASE, end=CALIBRATION_END, sets=SOFT)
        out = os.path.join(args.workdir, "soft_%d" % ranks)
        if args.reuse and os.path.exists(out + ".log"):
            case = rank_model.parse(out, F_MAX, ranks)
        else:
            case = rank_model.run(args.build, F_MAX, ranks, out, scenario=BASE, end=args.end,
                                  sets=SOFT)
        case.update(details(out, ranks))
        case["predicted_seconds_per_step"] = rank_model.predict(calibration, case)
        case["dof_updates_per_s"] = case["dofs"] / case["seconds_per_step"]
        ratios.append(case["predicted_seconds_per_step"] / case["seconds_per_step"])
        case["calibration"] = calibration
        runs.append(case)
        print("%d rank(s): %.3g DOFs, %d sub-steps of %.3g s, %.3g s each (model %.3g: %.2f), "
              "%.3g DOF-updates/s, %s, %.0f s from the statics on, peak %s GB per rank" % (
                  ranks, case["dofs"], case["steps"], case["sub_step_s"], case["seconds_per_step"],
                  case["predicted_seconds_per_step"], ratios[-1], case["dof_updates_per_s"],
                  case["status"], case["wall_time_s"]["total"],
                  "/".join("%.2f" % (b / 1e9) for b in case["run_peak_bytes_per_rank"])),
              flush=True)
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        json.dump({"load_average_1_5_15": list(os.getloadavg()), "runs": runs,
                   "model_over_measured": ratios}, open(args.out, "w"), indent=1)
    return 0 if all(0.8 <= r <= 1.2 for r in ratios) else 1


if __name__ == "__main__":
    sys.exit(main())
