# SPDX-License-Identifier: MIT
# `hilbridge test SCENARIO` on a scenario whose duration cuts its program off: exit 1 and the
# reason (which step of how many, the file and line, the axis still moving).
execute_process(COMMAND ${HILBRIDGE} test ${SCENARIO} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "expected exit status 1, got ${rc}")
endif()
if(NOT out MATCHES "FAIL cut off by duration at t=0\\.300 s: step 2 of 2 \\(move_absolute x, [^ ]*cut_off\\.yaml:14 program\\[1\\]\\) not completed; axis x still moving")
  message(FATAL_ERROR "the failure does not say what the duration cut off")
endif()
