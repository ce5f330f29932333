# Run tools/calibrate.py on a malformed data file and print what it said, then its exit code:
# the test's PASS_REGULAR_EXPRESSION matches the message, FAIL_REGULAR_EXPRESSION an exit
# code other than 2 or a Python traceback.
#   cmake -DPYTHON=... -DSCRIPT=.../calibrate.py -DLAW=normal -DDATA=... -DWORK=... [-DEXTRA=a|b] -P run_calibrate_bad.cmake
#   EXTRA: further arguments separated by |
file(MAKE_DIRECTORY "${WORK}")
string(REPLACE "|" ";" EXTRA "${EXTRA}")
execute_process(COMMAND "${PYTHON}" "${SCRIPT}" ${LAW} "${DATA}" --out "${WORK}" ${EXTRA}
  RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
message("${stderr}")
if(NOT rc STREQUAL "2")
  message("unexpected exit code ${rc} (expected 2)\nstdout:\n${stdout}")
else()
  message("exit code 2")
endif()
