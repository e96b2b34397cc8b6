#!/usr/bin/env bash
# Fuzzes the style reader (`style`) and the head loader (`obj_head`) for
# RUNS inputs each (default 1,000,000), starting from the seeds: the
# example and test styles, assets/head.obj, and the small OBJ files in
# fuzz/seeds/obj_head/. Prints libFuzzer's final figures per target (also
# in fuzz/<target>.log). Needs cargo-fuzz (installed if missing) and uses
# RUSTC_BOOTSTRAP=1 for the nightly flags libFuzzer's build needs on a
# stable toolchain. Usage: crates/app/fuzz/run.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
root=../..
runs="${1:-1000000}"
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked
export RUSTC_BOOTSTRAP=1
mkdir -p fuzz/corpus/style fuzz/corpus/obj_head
cp -n "$root"/assets/styles/*.ron "$root"/tests/fixtures/*.ron fuzz/corpus/style/
for f in "$root"/assets/styles/groomed/*.ron; do cp -n "$f" "fuzz/corpus/style/groomed_$(basename "$f")"; done
cp -n "$root"/assets/head.obj fuzz/seeds/obj_head/*.obj fuzz/corpus/obj_head/
failed=0
for target in style obj_head; do
    start=$(date +%s)
    # -O -a: optimised, with debug assertions (integer overflow panics).
    # -timeout: no input may take a second. -malloc_limit_mb: no single
    # allocation may pass 16 MiB for an input of at most 64 KiB (head.obj,
    # 430 KB, is read only up to that). The RSS limit is loose:
    # AddressSanitizer's quarantine alone may hold 256 MiB.
    status=0
    cargo fuzz run -O -a "$target" "fuzz/corpus/$target" -- \
        -runs="$runs" -timeout=1 -rss_limit_mb=2048 -malloc_limit_mb=16 -max_len=65536 \
        -print_final_stats=1 >"fuzz/$target.log" 2>&1 || status=$?
    echo "$target: exit $status, $(grep -E '^stat::number_of_executed_units' "fuzz/$target.log" | tr -s ' '), $(grep -E '^stat::peak_rss_mb' "fuzz/$target.log" | tr -s ' '), $(( $(date +%s) - start )) s"
    [[ $status == 0 ]] || { grep -E 'ERROR|panicked' "fuzz/$target.log" | head -3; failed=1; }
done
exit "$failed"
