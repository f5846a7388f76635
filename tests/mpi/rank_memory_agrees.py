"""Every rank's peak resident memory per phase in a run's summary.json (issue #33;
docs/fem-soil.md, "Memory per rank"): under `mpirun -n N` memory.ranks holds, for each phase rank 0
measured, one peak per rank, each positive; rank 0's equal to memory.peak_resident_bytes (the
same reading, written twice); each rank's run_peak_bytes the largest of its phases; the run's
log names every rank's peak as summary.json has it (to the 3 digits the log prints, in GB); and,
an independent check, each rank but 0 peaks within a factor WITHIN of the FEM soil's estimate
for "each other rank" from the mesh (distributed/rank_plan.hpp's memory model, logged before the
split: "on N ranks, from the mesh (...) ... and X GB on each other rank").

usage: python3 rank_memory_agrees.py SUMMARY.json LOG RANKS [--no-estimate]
--no-estimate: the estimate is not checked (under AddressSanitizer, whose shadow memory and freed
blocks count in the peaks). exit 0: agrees; 1: does not (said why)."""
import json
import re
import sys

WITHIN = 1.5  # the memory model against the measured peak, either way [-]


def fail(why):
    print(f"rank_memory_agrees: {why}")
    sys.exit(1)


summary_path, log_path, ranks = sys.argv[1], sys.argv[2], int(sys.argv[3])
check_estimate = "--no-estimate" not in sys.argv[4:]
memory = json.load(open(summary_path))["memory"]
per_rank = memory.get("ranks")
if per_rank is None or per_rank["count"] != ranks:
    fail(f"memory.ranks missing or not {ranks} ranks: {json.dumps(memory)}")
own = memory["peak_resident_bytes"]
if list(per_rank["peak_resident_bytes"]) != list(own):
    fail(f"phases differ: {list(per_rank['peak_resident_bytes'])} against {list(own)}")
for phase, peaks in per_rank["peak_resident_bytes"].items():
    if len(peaks) != ranks or min(peaks) <= 0:
        fail(f"{phase}: {peaks}, expected {ranks} positive peaks")
    if peaks[0] != own[phase]:
        fail(f"{phase}: rank 0's {peaks[0]} is not peak_resident_bytes' {own[phase]}")
for k in range(ranks):
    largest = max(peaks[k] for peaks in per_rank["peak_resident_bytes"].values())
    if per_rank["run_peak_bytes"][k] != largest:
        fail(f"rank {k}: run_peak_bytes {per_rank['run_peak_bytes'][k]}, its phases' largest {largest}")
log = open(log_path).read()
line = re.search(r"peak resident memory per rank[^\n]*", log)
if not line:
    fail("the log has no line 'peak resident memory per rank'")
for k in range(ranks):
    said = re.search(rf"rank {k} ([0-9.e+-]+) GB", line.group(0))
    if not said or abs(float(said.group(1)) - per_rank["run_peak_bytes"][k] / 1e9) > \
            5e-3 * per_rank["run_peak_bytes"][k] / 1e9:
        fail(f"rank {k}: the log's line '{line.group(0)}' against {per_rank['run_peak_bytes'][k]} B")
estimate = re.search(rf"on {ranks} ranks, from the mesh \([^\n]* and ([0-9.e+-]+) GB on each other rank",
                     log)
if not estimate:
    fail("the log has no estimate per rank from the mesh")
for k in range(1, ranks if check_estimate else 1):
    ratio = float(estimate.group(1)) * 1e9 / per_rank["run_peak_bytes"][k]
    if not 1 / WITHIN <= ratio <= WITHIN:
        fail(f"rank {k}: peak {per_rank['run_peak_bytes'][k]} B, estimated {estimate.group(1)} GB "
             f"(ratio {ratio:.3f}, not within {WITHIN})")
print(f"rank_memory_agrees: estimate per other rank {estimate.group(1)} GB"
      f"{'' if check_estimate else ' (not checked: AddressSanitizer)'}; " + ", ".join(
    f"rank {k} {per_rank['run_peak_bytes'][k] / 1e6:.1f} MB" for k in range(ranks)) +
    "; by phase " + json.dumps(per_rank["peak_resident_bytes"]))
