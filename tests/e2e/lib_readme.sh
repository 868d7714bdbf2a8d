# lib_readme.sh — lib/README, the map of the library, names every source
# file in lib/ and no file that is not there (a file line starts with the
# file's name).
. "$PM_TOP/tests/lib.sh"

readme="$PM_TOP/lib/README"
check "lib/README exists" test -f "$readme"
sed -n 's/^\([A-Za-z0-9_.-]*\.\(c\|cpp\|h\)\)\([ 	].*\)\{0,1\}$/\1/p' "$readme" | sort >listed.txt
(cd "$PM_TOP/lib" && ls *.c *.cpp *.h 2>/dev/null) | sort >present.txt
comm -13 listed.txt present.txt >missing.txt
comm -23 listed.txt present.txt >extra.txt
check "lib/README lists every lib/ source file" test ! -s missing.txt
[ -s missing.txt ] && echo "# not in lib/README: $(tr '\n' ' ' <missing.txt)"
check "every file lib/README names exists" test ! -s extra.txt
[ -s extra.txt ] && echo "# in lib/README, not in lib/: $(tr '\n' ' ' <extra.txt)"
check "lib/README names each file once" test "$(uniq -d listed.txt | wc -l)" -eq 0
