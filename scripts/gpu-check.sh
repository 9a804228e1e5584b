#!/usr/bin/env bash
# The checks a GPU machine is lent for, as one script: run it there from the folder that holds a
# bundle (scripts/bundle.sh), with a folder for what it writes:
#
#   bash scripts/bundle.sh .gpu-bundle                       # here
#   bash scripts/gpu-check.sh .gpu-bundle "$OUT" [SECONDS]   # there (SECONDS: the budget, 540 by default)
#
# It prints the card and the driver, then runs, each step within its share of the budget (and
# what the steps before it left unused) and its
# output kept in OUT/steps.tgz (remade after every step: a lent machine's tool brings back a few
# files, 8 on the H200's, and run 12 lost the tracer's tests to that; OUT/summary.txt beside it):
# the CL tests on the GPU's OpenCL and on PoCL where it is installed, the GL tests (the tracer's
# first; gl-tests-compute-pass: the few that hold the exact tracer's compute passes, the walks,
# the texel shadows and the beam start, to the draw's hits, shadows, colours and depths, and the
# GL state they leave), bench-tracers at 1280x720 (also with llvmpipe's pyramid layout) and
# 3840x2160, the frame bench (water, decals, planet, the transfer table) at both sizes, the decal
# wall and the planet at 1280x720 again with hier walking in the draw (bench-720p has them where
# TracePass::Auto's trial put them: the wall table's last column gives its medians of both
# passes), the texel shadows forced on and off where the scenes' rule would choose otherwise, the
# hier scenes with float32 surfaces (float16, Auto's choice on a GPU, in bench-720p), the
# external-memory transfer path's tests and table, the ringed planet and the noise on the
# triplanar box at 1280x720 (the box's hier where Auto puts it and in the draw), and a draw's
# issue time under both GlStatePolicy values with the driver's threaded optimisation off and on. A
# step that runs out of time is cut and says so; the rest go on.
# HFX_GPU_STEPS may name fewer steps (say "gl-tests-tracer bench-tracers-720p"): the budget is
# then shared among those.
# Nothing here installs anything: the bundle carries what the binaries need
# but the GL and OpenCL drivers, and glvnd's libraries where a bare GPU image lacks them (EGL then
# finds no device: unpack Debian's libegl1 libglvnd0 libopengl0 libgl1 libglx0 into / first, as
# docs/BENCHMARKS.md's NVIDIA section says).
set -uo pipefail
bundle=$(cd "${1:?usage: gpu-check.sh BUNDLE OUT [SECONDS]}" && pwd)
out=$(realpath -m "${2:?usage: gpu-check.sh BUNDLE OUT [SECONDS]}")
budget=${3:-540}
mkdir -p "$out"
work=$(mktemp -d) # the steps' logs and tables, packed into $out/steps.tgz after each step
start=$(date +%s)
run=(bash "$bundle/run.sh")

# Each step's share of the budget, in percent of all steps; HFX_GPU_STEPS selects.
declare -A shares=([cl-tests-gpu]=12 [cl-tests-pocl]=8 [gl-tests-tracer]=16 [gl-tests-rest]=10
                   [gl-tests-compute-pass]=4 [bench-tracers-720p]=12 [bench-tracers-720p-atlas]=10 [bench-tracers-4k]=12 [bench-720p]=18
                   [bench-720p-in-draw]=8 [bench-4k]=14 [bench-planet-rings]=8 [bench-triplanar-720p]=6
                   [bench-triplanar-720p-in-draw]=6
                   [bench-draw-issue]=3 [bench-planet-gas]=6 [bench-720p-texels]=8 [bench-720p-float32]=8
                   [transfer-external]=8)
# By default every step but gl-tests-compute-pass, which gl-tests-rest holds.
selected=${HFX_GPU_STEPS:-$(printf '%s\n' "${!shares[@]}" | grep -vx gl-tests-compute-pass | tr '\n' ' ')}
total=0
for n in $selected; do
    [ -n "${shares[$n]:-}" ] || { echo "gpu-check: no step '$n' (steps: ${!shares[*]})" >&2; exit 2; }
    total=$((total + shares[$n]))
