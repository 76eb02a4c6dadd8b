#!/usr/bin/env bash
# Builds the certificate fuzzer (reader + verifier) with clang (libFuzzer + ASan + UBSan)
# straight from the verifier's sources (certify/, the model reader, as hipair-verify is built),
# seeds it with the certificate corpus, and fuzzes for SECONDS.
# usage: run_certificate_fuzz.sh CLANGXX SOURCE_DIR WORK_DIR SECONDS
# exit: 0 no crash found; 1 crash/leak/timeout found (the input is saved in WORK_DIR); 77 no
# libFuzzer runtime (skipped).
set -uo pipefail
clangxx=$1 seconds=$4
mkdir -p "$3/objects" "$3/corpus"
source=$(cd "$2" && pwd) work=$(cd "$3" && pwd)   # absolute: the fuzzer runs in WORK_DIR

# Skip when clang cannot link a fuzzer.
printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' >"$work/probe.cpp"
if ! "$clangxx" -fsanitize=fuzzer "$work/probe.cpp" -o "$work/probe" >"$work/probe.log" 2>&1; then
  echo "clang's libFuzzer runtime is not available: skipping"; cat "$work/probe.log"; exit 77
fi

flags=(-std=c++20 -O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined
       -fno-sanitize-recover=undefined -I"$source/include" -I"$source/src" -I"$source"
       -DHIPAIR_EXAMPLES="\"$source/examples/models\"")
sources=("$source"/src/core/*.cpp "$source"/src/model/*.cpp "$source"/src/io/atomic_file.cpp
         "$source"/certify/certificate_reader.cpp "$source"/certify/exact_geometry.cpp
         "$source"/certify/interval_geometry.cpp "$source"/certify/check.cpp
         "$source"/tests/fuzz/certificate_verifier_fuzzer.cpp)
# Objects built with other flags (another source directory) are rebuilt.
if [ "$(cat "$work/objects/flags.txt" 2>/dev/null)" != "${flags[*]}" ]; then rm -f "$work"/objects/*.o; fi
printf '%s' "${flags[*]}" >"$work/objects/flags.txt"
objects=()
pids=()
for file in "${sources[@]}"; do
  object="$work/objects/$(basename "$(dirname "$file")")-$(basename "$file" .cpp).o"
  objects+=("$object")
  if [ ! -f "$object" ] || [ "$file" -nt "$object" ]; then
    "$clangxx" "${flags[@]}" -c "$file" -o "$object" &
    pids+=($!)
    # At most two compilers at a time (the machine has two cores).
    if [ ${#pids[@]} -ge 2 ]; then wait "${pids[0]}" || { echo "compile failed"; exit 1; }; pids=("${pids[@]:1}"); fi
  fi
done
for pid in "${pids[@]}"; do wait "$pid" || { echo "compile failed"; exit 1; }; done
"$clangxx" -fsanitize=fuzzer,address,undefined "${objects[@]}" -lmpfi -lmpfr -lgmpxx -lgmp \
  -o "$work/certificate_verifier_fuzzer" || { echo "link failed"; exit 1; }

shopt -s nullglob
for seed in "$source"/tests/data/certificates/*.json "$source"/tests/fuzz/certificate_regressions/*; do
  cp "$seed" "$work/corpus/" 2>/dev/null
done

cat >"$work/certificate.dict" <<'DICT'
"\"hipair_certificate\""
"\"claim\""
"\"interference\""
"\"clearance\""
"\"jam\""
"\"free_passage\""
"\"statement\""
"\"model\""
"\"content_hash\""
"\"parameters\""
"\"overridden\""
"\"roundings\""
"\"pointer\""
"\"expression\""
"\"bound\""
"\"pair\""
"\"configuration\""
"\"tangent\""
"\"offset\""
"\"centre\""
"\"pi\""
"\"angle\""
"\"angle_error\""
"\"point\""
"\"crossing\""
"\"edge\""
"\"across\""
"\"along\""
"\"part\""
"\"loop\""
"\"label\""
"\"distance\""
"\"driver\""
"\"follower\""
"\"direction\""
"\"trap\""
"\"cut\""
"\"lower_wall\""
"\"upper_wall\""
"\"range\""
"\"path\""
"\"boxes\""
"\"1e400\""
"\"-1e-300\""
"\"1/3\""
"\"190000000000\""
DICT

cd "$work" || exit 1
"$work/certificate_verifier_fuzzer" -max_total_time="$seconds" -max_len=16384 -timeout=120 -rss_limit_mb=2560 \
  -dict="$work/certificate.dict" -artifact_prefix="$work/" -print_final_stats=1 "$work/corpus" >"$work/fuzz.log" 2>&1
status=$?
tail -n 25 "$work/fuzz.log"
if [ $status -ne 0 ]; then
  echo "FUZZER FOUND A PROBLEM (exit $status); inputs: $(ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* 2>/dev/null)"
  exit 1
fi
echo "no crash in ${seconds}s"
