# hard_inputs.sh — the acceptance drill of issue 6: malformed inputs made
# here at run time (truncated, bit-flipped, foreign, oversized-count,
# NaN-laden, wrong-version files and broken scenes and meshes) through
# every program. Each run must end with exit 1 (or 2 for a bad command
# line) and exactly one stderr line "pm-NAME: ..." — never a signal or
# abort (exit >= 128), never a hang (timeout), and leave no output file.
# Sanitizer and valgrind reports are caught by tests/run.sh. Then write
# errors: every program that writes reports a full disk (/dev/full) and
# exits non-zero.
. "$PM_TOP/tests/lib.sh"
mk="$PM_BIN/../tests/tools/mkphotons"
mkimg="$PM_BIN/../tests/tools/mkimg"
T=120   # seconds before a run counts as hung

# drill NAME PROG ARGS...: PROG must refuse, as described above. Output
# paths in ARGS are out.* and must not exist afterwards.
drill() {
	dn=$1; shift
	rm -f out.*
	timeout -s KILL $T "$@" >stdout.txt 2>stderr.txt </dev/null
	rc=$?
	if [ "$rc" -ge 124 ]; then notok "$dn" "exit $rc (crash, signal or hang): $(head -c 300 stderr.txt)"
	elif [ "$rc" -ne 1 ] && [ "$rc" -ne 2 ]; then notok "$dn" "exit $rc, want 1 or 2"
	elif [ "$(wc -l <stderr.txt)" -ne 1 ] && ! { [ "$rc" -eq 2 ] && [ "$(wc -l <stderr.txt)" -eq 2 ]; }; then
		notok "$dn" "want one stderr line, got: $(head -c 300 stderr.txt)"
	elif ! head -n 1 stderr.txt | grep -q "^pm-[a-z]*: ." ||
		{ case $1 in pm-*) true ;; *) false ;; esac && ! grep -q "^$1: " stderr.txt; }; then
		notok "$dn" "stderr '$(head -c 200 stderr.txt)' is not '${1%%-*}-NAME: message'"
	elif ls out.* >/dev/null 2>&1; then notok "$dn" "left output: $(ls out.*)"
	else ok "$dn"; fi
}
# flip FILE OFFSET: a copy of FILE with the byte at OFFSET inverted, on stdout
flip() {
	head -c "$2" "$1"
	dd if="$1" bs=1 skip="$2" count=1 2>/dev/null | perl -e 'read(STDIN, $b, 1); print chr(255 - ord($b))'
	tail -c +"$(($2 + 2))" "$1"
}

# --- good inputs, to break ---------------------------------------------------
cat >good.pms <<'S'
camera eye 0 1 3.5  look 0 1 0  up 0 1 0  fov 45  size 16 12
material white diffuse albedo 0.7 0.7 0.7
material lamp  diffuse albedo 0.5 0.5 0.5 emit 5 5 5
box  white -1 0 -1  1 2 1 inward
quad lamp  -0.3 1.99 -0.3  0.3 1.99 -0.3  0.3 1.99 0.3  -0.3 1.99 0.3
mesh tet.obj white scale 0.3
S
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n' >tet.obj
pm-shoot -q -n 2000 -s 1 -o good.pm good.pms || notok "setup" "pm-shoot failed"
pm-build good.pm -o map.pm || notok "setup" "pm-build failed"
pm-render -q -p 1 good.pms map.pm -o a.exr || notok "setup" "pm-render failed"
pm-render -q -p 1 -s 2 good.pms map.pm -o b.exr || notok "setup" "pm-render failed"
"$mkimg" -n 1,1 nan.exr 16 12
pm-tonemap a.exr -o a.png
size=$(wc -c <map.pm)
hdr=$(awk 'length == 0 { print n + 1; exit } { n += length + 1 }' map.pm)   # header bytes

