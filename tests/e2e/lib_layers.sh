# lib_layers.sh — the dependency direction of lib/: the layers are the
# folders in the order lib/README lists them, bottom up; a file in lib/ may
# include headers of its own layer and of layers listed before it only.
# Every project header is included by its path under lib/ ("base/err.h"),
# from lib/, tools/, tests/ and bench/ alike; a bare "err.h" is refused
# (it would build only with the right -I and hide the layer).
. "$PM_TOP/tests/lib.sh"

sed -n 's/^\([a-z]*\)\/  .*/\1/p' "$PM_TOP/lib/README" >order.txt
check "lib/README lists the layers" test -s order.txt
# FILE LAYER INCLUDED-PATH, one line per project #include.
(cd "$PM_TOP" && for f in lib/*/*.c lib/*/*.cpp lib/*/*.h tools/*.c tools/*.h \
	tests/*/*.c tests/*/*.h tests/*.h bench/*.c bench/*.cpp bench/*.h; do
	[ -f "$f" ] || continue
	sed -n 's/^[ 	]*#[ 	]*include[ 	]*"\([^"]*\)".*/\1/p' "$f" |
		while read -r h; do echo "$f $h"; done
done) >includes.txt
check "the tree has project includes to check" test -s includes.txt
check_includes() {
	awk -v top="$PM_TOP" '
		NR == FNR { rank[$1] = NR; next }
		{
			f = $1; h = $2
			split(f, p, "/")
			dir = f; sub(/\/[^\/]*$/, "", dir)
			if (h ~ /\//) {
				split(h, q, "/")
				if (!(q[1] in rank)) { print f ": \"" h "\": no layer " q[1]; next }
				if ((getline line < (top "/lib/" h)) < 0) { print f ": \"" h "\": no such header"; next }
				close(top "/lib/" h)
				if (p[1] == "lib" && rank[q[1]] > rank[p[2]])
					print f ": includes \"" h "\", of layer " q[1] " above its own (" p[2] ")"
			} else if (p[1] == "lib") {
				print f ": \"" h "\": include lib headers by their path (\"LAYER/" h "\")"
			} else {
				# a header of the tools or tests themselves: beside it or in the
				# folder above (tests/check.h, by -Itests)
				up = dir; sub(/\/[^\/]*$/, "", up)
				if ((getline line < (top "/" dir "/" h)) > 0) close(top "/" dir "/" h)
				else if (up != dir && (getline line < (top "/" up "/" h)) > 0) close(top "/" up "/" h)
				else print f ": \"" h "\": not a header of its own; lib headers go by path (\"LAYER/" h "\")"
			}
		}' order.txt "$1"
}
check_includes includes.txt >bad.txt
check "every include names a layer at or below the includer's" test ! -s bad.txt
sed 's/^/# /' bad.txt | head -20
# The check itself: a header of a higher layer included from a lower one
# is caught (a scene file including a pass), and so is a bare name.
printf 'lib/scene/x.c passes/render.h\nlib/base/y.c err.h\nlib/passes/z.c scene/scene.h\n' >planted.txt
check_includes planted.txt >caught.txt
check "an upward include and a bare include are caught, a downward one not" \
	test "$(cut -d: -f1 caught.txt | tr '\n' ' ')" = "lib/scene/x.c lib/base/y.c "
