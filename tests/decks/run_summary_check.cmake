# Run a deck (its exit code as expected), then check that the result file's /summary records
# everything the listing's closing summary says (check_summary.py).
#   cmake -DEXE=... -DDECK=... -DWORK=... -DPYTHON=... -DCHECK=... -DEXPECT_RC=n
#         -P run_summary_check.cmake
get_filename_component(name "${DECK}" NAME_WE)
set(out "${WORK}/summary_${name}.h5")
file(REMOVE "${out}" "${WORK}/summary_${name}.lis")
execute_process(COMMAND "${EXE}" "${DECK}" -q -o "${out}" -l "${WORK}/summary_${name}.lis"
  RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT rc STREQUAL "${EXPECT_RC}")
  message(FATAL_ERROR "expected exit code ${EXPECT_RC}, got '${rc}'\n${stdout}\n${stderr}")
endif()
execute_process(COMMAND "${PYTHON}" "${CHECK}" "${out}" "${WORK}/summary_${name}.lis"
  RESULT_VARIABLE rc OUTPUT_VARIABLE cout ERROR_VARIABLE cerr)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "summary check failed:\n${cout}\n${cerr}")
endif()
message(STATUS "${cout}")
