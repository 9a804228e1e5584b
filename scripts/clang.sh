#!/usr/bin/env bash
# Builds everything with clang (Debian's, 14 on bookworm) into build-clang/ with the project's
# warnings, then runs the tests through CTest: CI builds with GCC only, and clang before 16 refuses
# some C++20 that GCC takes (a structured binding captured in a lambda, _Float16 on x86). Extra
# arguments go to ctest (`bash scripts/clang.sh -L core` for a quick look).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh clang
CC=clang CXX=clang++ cmake -S . -B build-clang -DCMAKE_BUILD_TYPE=Release -Wno-dev > build-clang.log 2>&1 ||
    { cat build-clang.log; exit 1; }
cmake --build build-clang -j"$(nproc)" >> build-clang.log 2>&1 || { grep -E "error|warning:" build-clang.log | head -40; exit 1; }
if grep -q "warning:" build-clang.log; then
    grep "warning:" build-clang.log | sort -u | head -40
    echo "clang: the build warns (build-clang.log)"
    exit 1
fi
echo "clang: built with no warning"
ctest --test-dir build-clang --output-on-failure -j2 --timeout 300 "$@"
