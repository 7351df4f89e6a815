#!/bin/sh
# valgrind.sh: the coarse patch case under valgrind memcheck, with both
# contact methods (augmented Lagrangian, node-to-surface). Fails on any
# error record (invalid access, uninitialised value, definitely or possibly
# lost memory) whose stack passes through the plugin (ffcontact.so, ffc_*);
# FreeFEM's own exit-time leaks are not the plugin's.
cd "$(dirname "$0")/.." || exit 2
root=$(pwd)
FF_LOADPATH="$root/build;/usr/lib/freefem++/;./"
FF_INCLUDEPATH="$root/scripts;$root/tests/edp;/usr/include/freefem++/idp/;./"
export FF_LOADPATH FF_INCLUDEPATH
status=0
for method in al nts; do
log=$(mktemp)
valgrind --leak-check=full --num-callers=40 --log-file="$log" \
    FreeFem++ -nw -v 0 scripts/patch.edp -h1 0.5 -h2 0.4 -verbose 0 -method $method -out /tmp/ffc-valgrind-patch \
    > /dev/null 2>&1
rc=$?
# records are separated by lines holding only the "==pid==" prefix
bad=$(awk '
    /^==[0-9]+== *$/ { if (rec ~ /ffc/ && rec ~ /(Invalid|uninitialised|Uninitialised|definitely lost|possibly lost|Mismatched|overlap)/) n++; rec = ""; next }
    { rec = rec "\n" $0 }
    END { if (rec ~ /ffc/ && rec ~ /(Invalid|uninitialised|Uninitialised|definitely lost|possibly lost|Mismatched|overlap)/) n++; print n + 0 }' "$log")
summary=$(grep "ERROR SUMMARY" "$log")
if [ "$rc" -ne 0 ] || [ "$bad" -ne 0 ]; then
    echo "valgrind ($method): exit $rc, $bad error records in the plugin; $summary"
    awk '/ffc/' "$log" | head -40
    status=1
else
    echo "valgrind ($method): no error from the plugin ($summary)"
fi
rm -f "$log"
done
exit $status
