# lib.sh — helpers for end-to-end tests; sourced by tests/e2e/*.sh, which run
# in a fresh temporary directory with $PM_BIN (the built programs) and
# $PM_TOP (the source tree) set by tests/run.sh.
PATH="$PM_BIN:$PATH"
ok() { echo "ok - $1"; }
notok() { echo "not ok - $1: $2"; }
# check NAME CONDITION-COMMAND... : ok if the command succeeds.
check() { n=$1; shift; if "$@"; then ok "$n"; else notok "$n" "failed: $*"; fi; }
# expect_fail NAME STATUS PATTERN CMD... : the command must exit with STATUS
# and print one stderr line matching the grep pattern PATTERN (for status 2,
# a usage line may follow it).
expect_fail() {
	n=$1 st=$2 pat=$3; shift 3
	"$@" >/dev/null 2>stderr.txt
	rc=$?
	if [ "$rc" -ne "$st" ]; then notok "$n" "exit $rc, want $st ($(head -c 300 stderr.txt))"
	elif ! grep -q -e "$pat" stderr.txt; then notok "$n" "stderr '$(head -c 300 stderr.txt)' lacks '$pat'"
	elif [ "$(wc -l <stderr.txt)" -ne 1 ] && ! { [ "$st" -eq 2 ] &&
		[ "$(wc -l <stderr.txt)" -eq 2 ] && sed -n 2p stderr.txt | grep -q '^usage: '; }; then notok "$n" "want one stderr line, got: $(head -c 300 stderr.txt)"
	else ok "$n"; fi
}
# num_near NAME VALUE WANT TOL : |VALUE - WANT| <= TOL (floats, via awk); a
# VALUE that is not a finite number (empty, nan, inf) fails.
num_near() {
	if printf '%s\n' "$2" | grep -Eq '^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$' &&
		awk -v a="$2" -v b="$3" -v t="$4" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'; then ok "$1"
	else notok "$1" "$2 not within $4 of $3"; fi
}
# kv FILE KEY : value of a "key: value" line.
kv() { sed -n "s/^$2: *//p" "$1" | head -n 1; }
