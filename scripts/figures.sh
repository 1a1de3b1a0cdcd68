#!/usr/bin/env bash
# Regenerates every figure of the README and docs/gallery.md, and measures the timings the
# README quotes, on this machine; then reruns the Python worked example into docs/python
# (`examples/python/rotor_7006.py --out docs/python`, with target/py-venv/bin/python or $PYTHON:
# the package installed as scripts/test_python.sh does; SKIP_PYTHON=1 leaves it out). Writes docs/figures/timings.md (date, `uname -a`, `nproc`, the
# load average before and after every command, wall and CPU time).
#
#   bash scripts/figures.sh            # everything: ≈ 10 min on 2 idle cores (the seed study ≈ 5 min)
#   SKIP_HARMONIC=1 bash scripts/figures.sh   # without the harmonic study (≈ 3–4 min of it)
#
# Studies resume from their output directory (out/figures/…); delete it to measure from scratch
# (the timings file says how many points were already there).
set -euo pipefail
cd "$(dirname "$0")/.."
FIG=docs/figures
OUT=out/figures
mkdir -p "$FIG" "$OUT"
cargo build --release -p ehl-bearing-cli
BIN=target/release/ehl-bearing
LOG="$FIG/timings.md"
# Before the log is rewritten (the log itself is tracked).
dirty=$(git diff --quiet || echo ' (with uncommitted changes)')
{
  echo "# Timings of scripts/figures.sh"
  echo
  echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "- machine: \`$(uname -a)\`"
  echo "- cores (nproc): $(nproc)"
  echo "- commit: $(git rev-parse --short HEAD)$dirty"
  echo
  echo "| command | wall s | CPU s (user+sys) | load average before | after |"
  echo "|---|---|---|---|---|"
} > "$LOG"

# run NAME CMD...: runs the command, prints its output to OUT/NAME.txt, appends a timing row.
run() {
  local name=$1
  shift
  local before after t
  before=$(cut -d' ' -f1-3 /proc/loadavg)
  /usr/bin/time -f '%e %U %S' -o "$OUT/$name.time" "$@" > "$OUT/$name.txt" 2> "$OUT/$name.err"
  t=$(tail -1 "$OUT/$name.time")
  after=$(cut -d' ' -f1-3 /proc/loadavg)
  read -r wall user sys <<< "$t"
  echo "| \`${*#"$BIN"}\` | $wall | $(echo "$user + $sys" | bc | sed "s/^\./0./") | $before | $after |" >> "$LOG"
  echo "$name: $wall s wall"
}

# One EHL contact: the seed's most loaded inner contact (examples/contact_7006_inner.toml).
run ehl "$BIN" ehl examples/contact_7006_inner.toml --fields "$OUT/ehl_7006_inner"
for f in pressure_map film_map centreline_rolling centreline_transverse; do
  cp "$OUT/ehl_7006_inner/$f.png" "$FIG/ehl_7006_inner_$f.png"
done
# The contact law of the same contact, quasi-static and harmonic.
run contact_qs "$BIN" contact examples/contact_7006_inner.toml -o "$OUT/contact_qs"
cp "$OUT/contact_qs/force_approach.png" "$FIG/contact_7006_inner_quasi_static_force_approach.png"
run contact_harmonic "$BIN" contact examples/contact_7006_inner.toml --method harmonic -o "$OUT/contact_harmonic"
cp "$OUT/contact_harmonic/force_approach.png" "$FIG/contact_7006_inner_harmonic_force_approach.png"
cp "$OUT/contact_harmonic/time_history.png" "$FIG/contact_7006_inner_harmonic_time_history.png"
# The main command of the README.
run characterize "$BIN" characterize examples/7006.toml
# The seed study (4 load scales × 3 speeds).
pts=$( (ls "$OUT/study_7006/points" 2>/dev/null || true) | wc -l)
run study "$BIN" study examples/study_7006.toml -o "$OUT/study_7006"
echo "(study: $pts points were already in $OUT/study_7006 before the run)" >> "$LOG"
for f in d_vs_load delta_f_vs_load k_vs_load; do
  cp "$OUT/study_7006/$f.png" "$FIG/study_7006_quasi_static_$f.png"
done
cp "$OUT/study_7006/trends.json" "$FIG/study_7006_quasi_static_trends.json"
if [ -z "${SKIP_HARMONIC:-}" ]; then
  pts=$( (ls "$OUT/study_7006_harmonic/points" 2>/dev/null || true) | wc -l)
  run study_harmonic "$BIN" study examples/study_7006_harmonic.toml -o "$OUT/study_7006_harmonic"
  echo "(harmonic study: $pts points were already in $OUT/study_7006_harmonic before the run)" >> "$LOG"
  for f in d_vs_load delta_f_vs_load k_vs_load; do
    cp "$OUT/study_7006_harmonic/$f.png" "$FIG/study_7006_harmonic_$f.png"
  done
  cp "$OUT/study_7006_harmonic/trends.json" "$FIG/study_7006_harmonic_trends.json"
fi
# The Python worked example: a rotor on two 7006 bearings (docs/python/rotor_7006.md).
if [ -z "${SKIP_PYTHON:-}" ]; then
  run rotor_7006 "${PYTHON:-target/py-venv/bin/python}" examples/python/rotor_7006.py --out docs/python
fi
echo >> "$LOG"
echo "Figures: docs/gallery.md. Command outputs: $OUT/*.txt." >> "$LOG"
cat "$LOG"
