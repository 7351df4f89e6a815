#!/bin/sh
# run.sh: the test driver.  Runs the C unit tests (cmocka) and the FreeFEM
# tests, prints what failed, and ends with one line "N passed, N failed".
#   tests/edp/test_*.edp   must exit 0
#   tests/edp/err_*.edp    must exit non-zero and print the text given on
#                          their first line after "// expect: " (run in the
#                          environment a second line "// env: NAME='value'" sets)
# Optional argument: a pattern that test names must contain.
cd "$(dirname "$0")/.." || exit 2
pat=${1:-}
pass=0; fail=0
log=$(mktemp)
report() { echo "FAIL: $1"; sed 's/^/    /' "$log" | tail -40; }

# a cmocka binary: counts its passed and failed tests (a crash counts one)
cmocka() {   # cmocka <command> <what>
    $1 >"$log" 2>&1
    rc=$?
    p=$(sed -n 's/.*\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -1)
    f=$(sed -n 's/.*\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -1)
    p=${p:-0}; f=${f:-0}
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi
    pass=$((pass + p)); fail=$((fail + f))
    [ "$f" -gt 0 ] && report "$1 ($2)"
    return 0
}

for t in build/tests/test_*; do
    [ -x "$t" ] || continue
    case "$t" in *"$pat"*) ;; *) continue ;; esac
    cmocka "$t" "C unit tests"
done

# the C tests of the parallel engine, on 2 ranks (mpiexec; timeout: a rank
# left waiting in a collective call is a failure, not a hang)
for t in build/mpi/tests/test_*; do
    [ -x "$t" ] || continue
    case "mpi $t" in *"$pat"*) ;; *) continue ;; esac
    [ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    cmocka "timeout 300 mpiexec --oversubscribe --bind-to none -np 2 $t" "MPI C unit tests, 2 ranks"
done

# case studies on 2 and 4 ranks against one process (4 on 2 cores:
# oversubscribed, correctness only), and the messages when MPI is missing
case "mpi-answers" in *"$pat"*)
    for np in 2 4; do
        if timeout 900 sh tests/mpi/same_answers.sh $np quick >"$log" 2>&1; then pass=$((pass + 1))
        else fail=$((fail + 1)); report "tests/mpi/same_answers.sh $np"; fi
    done ;;
esac
case "mpi-missing" in *"$pat"*)
    if sh tests/mpi/missing.sh >"$log" 2>&1; then pass=$((pass + 1)); else fail=$((fail + 1)); report "tests/mpi/missing.sh"; fi ;;
esac

# the same C tests under AddressSanitizer and UndefinedBehaviorSanitizer
for t in build/asan/test_*; do
    [ -x "$t" ] || continue
    case "asan $t" in *"$pat"*) ;; *) continue ;; esac
    cmocka "$t" "sanitizers"
done

# fuzzing for a bounded time (FUZZ_TEST_SECONDS each; longer: make fuzz)
for t in build/fuzz/fuzz_*; do
    [ -x "$t" ] || continue
    case "fuzz $t" in *"$pat"*) ;; *) continue ;; esac
    corpus=build/fuzz/corpus-$(basename "$t")
    mkdir -p "$corpus"
    if "$t" -max_total_time="${FUZZ_TEST_SECONDS:-15}" "$corpus" tests/fuzz/regress >"$log" 2>&1; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1)); report "$t (fuzzing found a failure; the input is saved as crash-*)"
    fi
done

# the plugin under valgrind memcheck
case "valgrind" in *"$pat"*)
    if command -v valgrind >/dev/null 2>&1; then
        if sh tests/valgrind.sh >"$log" 2>&1; then pass=$((pass + 1)); else fail=$((fail + 1)); report "tests/valgrind.sh"; fi
    fi ;;
esac

# a user's script run from outside the repository (relative paths, gmshFile)
case "outside" in *"$pat"*)
    if sh tests/outside.sh >"$log" 2>&1; then pass=$((pass + 1)); else fail=$((fail + 1)); report "tests/outside.sh"; fi ;;
esac

# every name README.md documents (plugin calls, settings, options, statistics, JSON fields) exists in the code
case "docnames" in *"$pat"*)
    if sh tests/docnames.sh >"$log" 2>&1; then pass=$((pass + 1)); else fail=$((fail + 1)); report "tests/docnames.sh"; fi ;;
esac

# the exercises: reference solutions right, common slips called wrong
case "exercises" in *"$pat"*)
    sh tests/exercises.sh >"$log" 2>&1
    p=$(sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed$/\1/p' "$log" | tail -1)
    f=$(sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed$/\2/p' "$log" | tail -1)
    p=${p:-0}; f=${f:-1}
    pass=$((pass + p)); fail=$((fail + f))
    [ "$f" -gt 0 ] && report "tests/exercises.sh (make exercises-check)" ;;
esac

for t in tests/edp/test_*.edp tests/hard/*.edp; do
    [ -f "$t" ] || continue
    case "$t" in *"$pat"*) ;; *) continue ;; esac
    sh scripts/ff "$t" >"$log" 2>&1
    rc=$?
    if [ "$rc" -eq 0 ]; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1)); report "$t (exit $rc)"
    fi
done

for t in tests/edp/err_*.edp; do
    [ -f "$t" ] || continue
    case "$t" in *"$pat"*) ;; *) continue ;; esac
    want=$(sed -n '1s|^// expect: ||p' "$t")
    # (a second line "// env: NAME='value'" sets the environment it runs in;
    # the shell evaluates it: quote a value with spaces)
    setenv=$(sed -n '2s|^// env: ||p' "$t")
    eval "env $setenv sh scripts/ff \"\$t\"" >"$log" 2>&1
    rc=$?
    if [ -n "$want" ] && [ "$rc" -ne 0 ] && [ "$rc" -lt 128 ] && grep -qF -- "$want" "$log"; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1)); report "$t (exit $rc, expected a clean error with: $want)"
    fi
done
# every FreeFEM test again on 2 ranks (sh scripts/ff -np 2): the same
# verdicts, and no rank left waiting in a collective call (timeout)
for t in tests/edp/test_*.edp tests/edp/err_*.edp; do
    [ -f "$t" ] || continue
    case "np2 $t" in *"$pat"*) ;; *) continue ;; esac
    [ "$(id -u)" -eq 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    setenv=$(sed -n '2s|^// env: ||p' "$t")
    eval "env $setenv timeout 300 sh scripts/ff -np 2 \"\$t\"" >"$log" 2>&1
    rc=$?
    case "$t" in
        */err_*) want=$(sed -n '1s|^// expect: ||p' "$t")
                 if [ -n "$want" ] && [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] && grep -qF -- "$want" "$log"; then ok=1; else ok=0; fi ;;
        *) if [ "$rc" -eq 0 ]; then ok=1; else ok=0; fi ;;
    esac
    if [ "$ok" -eq 1 ]; then pass=$((pass + 1)); else fail=$((fail + 1)); report "$t on 2 ranks (exit $rc)"; fi
done
rm -f "$log"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
