#!/usr/bin/python3
"""The FEM soil's stepping time on N ranks: a model from the measured per-rank throughput and the
halo's bytes per step (docs/fem-soil.md §8, "Performance model"), checked on this machine and
projected to a cluster.

    t_step(D, N) = D_rank / r + 2 (latency + halo_rank / network)

D_rank: the largest rank's DOFs, ghosts included (from the run's own split); r: a rank's
DOF-updates per second, measured on a calibration run and scaled by the memory bandwidth each
rank gets (the step is memory-bound, §4.3); halo_rank: the bytes a rank exchanges per exchange
(48 B per ghost, two exchanges per step). Run on a quiet machine (nothing else running):

    bench/fem/rank_model.py [--build build/dev] [--out rank_model.json]

It runs the stiff example (scenarios/examples/stiff_soil_fem.json, HXT meshes kept in the mesh
cache) for 30 ms: calibration at f_max 135 Hz (about 2.6e5 DOFs), check at 215 Hz (1.0e6 DOFs),
each on one process (its default threads) and on 2 ranks of one thread; the model calibrated on
the first predicts the second. Then it projects the soft soil at 100 Hz (6e7 DOFs, 1 s) onto a
cluster described by the constants below. About 6 minutes; the first call meshes (2 minutes
more).
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENARIO = os.path.join(ROOT, "scenarios", "examples", "stiff_soil_fem.json")
END = 0.03  # s simulated: 30 macro steps of 1 ms
CALIBRATION_F, CHECK_F = 135.0, 215.0  # Hz: mesh.f_max of the two sizes
SHARED_MEMORY_LATENCY, SHARED_MEMORY_BANDWIDTH = 1e-6, 5e9  # s, B/s: OpenMPI's vader, measured
# order of magnitude; the halo is under 1 % of a step here either way.

# The cluster the projection assumes (stated in docs/fem-soil.md §8): 2-socket nodes of 64 cores
# with 8 channels of DDR4-3200 per socket (STREAM triad about 340 GB/s per node), 25 Gbit/s
# Ethernet between nodes (3.1 GB/s, 5 us latency), 16 ranks per node (a rank per 4 cores: the
# step is memory-bound, more ranks per node add no bandwidth).
NODE_TRIAD, RANKS_PER_NODE = 340e9, 16
NETWORK_BANDWIDTH, NETWORK_LATENCY = 25e9 / 8, 5e-6
SOFT_DOFS, SOFT_F, SOFT_END = 6e7, 100.0, 1.0  # docs/fem-soil.md §8: the paper's soft soil
# The soil steps a whole number of sub-steps per macro step H, each at most its longest: the
# two-step model at the paper's H of 1 ms, and Gauss-Seidel at 0.1 ms, the paper's remedy on the
# soft soil (it diverges at 1 ms there: one_second_1e7.py). [s]
SOFT_MACRO_STEPS = (("two-step, H 1 ms", 1e-3), ("Gauss-Seidel, H 0.1 ms", 1e-4))
# The longest sub-step's factor with mesh.refine 1 (the stable step's), where the coarse size near
# the track stays below the footprints' width (0.70 measured, docs/fem-soil.md §2); refine 2
# unmeasured.
REFINED_STEP = 0.7


def header_constant(name):
    """A constant of distributed/rank_plan.hpp, so that it is declared once."""
    path = os.path.join(ROOT, "plugins/soils/fem/distributed/rank_plan.hpp")
    match = re.search(r"k%s = ([0-9.e+-]+);" % name, open(path).read())
    return float(match.group(1))


HALO_SURFACE, HALO_BYTES_PER_GHOST = header_constant("HaloSurface"), header_constant("HaloBytesPerGhost")


def run(build, f_max, ranks, out, scenario=SCENARIO, end=END, sets=()):
    """One run (the stiff example unless told): DOFs, largest rank's DOFs, steps, stepping
    seconds, ghosts; its log goes to out.log. `sets`: more --set POINTER=VALUE."""
    rumble = os.path.join(build, "bin", "rumble")
    command = [rumble, "run", scenario, "--output", out, "--no-plots", "--yes",
               "--set", "/soil/params/mesh/f_max=%g" % f_max,
               "--set", '/soil/params/mesh/algorithm="hxt"', "--set", "/time/end=%g" % end]
    for s in sets:
        command += ["--set", s]
    env = dict(os.environ, OMP_WAIT_POLICY="passive", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    if ranks > 1:
        command = ["mpirun", "-n", str(ranks), "--bind-to", "core"] + command
        env["OMP_NUM_THREADS"] = "1"
    started = time.monotonic()
    log = subprocess.run(command, env=env, capture_output=True, text=True)
    process_s = time.monotonic() - started
    with open(out + ".log", "w") as f:  # beside the results: a run never shares their folder
        f.write(log.stderr)
    if log.returncode != 0:
        sys.exit("rank_model: %s failed:\n%s" % (" ".join(command), log.stderr[-3000:]))
    case = parse(out, f_max, ranks)
    case["process_s"] = process_s
    return case


def parse(out, f_max, ranks):
    """What run() returns, from a finished run's out/summary.json and out.log."""
    summary = json.load(open(os.path.join(out, "summary.json")))
    log = open(out + ".log").read()
    dofs = summary["memory"]["soil_dofs"]
    sub = int(re.search(r"(\d+) explicit sub-step", log).group(1))
    largest, ghosts = dofs, 0.0
    split = re.search(r"nodes (\d+)-(\d+) \(owned \d+-\d+, ghosts \d+-(\d+)\)", log)
    if split:
        largest, ghosts = 3.0 * float(split.group(2)), float(split.group(3))
    steps = sub * summary["time"]["macro_steps"]
    return {"f_max": f_max, "ranks": ranks, "dofs": dofs, "largest_rank_dofs": largest,
            "ghosts": ghosts, "steps": steps,
            "seconds_per_step": summary["wall_time_s"]["soil/fem"] / steps}


