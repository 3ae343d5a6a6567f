#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# `hilbridge profile calc sinumerik-elg`: the figures of the ELG manual's setting-up formulas and
# the exit codes (0 fine, 1 the ELG would refuse the data, 2 bad use).
#   calc_cli.sh HILBRIDGE
set -uo pipefail
hil=$1
fail=0
check() {  # check NAME WANT_RC REGEX ARGS...
  local name=$1 want=$2 re=$3 out rc
  shift 3
  out=$("$hil" profile calc sinumerik-elg "$@" 2>&1)
  rc=$?
  if [[ $rc -ne $want ]] || ! grep -Eq -- "$re" <<<"$out"; then
    echo "FAIL $name: exit $rc (want $want), output:"; echo "$out"; fail=1
  else
    echo "ok   $name"
  fi
}
# 18 000 pulses: MS = 360/(4*18000) = 0.005 deg, 500 kHz count 60*500000/18000 = 1666.67 rpm,
# 500 rpm = 150 kHz, 10 increments = 0.1 deg.
check units 0 'measuring-system unit MS +0\.005 deg' --pulses-per-rev 18000 --rpm 500 --increments 10
check limit 0 'max axis speed at 500 kHz +1666\.6667 rpm' --pulses-per-rev 18000
check frequency 0 'encoder frequency at 500 rpm +150000 Hz' --pulses-per-rev 18000 --rpm 500
check inc 0 'INC step of 10 increments +0\.1 deg' --pulses-per-rev 18000 --increments 10
# 2500 lines through ku = 18: A = 0.002 deg, MD 396* = 45000; 2000 rpm needs 1.5 MHz: refused.
check resolution 1 'MD 396\* = 360/\(4 A\) +45000 pulses' --lines 2500 --gear-ku 18 --rpm 2000
check too_fast 1 'problem: 2000 rpm needs 1500000 Hz' --lines 2500 --gear-ku 18 --rpm 2000
check fractional 1 'not a whole number' --resolution 0.007
# ud_z = sin 20 deg / (3 pi) * 360 = 13.06421 deg/mm (2.2.2), ud_y = cos 3 deg / (3 pi) * 360.
check ud_z 0 'ud_z = .* +13\.06421 deg/mm' --module 3 --helix-angle 20
check ud_y 0 'ud_y = .* +38\.14484 deg/mm' --module 3 --lead-angle 3
check module_needed 2 'need --module' --helix-angle 20
# Constants: Z0 = 1, Z2 = 10, N00 = 18000, N02 = 180000: 1 C count per B count, a pitch of 72000.
check constants 0 'C counts per B count .* +1$' --z0 1 --z2 10 --ud-z 8.18511 --n00 18000
check pitch 0 'one pitch in C counts .* +72000' --z0 1 --z2 10 --n00 18000
check alarm_2203 1 'alarm 2203' --z0 1 --z2 0
check bad_decimal 2 '--ud-z' --z0 1 --z2 10 --ud-z 1.1234567
check nothing 2 'give --pulses-per-rev'
# --json: one object on stdout (docs/json.md), the same exit codes; errors as {"error": ...}.
json_check() {  # json_check NAME WANT_RC PYTHON_ASSERTION ARGS...
  local name=$1 want=$2 expr=$3 out rc
  shift 3
  out=$("$hil" profile calc "$@" --json 2>/dev/null)
  rc=$?
  if [[ $rc -ne $want ]] || ! /usr/bin/python3 -c "import json,sys; j=json.loads(sys.argv[1]); assert $expr, j" "$out"; then
    echo "FAIL $name: exit $rc (want $want), output: $out"; fail=1
  else
    echo "ok   $name"
  fi
}
json_check json_units 0 "j['ok'] and j['lines'][0]['value'] == 0.005 and j['lines'][0]['unit'] == 'deg'" \
  sinumerik-elg --pulses-per-rev 18000
json_check json_problem 1 "not j['ok'] and 'Hz per track' in j['problems'][0]" sinumerik-elg --lines 2500 --gear-ku 18 --rpm 2000
json_check json_error 2 "j['exit_code'] == 2 and 'give' in j['error']" sinumerik-elg
json_check json_ip247 1 "j['device'] == 'ip247' and 'MD error 5' in j['problems'][0]" ip247 --pulses-per-rev 5
exit $fail
