# provenance.sh — pm-average knows which passes it averages (pm.pass_ids,
# formats/image.md): it refuses a file given twice, a pass rendered twice
# with the same seeds and time (a loop that forgot -s / -P), an average
# together with one of its own passes, and passes of different estimators,
# naming the files; --force averages anyway, warns, and records it in the
# output; averages list their passes' ids, so averages of averages are
# checked too; files without ids are accepted as before.
. "$PM_TOP/tests/lib.sh"
T=$PM_BIN/../tests/tools
scene=$PM_TOP/examples/fanout/scene.pms
# pair OUT EST SHOOT-ARGS RENDER-ARGS: one light pass and view pass.
pair() {
	pm-shoot -q -n 2000 $3 "$scene" | pm-build -q | pm-render -q -p 1 -e $2 $4 "$scene" - -o $1
}
ids() { "$T/exrattr" "$1" pm.pass_ids; }
for i in 1 2 3; do pair p$i.exr compensated "-P $i/3" "-P $i/3"; done
pair again.exr compensated "-P 1/3" "-P 1/3"
pair forgot1.exr compensated "" ""
pair forgot2.exr compensated "" ""
pm-render -q -p 1 -e path -P 2/3 "$scene" -o path2.exr
id1=$(ids p1.exr) id2=$(ids p2.exr) id3=$(ids p3.exr)

check "a pass records one id of 16 hex digits" sh -c "echo '$id1' | grep -qx '[0-9a-f]\{16\}'"
check "passes of different seeds have different ids" test "$id1" != "$id2" -a "$id2" != "$id3"
check "the same seeds and time give the same id" test "$(ids again.exr)" = "$id1"

expect_fail "a file given twice is refused" 1 "^pm-average: 'p1.exr' is given twice; --force averages anyway$" \
	pm-average p1.exr p1.exr -o x.exr
expect_fail "a pass rendered twice is refused, naming both files" 1 \
	"^pm-average: 'again.exr' repeats pass $id1 of 'p1.exr' (the same scene, estimator, seeds and time); --force averages anyway$" \
	pm-average p1.exr p2.exr again.exr -o x.exr
expect_fail "passes without -s or -P are the same pass" 1 "'forgot2.exr' repeats pass .* of 'forgot1.exr'" \
	pm-average forgot1.exr forgot2.exr -o x.exr
expect_fail "--stats alone refuses too" 1 "'forgot2.exr' repeats pass" pm-average -s forgot1.exr forgot2.exr
check "a refusal writes no output" test ! -e x.exr

# An average lists its passes' ids, sorted; an average of averages is checked.
sorted() { printf '%s\n' "$@" | sort | tr '\n' ' ' | sed 's/ $//'; }
pm-average -q p2.exr p1.exr -o a12.exr
check "an average lists its passes' ids, sorted" test "$(ids a12.exr)" = "$(sorted $id1 $id2)"
expect_fail "an average with one of its own passes is refused" 1 \
	"^pm-average: 'p2.exr' repeats pass $id2 of 'a12.exr' (the same scene, estimator, seeds and time); --force averages anyway$" \
	pm-average a12.exr p3.exr p2.exr -o x.exr
pm-average -q p3.exr -o a3.exr
expect_fail "two averages sharing a pass are refused" 1 "'a12.exr' repeats pass $id1 of 'again.exr'" \
	pm-average again.exr a3.exr a12.exr -o x.exr
pm-average -q a12.exr a3.exr -o tree.exr
pm-average -q p3.exr p1.exr p2.exr -o flat.exr
check "an average of averages lists the same ids as the flat average" \
	test "$(ids tree.exr)" = "$(sorted $id1 $id2 $id3)" -a "$(ids flat.exr)" = "$(ids tree.exr)"
pm-diff tree.exr flat.exr >d.txt
num_near "... and has its pixels" "$(kv d.txt max_abs)" 0 1e-5
check "no pm.forced without --force" sh -c "! '$T/exrattr' tree.exr pm.forced"

# The photon map's seeds are part of a pass's identity; the view seed too.
pair mapseed.exr compensated "-P 1/3 -s 77" "-P 1/3"
pair viewseed.exr compensated "-P 1/3" "-P 1/3 -s 77"
check "another light-pass seed makes another pass" test "$(ids mapseed.exr)" != "$id1"
check "another view seed makes another pass" test "$(ids viewseed.exr)" != "$id1"
pm-average -q p1.exr mapseed.exr viewseed.exr -o seeds.exr
check "... and they average without complaint" test $? -eq 0 -a -s seeds.exr

