#!/bin/sh
# run.sh: runs exercise k with the student's settings and predictions and
# checks them (make exercise N=<k> ARGS="<options> name=value ...").
# Options (-name value) go to the exercise's scene, name=value predictions
# to the checker. Exit status: the checker's (0 right, 3 a prediction wrong,
# 4 the run wrong, 2 bad input).
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
k=$1
[ -n "$k" ] || { echo "usage: make exercise N=<k> ARGS=\"<options> name=value ...\" (exercises: $(ls "$here" | sed -n 's/^ex\([0-9]*\)-.*\.edp$/\1/p' | sort -n | tr '\n' ' '))"; exit 2; }
shift
scene=$(ls "$here"/ex"$k"-*.edp 2>/dev/null | head -1)
[ -n "$scene" ] || { echo "no exercise $k (exercises: $(ls "$here" | sed -n 's/^ex\([0-9]*\)-.*\.edp$/\1/p' | sort -n | tr '\n' ' '))"; exit 2; }
opts=""; preds=""; want=""
names=$(sed -n 's/.*exQuantity("\([A-Za-z0-9_]*\)".*/\1/p' "$scene" | tr '\n' ' ')
# the options the scene reads, itself or through the case study it
# includes (a mistyped one would leave its default in place without a word)
files="$scene $(sed -n 's/^ *include "\([A-Za-z0-9_-]*\.edp\)".*/\1/p' "$scene" | sed "s|^|$root/scripts/|")"
# shellcheck disable=SC2086
known=$(grep -ho 'getARGV("-[A-Za-z0-9_]*"' $files | sed 's/getARGV("//; s/"$//' | sort -u | tr '\n' ' ')
for a in "$@"; do
    if [ -n "$want" ]; then opts="$opts $a"; want=""; continue; fi
    case "$a" in
        -*) case " $known " in
                *" $a "*) ;;
                *) echo "exercise $k: no option '$a'; its options are: $known(each as -name value)"; exit 2 ;;
            esac
            opts="$opts $a"; want=$a ;;
        *=*) preds="$preds $a" ;;
        *) echo "exercise $k: '$a' is neither an option (-name value) nor a prediction (name=value)"; exit 2 ;;
    esac
done
[ -z "$want" ] || { echo "exercise $k: option $want has no value"; exit 2; }
# shellcheck disable=SC2086
sh "$here/check.sh" --names "$names" $preds || exit 2
json=results/exercise-$k.json
rm -f "$json"
# shellcheck disable=SC2086
sh "$root/scripts/ff" "$scene" $opts || echo "(the scene stopped with status $?)"
# shellcheck disable=SC2086
sh "$here/check.sh" "$json" $preds
