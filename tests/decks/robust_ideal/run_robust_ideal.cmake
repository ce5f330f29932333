# Run kontakt2d on an ideal-contact deck that must converge (exit code 0) and check the
# contact conditions of its result file with CHECK (check_ideal_contact.py).
#   cmake -DEXE=... -DDECK=... -DWORK=... -DPYTHON=... -DCHECK=... -DCHECK_ARGS=a;b;c -P run_robust_ideal.cmake
get_filename_component(name "${DECK}" NAME_WE)
set(out "${WORK}/robust_ideal_${name}.h5")
file(REMOVE "${out}")
execute_process(COMMAND "${EXE}" "${DECK}" -o "${out}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "expected exit code 0, got '${rc}'\nstdout:\n${stdout}\nstderr:\n${stderr}")
endif()
execute_process(COMMAND "${PYTHON}" "${CHECK}" "${out}" ${CHECK_ARGS}
  RESULT_VARIABLE rc2 OUTPUT_VARIABLE checked ERROR_VARIABLE err2)
if(NOT rc2 STREQUAL "0")
  message(FATAL_ERROR "contact conditions of ${name} (exit code ${rc2}):\n${checked}\n${err2}")
endif()
message(STATUS "${checked}")
