#!/usr/bin/env bash
# tools/results.sh: writes docs/results.md from runs of scanpick-cli on the simulated suites and on
# PCL's sample scans. Every figure on that page comes from the runs below.
#
#   BUILD_DIR=build tools/results.sh
#
# It builds nothing: BUILD_DIR must hold a Release build of bin/scanpick-cli
# (cmake --build BUILD_DIR --target scanpick-cli). It
#   1. writes the suites once (scanpick-cli synth-suite: phoxi-bin, kinect-bin, teach);
#   2. teaches each part's views from the teach suite (scanpick-cli teach --crop-from-truth);
#   3. recognizes every scene of phoxi-bin (without and with ICP) and kinect-bin
#      (scanpick-cli recognize --suite) and scores the results (scanpick-cli eval, strictly and with
#      --accept-free-turns); then the same with the views taught with no preset (the parameters
#      teach derives from the part and the scan);
#   4. times each part's slowest phoxi-bin scene (scanpick-cli bench, views prepared and cold), the
#      teaching and the virtual scanner, and runs the stage benchmarks when they are built
#      (-DSCANPICK_BUILD_BENCHMARKS=ON);
#   5. scores supports varying in shape on a table, the rabbit figure and the milk carton;
#   6. writes docs/results.md from the eval reports, the results files and the bench output.
#
# Environment:
#   BUILD_DIR   build folder with bin/scanpick-cli (default: build)
#   WORK_DIR    suites, models, results and reports (default: BUILD_DIR/results); the suites and
#               the other synthetic scenes are written once and reused
#   OUT         the page written (default: docs/results.md)
#   PCL_DATA    folder with PCL's milk.pcd, milk_cartoon_all_small_clorox.pcd and tum_rabbit.vtk
#               (default: ../shared/data/pcl beside the checkout); without it the rabbit's and the
#               milk carton's tables say so
#   BENCH_RUNS  runs per scanpick-cli bench (default: 5)
# Needs jq. Takes several minutes on two cores. The times it reports are wall times: run it on an
# otherwise idle machine.
# shellcheck disable=SC2016 # backticks in the page text are Markdown, not commands
set -euo pipefail
export LC_ALL=C # printf reads and writes decimal points

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD_DIR=${BUILD_DIR:-build}
[[ $BUILD_DIR == /* ]] || BUILD_DIR=$PWD/$BUILD_DIR
CLI=$BUILD_DIR/bin/scanpick-cli
WORK=${WORK_DIR:-$BUILD_DIR/results}
[[ $WORK == /* ]] || WORK=$PWD/$WORK
OUT=${OUT:-$ROOT/docs/results.md}
[[ $OUT == /* ]] || OUT=$PWD/$OUT
PCL_DATA=${PCL_DATA:-$ROOT/../shared/data/pcl}
[[ $PCL_DATA == /* ]] || PCL_DATA=$PWD/$PCL_DATA
BENCH_RUNS=${BENCH_RUNS:-5}

if [[ ! -x $CLI ]]; then
  echo "results.sh: $CLI not found: build it first (cmake --build $BUILD_DIR --target scanpick-cli)" >&2
  exit 1
fi
if ! command -v jq > /dev/null; then
  echo "results.sh: jq not found: install it (apt-get install jq)" >&2
  exit 1
fi
cd "$ROOT" # scanpick-cli finds presets by name under resources/presets of the current folder
mkdir -p "$WORK"
SUITES=$WORK/suites
PHOXI=phoxi-m-1032
KINECT=kinect-v1
PARTS=(support pump-connector coat-rack cup)

log() { echo "results.sh: $*" >&2; }
now_ms() { echo $(($(date +%s%N) / 1000000)); }

# ---------------------------------------------------------------------------------------------
# What each part is taught and recognized with.

# The preset every part is taught and recognized with on a sensor: the sensor family's own.
sensor_preset() { # sensor
  case $1 in
    "$PHOXI") echo phoxi-bin ;;
    "$KINECT") echo kinect-bin ;;
  esac
}

# The views (teach suite scans) of a part: one per side it rests on, and on the PhoXi the view cut
# from a bin scan (not for the pump-connector, whose four table views find every instance).
part_views() { # sensor part
  local views="$2 $2-side1 $2-side2 $2-side3"
  [[ $1 == "$PHOXI" && $2 != pump-connector ]] && views+=" $2-bin"
  echo "$views"
}

# --model arguments for a part's views, one per line.
model_args() { # sensor-or-derived-sensor part
  local view
  for view in $(part_views "${1#derived-}" "$2"); do
    printf -- '--model\n%s\n' "$WORK/models/$1/$view.spmodel"
  done
}

# ---------------------------------------------------------------------------------------------
# 1. Suites

if [[ ! -f $SUITES/phoxi-bin/scene-023.gt.json || ! -f $SUITES/kinect-bin/scene-011.gt.json ||
  ! -d $SUITES/teach/$KINECT ]]; then
  log "writing the suites (synth-suite)"
  "$CLI" synth-suite --out "$SUITES" > "$WORK/synth-suite.log"
fi

# ---------------------------------------------------------------------------------------------
# 2. Teaching

TEACH_MS=$WORK/teach-ms.txt
: > "$TEACH_MS"
for sensor in "$PHOXI" "$KINECT"; do
  mkdir -p "$WORK/models/$sensor"
  for part in "${PARTS[@]}"; do
    preset=$(sensor_preset "$sensor")
    for view in $(part_views "$sensor" "$part"); do
      log "teaching $sensor/$view ($preset)"
      T=$SUITES/teach/$sensor
      t0=$(now_ms)
      "$CLI" teach --scan "$T/$view.pcd" --crop-from-truth "$T/$view.gt.json" --remove-floor \
        --sensor "$sensor" --preset "$preset" --name "$part" \
        --out "$WORK/models/$sensor/$view.spmodel" > "$WORK/models/$sensor/$view.log"
      echo "$sensor $(($(now_ms) - t0))" >> "$TEACH_MS"
    done
  done
done

# The same views taught with no preset: every value derived from the part and the scan.
for sensor in "$PHOXI" "$KINECT"; do
  mkdir -p "$WORK/models/derived-$sensor"
  for part in "${PARTS[@]}"; do
    for view in $(part_views "$sensor" "$part"); do
      log "teaching $sensor/$view (derived)"
      T=$SUITES/teach/$sensor
      "$CLI" teach --scan "$T/$view.pcd" --crop-from-truth "$T/$view.gt.json" --remove-floor \
        --sensor "$sensor" --name "$part" --out "$WORK/models/derived-$sensor/$view.spmodel" \
        > "$WORK/models/derived-$sensor/$view.log"
    done
  done
done

# ---------------------------------------------------------------------------------------------
# 3. Recognition and evaluation on the suites

# Recognizes every scene of a suite with a part's views and scores the results strictly and with
# the reported turns and alternatives accepted: RESULTS/SUITE/NAME/ (results files),
# NAME.strict.json and NAME.accepted.json (eval reports).
# With name NAME-derived, the views taught with no preset, recognized with their parameters.
run_suite() { # suite sensor part name [recognize options...]
  local suite=$1 sensor=$2 part=$3 name=$4
  shift 4
  local res=$WORK/results/$suite/$name models recipe
  if [[ $name == *-derived ]]; then
    mapfile -t models < <(model_args "derived-$sensor" "$part")
    recipe=()
  else
    mapfile -t models < <(model_args "$sensor" "$part")
    recipe=(--preset "$(sensor_preset "$sensor")")
  fi
  log "recognizing $suite with the $part's views ($name)"
  rm -rf "$res"
  mkdir -p "$res"
  "$CLI" recognize --suite "$SUITES/$suite" "${models[@]}" "${recipe[@]}" "$@" --out "$res" \
    > "$res.log"
  "$CLI" eval --suite "$SUITES/$suite" --results "$res" --json "$res.strict.json" > "$res.strict.txt"
  "$CLI" eval --suite "$SUITES/$suite" --results "$res" --accept-free-turns \
    --json "$res.accepted.json" > "$res.accepted.txt"
}

for part in "${PARTS[@]}"; do
  run_suite phoxi-bin "$PHOXI" "$part" "$part"
  run_suite phoxi-bin "$PHOXI" "$part" "$part-icp" --set refine.enabled=true
  run_suite kinect-bin "$KINECT" "$part" "$part"
  run_suite phoxi-bin "$PHOXI" "$part" "$part-derived"
  run_suite kinect-bin "$KINECT" "$part" "$part-derived"
done

# ---------------------------------------------------------------------------------------------
# 4. Speed

mkdir -p "$WORK/bench"
for part in "${PARTS[@]}"; do
  report=$WORK/results/phoxi-bin/$part.accepted.json
  scene=$(jq -r '.scenes | map(select(.total_ms != null)) | max_by(.total_ms) | .name' "$report")
  echo "$scene" > "$WORK/bench/$part.scene"
  mapfile -t models < <(model_args "$PHOXI" "$part")
  preset=$(sensor_preset "$PHOXI")
  log "bench: the $part's slowest scene, $scene"
  "$CLI" bench "${models[@]}" --scene "$SUITES/phoxi-bin/$scene.pcd" --preset "$preset" \
    --runs "$BENCH_RUNS" --prepare > "$WORK/bench/$part.prepared.txt"
  "$CLI" bench "${models[@]}" --scene "$SUITES/phoxi-bin/$scene.pcd" --preset "$preset" \
    --runs "$BENCH_RUNS" > "$WORK/bench/$part.cold.txt"
done

# The stage benchmarks (Google Benchmark), when BUILD_DIR was configured with
# -DSCANPICK_BUILD_BENCHMARKS=ON.
MICRO=()
for b in bench_core_stages bench_refine bench_voting; do
  if [[ -x $BUILD_DIR/bin/$b ]]; then
    log "$b"
    "$BUILD_DIR/bin/$b" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
      --benchmark_format=json > "$WORK/bench/$b.json"
    MICRO+=("$b")
  fi
done

mkdir -p "$WORK/synth"
: > "$WORK/synth-ms.txt"
for part in "${PARTS[@]}"; do
  t0=$(now_ms)
  "$CLI" synth --part "$part" --count 10 --sensor "$PHOXI" --seed 1 --out "$WORK/synth/$part" \
    > /dev/null
  echo "$part $(($(now_ms) - t0))" >> "$WORK/synth-ms.txt"
done

# ---------------------------------------------------------------------------------------------
# 5. Parts on a table varying in shape, the rabbit figure, the milk carton

DEFORMATIONS=(0 0.02 0.05 0.1)
for F in "${DEFORMATIONS[@]}"; do
  dir=$WORK/deformed/F$F
  if [[ ! -f $dir/scene-004.gt.json ]]; then
    log "synth: supports on a table varying by $F"
    mkdir -p "$dir"
    for S in 0 1 2 3 4; do
      "$CLI" synth --part support --layout scatter --count 6 --seed "$S" --deform "$F" \
        --out "$dir/scene-00$S" > /dev/null
    done
  fi
  res=$WORK/results/deformed/F$F
  rm -rf "$res"
  mkdir -p "$res"
  models=()
  for view in support support-side1 support-side2 support-side3; do
    models+=(--model "$WORK/models/$PHOXI/$view.spmodel")
  done
  "$CLI" recognize --suite "$dir" "${models[@]}" --preset phoxi-bin \
    --set floor.bin_floor_fraction=0 --out "$res" > "$res.log"
  "$CLI" eval --suite "$dir" --results "$res" --teach-truth "$SUITES/teach/$PHOXI" \
    --json "$res.strict.json" > "$res.strict.txt"
done

RABBIT=$PCL_DATA/tum_rabbit.vtk
RABBIT_PRESETS=(kinect kinect-bin)
if [[ -f $RABBIT ]]; then
  dir=$WORK/rabbit
  if [[ ! -f $dir/scenes/scene-009.gt.json ]]; then
    log "synth: the rabbit figure with a Kinect"
    mkdir -p "$dir/teach" "$dir/scenes"
    for S in 1 2; do
      "$CLI" synth --mesh "$RABBIT" --close-holes --layout teach --teach-side "$S" --count 1 \
        --sensor "$KINECT" --out "$dir/teach/rabbit-side$S" > /dev/null
    done
    "$CLI" synth --mesh "$RABBIT" --close-holes --layout scatter --count 1 --seed 102 \
      --sensor "$KINECT" --out "$dir/teach/rabbit-dropped" > /dev/null
    for N in 0 1 2 3 4 5 6 7; do
      "$CLI" synth --mesh "$RABBIT" --close-holes --layout scatter --count 3 --seed $((N + 1)) \
        --sensor "$KINECT" --out "$dir/scenes/scene-00$N" > /dev/null
    done
    for N in 8 9; do
      "$CLI" synth --mesh "$RABBIT" --close-holes --layout bin --count 5 --seed "$N" \
        --sensor "$KINECT" --out "$dir/scenes/scene-00$N" > /dev/null
    done
  fi
  for P in "${RABBIT_PRESETS[@]}"; do
    mkdir -p "$dir/models/$P"
    for S in 1 2; do
      "$CLI" teach --scan "$dir/teach/rabbit-side$S.pcd" \
        --crop-from-truth "$dir/teach/rabbit-side$S.gt.json" --remove-floor --sensor "$KINECT" \
        --preset "$P" --name tum_rabbit --out "$dir/models/$P/rabbit-side$S.spmodel" > /dev/null
    done
    # The rabbit dropped on the table, resting in the third way: cut out by its box.
    "$CLI" teach --scan "$dir/teach/rabbit-dropped.pcd" \
      --crop-box=-109.3,-124.1,799.3,169.9,93.6,1078.3 --remove-floor --sensor "$KINECT" \
      --preset "$P" --name tum_rabbit --out "$dir/models/$P/rabbit-dropped.spmodel" > /dev/null
    res=$WORK/results/rabbit/$P
    rm -rf "$res"
    mkdir -p "$res"
    "$CLI" recognize --suite "$dir/scenes" --model "$dir/models/$P/rabbit-side1.spmodel" \
      --model "$dir/models/$P/rabbit-side2.spmodel" --model "$dir/models/$P/rabbit-dropped.spmodel" \
      --preset "$P" --out "$res" > "$res.log"
    "$CLI" eval --suite "$dir/scenes" --results "$res" --teach-truth "$dir/teach" \
      --teach-truth "$dir/teach/rabbit-dropped.gt.json" --json "$res.strict.json" > "$res.strict.txt"
  done
fi

MILK=$WORK/results/milk.json
rm -f "$MILK"
if [[ -f $PCL_DATA/milk.pcd && -f $PCL_DATA/milk_cartoon_all_small_clorox.pcd ]]; then
  log "the milk carton"
  mkdir -p "$WORK/results"
  "$CLI" teach --scan "$PCL_DATA/milk.pcd" --units m \
    --crop-box=-100000,-100000,-100000,100000,100000,100000 --name milk \
    --out "$WORK/models/milk.spmodel" > /dev/null
  "$CLI" recognize --model "$WORK/models/milk.spmodel" \
    --scene "$PCL_DATA/milk_cartoon_all_small_clorox.pcd" --units m --out "$MILK" \
    > "$WORK/results/milk.log"
fi

# ---------------------------------------------------------------------------------------------
# 6. The page

# A number as the page prints it; "–" for null or nothing.
num() { # printf-format value
  # shellcheck disable=SC2059 # the format is the caller's
  if [[ -z ${2:-} || $2 == null ]]; then printf '–'; else printf "$1" "$2"; fi
}
# A field of an eval report's overall summary (jq path after .overall).
ov() { # report path
  jq -r ".overall | $2 | if . == null then \"null\" else . end" "$1"
}
# A statistic of an eval report's overall summary, null when it counts nothing.
st() { # report stats-name field (median, p95, max)
  ov "$1" "(.$2 | if .count == 0 then null else .$3 end)"
}
# Whether an awk condition on the given variables holds: holds 'p>=0.98' p=0.99
holds() { # condition name=value...
  local condition=$1
  shift
  local args=()
  for kv in "$@"; do args+=(-v "$kv"); done
  awk "${args[@]}" "BEGIN { exit !($condition) }"
}
# The median wall time (ms) of a row of scanpick-cli bench's table.
bench_row() { # file row
  awk -F'|' -v row="$2" 'index($2, " " row) == 1 { gsub(/ /, "", $3); print $3 }' "$1"
}
# Median / largest of the numbers on stdin.
median_of() { sort -n | awk '{ v[NR] = $1 } END { if (NR) print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
max_of() { sort -n | tail -1; }
# The largest refine stage (ms) over a folder of results files.
refine_max() { jq -s 'map(.timings_ms.refine) | max' "$1"/scene-*.json; }

R=$WORK/results/phoxi-bin
K=$WORK/results/kinect-bin

phoxi_goal() { # part: the bin goal's status for one part
  local s=$R/$1.strict.json a=$R/$1.accepted.json
  local check='p >= 0.98 && r >= 0.90 && t <= 1.0 && d <= 2.0'
  if holds "$check" p="$(ov "$s" .precision)" r="$(ov "$s" .recall)" \
    t="$(st "$s" translation_error_mm median)" d="$(st "$s" rotation_error_deg median)"; then
    echo "met strictly"
  elif holds "$check" p="$(ov "$a" .precision)" r="$(ov "$a" .recall)" \
    t="$(st "$a" translation_error_mm median)" d="$(st "$a" rotation_error_deg median)"; then
    echo "met with the reported turns and alternatives accepted"
  else
    echo "not met"
  fi
}

teach_max=$(awk -v s="$PHOXI" '$1 == s { print $2 }' "$TEACH_MS" | max_of)
all_medians=() all_p95=() all_max=() icp_medians=()
for part in "${PARTS[@]}"; do
  all_medians+=("$(st "$R/$part.accepted.json" time_per_scene_ms median)")
  all_p95+=("$(st "$R/$part.accepted.json" time_per_scene_ms p95)")
  all_max+=("$(st "$R/$part.accepted.json" time_per_scene_ms max)")
  icp_medians+=("$(st "$R/$part-icp.accepted.json" translation_error_mm median)")
done
scene_max=$(printf '%s\n' "${all_max[@]}" | max_of)
cold_max=$(for part in "${PARTS[@]}"; do bench_row "$WORK/bench/$part.cold.txt" total; done | max_of)
median_max=$(printf '%s\n' "${all_medians[@]}" | max_of)
p95_max=$(printf '%s\n' "${all_p95[@]}" | max_of)
icp_max=$(printf '%s\n' "${icp_medians[@]}" | max_of)
met_if() { if holds "$1" "${@:2}"; then echo met; else echo "not met"; fi; }

commit=$(git -C "$ROOT" rev-parse --short HEAD 2> /dev/null || echo unknown)
git -C "$ROOT" diff --quiet HEAD 2> /dev/null || commit+=" with uncommitted changes"
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)

{
  cat << EOF
# Results

Current figures of scanpick on the simulated suites of \`scanpick-cli synth-suite\` and on PCL's
sample scans. The whole page is written by one command, from a Release build of \`scanpick-cli\`:

\`\`\`sh
BUILD_DIR=build tools/results.sh
\`\`\`

It writes the suites, teaches each part's views, recognizes every scene, scores the results with
\`scanpick-cli eval\`, times the slowest scenes with \`scanpick-cli bench\` and writes this page
from their reports (the script's header lists each step). How the figures are measured:
[accuracy.md](accuracy.md) and [benchmarks.md](benchmarks.md); why the mechanisms behind them
exist: [design notes](design-notes.md).

Last written from commit $commit on $(nproc) cores (${cpu:-unknown CPU}).

**Strictly** scores each detection's pose as reported. **Accepted** (\`eval --accept-free-turns\`)
also counts a detection right when the truth is one of the poses it reports as not told apart by
the scan: any turn about its \`free_turn_axis\` (a pump-connector lying on its side, a cup whose
handle is hidden) or one of its \`alternative_poses\` (a coat-rack seen from below). Recall counts
instances at least 50 % visible; a detection is right within 0.1 × the part's diameter and 10°,
symmetry-aware ([evaluation.md](evaluation.md)).

## Goals

| goal | status |
|---|---|
EOF
  printf '| PhoXi bins: precision ≥ 0.98, recall ≥ 0.90, median error ≤ 1 mm and ≤ 2° before ICP |'
  for part in "${PARTS[@]}"; do
    printf ' %s: %s (strictly %s / %s, accepted %s / %s).' "$part" "$(phoxi_goal "$part")" \
      "$(num %.3f "$(ov "$R/$part.strict.json" .precision)")" \
      "$(num %.3f "$(ov "$R/$part.strict.json" .recall)")" \
      "$(num %.3f "$(ov "$R/$part.accepted.json" .precision)")" \
      "$(num %.3f "$(ov "$R/$part.accepted.json" .recall)")"
  done
  printf ' |\n'
  printf '| a PhoXi 1032 × 772 scene in ≤ 2 s | %s: the slowest scene of the suite %s ms with the views prepared at load; a fresh recognizer that prepares the views with the slowest scene at most %s ms (`bench`, cold) |\n' \
    "$(met_if 's <= 2000 && c <= 2000' s="$scene_max" c="$cold_max")" \
    "$(num %.0f "$scene_max")" "$(num %.0f "$cold_max")"
  printf '| teaching a view in ≤ 1 s | %s: at most %s ms per view (the whole `teach` process) |\n' \
    "$(met_if 't <= 1000' t="$teach_max")" "$(num %.0f "$teach_max")"
  printf '| design goal: 300 ms per scene | median: %s (at most %s ms); 95th percentile: %s (at most %s ms) |\n' \
    "$(met_if 'm <= 300' m="$median_max")" "$(num %.0f "$median_max")" \
    "$(met_if 'p <= 300' p="$p95_max")" "$(num %.0f "$p95_max")"
  printf '| sub-0.1 mm poses after refinement (median origin error, `refine.enabled`) | %s:' \
    "$(met_if 'e <= 0.1' e="$icp_max")"
  for i in "${!PARTS[@]}"; do
    printf ' %s %s mm%s' "${PARTS[$i]}" "$(num %.3f "${icp_medians[$i]}")" \
      "$([[ $i -lt $((${#PARTS[@]} - 1)) ]] && echo , || echo)"
  done
  printf ' |\n'
  cat << 'EOF'
| ideal test, 1 mm noise: ≥ 9 of 12 poses | checked by tests/integration/IdealRecognitionTest.cpp: at least 11 of 12 with verification on; the thesis's set-up (feature score only) finds 7 |
| the real milk carton found exactly once, ≥ 80 % of the model within 5 mm | checked by tests/integration/RealMilkTest.cpp; the detection below |
| several part types in one scene: only the taught type reported | checked by tests/integration/MixedPartsTest.cpp; on phoxi-bin every part runs on the mixed bins too, and a detection of another part counts as false |
| repeatability | checked by tests/unit/pipeline/RecognizerTest.cpp, tests/integration/SurfaceVotingTest.cpp and tests/integration/CliRepeatabilityTest.cpp (two `recognize` runs give byte-identical results but for their times) |

## Bin picking with a PhoXi M (phoxi-bin)

24 simulated bins (PhoXi M 1032 × 772): five of each part and four of all four mixed. Each part
runs on all 24 scenes. Its views are taught from the teach suite with `--crop-from-truth` (which
also stores each view's place in the part, so `recognize` joins them): one per side the part
rests on and, but for the pump-connector, one cut from a bin scan. Every part is taught and
recognized with the PhoXi preset `phoxi-bin`, no part's own parameters.

Produced by `scanpick-cli recognize --suite suites/phoxi-bin --model VIEW.spmodel … --preset
phoxi-bin --out res/PART` and `scanpick-cli eval --suite suites/phoxi-bin --results res/PART --json
PART.strict.json`, again with `--accept-free-turns`. Without ICP (`refine.enabled` off):

| part | views, preset | detections | strictly: right / precision / recall | accepted: right / precision / recall / R@P99 | median / p95 / max origin error (mm) | median / p95 rotation error (°) | median / p95 grip error (mm) |
|---|---|---|---|---|---|---|---|
EOF
  for part in "${PARTS[@]}"; do
    s=$R/$part.strict.json
    a=$R/$part.accepted.json
    n=$(part_views "$PHOXI" "$part" | wc -w)
    printf '| %s | %s, `%s` | %s | %s / %s / %s | %s / %s / %s / %s | %s / %s / %s | %s / %s | %s / %s |\n' \
      "$part" "$n" "$(sensor_preset "$PHOXI")" "$(ov "$s" .detections)" \
      "$(ov "$s" .true_positives)" "$(num %.3f "$(ov "$s" .precision)")" \
      "$(num %.3f "$(ov "$s" .recall)")" \
      "$(ov "$a" .true_positives)" "$(num %.3f "$(ov "$a" .precision)")" \
      "$(num %.3f "$(ov "$a" .recall)")" "$(num %.3f "$(ov "$a" .recall_at_99_precision)")" \
      "$(num %.3f "$(st "$a" translation_error_mm median)")" \
      "$(num %.2f "$(st "$a" translation_error_mm p95)")" \
      "$(num %.2f "$(st "$a" translation_error_mm max)")" \
      "$(num %.3f "$(st "$a" rotation_error_deg median)")" \
      "$(num %.2f "$(st "$a" rotation_error_deg p95)")" \
      "$(num %.3f "$(st "$a" grip_error_mm median)")" \
      "$(num %.2f "$(st "$a" grip_error_mm p95)")"
  done
  read -r visible recalled detections right < <(jq -rs \
    'map(.overall) | [(map(.visible_instances) | add), (map(.recalled_visible_instances) | add),
     (map(.detections) | add), (map(.true_positives) | add)] | @tsv' \
    "$R"/{support,pump-connector,coat-rack,cup}.accepted.json)
  printf '\nAll four parts, accepted: %s of %s visible instances found; %s of %s detections right.\n' \
    "$recalled" "$visible" "$right" "$detections"
  cat << 'EOF'

With ICP: the same with `--set refine.enabled=true` added to `recognize` (the detections are those
found without it; the refine stage's time is `timings_ms.refine` of the results files):

| part | accepted: median / p95 / max origin error (mm) | median rotation error (°) | strictly right: median origin error (mm) | refine stage, largest per scene (ms) |
|---|---|---|---|---|
EOF
  for part in "${PARTS[@]}"; do
    a=$R/$part-icp.accepted.json
    s=$R/$part-icp.strict.json
    printf '| %s | %s / %s / %s | %s | %s | %s |\n' "$part" \
      "$(num %.3f "$(st "$a" translation_error_mm median)")" \
      "$(num %.2f "$(st "$a" translation_error_mm p95)")" \
      "$(num %.2f "$(st "$a" translation_error_mm max)")" \
      "$(num %.3f "$(st "$a" rotation_error_deg median)")" \
      "$(num %.3f "$(st "$s" translation_error_mm median)")" \
      "$(num %.0f "$(refine_max "$R/$part-icp")")"
  done
  cat << 'EOF'

## Bin picking with a Kinect v1 (kinect-bin)

12 simulated bins (Kinect v1 640 × 480, camera 1.1 m above the floor), each part on all 12; four
table views per part, preset `kinect-bin` (surface voting, no lines or circles). Produced
by `scanpick-cli recognize --suite suites/kinect-bin …` and `scanpick-cli eval` as above; strictly.

| part | detections | right | precision | recall | median origin error (mm) | median rotation error (°) | median / p95 time per scene (ms) |
|---|---|---|---|---|---|---|---|
EOF
  for part in "${PARTS[@]}"; do
    s=$K/$part.strict.json
    printf '| %s | %s | %s | %s | %s | %s | %s | %s / %s |\n' "$part" "$(ov "$s" .detections)" \
      "$(ov "$s" .true_positives)" "$(num %.3f "$(ov "$s" .precision)")" \
      "$(num %.3f "$(ov "$s" .recall)")" \
      "$(num %.2f "$(st "$s" translation_error_mm median)")" \
      "$(num %.2f "$(st "$s" rotation_error_deg median)")" \
      "$(num %.0f "$(st "$s" time_per_scene_ms median)")" \
      "$(num %.0f "$(st "$s" time_per_scene_ms p95)")"
  done
  cat << 'EOF'

## With no preset

The same views taught with no preset (`teach` without `--preset`: every value derived from the
part and the scan, [user guide](user-guide.md#parameters-derived-at-teach)), recognized with the
parameters stored in the first view (`recognize` without `--preset`); strictly and accepted as
above.

| suite | part | detections | strictly: right / precision / recall | accepted: precision / recall | accepted: median origin error (mm) | median time per scene (ms) |
|---|---|---|---|---|---|---|
EOF
  for suite in phoxi-bin kinect-bin; do
    for part in "${PARTS[@]}"; do
      s=$WORK/results/$suite/$part-derived.strict.json
      a=$WORK/results/$suite/$part-derived.accepted.json
      printf '| %s | %s | %s | %s / %s / %s | %s / %s | %s | %s |\n' "$suite" "$part" \
        "$(ov "$s" .detections)" "$(ov "$s" .true_positives)" \
        "$(num %.3f "$(ov "$s" .precision)")" "$(num %.3f "$(ov "$s" .recall)")" \
        "$(num %.3f "$(ov "$a" .precision)")" "$(num %.3f "$(ov "$a" .recall)")" \
        "$(num %.3f "$(st "$a" translation_error_mm median)")" \
        "$(num %.0f "$(st "$s" time_per_scene_ms median)")"
    done
  done
  cat << 'EOF'

## Speed

phoxi-bin without ICP. *Per scene*: `eval`'s time per scene, the views prepared once at load
(`recognize` prints the preparation). *Slowest scene*: the suite's slowest scene of the part in
`scanpick-cli bench --runs N`, the median of N runs with a fresh recognizer each; *prepared* with
`--prepare` (as a cell that prepared its views at load), *cold* without (the views prepared with
the scene).

| part | views prepared at load (ms) | per scene: median / p95 / max (ms) | slowest scene | its total, prepared / cold (ms) |
|---|---|---|---|---|
EOF
  for part in "${PARTS[@]}"; do
    a=$R/$part.accepted.json
    prep=$(sed -n 's/^prepared [0-9]* view(s) in \([0-9.]*\) ms.*/\1/p' "$R/$part.log" | head -1)
    printf '| %s | %s | %s / %s / %s | %s | %s / %s |\n' "$part" "$(num %.0f "$prep")" \
      "$(num %.0f "$(st "$a" time_per_scene_ms median)")" \
      "$(num %.0f "$(st "$a" time_per_scene_ms p95)")" \
      "$(num %.0f "$(st "$a" time_per_scene_ms max)")" "$(cat "$WORK/bench/$part.scene")" \
      "$(num %.0f "$(bench_row "$WORK/bench/$part.prepared.txt" total)")" \
      "$(num %.0f "$(bench_row "$WORK/bench/$part.cold.txt" total)")"
  done
  printf '\nStages of the slowest scenes, views prepared (median wall ms of `bench --prepare`):\n\n'
  printf '| part | preprocess | clustering | keypoints | features | matching (+ verification, merge) | total |\n|---|---|---|---|---|---|---|\n'
  for part in "${PARTS[@]}"; do
    b=$WORK/bench/$part.prepared.txt
    printf '| %s |' "$part"
    for row in preprocess clustering keypoints features matching total; do
      printf ' %s |' "$(num %.0f "$(bench_row "$b" "$row")")"
    done
    printf '\n'
  done
  printf '\nTeaching a PhoXi view (the whole `teach` process, loading and writing included): median %s ms, at most %s ms.\n' \
    "$(awk -v s="$PHOXI" '$1 == s { print $2 }' "$TEACH_MS" | median_of)" "$(num %.0f "$teach_max")"
  printf '\nThe virtual scanner, a PhoXi M 1032 × 772 bin of ten parts (`scanpick-cli synth --part P --count 10 --seed 1`, the whole process):'
  awk '{ printf "%s %s %.1f s", (NR > 1 ? "," : ""), $1, $2 / 1000 } END { print "." }' \
    "$WORK/synth-ms.txt"
  cat << 'EOF'

Stage benchmarks: Google Benchmark programs on synthetic scenes made in code, each stage alone
([benchmarks.md](benchmarks.md#stage-benchmarks) says what each measures); the median of 5
repetitions of `PROGRAM --benchmark_repetitions=5 --benchmark_report_aggregates_only=true`.

EOF
  if ((${#MICRO[@]})); then
    printf '| program | benchmark | wall (ms) | CPU (ms) |\n|---|---|---|---|\n'
    for b in "${MICRO[@]}"; do
      jq -r --arg b "$b" '.benchmarks[] | select(.aggregate_name == "median")
        | "| \($b) | `\(.run_name)` | \(.real_time * 100 | round / 100) | \(.cpu_time * 100 | round / 100) |"' \
        "$WORK/bench/$b.json"
    done
  else
    printf 'Not run: these programs are built when BUILD_DIR is configured with `-DSCANPICK_BUILD_BENCHMARKS=ON`.\n'
  fi
  cat << 'EOF'

## Parts on a table varying in shape

Supports scattered on a table, six per scene, five scenes per row (`synth --part support --layout
scatter --count 6 --seed 0..4 --deform F`: each instance stretched, sheared and bent by up to F),
searched with the four table views taught from the part as designed, preset `phoxi-bin` with
`--set floor.bin_floor_fraction=0` (a table, not a bin), scored against the design by `scanpick-cli eval --suite DIR --results RES
--teach-truth suites/teach/phoxi-m-1032`; strictly.

| deformation F | detections | right | precision | recall | median / p95 origin error (mm) | median / p95 rotation error (°) |
|---|---|---|---|---|---|---|
EOF
  for F in "${DEFORMATIONS[@]}"; do
    s=$WORK/results/deformed/F$F.strict.json
    printf '| %s | %s | %s | %s | %s | %s / %s | %s / %s |\n' "$F" "$(ov "$s" .detections)" \
      "$(ov "$s" .true_positives)" "$(num %.3f "$(ov "$s" .precision)")" \
      "$(num %.3f "$(ov "$s" .recall)")" \
      "$(num %.3f "$(st "$s" translation_error_mm median)")" \
      "$(num %.3f "$(st "$s" translation_error_mm p95)")" \
      "$(num %.3f "$(st "$s" rotation_error_deg median)")" \
      "$(num %.3f "$(st "$s" rotation_error_deg p95)")"
  done
  cat << 'EOF'

## The rabbit figure with a Kinect v1

PCL's scanned rabbit figure (`tum_rabbit.vtk`, capped by `synth --close-holes`) scanned by the
simulated Kinect v1 from 1 m: eight scatters of three rabbits on a table and two bins of five.
Three views: lying, standing, and one dropped on the table resting the third way. The thesis's
set-up (`kinect`, its table 5.6: lines and circles) against surface voting (`kinect-bin`);
`scanpick-cli recognize --suite` and `scanpick-cli eval` as above, strictly.

| preset | detections | right | precision | recall | median origin error (mm) | median rotation error (°) | median time per scene (ms) |
|---|---|---|---|---|---|---|---|
EOF
  if [[ -f $RABBIT ]]; then
    for P in "${RABBIT_PRESETS[@]}"; do
      s=$WORK/results/rabbit/$P.strict.json
      printf '| `%s` | %s | %s | %s | %s | %s | %s | %s |\n' "$P" "$(ov "$s" .detections)" \
        "$(ov "$s" .true_positives)" "$(num %.3f "$(ov "$s" .precision)")" \
        "$(num %.3f "$(ov "$s" .recall)")" \
        "$(num %.2f "$(st "$s" translation_error_mm median)")" \
        "$(num %.2f "$(st "$s" rotation_error_deg median)")" \
        "$(num %.0f "$(st "$s" time_per_scene_ms median)")"
    done
  else
    printf '| not run: %s not found | | | | | | | |\n' "$RABBIT"
  fi
  cat << 'EOF'

## The milk carton (a real Kinect v1 scan)

PCL's `milk.pcd` taught whole with no preset and no sensor (`teach --units m`: every value derived
from the scan and the carton) and searched in `milk_cartoon_all_small_clorox.pcd` (organized 640 ×
480) by `scanpick-cli recognize --scene … --units m`; the figures are those of its results file.

EOF
  if [[ -f $MILK ]]; then
    printf '| detections | best score | total time (ms) | of it, features (ms) |\n|---|---|---|---|\n'
    printf '| %s | %s | %s | %s |\n' "$(jq '.detections | length' "$MILK")" \
      "$(num %.3f "$(jq -r '.detections[0].score // "null"' "$MILK")")" \
      "$(num %.0f "$(jq -r '.timings_ms.total' "$MILK")")" \
      "$(num %.0f "$(jq -r '.timings_ms.features' "$MILK")")"
  else
    printf 'Not run: PCL'"'"'s milk scans not found in %s.\n' "$PCL_DATA"
  fi
} > "$OUT.tmp"
mv "$OUT.tmp" "$OUT"
log "wrote $OUT"