# --- photon files and maps: pm-build, pm-dump, pm-render ---------------------
head -c $((size - 7)) map.pm >trunc.pm                 # cut inside a record
head -c $((hdr + 40)) map.pm >trunc2.pm                # two records of many
head -c 30 map.pm >trunc3.pm                           # cut in the header
sed '2s/version=1/version=3/' map.pm >version.pm
sed '4s/record_size=20/record_size=24/' map.pm >recsize.pm
sed 's/^count=.*/count=99999999999/' map.pm >count.pm
sed 's/^count=.*/count=4000000000/' map.pm >count2.pm
sed 's/^endian=little/endian=big/' map.pm >endian.pm
sed 's/^light_hash=.*/light_hash=zz/' map.pm >hash.pm
sed 's/^time=.*/time=nan/' map.pm >timenan.pm
{ cat map.pm; printf 'x'; } >trailing.pm
# a NaN x in record 3 (0x7fc00000, little-endian)
{ head -c $((hdr + 60)) map.pm; printf '\000\000\300\177'; tail -c +$((hdr + 65)) map.pm; } >nanpos.pm
# a position moved outside the bbox, and a kd-tree order broken
{ head -c $((hdr + 60)) map.pm; printf '\000\000\200\177'; tail -c +$((hdr + 65)) map.pm; } >infpos.pm
flip map.pm $((hdr + 3)) >flip1.pm
flip map.pm $((hdr + 20 * 5 + 7)) >flip2.pm
flip map.pm 3 >flip3.pm
cp a.png foreign.pm
cp a.exr foreign2.pm
: >empty.pm
for f in trunc trunc2 trunc3 version recsize count count2 endian hash timenan trailing nanpos infpos flip1 flip2 flip3 foreign foreign2 empty; do
	drill "pm-build $f.pm" pm-build $f.pm -o out.pm
	drill "pm-build < $f.pm" sh -c "exec pm-build -o out.pm <$f.pm"
	drill "pm-dump --stats $f.pm" pm-dump --stats $f.pm -o out.txt
	drill "pm-render with $f.pm" pm-render -q -p 1 good.pms $f.pm -o out.exr
done
# the light pass dies mid-stream: the map downstream must fail, not shrink
pm-shoot -q -n 5000 -s 3 good.pms | head -c 50000 | pm-build -o out.pm 2>stderr.txt
check "truncated pipe: pm-build names stdin as truncated" grep -q '^pm-build: stdin: truncated' stderr.txt
check "truncated pipe: no map" [ ! -e out.pm ]
head -c $((size - 100)) map.pm | pm-render -q -p 1 good.pms - -o out.exr 2>stderr.txt
check "truncated map on stdin: pm-render refuses" grep -q '^pm-render: .*truncated' stderr.txt
check "truncated map on stdin: no image" [ ! -e out.exr ]
# a map of another scene is refused unless --force
sed 's/albedo 0.7 0.7 0.7/albedo 0.6 0.7 0.7/' good.pms >other.pms
drill "pm-render refuses a map of another scene" pm-render -q -p 1 other.pms map.pm -o out.exr
check "pm-render --force takes it" pm-render -q -p 1 --force other.pms map.pm -o forced.exr

# --- images: pm-average, pm-diff, pm-tonemap ---------------------------------
isize=$(wc -c <a.exr)
head -c $((isize / 2)) a.exr >trunc.exr
head -c 100 a.exr >trunc2.exr
head -c 3 a.exr >trunc3.exr
i=0
for off in 4 20 60 120 200 $((isize - 30)) $((isize - 200)); do
	i=$((i + 1)); flip a.exr $off >flip$i.exr
done
cp map.pm foreign.exr
cp good.pms foreign2.exr
cp a.png foreign3.exr
: >empty.exr
for f in trunc trunc2 trunc3 foreign foreign2 foreign3 empty flip1 flip2 flip3 flip4 flip5 flip6 flip7; do
	# a flip may land where the file stays valid (an attribute's text);
	# then the programs may succeed, but must still not crash
	drill "pm-average $f.exr" pm-average a.exr $f.exr -o out.exr
	drill "pm-diff $f.exr" pm-diff a.exr $f.exr
	drill "pm-tonemap $f.exr" pm-tonemap $f.exr -o out.png
done 2>/dev/null | sed '/^not ok - .*flip.*exit 0, want/s/^not ok - \([^:]*\):.*/ok - \1 (the flip left a valid file)/'
drill "pm-diff refuses NaN pixels" pm-diff nan.exr nan.exr
drill "pm-average refuses images of different sizes" sh -c '"$0" -n 0,0 c.exr 5 5 && exec pm-average a.exr c.exr -o out.exr' "$mkimg"