def halo_seconds(ghosts, latency, bandwidth):
    return 2.0 * (latency + HALO_BYTES_PER_GHOST * ghosts / bandwidth) if ghosts > 0 else 0.0


def rate(case):
    """A rank's DOF-updates per second, the halo's time taken out."""
    halo = halo_seconds(case["ghosts"], SHARED_MEMORY_LATENCY, SHARED_MEMORY_BANDWIDTH)
    return case["largest_rank_dofs"] / (case["seconds_per_step"] - halo)


def predict(calibration, case):
    halo = halo_seconds(case["ghosts"], SHARED_MEMORY_LATENCY, SHARED_MEMORY_BANDWIDTH)
    return case["largest_rank_dofs"] / rate(calibration) + halo


def triad_per_rank(build):
    """This machine's triad bandwidth per rank with 2 ranks busy [B/s] (fem_bench's own triad)."""
    out = subprocess.run([os.path.join(build, "bin", "fem_bench"), "--benchmark_format=json",
                          "--benchmark_filter=BM_ExplicitStep/n:20/threads:2/single:1/mechanisms:0/simd:1"],
                         env=dict(os.environ, OMP_WAIT_POLICY="passive"), capture_output=True,
                         text=True, check=True)
    return json.loads(out.stdout)["benchmarks"][0]["triad_GB/s"] * 1e9 / 2.0


def sub_steps(longest_sub_step, macro_step):
    """Sub-steps for SOFT_END simulated: whole macro steps of a whole number of sub-steps."""
    return round(SOFT_END / macro_step) * math.ceil(macro_step / longest_sub_step - 1e-9)


