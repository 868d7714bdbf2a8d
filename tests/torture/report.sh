#!/bin/sh
# report.sh — the torture harness over many scenes: N generated scenes
# (seeds FIRST_SEED .. FIRST_SEED+N-1, tests/tools/genscene) and every fixed
# scene in tests/torture/regress/, each run by scene.sh (compensated and
# classical estimates from the same photon maps against the path tracer,
# and the furnace twin against the exact 2), at most P at a time.
#
# Usage: tests/torture/report.sh N [FIRST_SEED] [OUTDIR]
#   FIRST_SEED  default 1; OUTDIR default tests/torture/out
# Writes OUTDIR/report.md (a table of every scene's numbers and bars, and a
# summary: how many pass each bar, medians), OUTDIR/worst.png (the worst
# scenes, one row each: compensated | classical | path | |error| of the
# compensated, 5x5 box mean, x4) and OUTDIR/worst-furnace.png (the same for the furnace
# twins, against the exact 2), and OUTDIR/seed-S/, OUTDIR/regress-NAME/
# (each scene's files and stats.txt; see scene.sh).
# Settings: scene.sh's (N is taken by the argument here: set PASSES for the
# pass pairs per scene, default 12; SPP default 2, FURNACE_N 12, REFSPP 64), and
#   P=2       scenes at a time (each program runs with J=1 thread)
#   REGRESS=1 also the regression scenes (0: not)
#   KNOWN=0   1: also the scenes of known/ (generated scenes that failed)
#   REUSE=0   1: keep a scene whose stats.txt exists, do not rerun it
#   WORST=8   rows in the contact sheets
set -eu
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/../.." && pwd)
[ $# -ge 1 ] && [ $# -le 3 ] || { echo "usage: report.sh N [FIRST_SEED] [OUTDIR]" >&2; exit 2; }
count=$1 first=${2:-1} out=${3:-$top/tests/torture/out}
case $count$first in *[!0-9]*) echo "usage: report.sh N [FIRST_SEED] [OUTDIR]" >&2; exit 2 ;; esac
P=${P:-2} REGRESS=${REGRESS:-1} KNOWN=${KNOWN:-0} REUSE=${REUSE:-0} WORST=${WORST:-8}
bin=${PM_BIN:-$top/build/bin}
tools=$bin/../tests/tools
mkdir -p "$out"
out=$(cd "$out" && pwd)

# The job list: "ARG DIR" per line.
jobs=$out/jobs.txt
: >"$jobs"
s=$first
while [ "$s" -lt $((first + count)) ]; do
	echo "$s $out/seed-$s" >>"$jobs"
	s=$((s + 1))
done
if [ "$REGRESS" = 1 ]; then
	for f in "$here"/regress/*.pms; do
		[ -f "$f" ] && echo "$f $out/regress-$(basename "$f" .pms)" >>"$jobs"
	done
fi
# KNOWN=1: also the generated scenes that failed a bar in the committed
# report, kept as files in known/ (so a change to genscene cannot lose them).
if [ "$KNOWN" = 1 ]; then
	for f in "$here"/known/*/scene.pms; do
		[ -f "$f" ] && echo "$f $out/known-$(basename "$(dirname "$f")")" >>"$jobs"
	done
fi
njobs=$(wc -l <"$jobs")
echo "report.sh: $njobs scenes, $P at a time, into $out" >&2
export PM_BIN="$bin" REUSE here
# The committed report's settings: enough passes that the split-half bias
# and the furnace means are mostly bias, cheap enough for 200 scenes in
# well under an hour on two cores.
export N="${PASSES:-12}" SPP="${SPP:-2}" FURNACE_N="${FURNACE_N:-12}" REFSPP="${REFSPP:-64}"
t0=$(date +%s)
# A failed scene leaves DIR/log.txt and no stats.txt; the others go on.
xargs -P "$P" -L 1 sh -c '
	d=$2
	if [ "$REUSE" = 1 ] && [ -f "$d/stats.txt" ]; then exit 0; fi
	mkdir -p "$d"
	if J=1 sh "$here/scene.sh" "$1" "$d" >"$d/log.txt" 2>&1; then
		echo "  $(basename "$d"): $(sed -n "s/^verdict=//p" "$d/stats.txt") / furnace $(sed -n "s/^furnace_verdict=//p" "$d/stats.txt") ($(sed -n "s/^seconds=//p" "$d/stats.txt") s)" >&2
	else
		echo "  $(basename "$d"): FAILED (see $d/log.txt)" >&2
	fi' sh <"$jobs" || true
