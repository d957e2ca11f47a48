#!/bin/sh
# A broken hofem for the checkers' rejects_broken tests (verification/unit/CMakeLists.txt):
# runs the real one ($FAKE_HOFEM_REAL) with the same arguments and breaks its
# answer as $FAKE_HOFEM_BREAK says, so a checker is shown to notice:
#   drop-line  the real output without its last line, exit status 0
#   exit       the real output unchanged, exit status 1 (the words of a success
#              from a command that failed)
set -e
out=$("$FAKE_HOFEM_REAL" "$@")
case "$FAKE_HOFEM_BREAK" in
  drop-line) printf '%s\n' "$out" | sed '$d' ;;
  exit) printf '%s\n' "$out"; exit 1 ;;
  *) echo "fake_hofem.sh: FAKE_HOFEM_BREAK must be drop-line or exit, not '$FAKE_HOFEM_BREAK'" >&2; exit 2 ;;
esac
