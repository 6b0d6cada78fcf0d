#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The visualization scripts on a tiny run of a shipped case: the five-grain
# assembly (prm/five_grains_implicit.prm and _explicit.prm) to t = 2 us.
# Checks:
#  - the particle field fringe_order written by grainmpm equals
#    thickness / fringe value times principal_stress_difference (read back
#    through ParaView's own reader);
#  - fringe_pattern.py, render_grains.py, plot_energy.py, force_chains.py
#    and plot_loads.py each answer --help and write a PNG of the requested
#    size that is not blank;
#  - force_chains.py stops with a clear message without contacts.pvd;
#  - fringe_pattern.py stops with a clear message on a run without
#    fringe_order values.
# Usage: scripts_01.sh GRAINMPM SOURCE_DIR WORK_DIR
set -uo pipefail
grainmpm=$1
source_dir=$2
work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1

passed=0
failed=0
check() {
  local name=$1
  shift
  if "$@" > "$name.log" 2>&1; then
    echo "PASS $name"
    passed=$((passed + 1))
  else
    echo "FAIL $name"
    sed 's/^/    /' "$name.log" | tail -20
    failed=$((failed + 1))
  fi
}

for tool in pvbatch Xvfb /usr/bin/python3; do
  if ! command -v "$tool" > /dev/null; then
    echo "FAIL: $tool not found: run scripts/install-dependencies.sh"
    exit 1
  fi
done

# One virtual display for all ParaView calls (several xvfb-run -a in a row
# can race for the same display number); Xvfb picks a free one itself.
# -noreset: by default an X server resets itself whenever its last client
# disconnects, and a pvbatch that connects while the reset is under way
# gets no display or no GLX window (vtkXOpenGLRenderWindow aborts with "bad
# X server connection" or in CreateAWindow). Each pvbatch below is the only
# client, so without -noreset every one of them starts right after a reset.
Xvfb -displayfd 3 -screen 0 1600x1200x24 -nolisten tcp -ac -noreset \
  3> display.txt 2> xvfb.log &
xvfb_pid=$!
trap 'kill $xvfb_pid 2> /dev/null; wait $xvfb_pid 2> /dev/null' EXIT
for _ in $(seq 100); do
  [ -s display.txt ] && break
  sleep 0.1
done
if ! [ -s display.txt ]; then
  echo "FAIL: Xvfb did not start"
  cat xvfb.log
  exit 1
fi
export DISPLAY=":$(head -1 display.txt)"

# pv SCRIPT ARGS: pvbatch on the virtual display.
pv() {
  pvbatch "$@"
}

for scheme in explicit implicit; do
  cat > "$scheme.prm" <<PRM
include $source_dir/prm/five_grains_$scheme.prm
subsection Time stepping
  set End time = 2
end
subsection Output
  set Output directory = results-$scheme
  set Output interval  = 1
  set Test mode        = true
end
PRM
  check "run_$scheme" "$grainmpm" "$scheme.prm"
done

# A PNG of WIDTH x HEIGHT whose pixels are not all alike: dark and bright
# pixels (fringes), or [N] colours (five grains and the background).
cat > not_blank.py <<'PY'
import sys
import matplotlib.image as image
picture = image.imread(sys.argv[1])
height, width = picture.shape[0], picture.shape[1]
if (width, height) != (int(sys.argv[2]), int(sys.argv[3])):
    sys.exit("size %dx%d, expected %sx%s" % (width, height, sys.argv[2], sys.argv[3]))
if len(sys.argv) > 4:
    # Grains: at least N colours that each cover 1 % of the picture.
    colours = {}
    for row in (picture[:, :, :3] * 15).round().astype(int):
        for pixel in row:
            key = tuple(pixel)
            colours[key] = colours.get(key, 0) + 1
    common = [c for c, n in colours.items() if n > 0.01 * width * height]
    print("%d colours cover 1 %% each" % len(common))
    if len(common) < int(sys.argv[4]):
        sys.exit("fewer colours than grains: the picture is blank")
    sys.exit(0)
grey = picture[:, :, :3].mean(axis=2)
spread = float(grey.max() - grey.min())
dark = float((grey < 0.2).mean())
bright = float((grey > 0.8).mean())
print("spread %.3f, dark %.3f, bright %.3f" % (spread, dark, bright))
if spread < 0.5 or dark < 0.01 or bright < 0.01:
    sys.exit("the picture is blank")
PY

