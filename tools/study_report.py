#!/usr/bin/python3
"""The report of a Rumble study (written by `rumble study`): one self-contained HTML page that a
person opens first, and its figures as PNG and SVG files.

usage: tools/study_report.py STUDY_OUTPUT_DIR

Reads STUDY_OUTPUT_DIR/study.json (the runs, their status and results directories) and, for
every run that has them, its summary.json, post/ppv.csv, post/cwt_*.csv,
post/third_octave.csv, contact.csv and interface.csv. Writes STUDY_OUTPUT_DIR/report.html (figures embedded, so the page can be mailed
or archived alone) and STUDY_OUTPUT_DIR/figures/*.png and *.svg:
  ppv_vs_distance    vertical PPV against distance from the track, one panel per value of the
                     study's first axis, one line per run (the seed paper's Figures 4 and 5)
  scalogram_<dist>   wavelet scalograms |W(t, f)| of the vertical velocity at the receivers
                     nearest 2.5 m and 5 m, one panel per run (Figures 6 and 7)
  third_octave       vertical one-third-octave velocity levels at the receivers nearest 2.5 m
                     and 5 m, one line per run
  contact_force      the first wheel's wheel/rail force of every run
  interface          the energy passed through the track/soil cut, the coupler's residual and
                     its predictor residual (the coupling error of each step, of the scheme's
                     order: docs/couplers.md) over time: a diverging run shows here first
and the tables: PPV per distance per run, each run's co-simulation diagnostics (with the energy
residual at the cut and when a diverging run was caught), and per receiver
the indicators of post/ppv.csv (PPV, dominant frequency, KB_F,max, DIN 4150-3 / BS 7385-2 ratios). Needs
python3-matplotlib and numpy (Debian packages).
"""
import base64
import html
import io
import json
import math
import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402
from results_files import open_new  # noqa: E402


# ------------------------------------------------------------------------------------ reading
def read_csv(path):
    """Header (list of names) and data (2-D array) of a results CSV; None when absent/empty."""
    try:
        with open(path) as f:
            header = [h.strip().strip('"') for h in f.readline().strip().split(",")]
        data = np.genfromtxt(path, delimiter=",", skip_header=1, ndmin=2)
    except (OSError, ValueError):
        return None
    if data.size == 0:
        return None
    return header, data


def read_table(path):
    """Rows of a CSV with a text column (post/ppv.csv) as dicts of strings."""
    try:
        with open(path) as f:
            lines = [ln.rstrip("\n") for ln in f if ln.strip()]
    except OSError:
        return []
    if not lines:
        return []
    header = split_csv_line(lines[0])
    return [dict(zip(header, split_csv_line(ln))) for ln in lines[1:]]


def split_csv_line(line):
    out, field, quoted = [], "", False
    i = 0
    while i < len(line):
        c = line[i]
        if quoted:
            if c == '"' and i + 1 < len(line) and line[i + 1] == '"':
                field += '"'
                i += 1
            elif c == '"':
                quoted = False
            else:
                field += c
        elif c == '"':
            quoted = True
        elif c == ",":
            out.append(field)
            field = ""
        else:
            field += c
        i += 1
    out.append(field)
    return out


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def load_json(path):
    try:
        return json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return {}


class Run:
    """One run of the study as its files describe it."""

    def __init__(self, entry, study_dir):
        self.name = entry.get("name", "?")
        self.status = entry.get("status", "unknown")
        self.entry = entry
        results = entry.get("results") or entry.get("results_dir") or self.name
        self.dir = Path(results) if os.path.isabs(results) else study_dir / results
        self.summary = load_json(self.dir / "summary.json")
        self.ppv = read_table(self.dir / "post" / "ppv.csv")
        values = entry.get("axis_values")
        self.axes = values if isinstance(values, dict) else {}


# ------------------------------------------------------------------------------------ figures
def save(fig, directory, stem):
    """PNG and SVG as new files (a link at the name is removed, never followed); returns the PNG
    bytes for the page."""
    directory.mkdir(exist_ok=True)
    png = io.BytesIO()
    fig.savefig(png, format="png", dpi=110)
    for ext, payload in (("png", png.getvalue()), ("svg", None)):
        with open_new(directory / f"{stem}.{ext}") as f:
            if payload is not None:
                f.write(payload)
            else:
                fig.savefig(f, format="svg")
    plt.close(fig)
    return png.getvalue()