expect_fail "mixed estimators are refused, naming files and estimators" 1 \
	"^pm-average: 'path2.exr': estimator path differs from 'p1.exr' (compensated); --force averages anyway$" \
	pm-average p1.exr path2.exr -o x.exr

# --force: averaged, with a warning per kind of override, recorded.
pm-average --force p1.exr path2.exr again.exr p3.exr -o f.exr 2>err.txt
check "--force averages anyway" test $? -eq 0 -a "$("$T/exrattr" f.exr pm.passes)" = 4
check "--force warns about the estimators" grep -q "^pm-average: 'path2.exr': estimator path differs from 'p1.exr' (compensated); averaging anyway$" err.txt
check "--force warns about the repeated pass" grep -q "^pm-average: 'again.exr' repeats pass $id1 of 'p1.exr' .*; averaging anyway$" err.txt
check "... two warnings in all" test "$(wc -l <err.txt)" -eq 2
check "a forced average records what was forced" test "$("$T/exrattr" f.exr pm.forced)" = "estimator duplicates"
check "... its estimator is 'mixed'" test "$("$T/exrattr" f.exr pm.estimator)" = mixed
check "... and it lists the repeated id twice" test "$(ids f.exr)" = "$(sorted $id1 $id1 $(ids path2.exr) $id3)"
pm-average -q --force p1.exr again.exr -o fq.exr 2>err.txt
check "--force -q averages silently" test $? -eq 0 -a ! -s err.txt
expect_fail "a forced average is refused again with other passes" 1 "'p2.exr': estimator compensated differs from 'f.exr' (mixed)" \
	pm-average f.exr p2.exr -o x.exr
expect_fail "a forced average's own repeat is refused" 1 "^pm-average: 'fq.exr' holds pass $id1 twice; --force averages anyway$" \
	pm-average fq.exr p2.exr -o x.exr
pm-average -q --force fq.exr p2.exr -o ff.exr
check "averaging a forced average keeps pm.forced" test "$("$T/exrattr" ff.exr pm.forced)" = duplicates

# Files without ids (older pm, other programs) are accepted as before; the
# average then lists no ids, since it cannot list them all.
"$T/mkimg" -v 1,1,1 -a pm.estimator=compensated -a pm.scene_hash="$("$T/exrattr" p1.exr pm.scene_hash)" old.exr 48 36
pm-average -q old.exr p1.exr -o withold.exr
check "a file without pm.pass_ids is accepted" test $? -eq 0 -a "$("$T/exrattr" withold.exr pm.passes)" = 2
check "... and the average then lists no ids" sh -c "! '$T/exrattr' withold.exr pm.pass_ids"

"$T/mkimg" -a pm.passes=2 -a pm.pass_ids=$id1 short.exr 48 36
expect_fail "pm.pass_ids must list pm.passes ids" 1 "^pm-average: 'short.exr': pm.pass_ids has 1 ids but pm.passes is 2$" \
	pm-average short.exr -s
"$T/mkimg" -a "pm.pass_ids=$id1,$id2" -a pm.passes=2 comma.exr 48 36
expect_fail "a malformed pm.pass_ids is refused" 1 "^pm-average: 'comma.exr': pm.pass_ids is not a list of 16-digit hex ids$" \
	pm-average p3.exr comma.exr -o x.exr

# Thousands of passes: two averages of 5000 passes each (ids 1..10000; an
# argument holds at most 128 KiB, so one list of 10000 cannot be made here).
seq 1 5000 | awk '{ printf "%s%016x", (NR > 1 ? " " : ""), $1 }' >h1.txt
seq 5001 10000 | awk '{ printf "%s%016x", (NR > 1 ? " " : ""), $1 }' >h2.txt
"$T/mkimg" -a pm.passes=5000 -a "pm.pass_ids=$(cat h2.txt)" big2.exr 8 6
"$T/mkimg" -a pm.passes=5000 -a "pm.pass_ids=$(cat h1.txt)" big1.exr 8 6
pm-average -q big2.exr big1.exr -o big.exr
check "10000 ids: listed sorted in the average" test "$(ids big.exr)" = "$(cat h1.txt) $(cat h2.txt)"
pm-average -q big.exr -o big_again.exr
check "... and read back from it" test "$(ids big_again.exr)" = "$(ids big.exr)"
expect_fail "... and a repeat among them is found" 1 "'big.exr' repeats pass 0000000000001389 of 'big2.exr'" \
	pm-average big2.exr big.exr -o x.exr