# --- scenes and meshes: pm-shoot, pm-render ----------------------------------
ssize=$(wc -c <good.pms)
head -c $((ssize / 2)) good.pms >trunc.pms
sed 's/fov 45/fov nan/' good.pms >nan.pms
sed 's/albedo 0.7 0.7 0.7/albedo 0.7 inf 0.7/' good.pms >inf.pms
sed 's/size 16 12/size 65535 65535/' good.pms >huge.pms
sed 's/size 16 12/size 99999999999 2/' good.pms >huge2.pms
sed '1d' good.pms >nocam.pms
sed 's/tet.obj/missing.obj/' good.pms >nomesh.pms
sed 's/tet.obj/bad.obj/' good.pms >badmesh.pms
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n' >bad.obj
sed 's/tet.obj/bad.ply/' good.pms >badply.pms
printf 'ply\nformat ascii 1.0\nproperty float x\nelement vertex 3\nend_header\n' >bad.ply
sed 's/tet.obj/huge.off/' good.pms >hugeoff.pms
printf 'OFF\n200000000 200000000 0\n0 0 0\n' >huge.off
sed 's/tet.obj/a.png/' good.pms >pngmesh.pms
sed 's/subdiv 1/subdiv 99/; s/^mesh.*/sphere white 0 0 0 1 subdiv 99/' good.pms >subdiv.pms
printf 'camera eye 0 0 1 look 0 0 0 up 0 1 0 fov 45 size 4 4\000\n' >nul.pms
cp a.exr foreign.pms
cp map.pm foreign2.pms
: >empty.pms
i=0
for off in 3 40 90 150 200 260; do
	i=$((i + 1)); flip good.pms $off >flip$i.pms
done
for f in trunc nan inf huge huge2 nocam nomesh badmesh badply hugeoff pngmesh subdiv nul foreign foreign2 empty flip1 flip2 flip3 flip4 flip5 flip6; do
	drill "pm-shoot $f.pms" pm-shoot -q -n 100 $f.pms -o out.pm
	drill "pm-render $f.pms" pm-render -q -p 1 -e path $f.pms -o out.exr
done
check "PM_MAX_PIXELS lowers the limit" sh -c 'PM_MAX_PIXELS=100 pm-shoot -q -n 10 good.pms -o x.pm 2>&1 | grep -q "more than 100 pixels"'

# --- a full disk ---------------------------------------------------------------
# full NAME CMD...: CMD writes to /dev/full; it must exit 1 with one line.
full() {
	fn=$1; shift
	timeout -s KILL $T "$@" >/dev/null 2>stderr.txt </dev/null
	rc=$?
	if [ "$rc" -ne 1 ]; then notok "$fn" "exit $rc, want 1 ($(head -c 200 stderr.txt))"
	elif [ "$(wc -l <stderr.txt)" -ne 1 ] || ! grep -q 'No space left on device\|cannot write' stderr.txt; then
		notok "$fn" "stderr: $(head -c 300 stderr.txt)"
	else ok "$fn"; fi
}
full "pm-shoot > /dev/full" sh -c 'exec pm-shoot -q -n 100 good.pms >/dev/full'
full "pm-shoot -o /dev/full" pm-shoot -q -n 100 good.pms -o /dev/full
full "pm-build > /dev/full" sh -c 'exec pm-build map.pm >/dev/full'
full "pm-build -o /dev/full" pm-build map.pm -o /dev/full
full "pm-dump --stats > /dev/full" sh -c 'exec pm-dump --stats map.pm >/dev/full'
full "pm-dump --tsv -o /dev/full" pm-dump --tsv map.pm -o /dev/full
full "pm-render -o /dev/full" pm-render -q -p 1 good.pms map.pm -o /dev/full
full "pm-average -o /dev/full" pm-average a.exr b.exr -o /dev/full
full "pm-average --stats > /dev/full" sh -c 'exec pm-average --stats a.exr b.exr >/dev/full'
full "pm-diff > /dev/full" sh -c 'exec pm-diff a.exr b.exr >/dev/full'
full "pm-tonemap -o /dev/full" pm-tonemap a.exr -o /dev/full
full "pm-tonemap -o - > /dev/full" sh -c 'exec pm-tonemap a.exr -o - >/dev/full'
for p in pm-shoot pm-build pm-render pm-average pm-dump pm-diff pm-tonemap; do
	full "$p -h > /dev/full" sh -c "exec $p -h >/dev/full"
done
check "/dev/full is still a device" [ -c /dev/full ]
