#!/usr/bin/env bash
# Builds one libFuzzer target with clang (libFuzzer + ASan + UBSan) straight from the sources it
# exercises, seeds it, and fuzzes for SECONDS.
#   model_reader          the model reader (src/core, src/model); seeds: every example and test model
#   certificate_verifier  the certificate reader and the verifier, built from the verifier's own
#                         sources as hipair-verify is (certify/, the model reader); seeds: the
#                         certificate corpus and tests/fuzz/certificate_seeds (sliced_connected
#                         certificates of examples/models/peg-in-hole.json, session 68)
# Both targets share one object directory beside WORK_DIR: the reader's objects (src/core,
# src/model) are compiled once, under a lock, when the two tests run in parallel; each target's
# own objects are compiled after the lock is released, so that the model reader never waits for
# the verifier's.
# usage: run_fuzz.sh TARGET CLANGXX SOURCE_DIR WORK_DIR SECONDS
# exit: 0 no crash found; 1 crash/leak/timeout found (the input is saved in WORK_DIR); 2 usage;
# 77 no libFuzzer runtime (skipped).
set -uo pipefail
if [ $# -ne 5 ]; then echo "usage: run_fuzz.sh TARGET CLANGXX SOURCE_DIR WORK_DIR SECONDS" >&2; exit 2; fi
target=$1 clangxx=$2 seconds=$5
mkdir -p "$4/corpus"
source=$(cd "$3" && pwd) work=$(cd "$4" && pwd)   # absolute: the fuzzer runs in WORK_DIR
objects_dir="$(dirname "$work")/fuzz_objects"
mkdir -p "$objects_dir"

shopt -s nullglob
case "$target" in
  model_reader)
    # the template rules (src/model) take their interval sine and cosine from the parametric model
    sources=("$source"/tests/fuzz/model_reader_fuzzer.cpp "$source"/src/model/parametric/number_traits.cpp)
    seeds=("$source"/examples/models/*.json "$source"/tests/data/good/*.json "$source"/tests/data/bad/*.json
           "$source"/tests/fuzz/regressions/*)
    dictionary=model.dict ;;
  certificate_verifier)
    sources=("$source"/src/model/parametric/*.cpp
             "$source"/src/io/atomic_file.cpp "$source"/certify/tolerance_check.cpp "$source"/certify/free_path_check.cpp
             "$source"/certify/planar_check.cpp "$source"/certify/statement.cpp "$source"/certify/sliced_connected_check.cpp
             "$source"/certify/sliced_apart_check.cpp
             "$source"/certify/certificate_reader.cpp "$source"/certify/exact_geometry.cpp
             "$source"/certify/interval_geometry.cpp "$source"/certify/check.cpp
             "$source"/tests/fuzz/certificate_verifier_fuzzer.cpp)
    seeds=("$source"/tests/data/certificates/*.json "$source"/tests/fuzz/certificate_seeds/*.json
           "$source"/tests/fuzz/certificate_regressions/*)
    dictionary=certificate.dict ;;
  *) echo "run_fuzz.sh: unknown target '$target' (model_reader or certificate_verifier)" >&2; exit 2 ;;
esac
shared=("$source"/src/core/*.cpp "$source"/src/model/*.cpp)   # the model reader, in both targets

# Skip when clang cannot link a fuzzer.
printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' >"$work/probe.cpp"
if ! "$clangxx" -fsanitize=fuzzer "$work/probe.cpp" -o "$work/probe" >"$work/probe.log" 2>&1; then
  echo "clang's libFuzzer runtime is not available: skipping"; cat "$work/probe.log"; exit 77
fi

# -gline-tables-only: a report's stack names every function, file and line (inlined frames too)
# without the full debug information, most of these objects' compile time (as OSS-Fuzz builds).
# Through ccache when it is installed (as the project's build): the product's objects are compiled
# by the same command from any checkout and reused from an earlier run or clone. The compiler runs
# in the checkout and is given its files and include directories relative to it, the checkout
# mapped to "." in the debug information (ccache's hash_dir then hashes "." for the working
# directory); the examples' directory reaches the certificate fuzzer at run time (HIPAIR_EXAMPLES in
# its environment), not as a macro. Until session 73 (ci73) the compiler ran in WORK_DIR with
# absolute paths: every new checkout (CI's fresh clone) and every build directory missed the cache,
# about 130 s CPU of clang with ASan per target.
flags=(-std=c++20 -O1 -gline-tables-only -fdebug-prefix-map="$source"=. -fno-omit-frame-pointer
       -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
       -Iinclude -Isrc -I. -I/usr/include/eigen3)
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(ccache)

# An object is stale when it is missing, has no dependency list, or any file it was compiled
# from (the source and every header clang listed with -MMD) is missing or newer than it.
stale() {
  local object=$1 dep
  [ -f "$object" ] && [ -f "$object.d" ] || return 0
  for dep in $(sed -e 's/^[^:]*://' -e 's/\\$//' "$object.d"); do
    [ "${dep#/}" = "$dep" ] && dep="$source/$dep"   # the checkout's own files are listed relative to it
    [ -e "$dep" ] || return 0
    [ "$dep" -nt "$object" ] && return 0
  done
  return 1
}

# Compile the files given that are missing or stale, at most two compilers at a time (the machine
# has two cores).
compile() {
  local pids=() file object
  for file in "$@"; do
    object="$objects_dir/$(basename "$(dirname "$file")")-$(basename "$file" .cpp).o"
    objects+=("$object")
    if stale "$object"; then
      (cd "$source" && "${launcher[@]}" "$clangxx" "${flags[@]}" -MMD -MF "$object.d.tmp" \
         -c "${file#"$source"/}" -o "$object.tmp") &&
        mv "$object.d.tmp" "$object.d" && mv "$object.tmp" "$object" &
      pids+=($!)
      if [ ${#pids[@]} -ge 2 ]; then wait "${pids[0]}" || return 1; pids=("${pids[@]:1}"); fi
    fi
  done
  local pid
  for pid in "${pids[@]}"; do wait "$pid" || return 1; done
}
# The shared objects under the object directory's lock (the other target waits instead of racing);
# objects built with other flags (another source directory) are rebuilt.
objects=()
exec 9>"$objects_dir/lock"
flock 9
if [ "$(cat "$objects_dir/flags.txt" 2>/dev/null)" != "${flags[*]}" ]; then
  rm -f "$objects_dir"/*.o "$objects_dir"/*.o.d
fi
printf '%s' "${flags[*]}" >"$objects_dir/flags.txt"
compile "${shared[@]}" || { echo "compile failed"; exit 1; }
flock -u 9
compile "${sources[@]}" || { echo "compile failed"; exit 1; }
"$clangxx" -fsanitize=fuzzer,address,undefined "${objects[@]}" -lmpfi -lmpfr -lgmpxx -lgmp \
  -o "$work/${target}_fuzzer" || { echo "link failed"; exit 1; }

for seed in "${seeds[@]}"; do cp "$seed" "$work/corpus/" 2>/dev/null; done

cd "$work" || exit 1
HIPAIR_EXAMPLES="$source/examples/models" "$work/${target}_fuzzer" -max_total_time="$seconds" -max_len=16384 -timeout=120 -rss_limit_mb=2560 \
  -dict="$source/tests/fuzz/$dictionary" -artifact_prefix="$work/" -print_final_stats=1 "$work/corpus" \
  >"$work/fuzz.log" 2>&1
status=$?
tail -n 25 "$work/fuzz.log"
if [ $status -ne 0 ]; then
  echo "FUZZER FOUND A PROBLEM (exit $status); inputs: $(ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* 2>/dev/null)"
  exit 1
fi
echo "no crash in ${seconds}s"
