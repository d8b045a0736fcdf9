#!/usr/bin/env bash
# tools/peers.sh: runs scanpick and two peer recognizers on the same random-parts scenes with the
# same teach crops, scores all three with scanpick-cli eval and writes docs/peers.md.
#
#   BUILD_DIR=build PARTS=10 SEED=20160401 VIEWS=teach tools/peers.sh
#
# The suite is that of tools/random-parts.sh (scanpick-cli synth-suite --suite random-parts --parts
# PARTS --seed SEED; reused when WORK_DIR/suite already holds it). For each part, each table scan
# named in VIEWS is taught as random-parts.sh teaches it (--crop-from-truth --remove-floor, the
# part's own name, the parameters teach derives); a view whose crop is refused is skipped and
# counted. The part's three PhoXi bins are then recognized with those views by
#   - scanpick: scanpick-cli recognize (views prepared once);
#   - OpenCV PPF: peers_bench --method opencv-ppf (cv::ppf_match_3d::PPF3DDetector and its ICP);
#   - PCL: peers_bench --method pcl-cg (SHOT, geometric consistency grouping, ICP);
# the peers read the same .spmodel files (tests/benchmarks/peers/). Each method's results are
# scored per part with scanpick-cli eval (strictly). The page gives, per method, the distribution
# over parts (median and 10th percentile; a part that could not be taught or whose run stopped
# with an error counts with recall 0) and every part. It replaces OUT entirely. Needs jq and
# peers_bench (built when libopencv-contrib-dev is installed). It builds nothing.
#
# Environment: BUILD_DIR (default build), WORK_DIR (default BUILD_DIR/peers), PARTS (default 10),
# SEED (default 20160401), VIEWS (default "teach"; any of teach teach-side1 teach-side2
# teach-side3), BIN_DIR (default BUILD_DIR/bin: where scanpick-cli and peers_bench are; copy them
# elsewhere first when others rebuild), NICE (default 10: the niceness of every run), MIN_SCORE
# (default 0.3: peers_bench --min-score), OUT (default docs/peers.md).
set -euo pipefail
export LC_ALL=C

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD_DIR=${BUILD_DIR:-build}
[[ $BUILD_DIR == /* ]] || BUILD_DIR=$PWD/$BUILD_DIR
BIN_DIR=${BIN_DIR:-$BUILD_DIR/bin}
CLI=$BIN_DIR/scanpick-cli
PEERS=$BIN_DIR/peers_bench
WORK=${WORK_DIR:-$BUILD_DIR/peers}
PARTS=${PARTS:-10}
SEED=${SEED:-20160401}
VIEWS=${VIEWS:-teach}
NICE=${NICE:-10}
MIN_SCORE=${MIN_SCORE:-0.3}
OUT=${OUT:-$ROOT/docs/peers.md}
[[ -x $CLI ]] || { echo "peers.sh: $CLI not found: build scanpick-cli first" >&2; exit 1; }
[[ -x $PEERS ]] || { echo "peers.sh: $PEERS not found: build peers_bench (needs libopencv-contrib-dev)" >&2; exit 1; }
command -v jq > /dev/null || { echo "peers.sh: jq not found: apt-get install jq" >&2; exit 1; }
cd "$ROOT"
run() { nice -n "$NICE" "$@"; }

METHODS=(scanpick opencv-ppf pcl-cg)
declare -A TITLE=([scanpick]="scanpick" [opencv-ppf]="OpenCV PPF (surface_matching) + ICP"
  [pcl-cg]="PCL SHOT + geometric consistency + ICP")

mkdir -p "$WORK"
if [[ ! -f $WORK/suite.id || $(cat "$WORK/suite.id") != "$PARTS $SEED" ]]; then
  rm -rf "$WORK/suite" "$WORK/suite.id"
  run "$CLI" synth-suite --suite random-parts --parts "$PARTS" --seed "$SEED" --out "$WORK/suite" > /dev/null
  echo "$PARTS $SEED" > "$WORK/suite.id"
fi
rm -rf "$WORK/models" "$WORK/results" "$WORK/eval" "$WORK/logs"
mkdir -p "$WORK/models" "$WORK/results" "$WORK/eval" "$WORK/logs"
for method in "${METHODS[@]}"; do : > "$WORK/rows-$method.tsv"; done
: > "$WORK/failures.txt"

# One row per part and method: part, name, views skipped, precision, recall, median translation
# error (mm), median rotation error (deg), median and p95 time per scene (ms).
for dir in "$WORK"/suite/random-parts/part-*; do
  part=$(basename "$dir")
  name=$(jq -r '.instances[0].part' "$dir/teach.gt.json")
  models=() paths=() truths=() skipped=0
  for view in $VIEWS; do
    if run "$CLI" teach --scan "$dir/$view.pcd" --crop-from-truth "$dir/$view.gt.json" --remove-floor \
      --name "$name" --out "$WORK/models/$part-$view.spmodel" > "$WORK/logs/$part-$view-teach.log" 2>&1; then
      models+=(--model "$WORK/models/$part-$view.spmodel")
      truths+=("$dir/$view.gt.json")
    else
      skipped=$((skipped + 1))
    fi
  done
  for method in "${METHODS[@]}"; do
    results=$WORK/results/$method/$part
    log=$WORK/logs/$part-$method.log
    failed=
    if [[ ${#models[@]} -eq 0 ]]; then
      failed=1
    else
      mkdir -p "$results"
      if [[ $method == scanpick ]]; then
        run "$CLI" recognize "${models[@]}" --suite "$dir" --out "$results" > "$log" 2>&1 || failed=1
      else
        run "$PEERS" --method "$method" "${models[@]}" --suite "$dir" --out "$results" \
          --min-score "$MIN_SCORE" > "$log" 2>&1 || failed=1
      fi
      [[ -n $failed ]] && printf '%s, %s: %s\n' "$part" "$method" "$(grep -m1 'error' "$log")" >> "$WORK/failures.txt"
    fi
    if [[ -n $failed ]]; then
      printf '%s\t%s\t%s\t-\t0\t-\t-\t-\t-\n' "$part" "$name" "$skipped" >> "$WORK/rows-$method.tsv"
      continue
    fi
    json=$WORK/eval/$part-$method.json
    run "$CLI" eval --suite "$dir" --results "$results" --teach-truth "${truths[@]}" --json "$json" > /dev/null
    jq -r --arg part "$part" --arg name "$name" --arg skipped "$skipped" '
      [$part, $name, $skipped,
       (.overall.precision // "-" | tostring), (.overall.recall | tostring),
       ((if (.overall.translation_error_mm.count // 0) > 0
         then .overall.translation_error_mm.median else "-" end) | tostring),
       ((if (.overall.rotation_error_deg.count // 0) > 0
         then .overall.rotation_error_deg.median else "-" end) | tostring),
       ((.overall.time_per_scene_ms.median // "-") | tostring),
       ((.overall.time_per_scene_ms.p95 // "-") | tostring)] | @tsv' "$json" >> "$WORK/rows-$method.tsv"
  done
done

# Median and 10th percentile of column $2 (1-based) of rows file $1 over the parts with a value.
distribution() {
  cut -f"$2" "$1" | grep -v '^-$' | sort -g | awk '
    { v[NR] = $1 }
    END {
      if (NR == 0) { print "- | -"; exit }
      median = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
      printf "%.3f | %.3f", median, v[int(0.1 * (NR - 1)) + 1]
    }'
}
# Median of column $2 of rows file $1.
median_of() {
  cut -f"$2" "$1" | grep -v '^-$' | sort -g | awk '
    { v[NR] = $1 }
    END {
      if (NR == 0) { print "-"; exit }
      printf "%.3f", (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
    }'
}
# Median and 95th percentile of every scene's time (timings_ms.total) of method $1, all parts.
scene_times() {
  find "$WORK/results/$1" -name 'scene-*.json' -exec jq -r '.timings_ms.total' {} + 2> /dev/null |
    sort -g | awk '
    { v[NR] = $1 }
    END {
      if (NR == 0) { print "- | - | 0"; exit }
      median = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
      p = 0.95 * (NR - 1); i = int(p)
      p95 = (i + 1 < NR) ? v[i + 1] + (p - i) * (v[i + 2] - v[i + 1]) : v[NR]
      printf "%.0f | %.0f | %d", median, p95, NR
    }'
}

views_text=$(echo "$VIEWS" | sed 's/ /, /g')
{
  echo "# Peers on the same scenes"
  echo
  echo "Written by:"
  echo
  echo '```sh'
  echo "BUILD_DIR=build PARTS=$PARTS SEED=$SEED VIEWS=\"$VIEWS\" MIN_SCORE=$MIN_SCORE tools/peers.sh"
  echo '```'
  echo
  echo "scanpick and two open-source peers on the scenes of the [random-parts](random-parts.md) suite:"
  echo "$PARTS parts generated from seed $SEED, each searched in its three PhoXi M bins of ten. Every"
  echo "method gets the same models: the \`.spmodel\` files \`scanpick-cli teach --crop-from-truth"
  echo "--remove-floor\` writes from the part's table scans ($views_text), with no preset. All three"
  echo "are scored by \`scanpick-cli eval\` (strict: each reported pose; recall over instances at least"
  echo "50 % visible; true positive within 0.1 x the part's diameter and 10 deg, symmetry-aware)."
  echo
  echo "- **scanpick**: \`scanpick-cli recognize\` with the parameters teach derives for the part."
  echo "- **OpenCV PPF**: \`cv::ppf_match_3d::PPF3DDetector\` (Drost et al. 2010, \`libopencv-contrib-dev\`"
  echo "  4.6) with the values of OpenCV's sample \`ppf_load_match.cpp\`: \`PPF3DDetector(0.025, 0.05)\`,"
  echo "  \`match(scene, 1/40, 0.05)\`, the best poses (20 here, the sample keeps 2) refined by"
  echo "  \`ICP(100, 0.005, 2.5, 8)\`. OpenCV quantizes a cloud on a grid over its own box, each axis cut"
  echo "  into 1/step cells; model and scene are therefore voxel-sampled first at 0.025 and 0.05 x the"
  echo "  model's diameter, as its documentation describes the steps."
  echo "- **PCL**: the correspondence-grouping tutorial: uniform-sampling keypoints (model every"
  echo "  0.025 D, scene every 0.04 D), SHOT descriptors (radius 0.15 D), kd-tree nearest neighbours"
  echo "  below a squared distance of 0.25, \`pcl::GeometricConsistencyGrouping\` (size 0.04 D,"
  echo "  threshold 5), then \`pcl::IterativeClosestPoint\` (0.05 D, then 2 voxels); D is the part's"
  echo "  diameter and every length is at least a small multiple of the scan's point spacing."
  echo
  echo "Both peers (tests/benchmarks/peers/, executable \`peers_bench\`, not part of the product) see"
  echo "the scene as scanpick's floor removal leaves it, cut to the bin's inside as an operator's"
  echo "region of interest would (the smallest rectangle around the removed bin floor, less 5 mm, so"
  echo "that the walls go: found in the scan, not taken from the truth), voxel-sampled at"
  echo "max(point spacing, 0.01 D), with normals (PCL, radius 3 voxels, towards the camera); scanpick"
  echo "gets the whole scan. The model normals are those"
  echo "scanpick's refinement estimates. Their detections are scored alike: the share of the view's"
  echo "points facing the camera that have a scene point within one voxel; below $MIN_SCORE they are"
  echo "dropped, and one whose confirmed scene points are more than half another's, better one's is"
  echo "a duplicate. Times: per scene, once the scan is loaded and the models prepared (scanpick: its"
  echo "recognizer's total; peers: preparation, matching, ICP and scoring), on a 2-core machine shared"
  echo "with other work, all runs at nice $NICE."
  echo
  echo "## Over the parts"
  echo
  echo "Recall and precision: median and 10th percentile over the parts; errors: median over the parts"
  echo "of each part's median (true positives only; a part without any is left out, \"-\" below);"
  echo "time: median and 95th percentile over every scene."
  echo
  echo "| method | recall, median | recall, p10 | precision, median | precision, p10 | translation error (mm) | rotation error (deg) | time per scene, median (ms) | time per scene, p95 (ms) | scenes |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  for method in "${METHODS[@]}"; do
    rows=$WORK/rows-$method.tsv
    echo "| ${TITLE[$method]} | $(distribution "$rows" 5) | $(distribution "$rows" 4) | $(median_of "$rows" 6) | $(median_of "$rows" 7) | $(scene_times "$method") |"
  done
  for method in "${METHODS[@]}"; do
    echo
    echo "## ${TITLE[$method]}: each part"
    echo
    echo "| part | name | views skipped | precision | recall | median translation error (mm) | median rotation error (deg) | time per scene, median (ms) | time per scene, p95 (ms) |"
    echo "|---|---|---|---|---|---|---|---|---|"
    awk -F'\t' '{
        printf "| %s | %s | %s |", $1, $2, $3
        for (i = 4; i <= 7; ++i) printf " %s |", ($i == "-" ? "-" : sprintf("%.3f", $i))
        for (i = 8; i <= 9; ++i) printf " %s |", ($i == "-" ? "-" : sprintf("%.0f", $i))
        printf "\n" }' "$WORK/rows-$method.tsv"
  done
  if [[ -s $WORK/failures.txt ]]; then
    echo
    echo "Runs that stopped with an error (recall 0 above):"
    echo
    sed 's/^/- /' "$WORK/failures.txt"
  fi
} > "$OUT"
echo "wrote $OUT"
