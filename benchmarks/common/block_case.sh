# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The elastic block of build/benchmarks/explicit_step as a .prm case. Source
# it.

# write_block_case FILE DIM CELLS PER_DIR KERNEL STEPS OUTPUT_DIRECTORY:
# write to FILE the cells inside [0.25, 0.75]^DIM of a CELLS^DIM grid on the
# unit square (cube), PER_DIR^DIM points per cell with the shape functions
# KERNEL, linear elastic (E = 1000, nu = 0.3, rho = 1, plane strain in 2D),
# initial velocity 0.1 along x, gravity -1 along y, free-slip walls, USF,
# a time step of 0.1 h / c (c: the P-wave speed), STEPS steps, output only
# at the end.
write_block_case() {
  local file=$1 dim=$2 cells=$3 per_dir=$4 kernel=$5 steps=$6 output=$7
  local dt lower upper n_cells walls gravity physics block
  dt=$(awk 'BEGIN { E = 1000; nu = 0.3; rho = 1;
    c = sqrt(E * (1 - nu) / ((1 + nu) * (1 - 2 * nu) * rho));
    printf "%.12g", 0.1 / '"$cells"' / c }')
  if [ "$dim" = 3 ]; then
    lower="0, 0, 0"; upper="1, 1, 1"; n_cells="$cells, $cells, $cells"
    walls="x-: free slip, x+: free slip, y-: free slip, y+: free slip, z-: free slip, z+: free slip"
    gravity="0, -1, 0"; physics=""
    block="set Shape = box\n    set Centre = 0.5, 0.5, 0.5\n    set Size = 0.5, 0.5, 0.5\n    set Initial velocity = 0.1; 0; 0"
  else
    lower="0, 0"; upper="1, 1"; n_cells="$cells, $cells"
    walls="x-: free slip, x+: free slip, y-: free slip, y+: free slip"
    gravity="0, -1"; physics="\n  set Two-dimensional model = plane strain"
    block="set Shape = rectangle\n    set Centre = 0.5, 0.5\n    set Size = 0.5, 0.5\n    set Initial velocity = 0.1; 0"
  fi
  cat > "$file" <<EOF
set Dimension = $dim
subsection Background grid
  set Lower corner        = $lower
  set Upper corner        = $upper
  set Number of cells     = $n_cells
  set Boundary conditions = $walls
end
subsection Physics
  set Gravity = $gravity$(printf '%b' "$physics")
end
subsection Materials
  subsection block
    set Constitutive model = linear elastic
    set Density            = 1
    set Young's modulus    = 1000
    set Poisson's ratio    = 0.3
  end
end
subsection Grains
  subsection Grain 1
    $(printf '%b' "$block")
    set Material = block
  end
end
subsection Material points
  set Particles per cell = $per_dir
  set Shape functions    = $kernel
end
subsection Time stepping
  set Scheme                  = explicit leapfrog
  set Stress update           = USF
  set Time step               = $dt
  set Maximum number of steps = $steps
end
subsection Output
  set Output directory = $output
  set Output interval  = 1000
  set Write particles  = false
  set Write grid       = false
end
EOF
}