t1=$(date +%s)

# One TSV row per scene, fixed columns.
keys="scene desc seconds rmse_comp rmse_class max_comp max_class edge_pixels edge_mae_comp edge_mae_class edge_noise_comp edge_bias_comp edge_bias_class fireflies_comp fireflies_class ref_rel_stderr bar_rmse bar_max bar_edge bar_fireflies verdict furnace_rmse_comp furnace_rmse_class furnace_max_comp furnace_max_class furnace_edge_mae_comp furnace_edge_mae_class furnace_edge_bias_comp furnace_edge_bias_class furnace_fireflies_comp furnace_edge_mean_err_comp furnace_edge_mean_err_class furnace_bar_rmse furnace_bar_max furnace_bar_edge furnace_bar_fireflies furnace_bar_furnace furnace_verdict bar_furnace edge_mean_err_comp edge_mean_err_class dir settings"
tsv=$out/stats.tsv
echo "$keys" | tr ' ' '\t' >"$tsv"
failed=
while read -r arg d; do
	if [ -f "$d/stats.txt" ]; then
		awk -v keys="$keys" -v dir="$d" -F= '
			{ k = $1; sub(/^[^=]*=/, ""); gsub(/\t|\|/, " "); v[k] = $0 }
			END { v["dir"] = dir; n = split(keys, K, " ")
				for (i = 1; i <= n; i++) printf "%s%s", (K[i] in v) ? v[K[i]] : "-", i < n ? "\t" : "\n" }' "$d/stats.txt" >>"$tsv"
	else
		why=$(grep -m 1 'TIMEOUT' "$d/log.txt" 2>/dev/null || tail -n 1 "$d/log.txt" 2>/dev/null || echo "no log")
		failed="$failed
- $(basename "$d"): $(echo "$why" | cut -c 1-300)"
	fi
done <"$jobs"

# Badness, for the contact sheets: failed bars first, then how much worse
# than the classical estimate the compensated one is at edges and at most.
rank() {  # rank PREFIX: the worst scenes' directories
	awk -F'\t' -v p="$1" '
		NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
		function f(k) { return $(c[p k]) }
		f("verdict") != "-" {
			b = 0
			split("bar_rmse bar_max bar_edge bar_fireflies bar_furnace", B, " ")
			for (i in B) if ((p B[i]) in c && f(B[i]) == "fail") b++
			r1 = f("edge_bias_class") + 0 > 0 ? f("edge_bias_comp") / f("edge_bias_class") : 0
			r2 = f("max_class") + 0 > 0 ? f("max_comp") / f("max_class") : 0
			printf "%d %.6f %s\n", b, r1 + r2, $(c["dir"])
		}' "$tsv" | sort -k1,1nr -k2,2gr | head -n "$WORST" | cut -d' ' -f3
}
sheet() {  # sheet SUBDIR REFFILE OUT.png
	set --  "$1" "$2" "$3"
	files=
	for d in $(rank "$([ "$1" = furnace ] && echo furnace_)"); do
		[ -f "$d/$1/comp.exr" ] || continue
		files="$files $d/$1/comp.exr $d/$1/class.exr $d/$1/$2 $d/$1/err-comp.exr"
	done
	[ -n "$files" ] && "$tools/contactsheet" -c 4 -r 3 -a 4 -g 4 -f 5 -s 2 -o "$3" $files
}
sheet scene ref.exr "$out/worst.png" || echo "report.sh: no contact sheet" >&2
sheet furnace exact.exr "$out/worst-furnace.png" || echo "report.sh: no furnace contact sheet" >&2

unfinished=$(echo "$failed" | grep -c '^- ' || true)
# The report.
{
	echo "# Torture report"
	echo
	echo "Generated by \`tests/torture/report.sh $count $first\` on $(date -u '+%Y-%m-%d %H:%M UTC'),"
	echo "$(uname -sm), $(nproc) cores, commit $(git -C "$top" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$top" diff --quiet HEAD -- lib tools 2>/dev/null || echo ' (lib/ or tools/ modified)');"
	echo "$njobs scenes in $((t1 - t0)) s, $P at a time."
	echo "Settings: $(awk -F'\t' 'NR == 2 { print $NF }' "$tsv")."
	if [ -n "$failed" ]; then
		echo
		echo "**Scenes that did not finish** ($unfinished of $njobs; they count as failing every bar; see their log.txt):"
		echo "$failed"
	fi
	cat <<'TXT'

