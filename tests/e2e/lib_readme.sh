# lib_readme.sh — the map of the library: lib/README names every layer
# folder of lib/ and no other; each folder's README names every source file
# in it and no file that is not there (a file line starts with the file's
# name).
. "$PM_TOP/tests/lib.sh"

readme="$PM_TOP/lib/README"
check "lib/README exists" test -f "$readme"
sed -n 's/^\([a-z]*\)\/  .*/\1/p' "$readme" | sort >layers.txt
(cd "$PM_TOP/lib" && for d in */; do echo "${d%/}"; done) | sort >folders.txt
check "lib/README names every folder of lib/ and no other" cmp -s layers.txt folders.txt
[ -s layers.txt ] || notok "lib/README names layers" "no 'NAME/  text' lines"
check "lib/ has no source file outside a layer folder" \
	test -z "$(cd "$PM_TOP/lib" && ls *.c *.cpp *.h 2>/dev/null)"
for l in $(cat folders.txt); do
	r="$PM_TOP/lib/$l/README"
	check "lib/$l/README exists" test -f "$r"
	[ -f "$r" ] || continue
	sed -n 's/^\([A-Za-z0-9_.-]*\.\(c\|cpp\|h\)\)\([ 	].*\)\{0,1\}$/\1/p' "$r" | sort >listed.txt
	(cd "$PM_TOP/lib/$l" && ls *.c *.cpp *.h 2>/dev/null) | sort >present.txt
	comm -13 listed.txt present.txt >missing.txt
	comm -23 listed.txt present.txt >extra.txt
	check "lib/$l/README lists every source file in lib/$l" test ! -s missing.txt
	[ -s missing.txt ] && echo "# not in lib/$l/README: $(tr '\n' ' ' <missing.txt)"
	check "every file lib/$l/README names exists" test ! -s extra.txt
	[ -s extra.txt ] && echo "# in lib/$l/README, not in lib/$l: $(tr '\n' ' ' <extra.txt)"
	check "lib/$l/README names each file once" test "$(uniq -d listed.txt | wc -l)" -eq 0
done
