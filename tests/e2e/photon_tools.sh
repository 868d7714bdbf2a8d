# photon_tools.sh — pm-build and pm-dump over real pipes and files, with
# photons from the mkphotons test helper: counts, merging, the k nearest
# against a brute-force answer from the TSV, and every refusal.
. "$PM_TOP/tests/lib.sh"
mk="$PM_BIN/../tests/tools/mkphotons"

# --- a pipeline: photons -> map -> statistics --------------------------------
"$mk" -n 1000 -s 1 -p y=0 -p x=0 | pm-build | pm-dump --stats - >s1.txt
check "stats: 1000 photons" [ "$(kv s1.txt photons)" = 1000 ]
check "stats: 1000 emitted" [ "$(kv s1.txt emitted)" = 1000 ]
check "stats: a photon map" [ "$(kv s1.txt format)" = photonmap ]
check "stats: at most 20 bytes per photon" [ "$(kv s1.txt bytes_per_photon)" -le 20 ]
# 1000 nodes in a balanced tree: 2^9 <= 1000 < 2^10, so 10 levels
check "stats: tree depth 10" [ "$(kv s1.txt tree_depth)" = 10 ]
check "stats: history has both steps" [ "$(grep -c '^command: ' s1.txt)" = 2 ]
# powers are uniform in [0.5, 1.5) per channel and emitted = photons, so the
# total is the mean power, 1 (standard error about 0.01)
num_near "stats: total power near 1" "$(kv s1.txt total_power | cut -d' ' -f1)" 1 0.05

"$mk" -n 1000 -s 1 -p y=0 -p x=0 | pm-build -o map1.pm
check "stats: file_bytes is the file's size" [ "$(pm-dump --stats map1.pm | sed -n 's/^file_bytes: //p')" = "$(wc -c <map1.pm)" ]
pm-dump --tsv map1.pm >map1.tsv
check "tsv: header row and one line per photon" [ "$(wc -l <map1.tsv)" = 1001 ]
# the total flux from the TSV, summed independently, matches --stats
tot=$(awk 'NR > 1 { s += $7 } END { printf "%.9g", s }' map1.tsv)
num_near "tsv: flux sums to total_power" "$tot" "$(kv s1.txt total_power | cut -d' ' -f1)" 1e-6
# photons on y=0 arrive from +y, on x=0 from +x (mkphotons' hemispheres)
check "tsv: directions on the right side" awk 'NR > 1 && !(($2 == 0 && $5 > 0) || ($1 == 0 && $4 > 0)) { bad = 1 } END { exit bad }' map1.tsv

# --- merging -------------------------------------------------------------------
"$mk" -n 300 -s 1 -o a.pm
"$mk" -n 200 -s 2 -e 500 -o b.pm
pm-build a.pm b.pm -o ab.pm
pm-dump --stats ab.pm >ab.txt
pm-dump --stats a.pm >a.txt
pm-dump --stats b.pm >b.txt
check "merge: counts add" [ "$(kv ab.txt photons)" = 500 ]
check "merge: emitted adds" [ "$(kv ab.txt emitted)" = 800 ]
check "merge: seeds joined" [ "$(kv ab.txt seeds)" = 1,2 ]
check "merge: histories kept, oldest first" [ "$(grep '^command: ' ab.txt | cut -c10-21 | tr '\n' /)" = "mkphotons -n/mkphotons -n/pm-build a.p/" ]
want=$(awk -v a="$(kv a.txt total_power | cut -d' ' -f2)" -v b="$(kv b.txt total_power | cut -d' ' -f2)" 'BEGIN { print (a * 300 + b * 500) / 800 }')
num_near "merge: total power is the emitted-weighted mean" "$(kv ab.txt total_power | cut -d' ' -f2)" "$want" 1e-6
check "merge: the input is a plain photon file" [ "$(kv a.txt format)" = photons ]
# a map given as input is rebuilt, with one more history line
pm-build ab.pm -o ab2.pm
check "rebuild: same photons" [ "$(pm-dump --stats ab2.pm | sed -n 's/^photons: //p')" = 500 ]
check "rebuild: history grows" [ "$(pm-dump --stats ab2.pm | grep -c '^command: ')" = 4 ]
# stdin among files
"$mk" -n 50 -s 3 | pm-build a.pm - -o a3.pm
check "merge: stdin among files" [ "$(pm-dump --stats a3.pm | sed -n 's/^photons: //p')" = 350 ]

