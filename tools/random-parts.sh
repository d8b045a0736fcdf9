#!/usr/bin/env bash
# tools/random-parts.sh: scores scanpick on parts it has never seen and writes docs/random-parts.md.
#
#   BUILD_DIR=build PARTS=50 SEED=20160401 tools/random-parts.sh
#
# For each of PARTS parts generated from SEED (scanpick-cli synth-suite --suite random-parts), it
# teaches a view from each table scan (--crop-from-truth --remove-floor, the part's own name; a
# side whose crop holds too few points is skipped and counted), recognizes the part's three PhoXi
# bins with all its views (a part whose recognition stops with an error is listed with its
# message), and scores them with scanpick-cli eval (strictly, and with --accept-free-turns). The
# page lists every part and the distribution over parts (median, 10th percentile, worst; a part
# that could not be taught or recognized counts with recall 0). Use the default SEED for the
# record and a fresh one (SEED=$RANDOM) to check that a change holds on parts nobody has looked
# at. Needs jq. It builds nothing.
#
# Environment: BUILD_DIR (default build), WORK_DIR (default BUILD_DIR/random-parts), PARTS
# (default 50), SEED (default 20160401), PRESET (default none: the parameters teach derives for each part),
# SET (default none: space-separated KEY=VALUE, each given to teach and recognize as --set, to
# measure one parameter's effect), OUT (default docs/random-parts.md).
set -euo pipefail
export LC_ALL=C

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD_DIR=${BUILD_DIR:-build}
[[ $BUILD_DIR == /* ]] || BUILD_DIR=$PWD/$BUILD_DIR
CLI=$BUILD_DIR/bin/scanpick-cli
WORK=${WORK_DIR:-$BUILD_DIR/random-parts}
PARTS=${PARTS:-50}
SEED=${SEED:-20160401}
PRESET=${PRESET-}
OUT=${OUT:-$ROOT/docs/random-parts.md}
[[ -x $CLI ]] || { echo "random-parts.sh: $CLI not found: build scanpick-cli first" >&2; exit 1; }
command -v jq > /dev/null || { echo "random-parts.sh: jq not found: apt-get install jq" >&2; exit 1; }
cd "$ROOT"
preset_args=()
[[ -n $PRESET ]] && preset_args=(--preset "$PRESET")
SET=${SET-}
for kv in $SET; do preset_args+=(--set "$kv"); done

rm -rf "$WORK"
mkdir -p "$WORK"
"$CLI" synth-suite --suite random-parts --parts "$PARTS" --seed "$SEED" --out "$WORK/suite" > /dev/null

rows=$WORK/rows.tsv
: > "$rows"
: > "$WORK/failures.txt"
for dir in "$WORK"/suite/random-parts/part-*; do
  part=$(basename "$dir")
  name=$(jq -r '.instances[0].part' "$dir/teach.gt.json")
  models=() truths=() skipped=0
  for view in teach teach-side1 teach-side2 teach-side3; do
    if "$CLI" teach --scan "$dir/$view.pcd" --crop-from-truth "$dir/$view.gt.json" --remove-floor \
      "${preset_args[@]}" --name "$name" --out "$WORK/$part-$view.spmodel" > /dev/null 2>&1; then
      models+=(--model "$WORK/$part-$view.spmodel")
      truths+=("$dir/$view.gt.json")
    else
      skipped=$((skipped + 1))
    fi
  done
  if [[ ${#models[@]} -eq 0 ]]; then
    printf '%s\t%s\t%s\t-\t0\t-\t0\t-\t-\n' "$part" "$name" "$skipped" >> "$rows"
    continue
  fi
  mkdir -p "$WORK/$part-results"
  if ! "$CLI" recognize "${models[@]}" --suite "$dir" --out "$WORK/$part-results" \
    "${preset_args[@]}" > "$WORK/$part-recognize.log" 2>&1; then
    printf '%s\t%s\t%s\t-\t0\t-\t0\t-\t-\n' "$part" "$name" "$skipped" >> "$rows"
    printf '%s: %s\n' "$part" "$(grep -m1 'error' "$WORK/$part-recognize.log")" >> "$WORK/failures.txt"
    continue
  fi
  "$CLI" eval --suite "$dir" --results "$WORK/$part-results" --teach-truth "${truths[@]}" \
    --json "$WORK/$part-strict.json" > /dev/null
  "$CLI" eval --suite "$dir" --results "$WORK/$part-results" --teach-truth "${truths[@]}" \
    --accept-free-turns --json "$WORK/$part-accepted.json" > /dev/null
  jq -r --arg part "$part" --arg name "$name" --arg skipped "$skipped" \
    --slurpfile accepted "$WORK/$part-accepted.json" '
    [$part, $name, $skipped,
     (.overall.precision | tostring), (.overall.recall | tostring),
     ($accepted[0].overall.precision | tostring), ($accepted[0].overall.recall | tostring),
     ((.overall.translation_error_mm.median // "-") | tostring),
     ((.overall.time_per_scene_ms.median // "-") | tostring)] | @tsv' \
    "$WORK/$part-strict.json" >> "$rows"
done

# Median, 10th percentile and worst of column $1 (1-based) over the parts that were scored.
distribution() {
  cut -f"$1" "$rows" | grep -v '^-$' | sort -g | awk '
    { v[NR] = $1 }
    END {
      if (NR == 0) { print "- | - | -"; exit }
      median = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
      p10 = v[int(0.1 * (NR - 1)) + 1]
      printf "%.3f | %.3f | %.3f", median, p10, v[1]
    }'
}

{
  echo "# Random parts"
  echo
  echo "How scanpick does on parts it has never seen: $PARTS parts generated from seed $SEED"
  echo "(core/sim/RandomPart.h: plates, brackets, prisms, bushings, flanges, extrusions, 20-300 mm),"
  echo "each taught from its table scans on four sides and searched in three PhoXi M bins of ten (of a"
  echo "large part, as many as two layers of the bin's floor hold, in a bin at least 1.4 x 1.1 its"
  echo "diameter)."
  echo "Written by:"
  echo
  echo '```sh'
  echo "BUILD_DIR=build PARTS=$PARTS SEED=$SEED ${PRESET:+PRESET=$PRESET }${SET:+SET=\"$SET\" }tools/random-parts.sh"
  echo '```'
  echo
  if [[ -n $PRESET ]]; then
    echo "Teaching: \`teach --crop-from-truth --remove-floor --preset $PRESET\`."
  elif [[ -n $SET ]]; then
    echo "Teaching: \`teach --crop-from-truth --remove-floor\` with no preset and \`--set $SET\`"
    echo "(also given to recognize): the other values derived from the part and the scan."
  else
    echo "Teaching: \`teach --crop-from-truth --remove-floor\` with no preset: each view derives its"
    echo "parameters from the part and the scan ([user guide](user-guide.md#parameters-derived-at-teach))."
  fi
  echo "One view per side whose crop holds enough points (\"sides skipped\" counts the others);"
  echo "recognition with all of a part's views. Recall counts instances at least 50 % visible."
  echo "**Strict** scores each reported pose; **accepted** also counts a detection right up to the"
  echo "turns it reports the scan cannot tell (\`eval --accept-free-turns\`). Times: the recognizer's"
  echo "total per scene, the views prepared once."
  echo
  echo "## Over the parts"
  echo
  echo "| figure | median | 10th percentile | worst |"
  echo "|---|---|---|---|"
  echo "| precision, strict | $(distribution 4) |"
  echo "| recall, strict | $(distribution 5) |"
  echo "| precision, accepted | $(distribution 6) |"
  echo "| recall, accepted | $(distribution 7) |"
  echo
  echo "## Each part"
  echo
  echo "| part | name | sides skipped | precision | recall | precision, accepted | recall, accepted | median origin error (mm) | median time per scene (ms) |"
  echo "|---|---|---|---|---|---|---|---|---|"
  awk -F'\t' '{
      printf "| %s | %s | %s |", $1, $2, $3
      for (i = 4; i <= 9; ++i) printf " %s |", ($i == "-" ? "-" : sprintf("%.3f", $i))
      printf "\n" }' "$rows"
  if [[ -s $WORK/failures.txt ]]; then
    echo
    echo "Parts whose recognition stopped with an error (no figures above):"
    echo
    sed 's/^/- /' "$WORK/failures.txt"
  fi
} > "$OUT"
echo "wrote $OUT"
