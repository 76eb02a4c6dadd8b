#!/usr/bin/env bash
# Layering check (ctest: layering_includes): every library, verifier and example source includes
# only what its layer may see, so that the C-space adaptor (include/hipair/cspace.hpp and
# include/hipair/overlap.hpp) stays the only door into the C-space layers.
#
#   bash tests/layering/check_includes.sh SOURCE_DIR
#
# A file's layer is its folder: src/<layer>/, certify/ (the independent verifier), kernels/,
# include/hipair/ (public), examples/. Quoted includes "<folder>/..." are checked against the
# table below; CGAL (<CGAL/...>, <hipair/cgal/...>) belongs to the arrangement stages alone (the
# algebraic-traits stage and the circle-segment stage; CGAL's LP solver alone also in
# src/simulation/exact_lp.cpp, which wraps it behind rationals). Tests are
# exempt: they test internals on purpose. Prints every violation and exits 1 if there is one.
set -u
root="${1:?usage: check_includes.sh SOURCE_DIR}"
cd "$root" || exit 2

# Folders each layer may include with quoted includes (besides public <hipair/...>).
declare -A allowed=(
  [public]=""
  [kernels]="kernels"
  [core]="core"
  [model]="model core kernels"
  # The C-space, in the order the data flows: exact algebra -> contact curves -> overlap
  # oracle -> arrangement (CGAL) -> the adaptor (src/cspace, behind include/hipair/cspace.hpp).
  # One edge goes back: curve generation certifies the inscribed disks of its blocked-space
  # cull with the oracle's exact point location (oracle/overlap.hpp), while the oracle poses
  # parts in the curves layer's chart vocabulary (curves/contact_curves.hpp, curves/pose.hpp).
  [algebra]="algebra core kernels"
  [curves]="curves algebra oracle core model kernels"
  [oracle]="oracle curves algebra core model kernels"
  [arrangement]="arrangement curves algebra core"
  [cspace]="cspace arrangement oracle curves algebra core model kernels"
  [kinematics]="kinematics algebra curves core kernels"
  [tolerance]="tolerance core model kernels certify"
  [simulation]="simulation core kernels"
  [sliced]="sliced algebra core model kernels"
  [pinslot]="pinslot core sliced algebra"
  [certificates]="certificates certify core model kernels"
  [verifier]="certify core model io"
  [io]="io core"
  [render]="render io core"
  [cli]="cli io render core model"
  [examples]=""
)
# Single headers of another layer a layer may include besides its table: the algebraic-traits
# translation unit implements the opt-in accessor hipair::cgal::arrangement() (it needs the
# CGAL types, and CGAL stays in the arrangement files), which reads the kept arrangement
# from the adaptor's internals.
declare -A layer_interfaces=(
  [arrangement]="cspace/builder_impl.hpp"
)

layer_of() {
  case "$1" in
    include/hipair/*) echo public ;;
    kernels/*) echo kernels ;;
    certify/*) echo verifier ;;
    examples/*) echo examples ;;
    src/*/*) local rest="${1#src/}"; echo "${rest%%/*}" ;;
    *) echo "" ;;
  esac
}

violations=0
report() {
  echo "layering: $1:$2: $3" >&2
  violations=$((violations + 1))
}

while IFS= read -r file; do
  layer="$(layer_of "$file")"
  [ -n "$layer" ] || continue
  if [ -z "${allowed[$layer]+x}" ]; then
    report "$file" 0 "folder of unknown layer '$layer' (add it to tests/layering/check_includes.sh)"
    continue
  fi
  line_number=0
  while IFS= read -r line; do
    line_number=$((line_number + 1))
    [[ "$line" =~ ^[[:space:]]*#[[:space:]]*include[[:space:]]*([\"\<])([^\"\>]+)[\"\>] ]] || continue
    kind="${BASH_REMATCH[1]}" target="${BASH_REMATCH[2]}"
    if [ "$kind" = "<" ]; then
      if [[ "$target" == CGAL/* || "$target" == hipair/cgal/* ]] &&
         [[ "$file" != src/arrangement/algebraic_traits.cpp && "$file" != src/arrangement/circle_segment_traits.cpp &&
         "$file" != src/arrangement/quadratic_traits.cpp &&
            "$file" != include/hipair/cgal/* ]] &&
         # CGAL's linear programming solver (no arrangement type) in the one file that wraps it:
         # the exact LP of the simulator's stick/slip decisions (session 65; only rationals cross
         # its interface, src/simulation/exact_lp.hpp)
         ! [[ "$file" == src/simulation/exact_lp.cpp &&
              ( "$target" == CGAL/QP_functions.h || "$target" == CGAL/QP_models.h || "$target" == CGAL/gmpxx.h ) ]]; then
        report "$file" "$line_number" "includes <$target>: CGAL belongs to the arrangement stages (src/arrangement/algebraic_traits.cpp, circle_segment_traits.cpp, quadratic_traits.cpp)"
      fi
      continue
    fi
    folder="${target%%/*}"
    [ "$folder" != "$target" ] || continue   # a sibling header in the same folder
    ok=0
    for a in ${allowed[$layer]}; do [ "$a" = "$folder" ] && ok=1; done
    for a in ${layer_interfaces[$layer]:-}; do [ "$a" = "$target" ] && ok=1; done
    [ $ok = 1 ] || report "$file" "$line_number" "layer '$layer' includes \"$target\" (another layer's internals; use the public headers)"
  done <"$file"
done < <(find include kernels src certify examples -type f \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \) 2>/dev/null | sort)

# The public headers expose no internal access: the adaptor's internals stay behind
# src/cspace/cspace_access.hpp.
while IFS=: read -r file line_number _; do
  report "$file" "$line_number" "a public header exposes the C-space internals (implementation()/make_cspace())"
done < <(grep -nE '\b(implementation|make_cspace)[[:space:]]*\(' -r include/hipair 2>/dev/null)

if [ $violations -gt 0 ]; then
  echo "layering: $violations violation(s)" >&2
  exit 1
fi
echo "layering: every include respects the layers"
