#!/usr/bin/env python3
"""Figures of docs/ACCURACY.md, drawn from the CSV that `hfx-demo bench-accuracy` writes.

    /usr/bin/python3 scripts/plot_accuracy.py docs   # reads docs/accuracy/accuracy.csv and crops_80.jpg

Writes docs/accuracy/error_vs_angle.png (mean error in texels and in screen pixels against the
view angle, per technique and map), cost_vs_error.png (mean error against height fetches and
against the 1280x720 draw time) and crops_80.png (the bricks map at 80 degrees, one labelled crop
per technique), and, where `hfx-demo bench-tracers --out docs/accuracy` has written
docs/accuracy/tracers.csv, time_vs_fetches.png (hier's draw time over POM's against its fetches
over POM's, mean and in lockstep lanes; what a 32-lane warp would wait for, per angle).
Needs matplotlib (Debian: apt-get install python3-matplotlib).
"""
import csv
import sys
from pathlib import Path

try:
    import matplotlib
except ImportError:
    sys.exit(f"plot_accuracy.py: {sys.executable} has no matplotlib. Debian's (apt-get install "
             "python3-matplotlib) belongs to /usr/bin/python3: run the script with that, or pip install matplotlib")

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

FLOOR = 1e-4  # errors below this draw on the floor of the log axis (exact to float precision)
MARKERS = {"nm": "x", "parallax": "+", "steep": "v", "relief": "s", "secant": "D", "pom": "o", "hier": "*"}


def load(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for key in ("angle", "mean_texels", "p95_texels", "over4_share", "fetches", "mean_pixels", "over1px_share"):
            r[key] = float(r[key])
        r["ms"] = float(r["ms_1280x720"]) if r["ms_1280x720"] else None
    return rows


def ordered(values):
    seen = []
    for v in values:
        if v not in seen:
            seen.append(v)
    return seen


def error_vs_angle(rows, out):
    maps = ordered(r["map"] for r in rows)
    techniques = ordered(r["technique"] for r in rows)
    fig, axes = plt.subplots(2, len(maps), figsize=(4.2 * len(maps), 7.5), sharex=True, squeeze=False)
    for col, name in enumerate(maps):
        for row, (key, label) in enumerate((("mean_texels", "mean error (texels)"), ("mean_pixels", "mean error (pixels of a 192x192 image)"))):
            ax = axes[row][col]
            for t in techniques:
                pts = [(r["angle"], max(r[key], FLOOR)) for r in rows if r["map"] == name and r["technique"] == t]
                ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=MARKERS.get(t, "o"), label=t)
            ax.set_yscale("log")
            ax.set_ylim(FLOOR / 2, 300)
            ax.grid(True, which="major", alpha=0.4)
            if row == 0:
                ax.set_title(name)
            if row == 1:
                ax.set_xlabel("view angle from the normal (degrees)")
            if col == 0:
                ax.set_ylabel(label)
    # One legend for all panels, beside them: inside a panel it hid the first points' lines.
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, title="technique", fontsize=9, loc="center right")
    fig.suptitle(f"Error against the exact hit (floor {FLOOR:g}: exact to float precision)")
    fig.tight_layout(rect=(0, 0, 0.93, 1))
    fig.savefig(out, dpi=90)
    plt.close(fig)


