#!/usr/bin/env python3
"""A/B timing of two shader trees with `hfx-demo bench-tracers`.

Runs the bench with HFX_SHADER_DIR set to A, then to B, `pairs` times (A, B, A, B, ...), and
prints, per map and angle, hier's time over POM's in each run and B's ratio over A's: hier walking
every light ray in its draw, then the same rays walked in the compute pass (TracePass::Compute, its
three parts together), and that pass's shading draw alone (its GPU scope, against POM's whole
time: the control). The ratio within a run is what is compared: this machine is shared and
drifts between runs, and POM, unchanged by a hier-only change, is the control (for a change to POM,
read its ms instead).

    python3 scripts/ab_shaders.py /tmp/before-shaders shaders 2 [--bench-only bricks]

A and B are copies of shaders/ (the embedded ones are what a build without HFX_SHADER_DIR
draws). Extra arguments go to bench-tracers.
"""
import csv
import math
import os
import subprocess
import sys
import tempfile


def run(demo, shaders, extra, out):
    env = dict(os.environ, HFX_SHADER_DIR=os.path.abspath(shaders))
    subprocess.run([demo, "bench-tracers", "--frames", "5", "--out", out] + extra, env=env,
                   stdout=subprocess.DEVNULL, check=True)
    pom, hier, computed, shading = {}, {}, {}, {}
    with open(os.path.join(out, "tracers.csv")) as f:
        for row in csv.DictReader(f):
            key = (row["map"], int(row["angle"]))
            if row["technique"] == "pom":
                pom[key] = float(row["ms"])
            elif (row["technique"] == "hier" and float(row["pixel_budget"]) == 0.0
                  and row.get("texel_shadows", "0") == "0"):
                # Every light ray walked: in the draw, or in the compute pass (one row each).
                in_pass = row.get("compute_trace", "0") == "1"
                (computed if in_pass else hier)[key] = float(row["ms"])
                if in_pass and float(row.get("draw_ms", "0") or 0) > 0:
                    shading[key] = float(row["draw_ms"])
    return pom, {"hier's draw": hier, "the compute pass": computed, "the compute pass's shading draw": shading}


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    a, b, pairs, extra = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4:]
    demo = os.environ.get("HFX_DEMO", "build/demo/hfx-demo")
    for tree in (a, b):
        if not os.path.isfile(os.path.join(tree, "surface.frag")):
            sys.exit(f"{tree}: not a shader tree (no surface.frag)")
    if os.path.realpath(a) == os.path.realpath(b):
        sys.exit(f"{a} is both A and B: copy it to time a tree against itself (the noise floor)")
    runs = {a: [], b: []}
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(pairs):
            for tree in (a, b):
                runs[tree].append(run(demo, tree, extra, os.path.join(tmp, f"{len(runs[a]) + len(runs[b])}")))
    keys = sorted(runs[a][0][0])
    for name in runs[a][0][1]:
        if not runs[a][0][1][name]:
            continue  # a bench without that variant
        logs = []
        print(f"{name}:")
        print(f"{'map':<14} {'angle':>5}  {'hier/pom A':<16} {'hier/pom B':<16} {'pom ms A':>8} {'pom ms B':>8}  B/A")
        for key in keys:
            ra = [timed[name][key] / pom[key] for pom, timed in runs[a]]
            rb = [timed[name][key] / pom[key] for pom, timed in runs[b]]
            change = math.exp(sum(math.log(y / x) for x, y in zip(ra, rb)) / pairs)
            logs.append(math.log(change))
            pa = sum(pom[key] for pom, _ in runs[a]) / pairs
            pb = sum(pom[key] for pom, _ in runs[b]) / pairs
            print(f"{key[0]:<14} {key[1]:>5}  {' '.join(f'{x:.2f}' for x in ra):<16} "
                  f"{' '.join(f'{x:.2f}' for x in rb):<16} {pa:8.1f} {pb:8.1f}  {change:.3f}")
        print(f"geometric mean of B/A ({name} / pom): {math.exp(sum(logs) / len(logs)):.3f}\n")


if __name__ == "__main__":
    main()
