#!/usr/bin/env bash
# Regenerates the README gallery: bash docs/gallery.sh
set -euo pipefail
cd "$(dirname "$0")/.."
run() { cargo run --quiet --release -- render "$@"; }
run --problem 10 --overlay path --width 700 --height 720 --out docs/problem10-path.png
run --problem 10 --overlay values --width 700 --height 720 --out docs/problem10-values.png
run --problem 3 --overlay policy --width 700 --height 720 --out docs/problem3-policy.png
run --problem 10 --overlay path --mode reference --width 700 --height 720 --out docs/problem10-path-reference.png
run --problem 10 --overlay values --gamma 0.5 --width 700 --height 720 --out docs/problem10-values-gamma05.png
run --problem 10 --overlay visits --epsilon 0.9 --seed 0 --width 700 --height 720 --out docs/problem10-visits.png