def panel_key(run, axes):
    """Runs are grouped in panels by the value of the study's first axis; an explicit run whose
    name starts with one of that axis's values ("soft-two_step") joins that panel."""
    if not axes:
        return ""
    if run.axes:
        return run.axes.get(axes[0], "")
    head = run.name.split("-", 1)[0]
    return head if head in FIRST_AXIS_VALUES else ""


def line_label(run, axes):
    if axes and run.axes:
        rest = [str(run.axes[a]) for a in axes[1:] if a in run.axes]
        if rest:
            return " ".join(rest)
    if axes and panel_key(run, axes) and "-" in run.name:
        return run.name.split("-", 1)[1]
    return run.name


FIRST_AXIS_VALUES = set()


def stopped_note(run):
    """" (failed at 0.475 s)" for a run that did not complete (its indicators cover what it
    recorded), "" for one that did; from summary.json, so a run skipped as up to date too."""
    status = run.summary.get("status", "completed")
    if status == "completed":
        return ""
    stopped = (run.summary.get("time") or {}).get("reached")
    return f" ({status} at {stopped:.3g} s)" if stopped else f" ({status})"


def ppv_figure(runs, axes):
    groups = {}
    for r in runs:
        if r.ppv:
            groups.setdefault(panel_key(r, axes), []).append(r)
    if not groups:
        return None
    fig, panels = plt.subplots(1, len(groups), figsize=(4.2 * len(groups) + 1, 3.8), squeeze=False)
    for ax, (key, members) in zip(panels[0], groups.items()):
        for r in members:
            rows = [row for row in r.ppv if number(row.get("depth [m]", 0)) == 0 or len(r.ppv) < 3]
            d = np.array([number(row["distance [m]"]) for row in rows])
            v = np.array([number(row["PPV_z [m/s]"]) for row in rows]) * 1e3
            order = np.argsort(d)
            # A diverged run, up to where it got (the seed paper's Figure 4), drawn dashed.
            style = "o-" if not stopped_note(r) else "x--"
            ax.semilogy(d[order], v[order], style, ms=3, label=line_label(r, axes) + stopped_note(r))
        ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.yaxis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.set(xlabel="distance from the track [m]", ylabel="vertical PPV [mm/s]",
               title=f"{axes[0]} = {key}" if key else "vertical PPV")
        ax.grid(True, which="both", alpha=0.4)
        ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def cwt_files(run):
    """{distance [m]: (receiver, its cwt CSV, its ppv.csv row)}."""
    post = run.dir / "post"
    out = {}
    for row in run.ppv:
        name = row.get("receiver", "")
        safe = "".join(c if c.isalnum() or c in ".-_=" else "_" for c in name)
        path = post / f"cwt_{safe}.csv"
        if path.exists():
            out[number(row.get("distance [m]"))] = (name, path, row)
    return out


def mark_resolved_band(ax, row, horizontal):
    """The receiver's resolved frequency as a dashed red line (above it the record is the
    mesh's, docs/post-processing.md "The resolved band"); returns the title's mark."""
    f_resolved = number(row.get("f_resolved [Hz]"))
    if math.isnan(f_resolved):
        return ""
    line = ax.axhline if horizontal else ax.axvline
    line(f_resolved, color="red", ls="--", lw=1.0)
    if not unresolved(row):
        return ""
    return f" (* {UNRESOLVED_SHARE:.0%}+ of its energy above {f_resolved:.3g} Hz)"


