# progress.sh — progress bars: silent when stderr is not a terminal and with
# -q; on a terminal (a pty from script(1)) pm-shoot, pm-render and
# pm-average draw one, and the files they write are byte-identical to the
# silent runs'.
. "$PM_TOP/tests/lib.sh"
scene=$PM_TOP/examples/fanout/scene.pms

mkdir -p quiet tty q
(cd quiet && pm-shoot -n 20000 -s 1 "$scene" -o s.pm 2>e1 && pm-build -q s.pm -o m.pm &&
	pm-render -e classical -s 1 "$scene" m.pm -o r.exr 2>e2 &&
	pm-render -q -e classical -s 2 "$scene" m.pm -o r2.exr && pm-average r.exr r2.exr -o a.exr 2>e3)
check "not a terminal: no progress on stderr" test -e quiet/a.exr -a ! -s quiet/e1 -a ! -s quiet/e2 -a ! -s quiet/e3

if ! command -v script >/dev/null 2>&1; then
	ok "script(1) missing: terminal checks skipped"
	exit 0
fi
# script -q -e -c CMD /dev/null runs CMD on a pty; what it wrote comes out
# on script's stdout.
onpty() { script -qec "$1" /dev/null </dev/null; }
(cd tty && cp ../quiet/m.pm ../quiet/r2.exr . &&
	onpty "pm-shoot -n 20000 -s 1 '$scene' -o s.pm" >shoot.out &&
	onpty "pm-render -e classical -s 1 '$scene' m.pm -o r.exr" >render.out &&
	onpty "pm-average r.exr r2.exr -o a.exr" >avg.out)
check "terminal: pm-shoot shows photons stored" grep -q 'pm-shoot: photons \[#*\] 20000/20000 100%.* total' tty/shoot.out
check "terminal: pm-render shows rows" grep -q 'pm-render: rows \[#*\] 36/36 100%.* total' tty/render.out
check "terminal: pm-average shows images" grep -q 'pm-average: images \[#*\] 2/2 100%' tty/avg.out
check "terminal: time left or total shown" grep -q '[0-9]:[0-9][0-9] \(left\|total\)' tty/render.out
for f in s.pm r.exr a.exr; do
	check "terminal: $f byte-identical to the silent run" cmp -s quiet/$f tty/$f
done
(cd q && cp ../quiet/m.pm ../quiet/r2.exr . &&
	onpty "pm-shoot -q -n 20000 -s 1 '$scene' -o s.pm" >shoot.out &&
	onpty "pm-render -q -e classical -s 1 '$scene' m.pm -o r.exr" >render.out &&
	onpty "pm-average -q r.exr r2.exr -o a.exr" >avg.out)
check "terminal with -q: silent" test -e q/a.exr -a ! -s q/shoot.out -a ! -s q/render.out -a ! -s q/avg.out
