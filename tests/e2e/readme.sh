# readme.sh — the README's first pipeline ("One pass pair, and many") runs
# as written, pasted into a shell at the repository root whose PATH does
# not hold the programs: here a copy of the root's layout (build/bin, the
# Cornell box shrunk to 24 x 24 so that eight passes stay quick).
. "$PM_TOP/tests/lib.sh"
exrattr="$PM_BIN/../tests/tools/exrattr"

mkdir -p root/build root/examples
ln -s "$PM_BIN" root/build/bin
cp -R "$PM_TOP/examples/cornell" root/examples/
sed -i 's/size 256 256/size 24 24/' root/examples/cornell/cornell.pms
awk '/^## One pass pair, and many/ { s = 1 } s && /^```/ { if (b) exit; b = 1; next } b' \
	"$PM_TOP/README.md" >block.sh
check "the README has the block" grep -q '^pm-average ' block.sh

path=$(printf '%s' "$PATH" | sed "s|^$PM_BIN:||")
(cd root && PATH=$path HOME=$PWD sh -e ../block.sh) >out.txt 2>err.txt
rc=$?
check "the block runs from the repository root (exit 0)" test $rc -eq 0
[ $rc -eq 0 ] || echo "# $(tail -n 3 err.txt)"
check "it writes eight passes" test "$(ls root/pass-*.exr 2>/dev/null | wc -l)" -eq 8
check "their average counts eight passes" test "$("$exrattr" root/image.exr pm.passes)" = 8
check "and a PNG" sh -c 'head -c 8 root/image.png | od -An -c | grep -q "P   N   G"'