def scalogram_figure(runs, distance):
    """One panel per run: |W| at the receiver nearest `distance` [m]."""
    chosen = []
    for r in runs:
        files = cwt_files(r)
        if files:
            d = min(files, key=lambda x: abs(x - distance))
            if abs(d - distance) <= 0.5 * distance:
                chosen.append((r, d) + files[d])
    if not chosen:
        return None
    n = len(chosen)
    # One colour scale for all panels, so that the runs compare at a glance.
    tables = [read_csv(path) for (_, _, _, path, _) in chosen]
    vmax = max((np.nanmax(t[1][:, 2:]) * 1e3 for t in tables if t is not None), default=1.0)
    cols = min(3, n)
    rows = (n + cols - 1) // cols
    fig, panels = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.2 * rows), squeeze=False)
    for ax in panels.flat[n:]:
        ax.axis("off")
    for ax, (r, d, name, path, row), table in zip(panels.flat, chosen, tables):
        if table is None:
            continue
        header, data = table
        t, coi = data[:, 0], data[:, 1]
        freqs = np.array([number(h.split()[1]) for h in header[2:]])
        w = data[:, 2:] * 1e3
        # Rasterized: the SVG keeps vector axes around one image (as vectors, one scalogram
        # was a 43 MB SVG that took 35 s to render).
        mesh = ax.pcolormesh(t, freqs, w.T, shading="auto", cmap="viridis", vmin=0.0, vmax=vmax,
                             rasterized=True)
        ax.plot(t, coi, "w--", lw=0.8)
        ax.set_yscale("log")
        ax.set_ylim(freqs.min(), freqs.max())
        mark = mark_resolved_band(ax, row, horizontal=True)
        ax.set(xlabel="t [s]", ylabel="f [Hz]")
        ax.set_title(f"{r.name}{stopped_note(r)}: {name}{mark}", fontsize=8)
        fig.colorbar(mesh, ax=ax, label="|W| [mm/s]")
    fig.tight_layout()
    return fig


def third_octave_figure(runs, distances=(2.5, 5.0)):
    """Vertical one-third-octave velocity levels (post/third_octave.csv) at the receivers nearest
    each distance [m]: one panel per distance, one line per run."""
    panels = []
    for d in distances:
        lines = []
        for r in runs:
            table = read_csv(r.dir / "post" / "third_octave.csv")
            rows = {number(row.get("distance [m]")): row for row in r.ppv}
            names = {k: row.get("receiver", "") for k, row in rows.items() if not math.isnan(k)}
            if table is None or not names:
                continue
            near = min(names, key=lambda x: abs(x - d))
            if abs(near - d) > 0.5 * d:
                continue
            header, data = table
            col = next((i for i, h in enumerate(header) if h.startswith(names[near] + " vz L_v")),
                       None)
            if col is not None:
                lines.append((r.name, data[:, 1], data[:, col], header[col], rows[near]))
        if lines:
            panels.append((d, lines))
    if not panels:
        return None
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 3.6), squeeze=False)
    for ax, (d, lines) in zip(axes.flat, panels):
        for name, f, level, _, row in lines:
            drawn = ax.semilogx(f, level, marker="o", ms=3, lw=0.9, label=name)[0]
            f_resolved = number(row.get("f_resolved [Hz]"))
            if not math.isnan(f_resolved):  # above it, the bands are the mesh's
                ax.axvline(f_resolved, color=drawn.get_color(), ls="--", lw=0.9)
        unit = lines[0][3].split("L_v", 1)[-1].strip()  # e.g. "[dB re 1e-09 m/s]"
        ax.set(xlabel="band centre f_m [Hz]", ylabel=f"vertical L_v {unit}",
               title=f"one-third-octave levels near {d:g} m\n(dashed: each run's resolved band; "
                     "above it, the mesh's)")
        ax.grid(True, which="both", alpha=0.4)
        ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def contact_figure(runs):
    fig, ax = plt.subplots(figsize=(8, 3.6))
    drawn = False
    for r in runs:
        table = read_csv(r.dir / "contact.csv")
        if table is None:
            continue
        _, data = table
        ax.plot(data[:, 0], data[:, 1] / 1e3, lw=0.9, label=r.name)
        drawn = True
    if not drawn:
        plt.close(fig)
        return None
    ax.set(xlabel="t [s]", ylabel="contact force [kN]", title="first wheel: wheel/rail contact force")
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def interface_figure(runs):
    """Energy through the cut; the final residual; the predictor residual, the coupling error of
    each step with its scheme's order (docs/couplers.md), which the energy residual cannot show."""
    fig, (top, middle, bottom) = plt.subplots(3, 1, figsize=(8, 7.4), sharex=True)
    drawn = False
    for r in runs:
        table = read_csv(r.dir / "interface.csv")
        if table is None:
            continue
        header, data = table
        top.plot(data[:, 0], data[:, 3], lw=0.9, label=r.name)
        residual = np.where(data[:, 1] > 0, data[:, 1], np.nan)
        middle.semilogy(data[:, 0], residual, lw=0.7, label=r.name)
        if "predictor residual [-]" in header:
            column = data[:, header.index("predictor residual [-]")]
            bottom.semilogy(data[:, 0], np.where(column > 0, column, np.nan), lw=0.7, label=r.name)
        drawn = True
    if not drawn:
        plt.close(fig)
        return None
    top.set(ylabel="energy into the soil [J]", title="the track/soil cut")
    middle.set(ylabel="final residual [-]")
    bottom.set(xlabel="t [s]", ylabel="predictor residual [-]\n(coupling error per step)")
    for ax in (top, middle, bottom):
        ax.grid(True, which="both", alpha=0.4)
    top.legend(fontsize=7)
    fig.tight_layout()
    return fig