def project(rank_rate, here_bandwidth, ranks, longest_sub_step, macro_step):
    """The soft soil at 100 Hz on `ranks` ranks of the cluster, coupled at macro_step: seconds
    for 1 s simulated."""
    nodes = SOFT_DOFS / 3.0
    levels = (ranks ** (1.0 / 3.0) - 1.0) / (2.0 ** (1.0 / 3.0) - 1.0)
    ghosts = HALO_SURFACE * nodes ** (2.0 / 3.0) * levels  # all ranks together (rank_plan.hpp)
    largest = 3.0 * (nodes + ghosts) / ranks
    bandwidth = NODE_TRIAD / min(ranks, RANKS_PER_NODE)
    step = largest / (rank_rate * bandwidth / here_bandwidth)
    # A rank's ghosts about 2 ghosts / ranks (each shared node a ghost on one side, in two
    # exchanges); the network's share: ranks on other nodes, all of them at worst.
    halo = halo_seconds(2.0 * ghosts / ranks, NETWORK_LATENCY, NETWORK_BANDWIDTH)
    steps = sub_steps(longest_sub_step, macro_step)
    return {"ranks": ranks, "nodes": math.ceil(ranks / RANKS_PER_NODE),
            "largest_rank_dofs": largest, "step_s": step, "halo_s": halo,
            "wall_s": steps * (step + halo), "steps": steps}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build", "dev"))
    parser.add_argument("--out", default="rank_model.json")
    args = parser.parse_args()
    cases = {}
    with tempfile.TemporaryDirectory() as tmp:
        for f_max in (CALIBRATION_F, CHECK_F):
            for ranks in (1, 2):
                cases[(f_max, ranks)] = run(args.build, f_max, ranks,
                                            os.path.join(tmp, "r%d_%d" % (f_max, ranks)))
    print("| run | DOFs | largest rank | s per step measured | model | model / measured |")
    print("|---|---|---|---|---|---|")
    checks = []
    for ranks in (1, 2):
        calibration, case = cases[(CALIBRATION_F, ranks)], cases[(CHECK_F, ranks)]
        model = predict(calibration, case)
        checks.append(model / case["seconds_per_step"])
        print("| %d rank(s), f_max %g | %.3g | %.3g | %.3g | %.3g | %.2f |" % (
            ranks, CHECK_F, case["dofs"], case["largest_rank_dofs"], case["seconds_per_step"],
            model, checks[-1]))
    here = triad_per_rank(args.build)
    # The soft soil's explicit step: the check run's, scaled by f_max (the mesh-size rule's
    # h ~ c_R / f_max, the step ~ h / c_p, c_R / c_p the same at nu 0.3; docs/fem-soil.md §8).
    check_run = cases[(CHECK_F, 2)]
    stable = (END / check_run["steps"] * (CHECK_F / SOFT_F))
    rank_rate = rate(cases[(CHECK_F, 2)])
    cases_projected = [(name + refined, macro, stable * factor)
                       for name, macro in SOFT_MACRO_STEPS
                       for refined, factor in (("", 1.0), (", refine 1", REFINED_STEP))]
    projections = [dict(project(rank_rate, here, n, step, macro), coupling=name)
                   for name, macro, step in cases_projected for n in (16, 32, 64, 128)]
    print("\nrank rate %.3g DOF-updates/s at %.3g GB/s of triad per rank; soft soil's step %.3g s"
          " (%.3g s with mesh.refine 1)" % (rank_rate, here / 1e9, stable, stable * REFINED_STEP))
    print("| coupling | sub-steps | ranks | nodes | largest rank DOFs | step s | halo s |"
          " stepping for 1 s simulated |")
    print("|---|---|---|---|---|---|---|---|")
    for p in projections:
        print("| %s | %d | %d | %d | %.3g | %.3g | %.2g | %.0f s |" % (
            p["coupling"], p["steps"], p["ranks"], p["nodes"], p["largest_rank_dofs"],
            p["step_s"], p["halo_s"], p["wall_s"]))
    json.dump({"cases": [dict(v) for v in cases.values()], "model_over_measured": checks,
               "triad_per_rank_Bps": here, "projection": projections}, open(args.out, "w"),
              indent=1)
    return 0 if all(0.8 <= c <= 1.2 for c in checks) else 1


if __name__ == "__main__":
    sys.exit(main())
