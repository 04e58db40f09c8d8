#!/usr/bin/env bash
# Run every benchmark and print its figures (the README quotes them).
# Usage: bash benchmarks/run_all.sh
set -u
cd "$(dirname "$0")/.."
for b in benchmarks/bench_*.py benchmarks/accuracy_*.py; do
  [ -e "$b" ] || continue
  echo "=== $b"
  python "$b" || echo "(failed: $b)"
done
