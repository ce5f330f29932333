# The check tool's own test: run a good deck, then compare it with a check file
# whose every value is wrong (check_deck.py must exit with 1 and report that no
# check holds) or with a malformed one (exit code 2, the file and line named).
#   cmake -DEXE=... -DDECK=... -DWORK=... -DPYTHON=... -DCHECK_TOOL=... -DCHECK_FILE=...
#         -DEXPECT_RC=1|2 -DEXPECT=<regular expression> -P run_check_selftest.cmake
get_filename_component(name "${CHECK_FILE}" NAME_WE)
set(out "${WORK}/selftest_${name}.h5")
file(REMOVE "${out}")
execute_process(COMMAND "${EXE}" "${DECK}" -q -o "${out}" RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "expected exit code 0 from the program, got '${rc}'\n${stdout}\n${stderr}")
endif()
execute_process(COMMAND "${PYTHON}" "${CHECK_TOOL}" "${out}" "${CHECK_FILE}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE checked ERROR_VARIABLE err)
if(NOT rc STREQUAL "${EXPECT_RC}")
  message(FATAL_ERROR "expected exit code ${EXPECT_RC} from the check tool, got '${rc}'\n${checked}\n${err}")
endif()
if(NOT checked MATCHES "${EXPECT}")
  message(FATAL_ERROR "expected (regex) ${EXPECT} in the check tool's output:\n${checked}\n${err}")
endif()
if(err MATCHES "Traceback")
  message(FATAL_ERROR "a Python traceback escaped:\n${err}")
endif()
message(STATUS "${checked}")