Every number is about the mean of R, G and B per pixel. `comp` is the
compensated estimate, `class` the classical one, from the same photon maps;
the reference is the path tracer (an average of passes, with its standard
error), or the exact 2 for furnaces. Edge band: pixels whose compensated
estimate's cube meets another surface (the `edge` layer of the first
compensated pass). edge MAE: mean over the edge band of |local ratio - 1|,
local ratio = 5x5 box mean of the estimate / of the reference; at these
settings it is mostly noise (the estimates' and the reference's). edge
bias: the same local error with the noise taken out: the passes (and the
reference's passes) are split into odd and even halves, whose local errors
eA, eB have independent noise, so mean(eA eB) over the band estimates the
mean squared bias; shown as its square root (0 when the noise hides any
bias). Fireflies:
pixels above 3 ref + 5 stderr + 1% of the mean. The furnace twin is the same
geometry with every surface albedo 0.5, emission 1 (both sides), no point
lights: exact radiance 2.

Bars (each scene and each furnace twin): **rmse** rmse_comp <= 1.05 rmse_class;
**max** max_comp <= 2 max_class; **edge** edge bias comp <= 0.5 edge bias class;
**ff** no fireflies in comp; **1%** (furnace) |mean edge error of comp| <= 1%.

TXT
	awk -F'\t' -v unfinished="$unfinished" '
	NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
	function f(k) { return $(c[k]) }
	function g(v) { return v == "-" ? "-" : sprintf("%.3g", v) }
	function pct(v) { return v == "-" ? "-" : sprintf("%+.1f%%", 100 * v) }
	function b(v) { return v == "fail" ? "**FAIL**" : v == "pass" ? "ok" : v }
	# F columns: the furnace twin, or the scene itself when it is a furnace
	function fu(k) { return f("furnace_" k) != "-" ? f("furnace_" k) : (k == "bar_furnace" || k ~ /^edge_mean_err/) ? f(k) : "-" }
	function add(name, v) { if (v != "-" && v != "nan" && v != "") { n[name]++; val[name, n[name]] = v + 0 } }
	function tally(name, v) { if (v == "pass" || v == "fail") { tot[name]++; if (v == "pass") ok[name]++ } }
	function median(name,   i, j, t, m, a) {
		m = n[name]; if (!m) return "-"
		for (i = 1; i <= m; i++) a[i] = val[name, i]
		for (i = 2; i <= m; i++) { t = a[i]; for (j = i - 1; j >= 1 && a[j] > t; j--) a[j + 1] = a[j]; a[j + 1] = t }
		return m % 2 ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2
	}
	{
		rows = rows sprintf("| %s | %s | %s / %s | %s / %s | %s | %s / %s | %s / %s | %s / %s | %s | %s / %s | %s / %s | %s / %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
			f("scene"), f("desc"), g(f("rmse_comp")), g(f("rmse_class")), g(f("max_comp")), g(f("max_class")),
			f("edge_pixels"), g(f("edge_mae_comp")), g(f("edge_mae_class")), g(f("edge_bias_comp")), g(f("edge_bias_class")), f("fireflies_comp"), f("fireflies_class"),
			pct(f("ref_rel_stderr")),
			g(f("furnace_rmse_comp")), g(f("furnace_rmse_class")), g(f("furnace_edge_bias_comp")), g(f("furnace_edge_bias_class")),
			pct(fu("edge_mean_err_comp")), pct(fu("edge_mean_err_class")),
			b(f("bar_rmse")), b(f("bar_max")), b(f("bar_edge")), b(f("bar_fireflies")),
			b(f("furnace_bar_rmse")), b(f("furnace_bar_max")), b(f("furnace_bar_edge")), b(f("furnace_bar_fireflies")), b(fu("bar_furnace")),
			f("seconds"))
		split("bar_rmse bar_max bar_edge bar_fireflies verdict furnace_bar_rmse furnace_bar_max furnace_bar_edge furnace_bar_fireflies furnace_bar_furnace furnace_verdict", T, " ")
		for (i = 1; i <= 11; i++) tally(T[i], T[i] == "furnace_bar_furnace" ? fu("bar_furnace") : f(T[i]))
		if (f("rmse_class") + 0 > 0) add("rmse ratio comp/class", f("rmse_comp") / f("rmse_class"))
		if (f("max_class") + 0 > 0) add("max ratio comp/class", f("max_comp") / f("max_class"))
		if (f("edge_mae_class") + 0 > 0) add("edge MAE ratio comp/class", f("edge_mae_comp") / f("edge_mae_class"))
		add("edge MAE comp", f("edge_mae_comp")); add("edge MAE class", f("edge_mae_class"))
		add("edge MAE noise bound comp", f("edge_noise_comp"))
		add("edge bias comp", f("edge_bias_comp")); add("edge bias class", f("edge_bias_class"))
		add("fireflies comp", f("fireflies_comp")); add("fireflies class", f("fireflies_class"))
		add("reference relative stderr", f("ref_rel_stderr"))
		if (f("furnace_rmse_class") + 0 > 0) add("furnace rmse ratio comp/class", f("furnace_rmse_comp") / f("furnace_rmse_class"))
		if (f("furnace_edge_mae_class") + 0 > 0) add("furnace edge MAE ratio comp/class", f("furnace_edge_mae_comp") / f("furnace_edge_mae_class"))
		add("furnace edge bias comp", f("furnace_edge_bias_comp")); add("furnace edge bias class", f("furnace_edge_bias_class"))
		add("furnace mean edge error comp", fu("edge_mean_err_comp"))
		add("furnace mean edge error class", fu("edge_mean_err_class"))
		add("seconds per scene", f("seconds"))
	}
	END {
		print "## Summary"
		print ""
		print "| bar | scenes passing |"
		print "|---|---|"
		split("bar_rmse:rmse (comp <= 1.05 class)|bar_max:max (comp <= 2 class)|bar_edge:edge (bias comp <= 0.5 class)|bar_fireflies:no fireflies (comp)|verdict:all of the above|furnace_bar_rmse:furnace rmse|furnace_bar_max:furnace max|furnace_bar_edge:furnace edge bias|furnace_bar_fireflies:furnace fireflies|furnace_bar_furnace:furnace mean edge error <= 1%|furnace_verdict:furnace, all bars", L, "|")
		for (i = 1; i <= 11; i++) { split(L[i], kv, ":"); printf "| %s | %d / %d |\n", kv[2], ok[kv[1]], tot[kv[1]] + unfinished }
		if (unfinished) printf "\n(The %d scenes that did not finish count as failing every bar.)\n", unfinished
		print ""
		print "| median over scenes | value |"
		print "|---|---|"
		split("rmse ratio comp/class|max ratio comp/class|edge MAE ratio comp/class|edge MAE comp|edge MAE class|edge MAE noise bound comp|edge bias comp|edge bias class|fireflies comp|fireflies class|reference relative stderr|furnace rmse ratio comp/class|furnace edge MAE ratio comp/class|furnace edge bias comp|furnace edge bias class|furnace mean edge error comp|furnace mean edge error class|seconds per scene", M, "|")
		for (i = 1; i <= 18; i++) printf "| %s | %s |\n", M[i], g(median(M[i]))
		print ""
		print "## Scenes"
		print ""
		print "Pairs are comp / class. F: the furnace twin (error against 2). Bars: ok, **FAIL**, or na (no edge band)."
		print ""
		print "| scene | description | rmse | max | edge px | edge MAE | edge bias | fireflies | ref stderr | F rmse | F edge bias | F mean edge err | rmse | max | edge | ff | F rmse | F max | F edge | F ff | F 1% | s |"
		print "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
		printf "%s", rows
	}' "$tsv"
	echo
	echo "## The worst scenes"
	echo
	echo "\`worst.png\`: one row per scene, worst first (most failed bars, then the"
	echo "largest comp/class ratios of edge bias and max error): compensated | classical |"
	echo "path | the compensated estimate's relative error (compensated - path) / path,"
	echo "5x5 box mean, |.| x 4 (white: 25% or more). Each row has one"
	echo "exposure, set by the path image's mean. \`worst-furnace.png\`: the same for"
	echo "the furnace twins, against the exact 2."
	echo
	echo "Rows of worst.png: $(for d in $(rank ""); do printf '%s ' "$(basename "$d")"; done)"
	echo
	echo "Rows of worst-furnace.png: $(for d in $(rank furnace_); do printf '%s ' "$(basename "$d")"; done)"
	echo
	echo "![worst](worst.png)"
	echo
	echo "![worst furnace](worst-furnace.png)"
} >"$out/report.md"
echo "report.sh: $out/report.md" >&2
