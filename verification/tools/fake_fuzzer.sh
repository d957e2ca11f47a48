#!/bin/sh
# A stand-in for a libFuzzer target, for the tests of scripts/fuzz (ctest fuzz.script_*):
# linked as DIR/fuzz_<target>, run by `FUZZ_BIN=DIR scripts/fuzz --check`. It prints
# the lines scripts/fuzz reads and, for the target named in
#   FAKE_FUZZ_CRASH     writes a crash-* artifact and exits 1 (libFuzzer after a crash);
#   FAKE_FUZZ_ARTIFACT  writes a leak-* artifact but exits 0;
#   FAKE_FUZZ_EXIT      exits 1 without an artifact.
name=$(basename "$0")
target=${name#fuzz_}
prefix=""
for a in "$@"; do
  case "$a" in -artifact_prefix=*) prefix=${a#-artifact_prefix=} ;; esac
done
echo "INFO: Seed: 1234"
echo "#2	INITED cov: 10 ft: 20 corp: 1/1b exec/s: 0 rss: 30Mb"
if [ "$target" = "${FAKE_FUZZ_CRASH:-}" ]; then
  echo "==1==ERROR: AddressSanitizer: heap-buffer-overflow (fake)"
  printf 'x' >"${prefix}crash-0123456789abcdef0123456789abcdef01234567"
  exit 1
fi
if [ "$target" = "${FAKE_FUZZ_ARTIFACT:-}" ]; then
  printf 'y' >"${prefix}leak-0123456789abcdef0123456789abcdef01234567"
fi
if [ "$target" = "${FAKE_FUZZ_EXIT:-}" ]; then
  exit 1
fi
echo "#100	DONE cov: 12 ft: 25 corp: 2/2b exec/s: 100 rss: 31Mb"
echo "stat::number_of_executed_units: 100"
echo "stat::peak_rss_mb:              31"
exit 0
