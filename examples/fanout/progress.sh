# progress.sh — sourced by the fan-out scripts (examples/passes.sh,
# examples/progressive.sh, examples/fanout/*.sh): one overall progress line
# on stderr while pass pairs run, whatever runs them (a loop, xargs -P, GNU
# parallel, make -j), and one summary line at the end.
#
# pass.sh appends a line to the file $PM_PROGRESS_LOG when its pass is
# written, and runs the programs with -q, so their own bars do not fight
# over the terminal. A watcher in the background counts the lines once a
# second. At a terminal it rewrites one line in place,
#     LABEL: 5/8 passes, 1.9 s/pass, 0:06 left
# elsewhere (a log, a pipe) it writes that line when another tenth of the
# passes is done, or a minute after its last line if passes were done since:
# at most ten lines for a fast run of any size, and a sign of life in a slow
# one.
#
#   progress_begin N LABEL       count N passes (the first call starts the
#                                clock of the summary)
#   progress_end                 stop the watcher; the last count is shown
#   progress_summary LABEL IMAGE  "LABEL: P passes, S s, relative standard
#                                error X": P and X = mean_stderr / mean from
#                                `pm-average --stats IMAGE`, S since the first
#                                progress_begin
# The pm programs are found in $PM_BIN, else on PATH.

_progress_now() {
	_t=$(date +%s.%N)
	case $_t in *N*) _t=$(date +%s) ;; esac
	echo "$_t"
}

# _progress_line DONE TOTAL LABEL SECONDS: the progress line.
_progress_line() {
	awk -v d="$1" -v n="$2" -v l="$3" -v e="$4" 'BEGIN {
		if (d > 0) {
			left = int((n - d) * e / d + 0.5)
			printf "%s: %d/%d passes, %.3g s/pass, %d:%02d left", l, d, n, e / d, left / 60, left % 60
		} else
			printf "%s: 0/%d passes, %d:%02d so far", l, n, e / 60, e % 60
	}'
}

# The watcher, in the background: $1 passes, label $2, started at $3, log
# $4, the script's pid $5 (it stops if the script is gone).
_progress_watch() {
	# The scripts run with set -e; a failed look must not end the watcher
	# before its last line (a sleep already over cannot be killed, say).
	set +e
	_n=$1 _label=$2 _t0=$3 _log=$4 _pid=$5
	_tty=0 _shown=-1 _last=$3 _sleep=
	[ -t 2 ] && _tty=1
	trap '[ -z "$_sleep" ] || kill "$_sleep" 2>/dev/null; _progress_show; [ "$_tty" -eq 0 ] || echo >&2; exit 0' TERM
	while kill -0 "$_pid" 2>/dev/null; do
		_progress_show
		sleep 1 &
		_sleep=$!
		wait "$_sleep" || :
	done
}

# One look at the log, in the watcher: the line at a terminal; elsewhere
# only when a tenth more is done, all is done, or a minute has passed.
_progress_show() {
	_done=$(($(wc -l <"$_log") + 0))
	_now=$(_progress_now)
	_line=$(_progress_line "$_done" "$_n" "$_label" "$(awk -v a="$_now" -v b="$_t0" 'BEGIN { print a - b }')")
	if [ "$_tty" -eq 1 ]; then
		printf '\r%s\033[K' "$_line" >&2
	elif [ "$_done" -ne "$_shown" ] && { [ "$_done" -ge "$_n" ] || [ "$_shown" -lt 0 ] ||
		[ $((_done * 10 / _n)) -gt $((_shown * 10 / _n)) ] ||
		awk -v a="$_now" -v b="$_last" 'BEGIN { exit !(a - b >= 60) }'; }; then
		printf '%s\n' "$_line" >&2
		_shown=$_done _last=$_now
	fi
}

progress_begin() {
	: "${_pg_start:=$(_progress_now)}"
	[ "$1" -gt 0 ] || return 0    # a resumed make run with nothing left
	PM_PROGRESS_LOG=$(mktemp "${TMPDIR:-/tmp}/pm-progress.XXXXXX")
	export PM_PROGRESS_LOG
	_progress_watch "$1" "$2" "$(_progress_now)" "$PM_PROGRESS_LOG" $$ &
	_pg_watcher=$!
	# A failing pass ends the script (set -e): take the watcher along.
	trap 'progress_end' EXIT
	trap 'progress_end; exit 130' INT
	trap 'progress_end; exit 143' TERM
}

progress_end() {
	if [ -n "${_pg_watcher:-}" ]; then
		kill "$_pg_watcher" 2>/dev/null || :
		wait "$_pg_watcher" 2>/dev/null || :
		rm -f "$PM_PROGRESS_LOG"
	fi
	_pg_watcher=
	unset PM_PROGRESS_LOG
	trap - EXIT INT TERM
}

progress_summary() {
	_stats=$("${PM_BIN:+$PM_BIN/}pm-average" -q --stats "$2") || return 1
	echo "$_stats" | awk -v l="$1" -v e="$(awk -v a="$(_progress_now)" -v b="${_pg_start:-0}" 'BEGIN { print a - b }')" '
		/^passes:/ { p = $2 } /^mean_stderr:/ { s = $2 } /^mean:/ { m = $2 }
		END { printf "%s: %d passes, %.1f s, relative standard error %.4g\n", l, p, e, (m > 0 ? s / m : 0) }' >&2
}
