# OPTIONS RESULTS n writes the same increments as a run writing every one: run
# a deck with RESULTS 1 and with RESULTS EVERY (the RESULTS card replaced, or
# added to the OPTIONS block, or an OPTIONS block added after CONTROL's card),
# both with -s SOLVER, and compare (compare_runs.py --every): the second file
# must hold exactly the increments n with mod(n, EVERY) = 0 and the last, each
# equal to the first file's to 1e-12 relative (every nodal, Gauss-point and
# contact dataset; the counts of every increment).  A contact run skips the
# full field of the increments it does not write (with MUMPS's Schur
# complement it postpones their expansion into the next written one): this
# checks that nothing it writes depends on that.
#   cmake -DEXE=... -DDECK=... -DSOLVER=... -DEVERY=... -DWORK=... -DNAME=... -DPYTHON=... -DCOMPARE=...
#         -P run_results_every.cmake
set(dir "${WORK}/${NAME}")
file(REMOVE_RECURSE "${dir}")
file(MAKE_DIRECTORY "${dir}")
file(READ "${DECK}" text)
string(REGEX REPLACE "\nRESULTS[^\n]*" "" text "${text}")
foreach(every 1 ${EVERY})
  set(card "RESULTS   ${every}")
  if(text MATCHES "\nOPTIONS[ ]*\n")
    string(REGEX REPLACE "\nOPTIONS[ ]*\n" "\nOPTIONS\n${card}\n" deck_text "${text}")
  else()
    string(REGEX REPLACE "\nCONTROL[ ]*\n((#[^\n]*\n)*)([^\n]*\n)" "\nCONTROL\n\\1\\3OPTIONS\n${card}\n"
           deck_text "${text}")
  endif()
  if(NOT deck_text MATCHES "\n${card}\n")
    message(FATAL_ERROR "could not put ${card} into ${DECK}")
  endif()
  file(WRITE "${dir}/every${every}.dat" "${deck_text}")
  execute_process(COMMAND "${EXE}" "${dir}/every${every}.dat" -q -s ${SOLVER} -o "${dir}/every${every}.h5"
                  -l "${dir}/every${every}.lis"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0" AND NOT rc STREQUAL "4")   # completed, or completed with doubts
    message(FATAL_ERROR "kontakt2d -s ${SOLVER} with ${card} failed (${rc}):\n${out}\n${err}")
  endif()
endforeach()
execute_process(COMMAND "${PYTHON}" "${COMPARE}" "${dir}/every1.h5" "${dir}/every${EVERY}.h5" --every ${EVERY}
                --rtol 1e-12
  RESULT_VARIABLE rc OUTPUT_VARIABLE cmp ERROR_VARIABLE err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "RESULTS 1 and RESULTS ${EVERY} disagree on ${NAME}:\n${cmp}\n${err}")
endif()
string(STRIP "${cmp}" cmp)
message(STATUS "${NAME}: ${cmp}")
