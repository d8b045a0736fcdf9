#!/usr/bin/env bash
# Regenerates the user guide's screenshots (docs/images/gui-*.png) from the running application:
# the GUI tests drive the real windows under Xvfb and save each workflow's window as
# BUILD_DIR/gui-screenshots/docs/gui-*.png (tests/gui/GuiTestSupport.h saveDocImage); this copies
# them into docs/images. Usage: tests/gui/update-doc-images.sh [BUILD_DIR] (default: build)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build_dir="${1:-$here/build}"
targets=(scanpick test_gui_mainwindow test_gui_workflow test_gui_capture test_gui_depth)
cmake --build "$build_dir" --target "${targets[@]}" --parallel "${JOBS:-2}"
rm -rf "$build_dir/gui-screenshots/docs"
# Failing tests still leave their pictures; the copy below only takes what was written.
xvfb-run -a -s "-screen 0 1600x1200x24" \
  ctest --test-dir "$build_dir" -L gui -R 'WindowFixture|Workflow|Capture|DepthImage' --output-on-failure || true
shopt -s nullglob
images=("$build_dir"/gui-screenshots/docs/gui-*.png)
[ ${#images[@]} -gt 0 ] || { echo "no screenshots were written" >&2; exit 1; }
for f in "${images[@]}"; do
  size=$(stat -c %s "$f")
  [ "$size" -lt 307200 ] || { echo "$f is $size bytes (limit 300 KB)" >&2; exit 1; }
  cp "$f" "$here/docs/images/"
  echo "docs/images/$(basename "$f") ($((size / 1024)) KB)"
done