# --- the k nearest against brute force over the TSV ----------------------------
"$mk" -n 3000 -s 4 -p x=0 -p y=0 -p z=0 | pm-build -o map.pm
pm-dump --tsv map.pm >map.tsv
for metric in l2 linf; do
	for q in 0.3,0.2,0.1 0.9,0.9,0.9 -1,0.5,2 0.25,0.125,0; do
		pm-dump --near "$q" -k 7 --metric "$metric" map.pm | tail -n +2 | cut -f1,2 >near.txt
		# TSV row r (from 0) is photon index r
		awk -v q="$q" -v m="$metric" 'BEGIN { split(q, p, ",") }
			NR > 1 { dx = $1 - p[1]; dy = $2 - p[2]; dz = $3 - p[3]
				if (m == "l2") d = sqrt(dx * dx + dy * dy + dz * dz)
				else { if (dx < 0) dx = -dx; if (dy < 0) dy = -dy; if (dz < 0) dz = -dz
					d = dx; if (dy > d) d = dy; if (dz > d) d = dz }
				printf "%d\t%.9g\n", NR - 2, d }' map.tsv | sort -t "$(printf '\t')" -k2,2g -k1,1n | head -n 7 >brute.txt
		if [ "$(cut -f1 near.txt)" = "$(cut -f1 brute.txt)" ] && [ "$(wc -l <near.txt)" = 7 ] &&
		   paste near.txt brute.txt | awk '{ d = $2 - $4; if (d < 0) d = -d; if (d > 1e-6) exit 1 }'; then
			ok "near $metric $q matches brute force"
		else
			notok "near $metric $q matches brute force" "$(paste near.txt brute.txt | tr '\n' ' ')"
		fi
	done
done
check "near: k beyond the map returns all" [ "$(pm-dump --near 0,0,0 -k 5000 map.pm | wc -l)" = 3001 ]

# --- other views ---------------------------------------------------------------
pm-dump --ply map1.pm >map1.ply
check "ply: vertex count" grep -q '^element vertex 1000$' map1.ply
check "ply: one vertex line each" [ "$(sed '1,/^end_header$/d' map1.ply | wc -l)" = 1000 ]
check "ply: colours are bytes" awk '/^end_header$/ { on = 1; next } on && ($4 > 255 || $5 < 0 || NF != 9) { exit 1 }' map1.ply
pm-dump --header map1.pm >h.txt
check "header: starts with the magic" [ "$(head -n 1 h.txt)" = PM-PHOTONS ]
check "header: count line" grep -qx 'count=1000' h.txt
pm-dump --stats map1.pm -o st.txt
check "dump -o writes the file" grep -qx 'photons: 1000' st.txt

# --- refusals ------------------------------------------------------------------
"$mk" -n 1000 -s 5 -o full.pm
head -c 10000 full.pm >trunc.pm
expect_fail "truncated stream" 1 "^pm-build: stdin: truncated: 1000 photons promised, [0-9]* present$" sh -c 'pm-build -o t.pm <trunc.pm'
check "truncated: no output written" [ ! -e t.pm ]
# an existing output survives a failed run, and no temporary is left behind
cp map.pm out.pm
expect_fail "truncated input file" 1 "^pm-build: 'trunc.pm': truncated: 1000 photons promised" pm-build trunc.pm -o out.pm
check "failed build leaves out.pm untouched" cmp -s out.pm map.pm
check "failed build leaves no temporary" [ -z "$(ls -A | grep '^\.')" ]
check "header of a truncated file still readable" sh -c 'pm-dump --header - <trunc.pm | grep -qx count=1000'
expect_fail "trailing junk" 1 "^pm-dump: 'junk.pm': trailing data after 1000 photons$" sh -c 'cat full.pm full.pm >junk.pm; pm-dump --stats junk.pm'

