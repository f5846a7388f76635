#!/usr/bin/python3
"""Plots every soil receptance CSV in a directory (written by `rumble soil-frf`) on one figure.

usage: tools/plot_frf.py DIR      -> DIR/soil_frf.png (magnitude and phase, all soils)
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main(directory):
    d = Path(directory)
    files = sorted(d.glob("*.csv"))
    if not files:
        sys.exit(f"no CSV files in {d}")
    fig, (ax_mag, ax_phase) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for path in files:
        with open(path) as f:
            header = f.readline().strip().split(",")
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        for j in range(1, len(header), 2):
            label = header[j].replace(" |H| [m/N]", "")
            line, = ax_mag.loglog(data[:, 0], data[:, j], label=label)
            ax_phase.semilogx(data[:, 0], data[:, j + 1], color=line.get_color())
    ax_mag.set(ylabel="|H| [m/N]", title="soil receptance at the footprints")
    ax_phase.set(xlabel="f [Hz]", ylabel="phase [deg]")
    for ax in (ax_mag, ax_phase):
        ax.grid(True, which="both")
    ax_mag.legend(fontsize=7)
    fig.tight_layout()
    out = d / "soil_frf.png"
    fig.savefig(out, dpi=120)
    print(f"plot: {out}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
