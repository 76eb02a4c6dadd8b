#!/usr/bin/env bash
# Session 75 (verify75): hipair-verify's batch mode (--list FILE, --model MODEL CERTIFICATE...)
# gives every certificate the verdict a run of its own gives it, in any order and mix:
#  1. the committed certificate corpus (tests/data/certificates: valid certificates and their
#     mutations; its four costliest, 0.25 .. 4 s, left to verify_certificate_corpus) checked one
#     run each, then in one batch forward and seeded-shuffled: each batch's output must be
#     the single runs' lines ("CERTIFICATE: <verdict>") in the batch's order, byte for byte, and its
#     exit status the worst verdict's (1 if any invalid, else 3 if any unproven, else 0);
#  2. true and false certificates in every order: a list holding every ordered pair (a, b) of a
#     mix of valid and mutated certificates (a == b too), so that no verdict can depend on the
#     check before it;
#  3. the alteration generators (certificate_, motion_ and tolerance_certificate_alterations.py,
#     a few cases each: interference, clearance, jam, free passage and never-interferes
#     certificates with every number altered) with VERIFY_BOTH_WAYS: every altered certificate is
#     checked in a batch and by a run of its own, and the two must say the same;
#  4. bad input: a missing or malformed certificate in a list is refused naming it and the others
#     are still checked; an unreadable, empty or malformed list (or --list without one) is a usage
#     error (exit 2, its name on stderr, nothing on stdout).
# usage: run_verify_batch_tests.sh HIPAIR HIPAIR_VERIFY SOURCE_DIR WORK_DIR
set -uo pipefail
verify=$2
source "$(dirname "$0")/seeded_test.sh" "$1" "$3" "$4"
cd "$source" || exit 2

# The corpus as a list, paths relative to the repository.
grep -v '^#' tests/data/certificates/EXPECTED.txt |
  grep -Ev '^(geneva-tolerance-no-jam-0.9-threshold|geneva-tolerance-no-interference|geneva-tolerance-no-jam-4x-free-path|spur-free).json' |
  awk -F'|' '{ gsub(/ /, "", $1); gsub(/ /, "", $2); if ($1 != "") printf "tests/data/certificates/%s\t%s\n", $1, $2 }' \
  > "$work/corpus.list"
[ "$(wc -l < "$work/corpus.list")" -ge 50 ] || fail "the corpus list has fewer than 50 certificates"

# Single runs: each certificate's line and status (tab-separated: certificate, status, line).
: > "$work/single.txt"
while IFS=$'\t' read -r certificate model; do
  line=$("$verify" "$certificate" "$model")
  printf '%s\t%s\t%s\n' "$certificate" "$?" "$line" >> "$work/single.txt"
done < "$work/corpus.list"
for status in 0 1; do
  grep -q "$(printf '\t%s\t' $status)" "$work/single.txt" || fail "no certificate of the corpus has exit status $status"
done

# check_batch NAME LIST: the batch's output must be the single runs' lines in its order.
check_batch() {
  local name=$1 list=$2
  "$verify" --list "$list" > "$work/$name.out" 2> "$work/$name.err"
  local status=$?
  awk -F'\t' 'NR == FNR { line[$1] = $3; code[$1] = $2; next }
              { print $1 ": " line[$1]; if (code[$1] == 1) worst = 1; else if (code[$1] == 3 && worst != 1) worst = 3 }
              END { print (worst == "" ? 0 : worst) > "/dev/stderr" }' \
    "$work/single.txt" "$list" > "$work/$name.expected" 2> "$work/$name.status"
  cmp -s "$work/$name.out" "$work/$name.expected" ||
    fail "$name: the batch's verdicts differ from the single runs': $(diff "$work/$name.expected" "$work/$name.out" | head -4)"
  [ "$status" = "$(cat "$work/$name.status")" ] ||
    fail "$name: batch exit $status, the verdicts' worst is $(cat "$work/$name.status")"
  [ ! -s "$work/$name.err" ] || fail "$name: the batch wrote to stderr: $(head -2 "$work/$name.err")"
}

# 1. forward and shuffled (seeded)
check_batch forward "$work/corpus.list"
awk -v seed="$seed" 'BEGIN { srand(seed) } { printf "%.17f\t%s\n", rand(), $0 }' "$work/corpus.list" | sort -n | cut -f2- \
  > "$work/shuffled.list"
check_batch shuffled "$work/shuffled.list"
# --model MODEL CERTIFICATE...: the lever's certificates against lever-stop.json
mapfile -t lever < <(grep -P '\texamples/models/lever-stop.json$' "$work/corpus.list" | cut -f1)
[ "${#lever[@]}" -ge 4 ] || fail "fewer than 4 lever certificates in the corpus"
"$verify" --model examples/models/lever-stop.json "${lever[@]}" > "$work/model.out"
printf '%s\texamples/models/lever-stop.json\n' "${lever[@]}" > "$work/model.list"
check_batch model-as-list "$work/model.list"
cmp -s "$work/model.out" "$work/model-as-list.out" || fail "--model's verdicts differ from --list's"
# - : the list on standard input
"$verify" --list - < "$work/model.list" > "$work/stdin.out"
cmp -s "$work/stdin.out" "$work/model-as-list.out" || fail "--list -'s verdicts differ from the list file's"