"$mk" -n 10 -H 1 -o h1.pm
"$mk" -n 10 -H 2 -o h2.pm
expect_fail "different scenes refused" 1 "^pm-build: 'h2.pm': light_hash 0000000000000002 differs from 'h1.pm' (0000000000000001); --force merges anyway$" pm-build h1.pm h2.pm -o x.pm
check "different scenes: nothing written" [ ! -e x.pm ]
pm-build --force -q h1.pm h2.pm -o x.pm 2>force.err
check "--force merges different scenes" [ "$(pm-dump --stats x.pm | sed -n 's/^photons: //p')" = 20 ]
check "--force -q is quiet" [ ! -s force.err ]
pm-build --force h1.pm h2.pm -o x.pm 2>force.err
check "--force warns" grep -q "^pm-build: 'h2.pm': light_hash 0000000000000002 differs" force.err
"$mk" -n 10 -H 1 -t 0.5 -o t5.pm
expect_fail "different times refused" 1 "^pm-build: 't5.pm': time 0.5 differs from 'h1.pm' (0); --force merges anyway$" pm-build h1.pm t5.pm -o x.pm

printf 'hello, world\n' >garbage
expect_fail "garbage refused" 1 "^pm-dump: 'garbage': not a photon file (no PM-PHOTONS magic)$" pm-dump --stats garbage
expect_fail "empty input refused" 1 "^pm-build: stdin: empty, not a photon file$" sh -c 'pm-build </dev/null >/dev/null'
expect_fail "missing file" 1 "^pm-dump: cannot open 'nope.pm': No such file or directory$" pm-dump --tsv nope.pm
expect_fail "near needs a map" 1 "^pm-dump: 'a.pm': a photon file, not a photon map (kdtree=0); run pm-build on it first$" pm-dump --near 0,0,0 a.pm
sed 's/^version=1$/version=3/' full.pm >v2.pm
expect_fail "newer version refused" 1 "^pm-dump: 'v2.pm': photon file version 3 is newer than this pm (2)$" pm-dump --stats v2.pm

# --- the command line ----------------------------------------------------------
pm-build -h >help.txt; rc=$?
check "pm-build -h exits 0" [ "$rc" = 0 ]
check "pm-build -h lists every option" sh -c 'for o in -f --force -h -o -q; do grep -q -e " $o" help.txt || exit 1; done'
pm-dump -h >help.txt; rc=$?
check "pm-dump -h exits 0" [ "$rc" = 0 ]
check "pm-dump -h lists every option" sh -c 'for o in --header --near --ply --stats --tsv -k --metric -o; do grep -q -e " $o" help.txt || exit 1; done'
pm-build --bogus </dev/null >/dev/null 2>err.txt; rc=$?
check "pm-build: unknown option exits 2" [ "$rc" = 2 ]
check "pm-build: unknown option named" grep -q "^pm-build: unknown option '--bogus'$" err.txt
pm-dump map.pm 2>err.txt; rc=$?
check "pm-dump: no mode exits 2" [ "$rc" = 2 ]
pm-dump --near 1,2 map.pm 2>err.txt; rc=$?
check "pm-dump: bad point exits 2" [ "$rc" = 2 ]
check "pm-dump: bad point named" grep -q "^pm-dump: --near: '1,2' is not X,Y,Z$" err.txt
pm-dump --near 0,0,0 -k 0 map.pm 2>err.txt; rc=$?
check "pm-dump: -k 0 exits 2" [ "$rc" = 2 ]
pm-dump --stats --tsv map.pm 2>err.txt; rc=$?
check "pm-dump: two modes exit 2" [ "$rc" = 2 ]
