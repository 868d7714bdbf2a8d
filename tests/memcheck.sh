#!/bin/sh
# memcheck.sh — runs the end-to-end tests with every pm program under
# valgrind's memcheck (make memcheck): a tree BUILD/memcheck whose bin/ holds
# one wrapper script per program, so the tests, which find the programs
# through $PM_BIN, run them as
#   valgrind -q --error-exitcode=99 --leak-check=full
#            --errors-for-leak-kinds=definite PROGRAM ARGS...
# Each report goes to a file in $PM_REPORT_DIR, which tests/run.sh checks
# after every test: any memory error or definite leak fails it.
# Suppressions (tests/valgrind.supp) cover libgomp's thread pool, which
# OpenMP keeps alive until exit by design.
# Usage: tests/memcheck.sh BUILD_DIR [PATTERN]
B=$(cd "${1:-build}" && pwd) || exit 2
top=$(cd "$(dirname "$0")/.." && pwd)
command -v valgrind >/dev/null || { echo "memcheck: valgrind is not installed (sh mk/deps.sh memcheck)" >&2; exit 2; }
M=$B/memcheck
rm -rf "$M"
mkdir -p "$M/bin"
ln -s "$B/tests" "$M/tests"
for p in "$B"/bin/pm-*; do
	cat >"$M/bin/${p##*/}" <<W
#!/bin/sh
exec valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite \\
	--show-leak-kinds=definite --suppressions="$top/tests/valgrind.supp" \\
	--log-file="\${PM_REPORT_DIR:-/tmp}/valgrind.%p" "$p" "\$@"
W
	chmod +x "$M/bin/${p##*/}"
done
exec sh "$top/tests/run.sh" "$M" "${2:-tests/e2e/}"
