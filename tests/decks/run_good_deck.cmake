# Run kontakt2d on a deck that must succeed: exit code 0 and a result file
# whose status attribute says "completed".
#   cmake -DEXE=... -DDECK=... -DWORK=... [-DARGS=...] [-DH5DUMP=...] -P run_good_deck.cmake
get_filename_component(name "${DECK}" NAME_WE)
set(out "${WORK}/${name}.h5")
file(REMOVE "${out}")
separate_arguments(extra UNIX_COMMAND "${ARGS}")
execute_process(COMMAND "${EXE}" "${DECK}" -o "${out}" ${extra}
  RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "expected exit code 0, got '${rc}'\nstdout:\n${stdout}\nstderr:\n${stderr}")
endif()
if(NOT EXISTS "${out}")
  message(FATAL_ERROR "no result file ${out}")
endif()
if(H5DUMP)
  execute_process(COMMAND "${H5DUMP}" -a status "${out}" OUTPUT_VARIABLE attr RESULT_VARIABLE rc2)
  if(NOT rc2 STREQUAL "0" OR NOT attr MATCHES "\"completed\"")
    message(FATAL_ERROR "result file ${out} does not say completed:\n${attr}")
  endif()
endif()
message(STATUS "${stdout}")