# ------------------------------------------------------------------------------------ tables
# A receiver with more than this share of its vertical energy above the band its soil resolves
# is marked: its raw indicators carry that much of the mesh's response (docs/post-processing.md,
# "The resolved band"; the same threshold warns in post.json). Whether its PPV is then mostly the
# mesh's, the PPV within the band beside it says.
UNRESOLVED_SHARE = 0.2


def unresolved(row):
    """True when more than UNRESOLVED_SHARE of the receiver's energy is above its band."""
    share = number(row.get("energy_z above f_resolved [-]"))
    return not math.isnan(share) and share > UNRESOLVED_SHARE


def ppv_cell(row):
    """Raw PPV_z [mm/s], marked * when unresolved(), with the PPV within the band beside."""
    raw = number(row["PPV_z [m/s]"])
    if math.isnan(raw):
        return "<td>-</td>"
    text = f"{raw * 1e3:.4g}"
    within = number(row.get("PPV_z resolved [m/s]"))
    if not math.isnan(within):
        text += ("<sup>*</sup>" if unresolved(row) else "") + f" ({within * 1e3:.4g})"
    return f"<td class='unresolved'>{text}</td>" if unresolved(row) else f"<td>{text}</td>"


def ppv_table(runs):
    distances = sorted({round(number(row["distance [m]"]), 6) for r in runs for row in r.ppv
                        if not math.isnan(number(row.get("distance [m]")))})
    if not distances:
        return "<p>No run recorded receivers.</p>"
    head = "".join(f"<th>{html.escape(r.name + stopped_note(r))}</th>" for r in runs)
    body = []
    for d in distances:
        cells = []
        for r in runs:
            rows = [row for row in r.ppv if abs(number(row["distance [m]"]) - d) < 1e-6]
            cells.append(ppv_cell(rows[0]) if rows else
                         "<td>no receivers</td>" if not r.ppv else "<td>-</td>")
        body.append(f"<tr><th>{d:g}</th>{''.join(cells)}</tr>")
    notes = ("<p>In brackets: the PPV within the band the soil's mesh resolves at that receiver "
             "(zero-phase low-pass at its resolved frequency); <sup>*</sup> and shaded: more than "
             f"{UNRESOLVED_SHARE:.0%} of the receiver's vertical energy lies above that band, so "
             "its raw PPV carries the mesh's response; where the bracket is much smaller, the raw "
             "PPV is mostly the mesh's, not the ground's. \"no receivers\": the run's soil "
             "records none (the reduced soils, Winkler and CLM, have no points but the "
             "footprints).</p>")
    return (f"<table><caption>Vertical PPV [mm/s] by distance from the track [m]</caption>"
            f"<tr><th>distance [m]</th>{head}</tr>{''.join(body)}</table>{notes}")


def resolved_band_verdict(runs):
    """The first screen's word on the resolved band: which runs' receivers have more than
    UNRESOLVED_SHARE of their energy above it."""
    marked = [f"{r.name} {row.get('receiver', '')} "
              f"({number(row.get('energy_z above f_resolved [-]')):.0%} above "
              f"{number(row.get('f_resolved [Hz]')):.3g} Hz)"
              for r in runs for row in r.ppv if unresolved(row)]
    if not marked:
        known = any(not math.isnan(number(row.get("f_resolved [Hz]"))) for r in runs for row in r.ppv)
        return ("<p>Every receiver's record lies mostly within the band its soil's mesh resolves "
                "(at most " f"{UNRESOLVED_SHARE:.0%} of its energy above it).</p>" if known else "")
    return (f"<p class='bad'>{len(marked)} receiver records have more than "
            f"{UNRESOLVED_SHARE:.0%} of their energy above the band their soil's mesh resolves, so "
            "their raw PPV, KB and scalograms show the mesh as well as the ground: "
            + html.escape("; ".join(marked)) + ". The tables give the PPV within "
            "the band beside the raw one; a finer mesh along the path (mesh.f_max, "
            "mesh.near_distance) makes the whole record valid.</p>")


