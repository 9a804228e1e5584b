#!/usr/bin/env bash
# Builds the libFuzzer targets with clang, AddressSanitizer and UndefinedBehaviorSanitizer into
# build-fuzz/, writes a seed corpus of small valid files, and fuzzes the height-map loader, the
# shot-list parser and the damage-log reader (a late-joining client's message) for SECONDS each
# (default 60). A crash, or undefined behaviour, stops with the reproducer's path.
#   scripts/fuzz.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
bash scripts/setup.sh
if ! command -v clang++ > /dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a > /dev/null 2>&1; then
    echo "fuzz: installing clang"
    sudo_cmd=()
    [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends clang > /dev/null
fi
flags="-fsanitize=address,undefined,fuzzer-no-link -fno-omit-frame-pointer -g"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHFX_BUILD_FUZZ=ON \
    -DHFX_BUILD_TESTS=OFF -DHFX_BUILD_DEMO=OFF -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
    -Wno-dev > build-fuzz.log 2>&1 || { cat build-fuzz.log; exit 1; }
cmake --build build-fuzz -j"$(nproc)" --target hfx-fuzz-heightmap hfx-fuzz-shots hfx-fuzz-damage hfx-fuzz-corpus \
    >> build-fuzz.log 2>&1 || { tail -n 60 build-fuzz.log; exit 1; }
corpus=build-fuzz/corpus
rm -rf "$corpus"
ASAN_OPTIONS=detect_leaks=0 ./build-fuzz/tests/fuzz/hfx-fuzz-corpus "$corpus"
export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1"  # leaks: scripts/sanitize.sh's job
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1" # undefined behaviour is a finding too
for target in heightmap shots damage; do
    mkdir -p build-fuzz/findings/$target
    echo "fuzz: $target for ${seconds}s"
    dict=()
    [ -f "tests/fuzz/$target.dict" ] && dict=("-dict=tests/fuzz/$target.dict")
    ./build-fuzz/tests/fuzz/hfx-fuzz-$target "${dict[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
        -max_len=65536 -artifact_prefix=build-fuzz/findings/$target/ -print_final_stats=1 \
        "$corpus/$target" 2> build-fuzz/$target.log ||
        { tail -n 40 build-fuzz/$target.log; echo "fuzz: $target found a crash (build-fuzz/findings/$target/)"; exit 1; }
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" build-fuzz/$target.log | sed "s/^/fuzz: $target /"
done
echo "fuzz: no crash in ${seconds}s per target"
