#!/bin/sh
# exercises.sh: make exercises-check. Runs every exercise's reference
# solution (the "check:" lines of scripts/exercises/SOLUTIONS.md: each must
# be judged right, run and predictions), then its common slip (the
# "wrong:" lines, checked on the same results: each must be judged a wrong
# prediction), then the checker on made-up results (a wrong run, bad
# input) and run.sh on bad input. Ends with "N passed, N failed".
cd "$(dirname "$0")/.." || exit 2
sol=scripts/exercises/SOLUTIONS.md
pass=0; fail=0
log=$(mktemp)
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $1"; sed 's/^/    /' "$log" | tail -30; }
for k in $(sed -n 's/^ *check: \([0-9]*\) .*/\1/p' "$sol" | sort -un); do
    sed -n "s/^ *check: $k //p" "$sol" > "$log.args"
    while read -r args; do
        # shellcheck disable=SC2086
        if sh scripts/exercises/run.sh "$k" $args >"$log" 2>&1 && grep -q "^Verdict: every prediction right, the run right" "$log"; then ok
        else bad "exercise $k, reference solution: $args"; fi
    done < "$log.args"
    sed -n "s/^ *wrong: $k //p" "$sol" > "$log.args"
    while read -r args; do
        # shellcheck disable=SC2086
        sh scripts/exercises/check.sh "results/exercise-$k.json" $args >"$log" 2>&1
        rc=$?
        if [ "$rc" -eq 3 ] && grep -q "prediction: WRONG" "$log" && grep -q "^Verdict: a prediction is WRONG" "$log"; then ok
        else bad "exercise $k, the slip $args not called wrong (exit $rc)"; fi
    done < "$log.args"
done
# the checker itself: a run far from theory is called wrong (exit 4); an
# unknown quantity and a prediction that is not a number are refused (exit 2)
fake=$(mktemp)
cat > "$fake" <<'JSON'
{
  "title": "made up",
  "settings": "none",
  "quantities": " x",
  "x_what": "a number",
  "x_why": "tol 0.1",
  "x_pwhy": "tol 0.1",
  "converged": 1,
  "exercise": 0,
  "x": 2,
  "x_expected": 1,
  "x_tol": 0.1,
  "x_ptol": 0.1
}
JSON
sh scripts/exercises/check.sh "$fake" x=1 >"$log" 2>&1
if [ $? -eq 4 ] && grep -q "run:        WRONG" "$log" && grep -q "prediction: right" "$log"; then ok; else bad "checker: a wrong run"; fi
sh scripts/exercises/check.sh "$fake" y=1 >"$log" 2>&1
if [ $? -eq 2 ] && grep -q 'no quantity "y"' "$log"; then ok; else bad "checker: an unknown quantity"; fi
sh scripts/exercises/check.sh "$fake" x=abc >"$log" 2>&1
if [ $? -eq 2 ] && grep -q "'abc' is not a number" "$log"; then ok; else bad "checker: a prediction that is not a number"; fi
# run.sh refuses bad input before the scene runs (no results file made)
for args in "x=1|no quantity" "a=1 a=2|predicted twice" "-hc|has no value" "a=abc|is not a number" "foo|neither an option" \
            "-HC 0.05|no option '-HC'; its options are: -F -hc" "-hc=0.05 a=1|no option '-hc=0.05'"; do
    rm -f results/exercise-1.json
    # shellcheck disable=SC2086
    sh scripts/exercises/run.sh 1 ${args%%|*} >"$log" 2>&1
    if [ $? -eq 2 ] && grep -q "${args#*|}" "$log" && [ ! -f results/exercise-1.json ]; then ok
    else bad "run.sh: '${args%%|*}' not refused with '${args#*|}'"; fi
done
rm -f "$fake" "$log" "$log.args"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
