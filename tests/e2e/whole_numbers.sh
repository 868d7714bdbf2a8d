# whole_numbers.sh — integer options (the shared parser of tools/util.c)
# take exponent form when the value is exact: -n 1e6, -n 2.5e5; a fraction
# (1.5, 1e-3) or an overflowing value (1e30) is a bad command line.
. "$PM_TOP/tests/lib.sh"

cp "$PM_TOP/tests/scenes/furnace.pms" s.pms

# same photons: the records of two files agree (their command lines differ)
same_photons() { pm-dump --tsv "$1" >"$1.tsv" && pm-dump --tsv "$2" >"$2.tsv" && cmp -s "$1.tsv" "$2.tsv"; }
pm-shoot -q -n 2.5e3 -s 7 -o a.pm s.pms && pm-dump --stats a.pm >a.txt
check "-n 2.5e3 stores 2500 photons" test "$(kv a.txt photons)" = 2500
pm-shoot -q -n 2500 -s 7e0 -j 1e0 -o b.pm s.pms
check "-s 7e0 -j 1e0 are -s 7 -j 1" same_photons a.pm b.pm
pm-shoot -q -n 250000e-2 -s 0.07e2 -o c.pm s.pms
check "-n 250000e-2 -s 0.07e2 are -n 2500 -s 7" same_photons a.pm c.pm
pm-shoot -q -n 2500 -s 8 -o d.pm s.pms
check "(another seed gives other photons)" sh -c '! { pm-dump --tsv d.pm | cmp -s - a.pm.tsv; }'
expect_fail "-n 1e6 is a million (past --max-photons 1e5)" 2 \
	"^pm-shoot: -n: 1000000 is more than 100000 photons" pm-shoot -n 1e6 --max-photons 1e5 s.pms
expect_fail "-n 1.5 refused" 2 "^pm-shoot: -n: '1.5' is not a whole number$" pm-shoot -n 1.5 s.pms
expect_fail "-n 1e-3 refused" 2 "^pm-shoot: -n: '1e-3' is not a whole number$" pm-shoot -n 1e-3 s.pms
expect_fail "-n 1e30 refused as out of range" 2 "^pm-shoot: -n: 1e30 is out of range \[0, 4000000000\]$" \
	pm-shoot -n 1e30 s.pms
expect_fail "-s 1e20 refused (not below 2^64)" 2 "^pm-shoot: -s: '1e20' is not a whole number below 2^64$" \
	pm-shoot -s 1e20 s.pms
expect_fail "-n 1e refused" 2 "^pm-shoot: -n: '1e' is not a whole number$" pm-shoot -n 1e s.pms
pm-build -o map.pm a.pm
pm-render -q -p 2e0 -k 5e1 -s 7 s.pms map.pm -o x.exr
pm-render -q -p 2 -k 50 -s 7 s.pms map.pm -o y.exr
pm-diff x.exr y.exr >d.txt
check "pm-render -p 2e0 -k 5e1 are -p 2 -k 50" test "$(kv d.txt max_abs)" = 0
