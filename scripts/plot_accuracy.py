#!/usr/bin/env python3
"""Figures of docs/ACCURACY.md, drawn from the CSV that `hfx-demo bench-accuracy` writes.

    /usr/bin/python3 scripts/plot_accuracy.py docs   # reads docs/accuracy/accuracy.csv and crops_80.jpg

Writes docs/accuracy/error_vs_angle.png (mean error in texels and in screen pixels against the
view angle, per technique and map), cost_vs_error.png (mean error against height fetches and
against the 1280x720 draw time) and crops_80.png (the bricks map at 80 degrees, one labelled crop
per technique). Needs matplotlib (Debian: apt-get install python3-matplotlib).
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
    axes[0][0].legend(title="technique", fontsize=8)
    fig.suptitle(f"Error against the exact hit (floor {FLOOR:g}: exact to float precision)")
    fig.tight_layout()
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
    fig.suptitle("Bricks at 80 degrees: mean error and 1280x720 draw time")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def main():
    docs = Path(sys.argv[1] if len(sys.argv) > 1 else "docs")
    folder = docs / "accuracy"
    rows = load(folder / "accuracy.csv")
    error_vs_angle(rows, folder / "error_vs_angle.png")
    cost_vs_error(rows, folder / "cost_vs_error.png")
    crops(rows, folder / "crops_80.jpg", folder / "crops_80.png")
    print(f"wrote {folder}/error_vs_angle.png, cost_vs_error.png, crops_80.png")


if __name__ == "__main__":
    main()
