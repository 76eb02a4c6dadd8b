#!/usr/bin/env bash
# Builds the model-reader fuzzer with clang (libFuzzer + ASan + UBSan) straight from the reader's
# sources, seeds it with every example and test model, and fuzzes for SECONDS.
# usage: run_fuzz.sh CLANGXX SOURCE_DIR WORK_DIR SECONDS
# exit: 0 no crash found; 1 crash/leak/timeout found (the input is saved in WORK_DIR); 77 no
# libFuzzer runtime (skipped).
set -uo pipefail
clangxx=$1 source=$2 work=$3 seconds=$4
mkdir -p "$work/objects" "$work/corpus"

# Skip when clang cannot link a fuzzer.
printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' >"$work/probe.cpp"
if ! "$clangxx" -fsanitize=fuzzer "$work/probe.cpp" -o "$work/probe" >"$work/probe.log" 2>&1; then
  echo "clang's libFuzzer runtime is not available: skipping"; cat "$work/probe.log"; exit 77
fi

flags=(-std=c++20 -O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined
       -fno-sanitize-recover=undefined -I"$source/include" -I"$source/src")
sources=("$source"/src/core/rational.cpp "$source"/src/core/sha256.cpp "$source"/src/core/model.cpp
         "$source"/src/model/*.cpp "$source"/tests/fuzz/model_reader_fuzzer.cpp)
objects=()
pids=()
for file in "${sources[@]}"; do
  object="$work/objects/$(basename "$file" .cpp).o"
  objects+=("$object")
  if [ ! -f "$object" ] || [ "$file" -nt "$object" ]; then
    "$clangxx" "${flags[@]}" -c "$file" -o "$object" &
    pids+=($!)
    # At most two compilers at a time (the machine has two cores).
    if [ ${#pids[@]} -ge 2 ]; then wait "${pids[0]}" || { echo "compile failed: ${sources[*]}"; exit 1; }; pids=("${pids[@]:1}"); fi
  fi
done
for pid in "${pids[@]}"; do wait "$pid" || { echo "compile failed"; exit 1; }; done
"$clangxx" -fsanitize=fuzzer,address,undefined "${objects[@]}" -lmpfi -lmpfr -lgmpxx -lgmp \
  -o "$work/model_reader_fuzzer" || { echo "link failed"; exit 1; }

shopt -s nullglob
for seed in "$source"/examples/models/*.json "$source"/tests/data/good/*.json "$source"/tests/data/bad/*.json \
            "$source"/tests/fuzz/regressions/*; do
  cp "$seed" "$work/corpus/" 2>/dev/null
done

cat >"$work/model.dict" <<'DICT'
"\"hipair\""
"\"name\""
"\"units\""
"\"deg\""
"\"rad\""
"\"parameters\""
"\"nominal\""
"\"tolerance\""
"\"range\""
"\"distribution\""
"\"normal\""
"\"sigma\""
"\"angle\""
"\"parts\""
"\"motion\""
"\"fixed\""
"\"rotation\""
"\"translation\""
"\"planar\""
"\"pin_slot\""
"\"pivot\""
"\"direction\""
"\"limits\""
"\"angle_limits\""
"\"initial\""
"\"offset\""
"\"loops\""
"\"start\""
"\"edges\""
"\"line_to\""
"\"arc_to\""
"\"center\""
"\"dir\""
"\"ccw\""
"\"cw\""
"\"circle\""
"\"radius\""
"\"polar\""
"\"features\""
"\"pin\""
"\"geneva_wheel\""
"\"spur_gear\""
"\"ratchet_wheel\""
"\"dynamics\""
"\"pairs\""
"sqrt("
"atan2("
"sin("
" deg"
"pi"
"^"
"1e-30"
"9007199254740993"
DICT

cd "$work" || exit 1
"$work/model_reader_fuzzer" -max_total_time="$seconds" -max_len=16384 -timeout=120 -rss_limit_mb=2560 \
  -dict="$work/model.dict" -artifact_prefix="$work/" -print_final_stats=1 "$work/corpus" >"$work/fuzz.log" 2>&1
status=$?
tail -n 25 "$work/fuzz.log"
if [ $status -ne 0 ]; then
  echo "FUZZER FOUND A PROBLEM (exit $status); inputs: $(ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* 2>/dev/null)"
  exit 1
fi
echo "no crash in ${seconds}s"
