# Run kontakt2d on a deck that must succeed: exit code 0, a result file whose
# status attribute says "completed", and the expected values of <deck>.check
# beside the deck (docs/DEVELOPERS.md: "Expected values of a good deck"),
# compared by CHECK_TOOL (tests/decks/check_deck.py) when Python is given.
#   cmake -DEXE=... -DDECK=... -DWORK=... [-DARGS=...] [-DH5DUMP=...]
#         [-DPYTHON=... -DCHECK_TOOL=...] -P run_good_deck.cmake
get_filename_component(name "${DECK}" NAME_WE)
get_filename_component(dir "${DECK}" DIRECTORY)
set(check_file "${dir}/${name}.check")
if(NOT EXISTS "${check_file}")
  message(FATAL_ERROR "no expected values for ${DECK}: every good deck carries them in ${name}.check beside it")
endif()
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
if(PYTHON AND CHECK_TOOL)
  execute_process(COMMAND "${PYTHON}" "${CHECK_TOOL}" "${out}" "${check_file}"
    RESULT_VARIABLE rc3 OUTPUT_VARIABLE checked ERROR_VARIABLE err3)
  if(NOT rc3 STREQUAL "0")
    message(FATAL_ERROR "expected values of ${name}.check (exit code ${rc3}):\n${checked}\n${err3}")
  endif()
  message(STATUS "${checked}")
else()
  message(STATUS "${name}.check not compared: needs python3 with h5py and numpy")
endif()
