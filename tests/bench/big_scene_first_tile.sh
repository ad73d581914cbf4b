#!/usr/bin/env bash
# Big-scene start-up in one run: the 5 M-triangle torus (tests/bench/make_big_mesh.py) from
# `prism render` start to the first tile, as binary PLY and as OBJ on one process with 2
# threads and on 3 ranks of this machine, then the 20 M torus's peak against the memory its
# scene holds. Rounds alternate the binaries given; prints every round and the medians.
#   tests/bench/big_scene_first_tile.sh DIR ROUNDS PRISM [PRISM...]
# DIR holds (or gets) the meshes: DIR/5m (300 MB) and DIR/20m (1.2 GB).
set -euo pipefail
if (($# < 3)); then
  sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
repo=$(cd "$(dirname "$0")/../.." && pwd)
dir=$1
rounds=$2
shift 2
binaries=("$@")
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # only needed as root
[[ -f $dir/5m/big-mesh-ply.yaml ]] || "$repo/tests/bench/make_big_mesh.py" "$dir/5m" 5000000 --ply
[[ -f $dir/20m/big-mesh-ply.yaml ]] || "$repo/tests/bench/make_big_mesh.py" "$dir/20m" 20000000 --ply
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# The first tile from the summary's time line (total − render where a binary does not say it).
first_tile() {
  sed -n 's/^time .*render \([0-9.]*\) s, \(first tile at \([0-9.]*\) s, \)\{0,1\}.*total \([0-9.]*\) s.*/\1 \3 \4/p' "$1" |
    awk '{ if ($2 != "") print $2; else printf "%.3f\n", $3 - $1 }'
}

declare -A samples
for ((r = 1; r <= rounds; r++)); do
  for b in "${binaries[@]}"; do
    name=$b  # as given: two builds may both end in build/prism
    for case in ply obj ranks; do
      scene=$dir/5m/big-mesh-ply.yaml
      [[ $case == obj ]] && scene=$dir/5m/big-mesh.yaml
      if [[ $case == ranks ]]; then
        mpiexec --oversubscribe -n 3 "$b" render "$scene" -o "$out/r.exr" --overwrite >"$out/log" 2>&1
      else
        "$b" render "$scene" -o "$out/r.exr" --overwrite --threads 2 >"$out/log" 2>&1
      fi
      t=$(first_tile "$out/log")
      samples[$name $case]+="$t "
      echo "round $r  $name  5M $case  first tile $t s"
    done
  done
done

median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
echo
echo "medians (s) of $rounds rounds; load at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
for b in "${binaries[@]}"; do
  name=$b
  ply=$(echo "${samples[$name ply]}" | median)
  obj=$(echo "${samples[$name obj]}" | median)
  ranks=$(echo "${samples[$name ranks]}" | median)
  printf '%-24s PLY %s  OBJ %s  3 ranks (PLY) %s  3 ranks / 1 process %.2f\n' "$name" "$ply" "$obj" \
    "$ranks" "$(awk -v a="$ranks" -v b="$ply" 'BEGIN { print a / b }')"
done

# The 20 M peak against the scene's held memory (the summary's bvh line: BVH and geometry).
echo
for b in "${binaries[@]}"; do
  name=$b
  /usr/bin/time -f "peak %M" "$b" render "$dir/20m/big-mesh-ply.yaml" -o "$out/r.exr" --overwrite \
    --threads 2 >"$out/log" 2>&1
  peak_kib=$(sed -n 's/^peak \([0-9]*\)$/\1/p' "$out/log")
  held_mib=$(sed -n 's/^bvh .*, \([0-9.]*\) \([GM]\)iB (+\([0-9.]*\) \([GMK]\)iB geometry).*/\1 \2 \3 \4/p' "$out/log" |
    awk '{ s = ($2 == "G") ? 1024 : 1; g = ($4 == "G") ? 1024 : ($4 == "K" ? 1 / 1024 : 1); print $1 * s + $3 * g }')
  printf '%-24s 20M peak %.0f MiB, scene holds %.0f MiB (bvh line), peak / held %.2f\n' "$name" \
    "$(awk -v k="$peak_kib" 'BEGIN { print k / 1024 }')" "$held_mib" \
    "$(awk -v k="$peak_kib" -v h="$held_mib" 'BEGIN { print k / 1024 / h }')"
done
