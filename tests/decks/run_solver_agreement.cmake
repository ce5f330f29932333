# Run one deck with the skyline solver and each of the sparse solvers of the
# build (SOLVERS: umfpack, mumps) and compare the displacements of each with
# the skyline's (compare_results.py, relative 1e-10).  The deck's own OPTIONS
# CONDENSE (AUTO by default) takes, for a contact deck, the condensation by
# solves with skyline and UMFPACK and the Schur complement of MUMPS's
# factorization with MUMPS; a contact deck of at most 10 000 equations is
# therefore run with MUMPS once more with CONDENSE OFF (the whole system
# factorized at every solution, the deck copied with the option added), so
# that every contact system is compared with the skyline run (on the larger
# decks the refactorizations would add minutes to the suite).  When GEO is given, the
# deck and its .geo are copied to WORK and the .msh is made there with gmsh
# first, so that nothing is generated in the source tree.  With CHECK_TOOL the
# skyline result is also compared with the expected values of <deck>.check
# beside the deck (for the decks that no run_good_deck.cmake test runs).
#   cmake -DEXE=... -DDECK=... -DWORK=... -DPYTHON=... -DCOMPARE=... -DSOLVERS=umfpack,mumps
#         [-DGEO=... -DGMSH=...] [-DCHECK_TOOL=...] -P run_solver_agreement.cmake
cmake_policy(SET CMP0057 NEW)   # if(... IN_LIST ...)
string(REPLACE "," ";" SOLVERS "${SOLVERS}")
get_filename_component(name "${DECK}" NAME_WE)
set(dir "${WORK}/${name}")
file(REMOVE_RECURSE "${dir}")
file(MAKE_DIRECTORY "${dir}")
if(GEO)
  file(COPY "${DECK}" "${GEO}" DESTINATION "${dir}")
  get_filename_component(deck_name "${DECK}" NAME)
  get_filename_component(geo_name "${GEO}" NAME)
  get_filename_component(geo_base "${GEO}" NAME_WE)
  set(deck "${dir}/${deck_name}")
  execute_process(COMMAND "${GMSH}" -2 -format msh41 "${dir}/${geo_name}" -o "${dir}/${geo_base}.msh"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "gmsh failed on ${geo_name} (${rc}):\n${out}\n${err}")
  endif()
else()
  set(deck "${DECK}")
endif()
foreach(solver skyline ${SOLVERS})
  execute_process(COMMAND "${EXE}" "${deck}" -q -s ${solver} -o "${dir}/${name}_${solver}.h5"
                  -l "${dir}/${name}_${solver}.lis"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "kontakt2d -s ${solver} failed (${rc}):\n${out}\n${err}")
  endif()
endforeach()
# MUMPS with CONDENSE OFF for a contact deck: the OPTIONS block gets the card
# (any CONDENSE card of the deck replaced), or one is added after CONTROL's card
file(READ "${deck}" text)
file(READ "${dir}/${name}_skyline.lis" listing)
set(neq 0)
if(listing MATCHES "Equations +: +([0-9]+)")
  set(neq "${CMAKE_MATCH_1}")
endif()
if("mumps" IN_LIST SOLVERS AND text MATCHES "\nCONTACT[ ]*\n" AND neq LESS_EQUAL 10000)
  string(REGEX REPLACE "\nCONDENSE[^\n]*" "" text "${text}")
  if(text MATCHES "\nOPTIONS[ ]*\n")
    string(REGEX REPLACE "\nOPTIONS[ ]*\n" "\nOPTIONS\nCONDENSE  OFF\n" text "${text}")
  else()
    string(REGEX REPLACE "\nCONTROL[ ]*\n((#[^\n]*\n)*)([^\n]*\n)" "\nCONTROL\n\\1\\3OPTIONS\nCONDENSE  OFF\n"
           text "${text}")
  endif()
  if(NOT text MATCHES "\nCONDENSE  OFF\n")
    message(FATAL_ERROR "could not add CONDENSE OFF to ${deck}")
  endif()
  # beside the run's other files (a gmsh deck was copied there with its mesh)
  set(off_deck "${dir}/${name}_condense_off.dat")
  file(WRITE "${off_deck}" "${text}")
  # a deck of a committed .msh (no GEO): the mesh goes beside the copy
  if(NOT GEO AND text MATCHES "\nGMSH +([^\n#]+)")
    string(STRIP "${CMAKE_MATCH_1}" msh_rel)
    get_filename_component(deck_dir "${DECK}" DIRECTORY)
    if(EXISTS "${deck_dir}/${msh_rel}")
      file(COPY "${deck_dir}/${msh_rel}" DESTINATION "${dir}")
    endif()
  endif()
  execute_process(COMMAND "${EXE}" "${off_deck}" -q -s mumps -o "${dir}/${name}_mumps_off.h5"
                  -l "${dir}/${name}_mumps_off.lis"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "kontakt2d -s mumps with CONDENSE OFF failed (${rc}):\n${out}\n${err}")
  endif()
  list(APPEND SOLVERS mumps_off)
endif()
foreach(solver ${SOLVERS})
  execute_process(COMMAND "${PYTHON}" "${COMPARE}" "${dir}/${name}_skyline.h5" "${dir}/${name}_${solver}.h5"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "skyline and ${solver} disagree on ${name}:\n${out}\n${err}")
  endif()
  string(STRIP "${out}" out)
  message(STATUS "${name}, skyline vs ${solver}: ${out}")
endforeach()
if(CHECK_TOOL)
  get_filename_component(deck_dir "${DECK}" DIRECTORY)
  set(check_file "${deck_dir}/${name}.check")
  if(NOT EXISTS "${check_file}")
    message(FATAL_ERROR "no expected values for ${DECK}: every good deck carries them in ${name}.check beside it")
  endif()
  execute_process(COMMAND "${PYTHON}" "${CHECK_TOOL}" "${dir}/${name}_skyline.h5" "${check_file}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "expected values of ${name}.check (exit code ${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endif()
