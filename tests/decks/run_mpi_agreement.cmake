# One deck, serially and under mpirun: the MPI build's check that N processes
# give the serial run's answer and one result file (docs/parallel.md).
#
# Runs DECK with the mumps solver once as a plain process and once under
# MPIEXEC with NP processes, each in a directory of its own, then checks that
# the MPI run left exactly one result file, and compares the two result files
# with COMPARE (compare_runs.py: the same increments and counts, every field to
# 1e-10).  With CONDENSE_OFF the deck's OPTIONS block gets `CONDENSE OFF`, so
# that the whole system is factorized at every solution.
#   cmake -DEXE=... -DMPIEXEC=... -DNP=2 -DDECK=... -DWORK=... -DNAME=... -DPYTHON=...
#         -DCOMPARE=... [-DCONDENSE_OFF=ON] -P run_mpi_agreement.cmake
set(dir "${WORK}/${NAME}")
file(REMOVE_RECURSE "${dir}")
file(MAKE_DIRECTORY "${dir}/serial" "${dir}/mpi")
file(READ "${DECK}" text)
if(CONDENSE_OFF)
  string(REGEX REPLACE "\nOPTIONS[ ]*\n" "\nOPTIONS\nCONDENSE  OFF\n" text "${text}")
  if(NOT text MATCHES "\nCONDENSE  OFF\n")
    message(FATAL_ERROR "${DECK} has no OPTIONS block to add CONDENSE OFF to")
  endif()
endif()
# (a deck that names no other file: it is copied to the work directory)
file(WRITE "${dir}/deck.dat" "${text}")
set(deck "${dir}/deck.dat")

execute_process(COMMAND "${EXE}" "${deck}" -q -s mumps -o result.h5 WORKING_DIRECTORY "${dir}/serial"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "serial run failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND "${MPIEXEC}" -np ${NP} "${EXE}" "${deck}" -s mumps -o result.h5
  WORKING_DIRECTORY "${dir}/mpi" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "mpirun -np ${NP} failed (${rc}):\n${out}\n${err}")
endif()
# one terminal: the root's header appears once
string(REGEX MATCHALL "Kontakt2D [0-9.]+ - static" headers "${out}")
list(LENGTH headers nheaders)
if(NOT nheaders EQUAL 1)
  message(FATAL_ERROR "expected the program's header once on the terminal, found it ${nheaders} times:\n${out}")
endif()
file(GLOB h5 "${dir}/mpi/*.h5")
list(LENGTH h5 nh5)
if(NOT nh5 EQUAL 1)
  message(FATAL_ERROR "expected one result file from mpirun -np ${NP}, found ${nh5}: ${h5}")
endif()
execute_process(COMMAND "${PYTHON}" "${COMPARE}" "${dir}/serial/result.h5" "${dir}/mpi/result.h5"
  RESULT_VARIABLE rc OUTPUT_VARIABLE cmp ERROR_VARIABLE err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "the serial run and mpirun -np ${NP} disagree on ${NAME}:\n${cmp}\n${err}")
endif()
string(STRIP "${cmp}" cmp)
message(STATUS "${NAME}, serial vs -np ${NP}: ${cmp}")
