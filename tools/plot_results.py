#!/usr/bin/python3
"""Plots a Rumble results directory (written by `rumble run`) into PNG files beside the CSVs.

usage: tools/plot_results.py RESULTS_DIR

Writes contact_force.png (wheel/rail forces), footprint_velocity.png (ground motion under a few
sleepers), peak_footprint_velocity.png (peak footprint velocity along the track) and, when the
soil recorded surface receivers, ppv_vs_distance.png. Needs python3-matplotlib and numpy
(Debian packages); uses the system interpreter, not a virtual environment.
"""
import json
import os
import sys
import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from results_files import open_new  # noqa: E402


def read_csv(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return header, data


def wheel_label(column):
    """contact.csv's "<vehicle> wheel <i> [N]" as a legend: "<vehicle>, wheel <i>", or "wheel <i>"
    for a vehicle itself named "wheel" (it read "wheel wheel 0")."""
    name = column.replace(" [N]", "")
    vehicle, _, wheel = name.rpartition(" wheel ")
    if not vehicle:
        return name
    return f"wheel {wheel}" if vehicle == "wheel" else f"{vehicle}, wheel {wheel}"


def save(fig, path):
    with open_new(path) as f:
        fig.savefig(f, format="png", dpi=120)


def main(directory):
    d = Path(directory)
    summary = json.loads((d / "summary.json").read_text())
    # Shortened: a scenario's name runs to 80 characters and more, beyond the figures' width.
    title = textwrap.shorten(summary.get("scenario", {}).get("name", d.name), width=60,
                             placeholder=" ...")
    written = []

    header, data = read_csv(d / "contact.csv")
    fig, ax = plt.subplots(figsize=(8, 4))
    for j in range(1, len(header)):
        ax.plot(data[:, 0], data[:, j] / 1e3, label=wheel_label(header[j]))
    ax.set(xlabel="t [s]", ylabel="contact force [kN]", title=f"{title}: wheel/rail contact")
    ax.grid(True)
    if len(header) <= 9:
        ax.legend(fontsize=7)
    fig.tight_layout()
    save(fig, d / "contact_force.png")
    written.append("contact_force.png")

    header, data = read_csv(d / "footprint_velocity.csv")
    n = len(header) - 1
    fig, ax = plt.subplots(figsize=(8, 4))
    for j in sorted({1 + n // 4, 1 + n // 2, 1 + (3 * n) // 4}):
        ax.plot(data[:, 0], data[:, j] * 1e3, label=header[j].replace(" [m/s]", ""))
    ax.set(xlabel="t [s]", ylabel="footprint velocity [mm/s] (down +)",
           title=f"{title}: ground motion under sleepers")
    ax.grid(True)
    ax.legend(fontsize=7)
    fig.tight_layout()
    save(fig, d / "footprint_velocity.png")
    written.append("footprint_velocity.png")

    xs = [float(h.split("=")[1].split(" ")[0]) for h in header[1:]]
    peak = np.abs(data[:, 1:]).max(axis=0)
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.plot(xs, peak * 1e3, "o-", ms=3)
    ax.set(xlabel="x along the track [m]", ylabel="peak |v| [mm/s]",
           title=f"{title}: peak footprint velocity")
    ax.grid(True)
    fig.tight_layout()
    save(fig, d / "peak_footprint_velocity.png")
    written.append("peak_footprint_velocity.png")

    if "ppv" in summary:
        dist = [p["distance_m"] for p in summary["ppv"]]
        ppv = [p["ppv_m_s"] * 1e3 for p in summary["ppv"]]
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.loglog(dist, ppv, "o-")
        ax.set(xlabel="distance from the track [m]", ylabel="PPV [mm/s]", title=f"{title}: PPV")
        ax.grid(True, which="both")
        fig.tight_layout()
        save(fig, d / "ppv_vs_distance.png")
        written.append("ppv_vs_distance.png")

    # Shown normalised ("results/x", not "scenarios/paper/../../results/x"), as rumble does.
    print(f"plots in {os.path.normpath(d)}: " + ", ".join(written))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
