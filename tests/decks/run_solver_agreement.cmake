# Run one deck with the skyline solver and each of the sparse solvers of the
# build (SOLVERS: umfpack, mumps) and compare the displacements of each with
# the skyline's (compare_results.py, relative 1e-10).  When GEO is given, the
# deck and its .geo are copied to WORK and the .msh is made there with gmsh
# first, so that nothing is generated in the source tree.  With CHECK_TOOL the
# skyline result is also compared with the expected values of <deck>.check
# beside the deck (for the decks that no run_good_deck.cmake test runs).
#   cmake -DEXE=... -DDECK=... -DWORK=... -DPYTHON=... -DCOMPARE=... -DSOLVERS=umfpack,mumps
#         [-DGEO=... -DGMSH=...] [-DCHECK_TOOL=...] -P run_solver_agreement.cmake
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
