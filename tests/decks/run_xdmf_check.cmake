# Run a deck that must succeed, then check its XDMF sidecar with check_xdmf.py.
#   cmake -DEXE=... -DDECK=... -DWORK=... -DPYTHON=... -DCHECK=... [-DCHECK_ARGS=a;b] -P run_xdmf_check.cmake
get_filename_component(name "${DECK}" NAME_WE)
set(out "${WORK}/xdmf_${name}.h5")
file(REMOVE "${out}" "${WORK}/xdmf_${name}.xdmf")
execute_process(COMMAND "${EXE}" "${DECK}" -q -o "${out}" -l "${WORK}/xdmf_${name}.lis"
  RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "expected exit code 0, got '${rc}'\n${stdout}\n${stderr}")
endif()
execute_process(COMMAND "${PYTHON}" "${CHECK}" "${WORK}/xdmf_${name}.xdmf" ${CHECK_ARGS}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "XDMF check failed:\n${out}\n${err}")
endif()
message(STATUS "${out}")
