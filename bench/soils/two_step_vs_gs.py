#!/usr/bin/python3
"""Compares a study's two-step run with its Gauss-Seidel run on the same FEM soil (the quick
study: scenarios/paper/study/quick.study.json; docs/soils.md section 9.1).

usage: bench/soils/two_step_vs_gs.py STUDY_OUTPUT [TWO_STEP_RUN] [GS_RUN]
       (runs default: medium-two_step, medium-gs)

Prints, as JSON:
* the two-step mismatch of summary.json (max_relative_residual_by_group: the FEM soil's
  footprint displacement / velocity in step 2 against the reduced soil's in step 1, relative to
  the FEM soil's largest value so far; docs/couplers.md);
* the two-step run against the Gauss-Seidel run: the largest difference of the footprint
  displacement (static included) and velocity over all footprints and times, relative to the
  Gauss-Seidel run's largest absolute value, the same for the wheel's contact force, and the
  ratio of the vertical PPV at each receiver.
"""
import csv
import json
import sys
from pathlib import Path


def table(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(v) for v in row] for row in rows[1:]]


def relative_difference(a_path, b_path):
    _, a = table(a_path)
    _, b = table(b_path)
    n = min(len(a), len(b))
    scale = max(abs(v) for row in b[:n] for v in row[1:])
    diff = max(abs(x - y) for ra, rb in zip(a[:n], b[:n]) for x, y in zip(ra[1:], rb[1:]))
    return diff / scale


def ppv(path):
    with open(path) as f:
        return {row["receiver"]: float(row["PPV_z [m/s]"]) for row in csv.DictReader(f)}


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    two = out / (sys.argv[2] if len(sys.argv) > 2 else "medium-two_step")
    gs = out / (sys.argv[3] if len(sys.argv) > 3 else "medium-gs")
    summary = json.loads((two / "summary.json").read_text())
    groups = summary["interface"]["max_relative_residual_by_group"]
    p2, pg = ppv(two / "post/ppv.csv"), ppv(gs / "post/ppv.csv")
    _, contact = table(two / "contact.csv")
    report = {
        "two_step_mismatch": {k: v for k, v in groups.items() if "mismatch" in k},
        "energy_J": {k: summary["interface"][k] for k in ("track_energy_J", "energy_exchanged_J",
                                                          "energy_residual_J")},
        "two_step_vs_gs": {
            "footprint_displacement": relative_difference(two / "footprint_displacement.csv",
                                                          gs / "footprint_displacement.csv"),
            "footprint_velocity": relative_difference(two / "footprint_velocity.csv",
                                                      gs / "footprint_velocity.csv"),
            "contact": relative_difference(two / "contact.csv", gs / "contact.csv"),
            "ppv_z_ratio": {k: p2[k] / pg[k] for k in pg},
        },
    }
    print(json.dumps(report, indent=2))


if __name__ == "__main__":
    main()
