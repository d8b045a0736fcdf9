#!/usr/bin/env bash
# scanpick set-up on Debian 12: installs what is missing, builds (Release) and then
#   demo  runs the main job on the bundled demo (default)
#   test  runs every test (ctest; GUI tests in a real X server under xvfb-run)
#   fuzz  builds the fuzz targets with clang and the sanitizers (build-fuzz/) and fuzzes each
#         reader for FUZZ_SECONDS (default 20); `test` ends with it
#   deps  only installs the packages
# Environment: BUILD_DIR (default: build), JOBS (default: number of cores), CI=true adds -Werror.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode="${1:-demo}"
build_dir="${BUILD_DIR:-$here/build}"
jobs="${JOBS:-$(nproc)}"

install_packages() {
  local wanted missing=()
  mapfile -t wanted < <(sed -e 's/#.*//' -e '/^[[:space:]]*$/d' "$here/cmake/packages.txt")
  for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "scanpick: installing ${#missing[@]} missing packages: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

build() {
  local werror=OFF
  [ "${CI:-}" = "true" ] && werror=ON
  cmake -S "$here" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSCANPICK_WERROR="$werror" >/dev/null
  cmake --build "$build_dir" --parallel "$jobs"
}

# The libFuzzer targets (tests/fuzz), built with clang and the sanitizers in their own folder,
# each fuzzed for FUZZ_SECONDS (default 20) from its seeds.
fuzz() {
  local fuzz_dir="${FUZZ_BUILD_DIR:-$here/build-fuzz}"
  CC=clang CXX=clang++ cmake -S "$here" -B "$fuzz_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSCANPICK_FUZZ=ON -DSCANPICK_FUZZ_SECONDS="${FUZZ_SECONDS:-20}" -DSCANPICK_BUILD_GUI=OFF \
    -DSCANPICK_BUILD_DEVICES=OFF -DSCANPICK_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build "$fuzz_dir" --parallel "$jobs" --target fuzz_cloud fuzz_mesh fuzz_model fuzz_json fuzz_multipart fuzz_link
  (cd "$fuzz_dir" && ctest --output-on-failure -L fuzz)
}

case "$mode" in
  deps) install_packages ;;
  demo)
    install_packages
    build
    demo_out="${DEMO_OUT:-$here/demo-output}"
    "$build_dir/bin/scanpick-cli" demo --out "$demo_out"
    # With a display, the desktop application opens on the demo and recognizes the bin there.
    if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && [ -x "$build_dir/bin/scanpick" ]; then
      "$build_dir/bin/scanpick" --scan "$demo_out/demo-bin.pcd" --model "$demo_out/support.spmodel" \
        --model "$demo_out/support-table.spmodel" --recognize ||
        echo "scanpick: the desktop application did not start; the overlay picture is $demo_out/demo-overlay.png"
    else
      echo "scanpick: no display (or no GUI build); the overlay picture is $demo_out/demo-overlay.png"
    fi ;;
  test)
    install_packages
    build
    cd "$build_dir"
    # Everything but the GUI in parallel; the GUI tests one at a time in a real X server.
    ctest --output-on-failure --timeout 900 -j "$jobs" -LE gui
    xvfb-run -a -s "-screen 0 1600x1200x24" ctest --output-on-failure --timeout 900 -L gui
    fuzz ;;
  fuzz)
    install_packages
    fuzz ;;
  *) echo "usage: cmake/setup.sh [demo|test|fuzz|deps]" >&2; exit 2 ;;
esac
