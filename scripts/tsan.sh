#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# ThreadSanitizer run of the threaded parts (docs/reliability.md, "ThreadSanitizer").
#
#   scripts/tsan.sh [--build-dir DIR] [--build-only] [--target PROGRAM...] [-- CTEST_ARGS...]
#
# Configures build-tsan/ (preset `tsan`: g++ -fsanitize=thread, -O1 -g1, no benchmarks), builds
# only the test programs of the threaded parts (list below; while holding one of the machine-wide
# build slots when /work/bin/hil-build exists, as scripts/fuzz.sh does) and runs their tests with
# TSAN_OPTIONS=halt_on_error=1: the first data race, lock-order inversion or thread leak fails the
# test that hit it, and the script. scripts/tsan.supp holds suppressions for third-party false
# positives only (none so far), each with its reason. --target builds only the given test programs
# (of the list below; repeatable); the run covers the programs built so far.
set -euo pipefail
cd "$(dirname "$0")/.."
src=$(pwd)
bd="$src/build-tsan"
build_only=0
ctest_args=()
only=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) bd=$2; shift 2 ;;
    --build-only) build_only=1; shift ;;
    --target) only+=("$2"); shift 2 ;;
    --) shift; ctest_args=("$@"); break ;;
    -h|--help) sed -n '3,14p' "$0"; exit 0 ;;
    *) echo "tsan.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done

# The threaded parts and the test programs that run them on threads:
#   Modbus drive worker + server  test_modbus_loopback, test_modbus_faults, test_modbus_transport,
#                                 test_modbus_server_abuse, test_modbus_interop_pymodbus_server (the
#                                 worker against Debian's pymodbus; skips without it)
#   Modbus I/O link worker        test_controller_modbus (TcpModbusIoBus against the simulated
#                                 terminal's server), test_modbus_io_terminal (libmodbus client)
#   socketcand hub + client       test_can_socketcand (loopback), test_can_socketcand_abuse
#   GPIO edge writer              test_gpio_edge_writer (AsyncEdgeWriter on mock lines)
#   serial emulator host, TCP     test_serial_line (TcpLine, TcpListener), test_serial_clm14_e2e
#                                 (EndpointHost on its own thread against a pty client)
targets=(
  test_modbus_loopback test_modbus_faults test_modbus_transport test_modbus_server_abuse
  test_modbus_interop_pymodbus_server
  test_controller_modbus test_modbus_io_terminal
  test_can_socketcand test_can_socketcand_abuse
  test_gpio_edge_writer
  test_serial_line test_serial_clm14_e2e
)
# Their googletest suites, as ctest names them (Suite.Test).
suites=(
  ModbusLoopback ModbusFaults ModbusServer ModbusTransport ModbusServerAbuse ModbusPymodbusServer
  ModbusIoLinkTcp ModbusIoLinkSim TerminalOverTcp
  SocketcandLoopback SocketcandAbuse
  AsyncEdgeWriter
  SerialStream PtyPair TcpLine TcpListener
  Clm14EndToEnd LineFormats/PtyFormats
)
regex="^($(IFS='|'; echo "${suites[*]}"))\\."
if [[ ${#only[@]} -gt 0 ]]; then
  for t in "${only[@]}"; do
    [[ " ${targets[*]} " == *" $t "* ]] || { echo "tsan.sh: $t is not one of: ${targets[*]}" >&2; exit 2; }
  done
  targets=("${only[@]}")
fi

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
t0=$SECONDS
if [[ ! -f "$bd/CMakeCache.txt" ]]; then
  cmake --preset tsan -B "$bd" -DHIL_WERROR=ON "${launcher[@]}" >/dev/null
fi

build() {
  local args=(--build "$bd" -j"$(nproc)")
  for t in "${targets[@]}"; do args+=(--target "$t"); done
  if [[ -d /work/bin && -x /work/bin/hil-build ]]; then
    while :; do
      for s in 1 2 3; do
        exec 9>/tmp/hil-build-slot$s
        if flock -n 9; then
          local rc=0
          nice -n 5 cmake "${args[@]}" || rc=$?
          exec 9>&-
          return $rc
        fi
      done
      sleep 3
    done
  fi
  cmake "${args[@]}"
}
build
echo "tsan.sh: build ${#targets[@]} test programs: $((SECONDS - t0)) s"
[[ $build_only == 1 ]] && exit 0

t1=$SECONDS
# halt_on_error: the first report fails the test. second_deadlock_stack: both stacks of a
# lock-order inversion. history_size: longer memory of old accesses (fewer "failed to restore
# the stack" in reports). The suppressions file must exist even when empty.
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 history_size=4 suppressions=$src/scripts/tsan.supp ${TSAN_OPTIONS:-}"
rc=0
ctest --test-dir "$bd" -R "$regex" -j"$(nproc)" --output-on-failure --no-tests=error "${ctest_args[@]}" || rc=$?
echo "tsan.sh: run: $((SECONDS - t1)) s"
exit $rc