def cost_vs_error(rows, out):
    techniques = ordered(r["technique"] for r in rows if r["technique"] != "nm")
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5))
    for t in techniques:
        mine = [r for r in rows if r["technique"] == t]
        left.scatter([r["fetches"] for r in mine], [max(r["mean_texels"], FLOOR) for r in mine],
                     marker=MARKERS.get(t, "o"), label=t)
        timed = [r for r in mine if r["ms"] is not None]
        right.scatter([r["ms"] for r in timed], [max(r["mean_texels"], FLOOR) for r in timed],
                      marker=MARKERS.get(t, "o"), label=t)
    for ax, xlabel in ((left, "height fetches per pixel (mean, without shadows)"),
                       (right, "draw time of a 1280x720 frame with shadows (ms, llvmpipe)")):
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(f"mean error (texels; below {FLOOR:g}: drawn at {FLOOR:g})")
        ax.grid(True, alpha=0.4)
    left.set_title("error against work, every map and angle")
    right.set_title("error against draw time, angles 0-80")
    left.legend(title="technique", fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def crops(rows, strip_path, out):
    techniques = ordered(r["technique"] for r in rows)
    strip = mpimg.imread(strip_path)
    width = strip.shape[1] // len(techniques)
    lookup = {r["technique"]: r for r in rows if r["map"] == "bricks" and r["angle"] == 80}
    fig, axes = plt.subplots(1, len(techniques), figsize=(2.1 * len(techniques), 2.6))
    for i, (ax, t) in enumerate(zip(axes, techniques)):
        ax.imshow(strip[:, i * width:(i + 1) * width])
        r = lookup.get(t)
        caption = f"{t}\n{r['mean_texels']:.3f} texels, {r['ms']:.0f} ms" if r and r["ms"] else t
        ax.set_title(caption, fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle("Bricks at 80 degrees: mean error and 1280x720 draw time (llvmpipe)")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def time_vs_fetches(path, out):
    """hier over POM, both with soft shadows: draw time against fetches, per map and angle."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "fetches_lanes8" not in rows[0]:
        print(f"{path}: no fetch counts (written before bench-tracers counted them); time_vs_fetches.png not drawn")
        return False
    pom = {(r["map"], r["angle"]): r for r in rows if r["technique"] == "pom"}
    # Full effort, every light ray walked (files written while the clearance map existed: without it).
    hier = [r for r in rows if r["technique"] == "hier" and float(r["pixel_budget"]) == 0.0
            and r.get("clearance_map", "0") == "0" and r.get("texel_shadows", "0") == "0"]
    # hier reading the texel shadows of the light, where the file has them, with
    # the beam start (files written before it had no column: theirs had none) and the walks they
    # leave in the draw (the deferred variant's fetches are counted in the draw alike).
    texels = [r for r in rows if r["technique"] == "hier" and r.get("texel_shadows", "0") == "1"
              and r.get("beam_start", "1") == "1" and r.get("defer_shadow_walks", "0") == "0"]
    maps = ordered(r["map"] for r in hier)
    colors = {m: f"C{i}" for i, m in enumerate(maps)}

    def ratio(r, key):
        return float(r[key]) / float(pom[(r["map"], r["angle"])][key])

    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5))
    for m in maps:
        mine = [r for r in hier if r["map"] == m]
        left.scatter([ratio(r, "fetches") for r in mine], [ratio(r, "ms") for r in mine], facecolors="none",
                     edgecolors=colors[m], label=f"{m}: mean fetches")
        left.scatter([ratio(r, "fetches_lanes8") for r in mine], [ratio(r, "ms") for r in mine], color=colors[m],
                     label=f"{m}: 8 lanes in lockstep")
        read = [r for r in texels if r["map"] == m]
        if read:
            left.scatter([ratio(r, "fetches_lanes8") for r in read], [ratio(r, "ms") for r in read], color=colors[m],
                         marker="^", label=f"{m}: with texel shadows, 8 lanes")
        right.plot([float(r["angle"]) for r in mine], [ratio(r, "fetches_lanes32") for r in mine], marker="o",
                   color=colors[m], label=m)
        if read:
            right.plot([float(r["angle"]) for r in read], [ratio(r, "fetches_lanes32") for r in read], marker="^",
                       linestyle="--", color=colors[m], label=f"{m}, texel shadows")
    top = 3.6
    left.plot([0.5, top], [0.5, top], color="grey", linestyle=":", label="time in proportion to fetches")
    for ax in (left, right):
        ax.axhline(1.25, color="red", linestyle="--", linewidth=1, label="1.25x, the draw-time target")
        ax.set_ylim(0.5, top)
        ax.grid(True, alpha=0.4)
    left.set_xlim(0.3, 2.6)
    left.set_xlabel("hier's fetches per pixel over POM's (view and light walk)")
    left.set_ylabel("hier's draw time over POM's (1280x720, llvmpipe)")
    left.set_title("draw time against the fetches the lanes wait for")
    right.set_xlabel("view angle from the normal (degrees)")
    right.set_ylabel("hier's fetches over POM's, 8x4 blocks in lockstep")
    right.set_title("what a 32-lane GPU warp would wait for")
    left.set_ylim(0.5, top + 0.8)  # room above the points for the legend
    left.legend(fontsize=6, loc="upper left", ncol=2)
    right.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)
    return True


def main():
    docs = Path(sys.argv[1] if len(sys.argv) > 1 else "docs")
    folder = docs / "accuracy"
    rows = load(folder / "accuracy.csv")
    error_vs_angle(rows, folder / "error_vs_angle.png")
    cost_vs_error(rows, folder / "cost_vs_error.png")
    crops(rows, folder / "crops_80.jpg", folder / "crops_80.png")
    drawn = ["error_vs_angle.png", "cost_vs_error.png", "crops_80.png"]
    if (folder / "tracers.csv").exists() and time_vs_fetches(folder / "tracers.csv", folder / "time_vs_fetches.png"):
        drawn.append("time_vs_fetches.png")
    print(f"wrote {folder}/" + ", ".join(drawn))


if __name__ == "__main__":
    main()