done

# step NAME CMD...: runs CMD, if selected, until the budget's share of the steps so far, this one
# included, is spent: its own share and whatever the steps before it left (a fast step hands its
# time on; none takes a later step's).
done_shares=0
step() {
    local name=$1
    shift
    [[ " $selected " == *" $name "* ]] || return 0
    done_shares=$((done_shares + shares[$name]))
    local elapsed=$(($(date +%s) - start))
    local left=$((budget - elapsed))
    local limit=$((budget * done_shares / total - elapsed))
    [ "$limit" -gt "$left" ] && limit=$left
    if [ "$limit" -lt 10 ]; then
        echo "== $name: skipped, the budget is spent" | tee -a "$out/summary.txt"
        return
    fi
    echo "== $name (at most ${limit}s)"
    local t0
    t0=$(date +%s)
    timeout -k 5 "$limit" "$@" > "$work/$name.txt" 2>&1
    local rc=$?
    local verdict="rc $rc"
    [ $rc -eq 124 ] && verdict="cut at ${limit}s"
    echo "== $name: $verdict in $(($(date +%s) - t0))s" | tee -a "$out/summary.txt"
    tail -n 25 "$work/$name.txt"
    tar -czf "$out/steps.tgz" -C "$work" .
}

{
    echo "bundle of $(cat "$bundle/commit" 2>/dev/null || echo '?'), $(date -u +%Y-%m-%dT%H:%MZ)"
    nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv 2>/dev/null || echo "no nvidia-smi"
    nproc
} | tee "$out/summary.txt"

step cl-tests-gpu env HFX_CL_PLATFORM=NVIDIA "${run[@]}" hfx-tests-cl --gtest_brief=1
step cl-tests-pocl env HFX_CL_PLATFORM=portable "${run[@]}" hfx-tests-cl --gtest_brief=1 --gtest_filter='-*Soak*'
tracer='TracerContract.*:Techniques.*:Transfer.*:Users.*'
step gl-tests-tracer "${run[@]}" hfx-tests-gl --gtest_brief=1 --gtest_filter="$tracer"
step gl-tests-rest "${run[@]}" hfx-tests-gl --gtest_brief=1 --gtest_filter="-$tracer"
# A subset of gl-tests-rest, for a run that times the compute pass: its walks against the draw's
# (hits, shadows, colours; a caster's depths), the depth output under an engine's conventions
# (reversed Z, MSAA, mirrors, oblique near planes), the screen motion, the deferred outputs, the triplanar mapping,
# the water sky's clouds against their CPU model (its integer hash: the same bits on any device) and
# the CPU's picks on meshes against the GPU's trace output (19 s on llvmpipe, 2 cores: 52 tests).
step gl-tests-compute-pass "${run[@]}" hfx-tests-gl --gtest_brief=1 \
    --gtest_filter='ExactTracerTest.*:ShadowMaps.*:DepthOutput.*:BeamStart.*:MotionOutput.*:DeferredOutputs.*:Triplanar.*:Sky.*:SkyModel.*:Picking.*:PickMesh.*:*TexelShadow*:GlState.*'
step bench-tracers-720p "${run[@]}" hfx-demo bench-tracers --width 1280 --height 720 --out "$work/720p"
# The same draws with llvmpipe's pyramid layout (GlWorkarounds::pyramidAtlas) on this GPU: what
# the mip chain and the gather are worth here.
step bench-tracers-720p-atlas env HFX_GL_WORKAROUNDS=pyramid-atlas=1 "${run[@]}" hfx-demo bench-tracers --width 1280 \
    --height 720 --out "$work/720p-atlas"
