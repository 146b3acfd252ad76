#!/usr/bin/env bash
# The long runs: the fuzz targets built with clang and libFuzzer (-fsanitize=fuzzer,address,undefined)
# in their own build folder, then run one at a time. README.md here.
#
#   tests/fuzz/run.sh NAME [LIBFUZZER_ARGS...]   e.g. run.sh fuzz_nmea -runs=1000000
#   tests/fuzz/run.sh all [LIBFUZZER_ARGS...]    every target of targets.txt in turn
#   tests/fuzz/run.sh build                      configure and build only
#
# Build folder: $MPGC_FUZZ_BUILD_DIR, default build-fuzz/ beside this checkout's build/. Each target
# keeps what libFuzzer found new in <build>/corpus/NAME (the seeds of targets.txt are read after
# it, never written) and a crash, leak or timeout input in <build>/artifacts/NAME/.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BUILD="${MPGC_FUZZ_BUILD_DIR:-$ROOT/build-fuzz}"
SHARED="$ROOT/../shared/data"
TARGETS="$ROOT/tests/fuzz/targets.txt"
export MPGC_SHARED_DATA="${MPGC_SHARED_DATA:-$SHARED}"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

names() { awk '/^fuzz_/ {print $1}' "$TARGETS"; }

build() {
  command -v clang++ >/dev/null || { echo "run.sh: clang++ is missing (deploy/install-deps.sh)" >&2; exit 2; }
  local flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g1"
  if [ ! -f "$BUILD/CMakeCache.txt" ]; then
    local gen=()
    if command -v ninja >/dev/null; then gen=(-G Ninja); fi
    CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" "${gen[@]}" -DMPGC_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" >/dev/null
  fi
  # Only the targets and what they link, one job at a time unless MPGC_JOBS says otherwise.
  cmake --build "$BUILD" -j "${MPGC_JOBS:-1}" --target "$@"
}

run_one() {
  local name="$1"
  shift
  local line
  line="$(awk -v n="$name" '$1 == n' "$TARGETS")"
  [ -n "$line" ] || { echo "run.sh: no target '$name' in $TARGETS (one of: $(names | tr '\n' ' '))" >&2; exit 2; }
  read -r _ _ max_len seeds <<<"$line"
  # libFuzzer takes folders only once one is given: the seed files and folders are copied into
  # <build>/seeds/NAME (read, never written), the work folder comes first (new inputs go there).
  rm -rf "$BUILD/seeds/$name"
  mkdir -p "$BUILD/seeds/$name" "$BUILD/corpus/$name" "$BUILD/artifacts/$name"
  local i=0
  for s in $seeds; do
    case "$s" in @shared/*) s="$SHARED/${s#@shared/}" ;; *) s="$ROOT/$s" ;; esac
    i=$((i + 1))
    if [ -d "$s" ]; then cp -r "$s" "$BUILD/seeds/$name/$i"; else cp "$s" "$BUILD/seeds/$name/$i-$(basename "$s")"; fi
  done
  echo "== $name" >&2
  "$BUILD/bin/$name" -max_len="$max_len" -timeout=20 -rss_limit_mb=4096 -print_final_stats=1 \
    -artifact_prefix="$BUILD/artifacts/$name/" "$@" "$BUILD/corpus/$name" "$BUILD/seeds/$name"
}

what="${1:-}"
[ -n "$what" ] || { sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
shift
case "$what" in
  build) build $(names) ;;
  all)
    build $(names)
    for n in $(names); do run_one "$n" "$@"; done
    ;;
  *)
    build "$what"
    run_one "$what" "$@"
    ;;
esac