def indicators_table(runs):
    """What a practitioner checks at each receiver (docs/post-processing.md): PPV, its dominant
    frequency, DIN 4150-2 KB_F,max, and PPV against the most demanding DIN 4150-3 line
    (sensitive buildings) and BS 7385-2 line (unreinforced or light framed)."""
    rows = []
    for r in runs:
        for row in r.ppv:
            def cell(key, scale=1.0, fmt="{:.3g}", raw=False):
                """A value; a raw one (of the whole record) is marked where unresolved()."""
                v = number(row.get(key))
                if math.isnan(v):
                    return "<td>-</td>"
                if raw and unresolved(row):
                    return f"<td class='unresolved'>{fmt.format(v * scale)}<sup>*</sup></td>"
                return f"<td>{fmt.format(v * scale)}</td>"
            ratio = number(row.get("PPV / DIN 4150-3 line 3 [-]"))
            css = " class='bad'" if not math.isnan(ratio) and ratio >= 1.0 else ""
            rows.append(
                f"<tr{css}><th>{html.escape(r.name + stopped_note(r))}</th>"
                f"<td>{html.escape(row.get('receiver', ''))}</td>"
                + cell("PPV_z [m/s]", 1e3, raw=True) + cell("PPV_3c [m/s]", 1e3, raw=True)
                + cell("f_dom [Hz]", raw=True) + cell("KB_F,max [m/s]", 1e3, raw=True)
                + cell("PPV / DIN 4150-3 line 3 [-]", raw=True)
                + cell("PPV / BS 7385-2 line 2 [-]", raw=True) + cell("f_resolved [Hz]")
                + cell("energy_z above f_resolved [-]", 100.0, "{:.0f}")
                + cell("PPV_z resolved [m/s]", 1e3) + "</tr>")
    if not rows:
        return ""
    return ("<table><caption>Indicators per receiver (rows at or above the DIN 4150-3 line 3 guide "
            "value in red; <sup>*</sup> and shaded: of a record with more than "
            f"{UNRESOLVED_SHARE:.0%} of its vertical energy above the band its soil's mesh "
            "resolves, so partly the mesh's: the last column says how much PPV the band keeps)"
            "</caption><tr><th>run</th><th>receiver</th><th>PPV_z [mm/s]</th>"
            "<th>PPV 3 components [mm/s]</th><th>dominant frequency [Hz]</th>"
            "<th>KB_F,max (DIN 4150-2) [mm/s]</th><th>PPV / DIN 4150-3 line 3</th>"
            "<th>PPV / BS 7385-2 line 2</th><th>resolved band [Hz]</th>"
            "<th>energy above it [%]</th><th>PPV_z within it [mm/s]</th></tr>"
            + "".join(rows) + "</table>")


def diagnostics_table(runs):
    rows = []
    for r in runs:
        s = r.summary
        coupling = s.get("coupling", {})
        its = coupling.get("iterations", {})
        iface = s.get("interface", {})
        groups = iface.get("max_relative_residual_by_group", {}) or {}
        residuals = "<br>".join(f"{html.escape(k)}: {v:.3g}" for k, v in groups.items()
                                if isinstance(v, (int, float)))
        wall = s.get("wall_time_s", {}).get("total")
        mean_its = its.get("mean_per_step")
        energy = iface.get("energy_exchanged_J")
        energy_residual = iface.get("energy_residual_J")
        predictor = iface.get("predictor_relative_residual")
        diverged = (s.get("divergence") or {}).get("t_detected_s")
        status = r.status if r.status != "unknown" else s.get("status", "unknown")
        css = "ok" if status in ("completed", "skipped") else "bad"
        message = html.escape(str(s.get("message", ""))[:300])
        rows.append(
            f"<tr class='{css}'><th>{html.escape(r.name)}</th><td>{html.escape(status)}</td>"
            f"<td>{'' if wall is None else f'{wall:.3g}'}</td>"
            f"<td>{s.get('time', {}).get('macro_step', '')}</td>"
            f"<td>{'' if mean_its is None else f'{mean_its:.3g}'}</td>"
            f"<td>{residuals}</td><td>{'' if energy is None else f'{energy:.4g}'}</td>"
            f"<td>{'' if energy_residual is None else f'{energy_residual:.3g}'}</td>"
            f"<td>{'' if predictor is None else f'{predictor:.3g}'}</td>"
            f"<td>{'' if diverged is None else f'{diverged:.4g}'}</td>"
            f"<td>{coupling.get('discarded_steps', '')}</td><td>{message}</td></tr>")
    return ("<table><caption>Co-simulation diagnostics</caption><tr><th>run</th><th>status</th>"
            "<th>wall time [s]</th><th>macro step [s]</th><th>iterations per step</th>"
            "<th>largest relative residual by channel group</th><th>energy into the soil [J]</th>"
            "<th>energy residual at the cut [J]</th>"
            "<th>predictor residual (coupling error, the scheme's order) [-]</th>"
            "<th>diverging from t [s]</th>"
            "<th>discarded steps</th><th>message</th></tr>" + "".join(rows) + "</table>")


