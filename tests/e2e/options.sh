# options.sh — one command-line convention for every program (tools/options.c):
# a missing value is named as missing, an unknown option gets the same
# message everywhere, every option -h lists has a long form that works,
# --version prints "pm-NAME VERSION" and is what files record, and the
# options that do not change outputs (-q, -j) write the same bytes in any
# spelling.
. "$PM_TOP/tests/lib.sh"
progs="pm-shoot pm-build pm-render pm-average pm-dump pm-diff pm-tonemap pm-import"

cat >box.pms <<'SCENE'
camera eye 0 1 3.4  look 0 1 0  up 0 1 0  fov 45  size 16 12
material white diffuse albedo 0.7 0.7 0.7
quad white -1 0 -1  1 0 -1  1 0 1  -1 0 1
quad white -1 2 -1  -1 2 1  1 2 1  1 2 -1
pointlight 0 1.5 0 power 2 2 2
SCENE

version=$(sed -n 's/^#define PM_VERSION "\(.*\)"$/\1/p' "$PM_TOP/lib/base/version.h")
check "lib/base/version.h defines PM_VERSION" test -n "$version"
for p in $progs; do
	out=$($p --version 2>&1); rc=$?
	check "$p --version exits 0" test $rc -eq 0
	check "$p --version prints '$p $version'" test "$out" = "$p $version"

	expect_fail "$p unknown long option" 2 "^$p: unknown option '--no-such-option'$" $p --no-such-option x
	expect_fail "$p unknown short option in a cluster" 2 "^$p: unknown option '-Z'$" $p -Zh x
	expect_fail "$p -o without its value" 2 "^$p: option '-o' needs a value$" $p x -o
	expect_fail "$p --output without its value" 2 "^$p: option '--output' needs a value$" $p x --output
	expect_fail "$p --help=x" 2 "^$p: option '--help' takes no value$" $p --help=x

	# Every option -h lists is "-x, --long" or "--long"; each long form is
	# accepted (--help and --version stop at once, others are refused later
	# for other reasons, never as unknown).
	$p -h >help.txt
	longs=$(sed -n 's/^  \(-., \)\{0,1\}\(--[a-z-]*\).*/\2/p; s/^      \(--[a-z-]*\).*/\1/p' help.txt | sort -u)
	check "$p -h lists long forms" test -n "$longs"
	sed -n 's/^  \(-[A-Za-z]\)[ ,].*/\1/p' help.txt >short.txt
	nolong=$(grep -c '^  -[A-Za-z] ' help.txt)
	check "$p: every short option in -h has a long form" test "$nolong" -eq 0
	bad=
	for l in $longs; do
		$p $l=1 x y >/dev/null 2>err.txt </dev/null
		grep -q "unknown option" err.txt && bad="$bad $l"
	done
	check "$p accepts all its long forms:${bad:- yes}" test -z "$bad"
	# The man page lists every option -h lists, in both forms.
	page=$PM_TOP/man/$p.1
	missing=
	for l in $longs $(cat short.txt); do
		sed 's/\\-/-/g; s/\\f[BIRP]//g' "$page" | grep -q -e "$l\b" || missing="$missing $l"
	done
	check "$p.1 lists every option of -h:${missing:- yes}" test -z "$missing"
done

# -q and --quiet, -j and --threads: the same bytes.
pm-shoot -n 2000 -s 1 -q -j 1 box.pms -o a.pm 2>/dev/null && mv a.pm q.pm &&
pm-shoot -n 2000 -s 1 --quiet --threads=2 box.pms -o a.pm 2>/dev/null && mv a.pm l.pm &&
pm-shoot --qui --thr 1 -n 2000 -s 1 box.pms -o a.pm 2>/dev/null && mv a.pm p.pm &&
pm-shoot -n 2000 -s 1 box.pms -o a.pm 2>/dev/null
check "pm-shoot: -q -j, --quiet --threads=, abbreviations and none write the same bytes" \
	sh -c 'cmp -s a.pm q.pm && cmp -s a.pm l.pm && cmp -s a.pm p.pm'
check "pm-shoot: the long forms of other options are recorded" \
	sh -c 'pm-shoot --photons 2000 --seed=1 box.pms -o b.pm && pm-dump --header b.pm | grep -q "^command=pm-shoot --photons 2000 --seed=1 box.pms -o b.pm$"'
pm-build -q -o m.pm a.pm && mv m.pm m1.pm && pm-build --quiet -o m.pm a.pm && mv m.pm m2.pm &&
	pm-build -qj1 -o m.pm a.pm && mv m.pm m3.pm
check "pm-build: -q, --quiet and -qj1 write the same bytes" sh -c 'cmp -s m1.pm m2.pm && cmp -s m1.pm m3.pm'
pm-render -q -p 1 box.pms m1.pm -o r.exr && mv r.exr r1.exr &&
	pm-render --quiet --threads 1 -p 1 box.pms m1.pm -o r.exr && mv r.exr r2.exr
check "pm-render: -q and --quiet --threads 1 write the same bytes" sh -c 'cmp -s r1.exr r2.exr'

# Every file records the pm that wrote it.
check "photon files record pm_version" grep -aq "^pm_version=$version\$" m1.pm
check "EXR images record pm.version" sh -c "pm-dump --header r1.exr | grep -q '^pm.version=$version\$'"
pm-average -q -o avg.exr r1.exr r1.exr --force
check "pm-average writes its own pm.version" sh -c "pm-dump --header avg.exr | grep -q '^pm.version=$version\$'"