step bench-tracers-4k "${run[@]}" hfx-demo bench-tracers --width 3840 --height 2160 --out "$work/4k"
step bench-720p "${run[@]}" hfx-demo bench --bench-only water,decals,planet,transfer --width 1280 --height 720
step bench-720p-in-draw "${run[@]}" hfx-demo bench --bench-only decals,planet --trace-pass draw --width 1280 --height 720
step bench-4k "${run[@]}" hfx-demo bench --bench-only water,decals,planet --width 3840 --height 2160
# The texel shadows' policy on this GPU: texelShadowsPay's 1.75 pixels per texel is llvmpipe's
# break-even, where their pass walked as slowly as the draw; here it is a compute pass on every
# unit. The decal wall (1.58 pixels per texel at 1280x720: off by that rule, in bench-720p) with
# them forced on, and the noise (7.19: on) without and with them: each scene's own technique
# draw, texel shadows included, against its POM draw.
step bench-720p-texels bash -c "bash '$bundle/run.sh' hfx-demo bench --bench-only decals --texel-shadows --width 1280 \
    --height 720 && for t in --no-texel-shadows --texel-shadows; do echo \"noise \$t\"; bash '$bundle/run.sh' hfx-demo \
    bench --bench-only noise \$t --width 1280 --height 720; done"
# The surface format: bench-720p stores the scenes' surfaces as SurfaceFormat::Auto chose here
# (float16 on a GPU; its transfer table has the water in every format); the hier scenes again with
# float32 texels, for the transfer and the draws each format costs them.
step bench-720p-float32 "${run[@]}" hfx-demo bench --bench-only decals,planet --surface-format float32 --width 1280 \
    --height 720
# The external-memory transfer path (Vulkan allocates on GL's device, GL and the GPU's OpenCL
# import it: no host copy for an EGL context; 1.3-4.0x staged's speed on an H200): the transfer tests (it against
# every other path, bit for bit, or why it is not offered), then the water's transfer table, every
# path and format (its rows: external-memory against staged).
step transfer-external bash -c "bash '$bundle/run.sh' hfx-tests-gl --gtest_brief=1 --gtest_filter='Transfer.*' && \
    bash '$bundle/run.sh' hfx-demo bench --bench-only transfer --width 1280 --height 720"
# The ringed planet seen whole (its rings' draw, their shadow and ring shine in the planet's draw).
step bench-planet-rings "${run[@]}" hfx-demo bench --bench-only planet --rings 1 --camera-distance 5 --width 1280 --height 720
# The noise on a rounded box through the triplanar mapping: what its loop over a pixel's projections
# costs a warp (its POM / NM beside the plane's in bench-720p's tables; on llvmpipe 1.6-1.9x the
# box's own texcoords, docs/BENCHMARKS.md), hier where TracePass::Auto's trial puts it (the box is
# convex: each projection may walk in the compute pass), then walking in the draw.
step bench-triplanar-720p "${run[@]}" hfx-demo bench --bench-only noise --triplanar 0.8 --width 1280 --height 720
step bench-triplanar-720p-in-draw "${run[@]}" hfx-demo bench --bench-only noise --triplanar 0.8 --width 1280 \
    --height 720 --trace-pass draw
# The host's time to issue a POM draw restoring the caller's GL state (about 120 queries) and under
# GlStatePolicy::Defaults (none), with NVIDIA's threaded optimisation off and on: on, each query
# waits for the driver's thread (docs/BENCHMARKS.md).
step bench-draw-issue bash -c "for t in 0 1; do echo \"__GL_THREADED_OPTIMIZATIONS=\$t\"; \
    __GL_THREADED_OPTIMIZATIONS=\$t bash '$bundle/run.sh' hfx-bench-kernels --benchmark_filter=DrawIssue \
    --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true; done"
# The planet's gas step on the GPU's OpenCL: its pressure solved exactly (FFTs and a tridiagonal
# solve per wavenumber, one work-item walking each column's rows) against Jacobi's sweeps, on the
# CPU device's 512x256 grid and the GPU's 1024x512 (on PoCL the exact solve costs less than 30
# sweeps; on an H200 the exact solve took 1.03x the sweeps' time).
step bench-planet-gas env HFX_CL_PLATFORM=NVIDIA "${run[@]}" hfx-bench-kernels --benchmark_filter=BM_PlanetGas \
    --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
echo "== done in $(($(date +%s) - start))s of ${budget}s" | tee -a "$out/summary.txt"