# fringe_order = 6.35 / 0.023 * principal_stress_difference.
cat > fields.py <<'PY'
import sys
from paraview import servermanager
from paraview.simple import PVDReader, UpdatePipeline
reader = PVDReader(FileName=sys.argv[1])
UpdatePipeline(time=reader.TimestepValues[-1], proxy=reader)
data = servermanager.Fetch(reader).GetPointData()
order = data.GetArray("fringe_order")
difference = data.GetArray("principal_stress_difference")
factor = 6.35 / 0.023
worst = 0.0
largest = 0.0
for i in range(order.GetNumberOfTuples()):
    largest = max(largest, order.GetValue(i))
    worst = max(worst, abs(order.GetValue(i) - factor * difference.GetValue(i)))
print("largest fringe order %.3g, worst difference %.3g" % (largest, worst))
if not (largest > 0.1 and worst <= 1e-6 * largest):
    sys.exit("fringe_order is not thickness / fringe value x (sigma_1 - sigma_2)")
PY
check fringe_order_field pv fields.py results-implicit/particles.pvd

visualization=$source_dir/visualization
check fringe_help pv "$visualization/fringe_pattern.py" --help
check render_help pv "$visualization/render_grains.py" --help
check plot_help /usr/bin/python3 "$visualization/plot_energy.py" --help

check fringe_pattern pv "$visualization/fringe_pattern.py" \
  results-implicit/particles.pvd --time 2 --output fringe.png --resolution 400 260
check fringe_png /usr/bin/python3 not_blank.py fringe.png 400 260

check render_grains pv "$visualization/render_grains.py" \
  results-explicit/particles.pvd results-implicit/particles.pvd \
  --times 0 2 --labels explicit implicit --output grains.png --panel-size 200 150
check grains_png /usr/bin/python3 not_blank.py grains.png 400 300 6

check plot_energy /usr/bin/python3 "$visualization/plot_energy.py" \
  results-explicit/energy.csv results-implicit/energy.csv \
  --labels explicit implicit --output energy.png
check energy_png /usr/bin/python3 -c "
import matplotlib.image as image, sys
p = image.imread('energy.png'); g = p[:, :, :3].mean(axis=2)
sys.exit(0 if p.shape[1] >= 800 and g.min() < 0.2 and g.max() > 0.8 else 'blank')"

# Force chains over the grains: coloured lines (saturated pixels, which the
# grey grains and the white background are not) on at least 0.1 % of the
# picture.
check force_chains_help pv "$visualization/force_chains.py" --help
check force_chains pv "$visualization/force_chains.py" \
  results-explicit/particles.pvd --times 1 2 --output chains.png --panel-size 300 300
check force_chains_png /usr/bin/python3 -c "
import matplotlib.image as image, sys
p = image.imread('chains.png')[:, :, :3]
if p.shape[:2] != (300, 600): sys.exit('size %s' % (p.shape[:2],))
saturation = p.max(axis=2) - p.min(axis=2)
share = float((saturation > 0.2).mean())
print('coloured share %.4f' % share)
sys.exit(0 if share > 0.001 else 'no force chains drawn')"
check force_chains_refuses_missing bash -c "! pvbatch '$visualization/force_chains.py' results-explicit/particles.pvd --contacts missing.pvd --output none.png > missing.log 2>&1 && grep -q 'Write contacts' missing.log && test ! -e none.png"

# The loads on the walls: the five grains press on the floor.
check plot_loads_help /usr/bin/python3 "$visualization/plot_loads.py" --help
check plot_loads /usr/bin/python3 "$visualization/plot_loads.py" \
  results-explicit/walls.csv results-implicit/walls.csv --load wall_y- \
  --labels explicit implicit --output loads.png
check loads_png /usr/bin/python3 -c "
import matplotlib.image as image, sys
p = image.imread('loads.png'); g = p[:, :, :3].mean(axis=2)
sys.exit(0 if p.shape[1] >= 600 and g.min() < 0.2 and g.max() > 0.8 else 'blank')"

# A run without a fringe value: a clear message, exit code not 0.
sed 's/set Material fringe value = 0.023/set Material fringe value = 0/' \
  "$source_dir/prm/five_grains_implicit.prm" > plain_base.prm
cat > plain.prm <<PRM
include $work/plain_base.prm
subsection Time stepping
  set End time = 1
end
subsection Output
  set Output directory = results-plain
  set Test mode        = true
end
PRM
check run_plain "$grainmpm" plain.prm
check fringe_refuses_zero bash -c "! pvbatch '$visualization/fringe_pattern.py' results-plain/particles.pvd --output none.png > refuse.log 2>&1 && grep -q 'Material fringe value' refuse.log && test ! -e none.png"

echo "$passed passed, $failed failed"
test "$failed" -eq 0