# ------------------------------------------------------------------------------------ page
STYLE = """
body { font-family: sans-serif; margin: 2em; max-width: 1400px; color: #222; }
table { border-collapse: collapse; margin: 1em 0; font-size: 0.9em; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: right; vertical-align: top; }
caption { font-weight: bold; text-align: left; padding: 0.3em 0; }
tr.bad { background: #fdd; }
td.unresolved { background: #eee; color: #777; }
p.bad { color: #a00; }
img { max-width: 100%; border: 1px solid #ddd; margin: 0.5em 0; }
"""


# Once the page has loaded, the body says how many of its images decoded ("3/3"): what a test
# reads back from a headless browser (tests/study).
IMAGE_CHECK = """
window.addEventListener('load', function () {
  var images = document.images, ok = 0;
  for (var i = 0; i < images.length; ++i) if (images[i].complete && images[i].naturalWidth > 0) ++ok;
  document.body.setAttribute('data-images-loaded', ok + '/' + images.length);
});
"""


def main(directory):
    study_dir = Path(directory)
    study = load_json(study_dir / "study.json")
    if not study:
        sys.exit(f"study_report.py: {study_dir / 'study.json'} is missing or not JSON; "
                 "run `rumble study FILE` first")
    axes = [a.get("name") for a in study.get("axes", []) if isinstance(a, dict)]
    runs = [Run(e, study_dir) for e in study.get("runs", [])]
    if study.get("axes"):
        FIRST_AXIS_VALUES.update(study["axes"][0].get("values", []))
    figures_dir = study_dir / "figures"
    sections = []
    for title, stem, fig in (
        ("Peak particle velocity against distance", "ppv_vs_distance", ppv_figure(runs, axes)),
        ("Wavelet transform at 2.5 m", "scalogram_2.5m", scalogram_figure(runs, 2.5)),
        ("Wavelet transform at 5 m", "scalogram_5m", scalogram_figure(runs, 5.0)),
        ("One-third-octave velocity levels", "third_octave", third_octave_figure(runs)),
        ("Wheel/rail contact force", "contact_force", contact_figure(runs)),
        ("The track/soil cut: energy, residual and coupling error", "interface",
         interface_figure(runs)),
    ):
        if fig is None:
            continue
        png = save(fig, figures_dir, stem)
        data = base64.b64encode(png).decode("ascii")
        sections.append(f"<h2>{html.escape(title)}</h2>"
                        f"<img alt='{html.escape(title)}' src='data:image/png;base64,{data}'>")
    name = html.escape(study.get("name", study_dir.name))
    description = html.escape(study.get("description", ""))
    failed = [r.name for r in runs if r.status not in ("completed", "skipped")]
    verdict = (f"<p class='bad'>{len(failed)} of {len(runs)} runs did not complete: "
               f"{html.escape(', '.join(failed))}.</p>" if failed
               else f"<p>All {len(runs)} runs completed.</p>")
    page = (f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{name}</title>"
            f"<style>{STYLE}</style><script>{IMAGE_CHECK}</script></head>"
            f"<body><h1>{name}</h1><p>{description}</p>{verdict}{resolved_band_verdict(runs)}"
            f"{ppv_table(runs)}{diagnostics_table(runs)}{''.join(sections)}{indicators_table(runs)}"
            f"<p>Figures also in {html.escape(str(figures_dir))} (PNG and SVG). Numbers per "
            f"receiver: each run's post/ppv.csv and post/post.json.</p></body></html>\n")
    path = study_dir / "report.html"
    tmp = study_dir / "report.html.tmp"
    with open_new(tmp, "w") as f:
        f.write(page)
    os.replace(tmp, path)
    print(f"study report: {path}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
