# tonemap.sh — pm-tonemap's defaults: auto exposure printed so it can be
# given back, a tone curve that keeps highlights, and an EXR read from a pipe.
. "$PM_TOP/tests/lib.sh"
T="$PM_BIN/../tests/tools"

# One room lit by a 2 W and by a 2048 W point light: the same seed gives
# images 1024 = 2^10 apart, which the default previews alike.
for w in 2 2048; do
	cat >room$w.pms <<SCENE
camera eye 0 1 3.4  look 0 1 0  up 0 1 0  fov 45  size 24 18
material white diffuse albedo 0.7 0.7 0.7
material red diffuse albedo 0.6 0.1 0.1
quad white -1 0 -1  1 0 -1  1 0 1  -1 0 1
quad white -1 2 -1  -1 2 1  1 2 1  1 2 -1
quad white -1 0 -1  -1 2 -1  1 2 -1  1 0 -1
quad red -1 0 -1  -1 0 1  -1 2 1  -1 2 -1
box white -0.5 0 -0.5  0 0.6 0
pointlight 0.3 1.5 0.5 power $w $w $w
SCENE
	pm-render -q -e path -p 2 -s 3 room$w.pms -o room$w.exr
	pm-tonemap room$w.exr -o room$w.png 2>ev$w.txt
	check "tonemap: default exits 0 ($w W)" test $? -eq 0
done
ev2=$(sed -n 's/^pm-tonemap: exposure \([-+][0-9.]*\) EV (auto: log-average luminance .* to 0.18)$/\1/p' ev2.txt)
ev2048=$(sed -n 's/^pm-tonemap: exposure \([-+][0-9.]*\) EV (auto: .*/\1/p' ev2048.txt)
check "tonemap: auto exposure printed as one line" test -n "$ev2" -a -n "$ev2048" -a "$(wc -l <ev2.txt)" -eq 1
num_near "tonemap: auto exposures 10 stops apart for 1024x the light" "$(awk -v a="$ev2" -v b="$ev2048" 'BEGIN { print a - b }')" 10 0.011
same=1
for xy in "2 2" "12 9" "20 15" "6 16" "12 1"; do
	a=$("$T/pngpix" room2.png $xy | tail -n 1) b=$("$T/pngpix" room2048.png $xy | tail -n 1)
	awk -v a="$a" -v b="$b" 'BEGIN { split(a, p); split(b, q)
		for (i = 1; i <= 3; i++) { d = p[i] - q[i]; if (d < -1 || d > 1) exit 1 } }' || same=0
done
check "tonemap: 2 W and 2048 W preview alike (within 1 code)" test $same -eq 1
pm-tonemap -e "$ev2" room2.exr -o back.png
check "tonemap: the printed EV given back gives the same PNG" cmp -s back.png room2.png
pm-tonemap -q room2.exr -o quiet.png 2>q.txt
check "tonemap -q: no exposure line, same PNG" test ! -s q.txt
check "tonemap -q: same PNG" cmp -s quiet.png room2.png
# The old default (EV 0, clamp) shows the 2 W room nearly black.
pm-tonemap -c clamp -e 0 room2.exr -o dark.png
check "tonemap: EV 0 differs from auto" sh -c "! cmp -s dark.png room2.png"

# Uniform images at 0.01 and 1000 map to middle grey 0.18 through the
# Reinhard curve (w = 4): 0.18 (1 + 0.18/16) / 1.18 = 0.15426 -> sRGB 109.
"$T/mkimg" -v 0.01,0.01,0.01 lo.exr 4 3
"$T/mkimg" -v 1000,1000,1000 hi.exr 4 3
pm-tonemap -q lo.exr -o lo.png
pm-tonemap -q hi.exr -o hi.png
check "tonemap: uniform 0.01 -> middle grey" test "$("$T/pngpix" lo.png 1 1 | tail -n 1)" = "109 109 109"
check "tonemap: uniform 1000 -> middle grey" test "$("$T/pngpix" hi.png 1 1 | tail -n 1)" = "109 109 109"
"$T/mkimg" -v 0,0,0 black.exr 4 3
pm-tonemap black.exr -o black.png 2>b.txt
check "tonemap: a black image says so" grep -q '^pm-tonemap: exposure +0.00 EV (auto: the image is black)$' b.txt

# Highlights: 1.5, 2.5, 3.5 are all white under clamp, distinct under
# reinhard (0.62 -> 207, 0.80 -> 231, 0.93 -> 247 from the formula).
for v in 1.5 2.5 3.5; do "$T/mkimg" -v $v,$v,$v h$v.exr 2 2; done
pm-tonemap -e 0 h1.5.exr h2.5.exr h3.5.exr -o hr.png
pm-tonemap -e 0 -c clamp h1.5.exr h2.5.exr h3.5.exr -o hc.png
check "tonemap: clamp whites out 1.5 and 3.5" test "$("$T/pngpix" hc.png 0 0 | tail -n 1) $("$T/pngpix" hc.png 12 0 | tail -n 1)" = "255 255 255 255 255 255"
r1=$("$T/pngpix" hr.png 0 0 | tail -n 1) r2=$("$T/pngpix" hr.png 6 0 | tail -n 1) r3=$("$T/pngpix" hr.png 12 0 | tail -n 1)
want() { awk -v x="$1" 'BEGIN { d = x * (1 + x / 16) / (1 + x); s = 1.055 * exp(log(d) / 2.4) - 0.055; print int(s * 255 + 0.5) }'; }
check "tonemap: reinhard keeps highlights apart (formula)" test "$r1 $r2 $r3" = "$(want 1.5) $(want 1.5) $(want 1.5) $(want 2.5) $(want 2.5) $(want 2.5) $(want 3.5) $(want 3.5) $(want 3.5)"
pm-tonemap -e 0 -w 2.5 h2.5.exr -o w.png
check "tonemap --white: white from the white point on" test "$("$T/pngpix" w.png 0 0 | tail -n 1)" = "255 255 255"
expect_fail "tonemap: unknown curve" 2 "^pm-tonemap: --curve: unknown curve 'filmic' (clamp or reinhard)$" pm-tonemap -c filmic lo.exr -o x.png
expect_fail "tonemap: bad white point" 2 "^pm-tonemap: --white: " pm-tonemap -w 0 lo.exr -o x.png

# An EXR from a pipe, alone or among files.
pm-tonemap -q - <room2.exr -o pipe.png
check "tonemap: stdin gives the same PNG as the file" cmp -s pipe.png room2.png
"$T/mkimg" -v 0.3,0.2,0.1 side.exr 5 18
pm-render -q -e path -p 2 -s 3 room2.pms -o - | pm-tonemap -q side.exr - -o mixed.png
pm-tonemap -q side.exr room2.exr -o mixedf.png
check "tonemap: a piped input beside a file" cmp -s mixed.png mixedf.png
expect_fail "tonemap: stdin named twice" 2 "^pm-tonemap: stdin (-) given as input more than once" pm-tonemap - - -o x.png
echo "not an image" | expect_fail "tonemap: stdin not an EXR" 1 "^pm-tonemap: stdin: not an OpenEXR file$" pm-tonemap - -o x.png
head -c 2000 room2.exr >cut.exr
expect_fail "tonemap: a cut EXR from a pipe" 1 "^pm-tonemap: stdin: truncated or corrupt OpenEXR file" sh -c 'cat cut.exr | pm-tonemap - -o x.png'
check "tonemap: no output after failures" test ! -e x.png