# 2. every ordered pair of a mix of valid and refused certificates (the first four of each in the
# seeded shuffle above, so the mix varies with the seed)
awk -F'\t' 'NR == FNR { code[$1] = $2; next }
             code[$1] == 0 && valid < 4 { print; valid++ } code[$1] != 0 && refused < 4 { print; refused++ }' \
  "$work/single.txt" "$work/shuffled.list" > "$work/mix.list"
: > "$work/pairs.list"
while IFS= read -r a; do
  while IFS= read -r b; do printf '%s\n%s\n' "$a" "$b" >> "$work/pairs.list"; done < "$work/mix.list"
done < "$work/mix.list"
[ "$(wc -l < "$work/pairs.list")" -eq 128 ] || fail "the pair list has $(wc -l < "$work/pairs.list") lines, not 128"
check_batch pairs "$work/pairs.list"

# 3. the alteration generators, every altered certificate both ways
# (the tolerance case: a never-interferes certificate of the lever and the sliding block (case 2);
# a no-jam case on the yoke has ~900 alterations, 35 s both ways, and is left to the alteration test)
for spec in "certificate_alterations.py 2 -" "motion_certificate_alterations.py 2 -" "tolerance_certificate_alterations.py 3 block"; do
  set -- $spec
  ALTERATIONS_KINDS=${3#-} VERIFY_BOTH_WAYS=1 python3 tests/fuzz/$1 "$hipair" "$verify" "$source" "$work/${1%.py}" "$seed" "$2" \
    > "$work/${1%.py}.log" 2>&1 || fail "$1 (both ways): $(grep -v '^note:' "$work/${1%.py}.log" | tail -3)"
  grep -q "'false rejected': [1-9]" "$work/${1%.py}.log" || fail "$1 (both ways): no false certificate was refused"
done

# 4. bad input
printf 'not json\n' > "$work/malformed.json"
{ head -2 "$work/corpus.list"; printf '%s\texamples/models/lever-stop.json\n' "$work/missing.json";
  printf '%s\texamples/models/lever-stop.json\n' "$work/malformed.json"; sed -n 3p "$work/corpus.list"; } > "$work/bad.list"
"$verify" --list "$work/bad.list" > "$work/bad.out" 2>&1
status=$?
[ $status -eq 1 ] || fail "a list with a missing and a malformed certificate: exit $status, not 1"
[ "$(wc -l < "$work/bad.out")" -eq 5 ] || fail "a list of 5 with bad certificates: $(wc -l < "$work/bad.out") lines"
grep -q "^$work/missing.json: invalid: .*missing.json" "$work/bad.out" || fail "the missing certificate is not refused naming it"
grep -q "^$work/malformed.json: invalid: malformed certificate" "$work/bad.out" || fail "the malformed certificate is not refused as such"
for i in 1 2 3; do
  certificate=$(sed -n "$((i > 2 ? 3 : i))p" "$work/corpus.list" | cut -f1)
  expected=$(awk -F'\t' -v c="$certificate" '$1 == c { print $1 ": " $3 }' "$work/single.txt")
  grep -qxF -- "$expected" "$work/bad.out" || fail "$certificate: not checked as alone next to bad certificates"
done
printf 'tests/data/certificates/lever-jam.json examples/models/lever-stop.json\n' > "$work/no-tab.list"
printf '\n' > "$work/empty.list"
for bad in "--list $work/no-tab.list:no-tab.list:2" "--list $work/empty.list:empty.list:2" "--list $work/absent.list:absent.list:2" \
           "--list::2" "--model examples/models/lever-stop.json::2"; do
  IFS=: read -r arguments name expected <<< "$bad"
  "$verify" $arguments > "$work/usage.out" 2> "$work/usage.err"
  status=$?
  [ $status -eq "$expected" ] || fail "hipair-verify $arguments: exit $status, not $expected"
  [ ! -s "$work/usage.out" ] || fail "hipair-verify $arguments: wrote to stdout: $(head -1 "$work/usage.out")"
  [ -z "$name" ] || grep -q "$name" "$work/usage.err" || fail "hipair-verify $arguments: the message does not name $name"
done
grep -q ':1: expected CERTIFICATE<TAB>MODEL' <<< "$("$verify" --list "$work/no-tab.list" 2>&1)" ||
  fail "a line without a tab is not named with its number"

[ $failures -eq 0 ] || { echo "verify batch tests: $failures failures (seed $seed)"; exit 1; }
echo "verify batch tests passed (seed $seed)"
