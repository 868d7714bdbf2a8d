# outputs.sh — outputs that cannot hurt: a name whose extension says another
# format, an output that is one of the inputs, a directory; and images
# through pipes (pm-render -o -, pm-average and pm-diff reading -).
. "$PM_TOP/tests/lib.sh"
T="$PM_BIN/../tests/tools"
cp "$PM_TOP/tests/scenes/furnace.pms" s.pms
pm-shoot -q -n 2000 -s 1 s.pms -o shot.pm
pm-build -q shot.pm -o map.pm
"$T/mkimg" -v 1,1,1 a.exr 4 3
"$T/mkimg" -v 2,2,2 b.exr 4 3
cp a.exr keep.exr

# Extensions that contradict the format (exit 2, nothing written).
expect_fail "render -o out.png refused" 2 "^pm-render: 'out.png' names a PNG image, but pm-render writes an OpenEXR image: name it .exr$" pm-render -q s.pms map.pm -o out.png
expect_fail "tonemap -o copy.exr refused" 2 "^pm-tonemap: 'copy.exr' names an OpenEXR image, but pm-tonemap writes a PNG image: name it .png$" pm-tonemap a.exr -o copy.exr
expect_fail "average -o x.PNG refused (any case)" 2 "^pm-average: 'x.PNG' names a PNG image" pm-average a.exr -o x.PNG
expect_fail "diff -o x.png refused" 2 "^pm-diff: 'x.png' names a PNG image" pm-diff -o x.png a.exr b.exr
expect_fail "shoot -o x.exr refused" 2 "^pm-shoot: 'x.exr' names an OpenEXR image, but pm-shoot writes a photon file: name it .pm$" pm-shoot -n 10 s.pms -o x.exr
expect_fail "shoot -o x.pms refused" 2 "^pm-shoot: 'x.pms' names a scene" pm-shoot -n 10 s.pms -o x.pms
expect_fail "build -o x.png refused" 2 "^pm-build: 'x.png' names a PNG image" pm-build shot.pm -o x.png
expect_fail "dump --ply -o x.pm refused" 2 "^pm-dump: 'x.pm' names a photon file, but pm-dump writes a PLY point cloud" pm-dump --ply map.pm -o x.pm
expect_fail "dump --tsv -o x.exr refused" 2 "^pm-dump: 'x.exr' names an OpenEXR image, but pm-dump writes text" pm-dump --tsv map.pm -o x.exr
check "nothing written for refused names" test ! -e out.png -a ! -e copy.exr -a ! -e x.PNG -a ! -e x.png -a ! -e x.exr -a ! -e x.pms -a ! -e x.pm
# Names without a known extension, or of the right format, pass.
pm-shoot -q -n 10 s.pms -o shot.photons
check "shoot: a name of no known extension is fine" test -s shot.photons
pm-dump --tsv map.pm -o map.tsv
check "dump --tsv -o map.tsv is fine" test -s map.tsv
pm-average a.exr -o avg.exr
check "average -o avg.exr is fine" test -s avg.exr

# An output that is one of the inputs (exit 2, the input untouched).
expect_fail "average over its own input refused" 2 "^pm-average: 'a.exr' is also an input: writing it would destroy it (choose another output)$" pm-average a.exr b.exr -o a.exr
expect_fail "the same file by another path refused" 2 "^pm-average: './a.exr' is also an input" pm-average a.exr b.exr -o ./a.exr
ln a.exr hard.exr
expect_fail "a hard link to an input refused" 2 "^pm-diff: 'hard.exr' is also an input" pm-diff -o hard.exr a.exr b.exr
expect_fail "build over its input refused" 2 "^pm-build: 'shot.pm' is also an input" pm-build shot.pm -o shot.pm
expect_fail "a missing input named as the output refused" 2 "^pm-average: 'new.exr' is also an input" pm-average new.exr -o new.exr
check "inputs untouched" cmp -s a.exr keep.exr

# Directories: say what is wrong (exit 1).
mkdir d
expect_fail "output a directory" 1 "^pm-tonemap: cannot write 'd': that names a directory, not a file$" pm-tonemap a.exr -o d
expect_fail "output ending in /" 1 "^pm-average: cannot write 'nodir/': that names a directory, not a file$" pm-average a.exr -o nodir/
expect_fail "output /" 1 "^pm-render: cannot write '/': that names a directory, not a file$" pm-render -q s.pms map.pm -o /

# Images through pipes.
pm-render -q -s 2 s.pms map.pm -o file.exr
pm-render -q -s 2 s.pms map.pm -o - >piped.exr
pm-diff file.exr piped.exr >d.txt
num_near "render -o - writes the same image" "$(kv d.txt max_abs)" 0 0
pm-render -q -s 3 s.pms map.pm -o c.exr
pm-render -q -s 2 s.pms map.pm -o - | pm-average - c.exr -o avgp.exr
pm-average file.exr c.exr -o avgf.exr
pm-diff avgp.exr avgf.exr >d.txt
num_near "average reads - from a pipe" "$(kv d.txt max_abs)" 0 0
pm-average -s - <a.exr >s.txt
check "average --stats of stdin" test "$(kv s.txt mean)" = 1
pm-diff - b.exr <a.exr >d.txt
num_near "diff reads - from a pipe" "$(kv d.txt max_abs)" 1 0
expect_fail "average: stdin twice" 2 "^pm-average: stdin (-) given as input more than once" pm-average - - -o t.exr
expect_fail "diff: stdin twice" 2 "^pm-diff: stdin (-) given as input more than once" pm-diff - -
expect_fail "diff: -o - would mix with the statistics" 2 "^pm-diff: -o -: the statistics go to stdout" pm-diff -o - a.exr b.exr
echo junk | expect_fail "average: a foreign stdin named stdin" 1 "^pm-average: stdin: not an OpenEXR file$" pm-average - -o t.exr
"$T/mkimg" -v 1,1,1 small.exr 2 2
expect_fail "average: sizes name stdin" 1 "^pm-average: stdin: size 2x2 differs from 'a.exr' (4x3)$" sh -c 'pm-average a.exr - -o t.exr <small.exr'
check "nothing written after failures" test ! -e t.exr

# Binary outputs to a terminal (a pty from script(1)) are refused.
if command -v script >/dev/null 2>&1; then
	script -qec "pm-render -q s.pms map.pm -o -; echo rc=\$?" /dev/null </dev/null >tty.out
	check "render -o - to a terminal refused" grep -q "pm-render: refusing to write an OpenEXR image to a terminal: use -o FILE or a pipe" tty.out
	check "render -o - to a terminal exits 1" grep -q "rc=1" tty.out
	script -qec "pm-tonemap a.exr -o -; echo rc=\$?" /dev/null </dev/null >tty.out
	check "tonemap -o - to a terminal refused" grep -q "pm-tonemap: refusing to write a PNG image to a terminal" tty.out
else
	ok "script(1) missing: terminal checks skipped"
fi

# Later additions: stdin redirected from the output, stdout wanted twice.
expect_fail "the output as stdin refused" 2 "^pm-average: 'a.exr' is also an input (as stdin)" sh -c 'pm-average - b.exr -o a.exr <a.exr'
expect_fail "average: -o - with --stats refused" 2 "^pm-average: -o - with --stats: both would go to stdout" pm-average -s a.exr -o -
check "inputs still untouched" cmp -s a.exr keep.exr
