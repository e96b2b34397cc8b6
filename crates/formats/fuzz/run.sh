#!/usr/bin/env bash
# Fuzzes every reader for RUNS inputs each (default 1,000,000), starting
# from the seeds in fuzz/seeds/, and prints libFuzzer's final figures per
# target (also in fuzz/<target>.log). Needs cargo-fuzz (installed if
# missing) and uses RUSTC_BOOTSTRAP=1 for the nightly flags libFuzzer's
# build needs on a stable toolchain. Usage: crates/formats/fuzz/run.sh [RUNS]
# (FUZZ_TARGETS="usdc usdz" runs some targets only).
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-1000000}"
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked
export RUSTC_BOOTSTRAP=1
failed=0
for target in ${FUZZ_TARGETS:-tfx hair usda usdc usdz obj abc}; do
    mkdir -p "fuzz/corpus/$target"
    cp -n fuzz/seeds/"$target"/* "fuzz/corpus/$target/"
    start=$(date +%s)
    # -O -a: optimised, with debug assertions (integer overflow panics).
    # -timeout: no input may take a second. -malloc_limit_mb: no single
    # allocation may pass 16 MiB while reading an input of at most 64 KiB
    # (the documented bound is 64 × the input, 4 MiB, in all). The RSS limit
    # is loose: AddressSanitizer's quarantine alone may hold 256 MiB.
    status=0
    cargo fuzz run -O -a "$target" "fuzz/corpus/$target" -- \
        -runs="$runs" -timeout=1 -rss_limit_mb=2048 -malloc_limit_mb=16 -max_len=65536 \
        -print_final_stats=1 >"fuzz/$target.log" 2>&1 || status=$?
    echo "$target: exit $status, $(grep -E '^stat::number_of_executed_units' "fuzz/$target.log" | tr -s ' '), $(grep -E '^stat::peak_rss_mb' "fuzz/$target.log" | tr -s ' '), $(( $(date +%s) - start )) s"
    [[ $status == 0 ]] || { grep -E 'ERROR|panicked' "fuzz/$target.log" | head -3; failed=1; }
done
exit "$failed"
