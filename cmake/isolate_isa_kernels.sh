#!/usr/bin/env bash
# Joins one instruction set's kernel objects into one object whose symbols cannot be confused
# with the baseline's (CMakeLists.txt, "Kernels per instruction set").
#
# The kernel sources include headers full of inline functions (glm, the standard library, Prism's
# own), and the compiler emits an out-of-line copy of each in every object that needs one, for
# that object's instruction set. The linker keeps one copy per name for the whole program: an
# AVX-512 copy could then serve baseline code and crash older CPUs with SIGILL. So every symbol
# this set defines gets the suffix .isa_<set> (objdump and perf show "f() [clone .isa_v3]"),
# except its entry points (prism_isa_*), which the rest of Prism calls through.
#
#   isolate_isa_kernels.sh LD NM OBJCOPY READELF SET OUTPUT OBJECT...
set -euo pipefail
ld=$1 nm=$2 objcopy=$3 readelf=$4 set=$5 output=$6
shift 6
joined="$output.joined.o"
renames="$output.renames"
"$ld" -r -o "$joined" "$@"
# Defined, external symbols only: references to what the set does not define (libc, the
# baseline's non-inline functions) stay as they are.
# The COMDAT groups' signatures too, which the linker matches by name whatever their binding
# (a constructor's group is named by a local symbol): a group kept under its old name would be
# merged with the baseline's.
{
  "$nm" --defined-only --extern-only --format=posix "$joined" | awk '{ print $1 }'
  "$readelf" -gW "$joined" | sed -n "s/^COMDAT group section \[ *[0-9]*\] \`\.group' \[\(.*\)\] contains.*/\1/p"
} | sort -u | awk -v suffix=".isa_$set" '$1 !~ /^prism_isa_/ { print $1, $1 suffix }' >"$renames"
"$objcopy" --redefine-syms="$renames" "$joined" "$output"
rm -f "$joined" "$renames"
