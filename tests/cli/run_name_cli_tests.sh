#!/usr/bin/env bash
# Names a model may not have, session 41 (hunt41): docs/model-format.md "Names and text". A name
# (the model's, a part's, a part named in a pair) is non-empty, without control characters, with
# single spaces (U+0020) between words as its only white space, of any length (messages cut it,
# session 38's hostile_cli_tests). Generated cases (a seed per run, printed on
# failure; HIPAIR_TEST_SEED repeats one): lever-stop.json with one name spoiled (only spaces, a
# tab, a space before or after, two spaces in a row, a control character, NUL, invalid UTF-8, a
# no-break or ideographic space, a zero-width space or a byte-order mark, a second part named like the first but for a space), through a random command that
# reads models: exit 2, one line naming the JSON pointer (the JSON reader's line and column for
# invalid UTF-8), nothing on stdout, nothing written. The examples and tests/data still load.
# usage: run_name_cli_tests.sh HIPAIR_BINARY SOURCE_DIR WORK_DIR
set -uo pipefail
# python3 resolved once to the interpreter itself: a pyenv shim starts a shell script per call
# (~0.7 s of CPU each), and these scripts call python3 in loops (session 43, build43).
hipair_python=$(python3 -c 'import sys; print(sys.executable)') && python3() { "$hipair_python" "$@"; }
hipair=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
seed=${HIPAIR_TEST_SEED:-61}; [ "$seed" = random ] && seed=$RANDOM
fail() { echo "FAIL (seed $seed): $*"; failures=$((failures + 1)); }
# shellcheck source=expect_refused.sh
source "$(dirname "$0")/expect_refused.sh"
commands=(validate "show --svg $work/x.svg" "cspace --json $work/x.json" "analyze --out $work/out"
          "tolerance --out $work/out" "certify --claim clearance --out $work/c.json" "simulate --t-end 0.01 --out $work/out")

# model-<k>.json and its expected pointer in pointer-<k>.txt, kind by kind
python3 - "$source/examples/models/lever-stop.json" "$work" "$seed" <<'EOF'
import json, random, sys
source, work, seed = sys.argv[1], sys.argv[2], int(sys.argv[3])
rng = random.Random(seed)
base = json.load(open(source))
base["pairs"] = [{"parts": ["lever", "stop"]}]
def word():
    return "".join(rng.choice("abcdefghij") for _ in range(rng.randint(1, 6)))
def spoil(kind):
    w = word()
    return {
        0: " " * rng.randint(1, 8),
        1: "\t" * rng.randint(1, 3),
        2: " " + w,
        3: w + " ",
        4: w + "  " + word(),
        5: w + chr(rng.choice([1, 7, 27, 31, 127, 0x85, 0x9B])) + word(),
        6: w + "\u0000",
        7: None,  # invalid UTF-8, written as bytes below
        8: w + rng.choice(["\u00a0", "\u3000", "\u2003", "\u202f"]) + word(),
        9: rng.choice(["\u200b", "\ufeff", "\u2060"]) + w,
    }[kind]
kinds = 11
for k in range(kinds * 2):
    kind = k % kinds
    model = json.loads(json.dumps(base))
    where = rng.choice(["model", "part", "pair"])
    if kind == 10:  # a second part named like the first but for a trailing or leading space
        twin = json.loads(json.dumps(model["parts"][1]))
        twin["name"] = rng.choice(["stop ", " stop"])
        model["parts"].append(twin)
        pointer = "/parts/2/name"
        text = json.dumps(model, ensure_ascii=rng.random() < 0.5)
    elif kind == 7:
        marker = "@@NAME@@"
        if where == "model": model["name"] = marker; pointer = "/name"
        elif where == "part": model["parts"][0]["name"] = marker; pointer = "/parts/0/name"
        else: model["pairs"][0]["parts"][1] = marker; pointer = "/pairs/0/parts/1"
        pointer = "line "  # the JSON reader refuses the bytes before any pointer exists
        text = json.dumps(model)
        bad = rng.choice([b"ab\xff", b"\xc3", b"\xc0\xaf", b"\xed\xa0\x80", b"\xf8\x88\x80\x80\x80", b"x\x80y"])
        open(f"{work}/model-{k}.json", "wb").write(text.encode().replace(marker.encode(), bad))
        open(f"{work}/pointer-{k}.txt", "w").write(pointer)
        continue
    else:
        name = spoil(kind)
        if where == "model": model["name"] = name; pointer = "/name"
        elif where == "part":
            part = rng.randint(0, 1)
            model["parts"][part]["name"] = name
            pointer = f"/parts/{part}/name"
        else:
            j = rng.randint(0, 1)
            model["pairs"][0]["parts"][j] = name
            pointer = f"/pairs/0/parts/{j}"
        text = json.dumps(model, ensure_ascii=rng.random() < 0.5)
    open(f"{work}/model-{k}.json", "w", encoding="utf-8").write(text)
    open(f"{work}/pointer-{k}.txt", "w").write(pointer)
# valid: single inner spaces, accents, a long name
model = json.loads(json.dumps(base))
model["name"] = "a b c " + "d" * 100000
model["parts"][0]["name"] = "lever arm \u00e9\u00e8"
model["pairs"][0]["parts"][0] = "lever arm \u00e9\u00e8"
open(f"{work}/model-ok.json", "w").write(json.dumps(model))
EOF
[ -s "$work/model-0.json" ] || { echo "FAIL: the generator wrote no model"; exit 1; }
RANDOM=$seed

"$hipair" validate "$work/model-ok.json" >"$work/ok.out" 2>&1 ||
  fail "a valid name (single inner spaces, accents, 100,006 characters) is refused: $(head -c 300 "$work/ok.out")"

cases=0
for model in "$work"/model-[0-9]*.json; do
  k=${model##*/model-}; k=${k%.json}
  pointer=$(cat "$work/pointer-$k.txt")
  command=${commands[RANDOM % ${#commands[@]}]}
  rm -rf "$work/out" "$work/x.svg" "$work/x.json" "$work/c.json"
  # shellcheck disable=SC2086
  timeout 60 "$hipair" $command "$model" >"$work/bad.out" 2>"$work/bad.err"
  status=$?
  cases=$((cases + 1))
  what="$command model-$k.json (pointer ${pointer:0:40})"
  expect_refused "$what" "${pointer:0:60}" -qF
  [ "$(wc -c <"$work/bad.err")" -lt 600 ] || fail "$what: a message of $(wc -c <"$work/bad.err") bytes"
done

# every example and test model still loads as before: validate's verdict is main's
loaded=0
while IFS= read -r model; do
  case $model in */bad/*|*/malformed/*|*/hostile/*) continue ;; esac
  grep -q '"parts"' "$model" || continue
  if "$hipair" validate "$model" >"$work/v.out" 2>&1; then
    loaded=$((loaded + 1))
  elif grep -q "a name may not" "$work/v.out"; then
    fail "$model no longer loads: $(head -c 300 "$work/v.out")"
  fi
done < <(find "$source/examples/models" "$source/tests/data" -name '*.json' | sort)
[ $loaded -gt 30 ] || fail "only $loaded models loaded"

echo "$cases malformed names, $loaded models loaded, $failures failures (seed $seed)"
[ $failures -eq 0 ]
