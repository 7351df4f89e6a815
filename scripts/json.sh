# json.sh: a case study's JSON fields for the shell scripts (sourced, from
# the repository's root: . scripts/json.sh). A missing file or field reads
# as empty.
#   val FILE KEY    the first value of KEY
#   last FILE KEY   the last one (after a multi-level case's per-level
#                   entries: the run's total)
#   tval FILE PART  val of time_PART (the time split)
val() { sed -n "s/.*\"$2\": \([^,}]*\).*/\1/p" "$1" 2>/dev/null | head -1; }
last() { sed -n "s/.*\"$2\": \([^,}]*\).*/\1/p" "$1" 2>/dev/null | tail -1; }
tval() { val "$1" "time_$2"; }
