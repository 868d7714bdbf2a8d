# manpages.sh — one man page per program: `make install PREFIX=...` puts
# the programs and the pages in place, each page renders without a warning
# (man -l --warnings, and groff -ww when there), has the sections a page
# needs, and its SYNOPSIS is the program's usage line word for word.
. "$PM_TOP/tests/lib.sh"
progs="pm-shoot pm-build pm-render pm-average pm-dump pm-diff pm-tonemap pm-import"

# Install from the source tree into a temporary prefix, with the build dir
# the test runs on. A make above us must not lend its jobserver or flags.
B=$(cd "$PM_BIN/.." && pwd)
pre=$(pwd)/prefix
env -u MAKEFLAGS -u MAKELEVEL -u MFLAGS make -s -C "$PM_TOP" B="$B" PREFIX="$pre" install >install.log 2>&1
check "make install PREFIX=... succeeds" test $? -eq 0
for p in $progs; do
	check "$p installed in PREFIX/bin" test -x "$pre/bin/$p"
	check "$p.1 installed in PREFIX/share/man/man1" test -s "$pre/share/man/man1/$p.1"
done

for p in $progs; do
	page=$PM_TOP/man/$p.1
	for s in NAME SYNOPSIS DESCRIPTION OPTIONS "EXIT STATUS" "SEE ALSO"; do
		grep -q "^\.SH \"*$s" "$page" || notok "$p.1 has section $s" "missing"
	done
	grep -q '^\.TH ' "$page" && grep -q '^\.SH \(FILES\|EXAMPLES\)' "$page"
	check "$p.1 has .TH and FILES or EXAMPLES" test $? -eq 0
	# SYNOPSIS: the lines between .nf and .fi, roff escapes undone.
	syn=$(sed -n '/^\.SH SYNOPSIS/,/^\.fi/p' "$page" | grep -v '^\.' | sed 's/\\-/-/g; s/\\&//g')
	use=$("$PM_BIN/$p" -h 2>&1 | sed -n 's/^usage: //p')
	if [ -n "$use" ] && [ "$syn" = "$use" ]; then ok "$p.1 SYNOPSIS matches -h's usage line"
	else notok "$p.1 SYNOPSIS matches -h's usage line" "page '$syn', program '$use'"; fi
	if command -v man >/dev/null 2>&1; then
		LC_ALL=C MANWIDTH=80 man --warnings -l "$pre/share/man/man1/$p.1" >out.txt 2>warn.txt
		check "man -l renders $p.1 without warnings" test $? -eq 0 -a ! -s warn.txt -a -s out.txt
		check "the rendered $p.1 names the program" grep -q "^ *$p " out.txt
	fi
	if command -v groff >/dev/null 2>&1; then
		LC_ALL=C groff -man -ww -z "$page" >gw.txt 2>&1
		check "groff -ww finds nothing to warn about in $p.1" test ! -s gw.txt
	fi
done
command -v man >/dev/null 2>&1 || command -v groff >/dev/null 2>&1 ||
	notok "man or groff to render the pages" "neither installed (mk/deps.sh installs man-db)"
