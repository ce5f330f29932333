# Fallback for pFUnit 4's CMake helper, for builds where find_package(PFUNIT) finds nothing.
#
#   add_pfunit_ctest(<name>
#                    TEST_SOURCES <file.pf>...
#                    [OTHER_SOURCES <source>...]
#                    [LINK_LIBRARIES <library>...]
#                    [LABELS <label>...]
#                    [WORKING_DIRECTORY <dir>])
#
# has the signature and behaviour of pFUnit 4's add_pfunit_ctest (include/add_pfunit_ctest.cmake):
#   * each .pf file is preprocessed into <file>.F90 in the build tree: a relative path is taken
#     relative to CMAKE_CURRENT_SOURCE_DIR and its .F90 goes to the same relative place under
#     CMAKE_CURRENT_BINARY_DIR; an absolute path is taken to be in the build tree already and
#     its .F90 is written beside it (an absolute path outside the build tree, which pFUnit would
#     also treat so, gets its .F90 in CMAKE_CURRENT_BINARY_DIR instead: the fallback never
#     writes into the source tree);
#   * the module in test_foo.pf must be named test_foo; its tests form the suite test_foo_suite;
#   * one executable <name> runs every suite of its TEST_SOURCES, with its Fortran modules in
#     <binary dir>/mod/<name>; LINK_LIBRARIES are linked with the plain (keyword-less)
#     target_link_libraries signature, as pFUnit does;
#   * one ctest test <name> runs `<name> --verbose` in WORKING_DIRECTORY (default: the current
#     binary directory), fails when the output says "Encountered 1 or more failures/errors
#     during testing" (the runner also exits with status 2), and carries LABELS.
# pFUnit's REGISTRY, EXTRA_USE, EXTRA_INITIALIZE and EXTRA_FINALIZE are refused; MAX_PES is
# ignored with a warning (the fallback is serial, like a pFUnit built without MPI).
#
#   pfunit_fallback_add_executable(<name> TEST_SOURCES ... [OTHER_SOURCES ...] [LINK_LIBRARIES ...])
#
# builds the same executable without registering a ctest test (used by the fallback's own
# self-tests, which check the output of deliberately failing suites).
#
# Variables:
#   PFUNIT_FALLBACK_ALLOW_CONTINUATION  accept directives continued with '&'. OFF by default,
#       because pFUnit 4 reads each directive from one line: a continued directive would
#       build here and fail to compile under pFUnit.
#
# The preprocessor (pf_preprocess.py) needs only Python 3's standard library; the runtime is
# the Fortran module `funit` in funit.f90, built once as the library pfunit_fallback.
# docs/DEVELOPERS.md lists the supported .pf subset.

include_guard(GLOBAL)

find_package(Python3 COMPONENTS Interpreter REQUIRED)

option(PFUNIT_FALLBACK_ALLOW_CONTINUATION
  "pFUnit fallback: accept @-directives continued with '&' (pFUnit 4 itself does not)" OFF)

set(PFUNIT_FALLBACK_PREPROCESSOR "${CMAKE_CURRENT_LIST_DIR}/pf_preprocess.py"
  CACHE INTERNAL "pFUnit fallback preprocessor")

if(NOT TARGET pfunit_fallback)
  add_library(pfunit_fallback STATIC "${CMAKE_CURRENT_LIST_DIR}/funit.f90")
  set_target_properties(pfunit_fallback PROPERTIES
    Fortran_MODULE_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}/mod/pfunit_fallback")
  target_include_directories(pfunit_fallback PUBLIC
    "${CMAKE_CURRENT_BINARY_DIR}/mod/pfunit_fallback")
endif()

# Preprocess the .pf files; put the .F90 files in <out_var>, the module names in <modules_var>.
function(_pfunit_fallback_sources out_var modules_var)
  set(out_files)
  set(modules)
  set(flags)
  if(PFUNIT_FALLBACK_ALLOW_CONTINUATION)
    list(APPEND flags --allow-continuation)
  endif()
  foreach(pf_file IN LISTS ARGN)
    get_filename_component(basename "${pf_file}" NAME_WE)
    get_filename_component(abs_file "${pf_file}" ABSOLUTE)
    if(NOT EXISTS "${abs_file}")
      message(FATAL_ERROR "add_pfunit_ctest: test source ${pf_file} does not exist")
    endif()
    if(IS_ABSOLUTE "${pf_file}")
      file(RELATIVE_PATH in_build "${CMAKE_BINARY_DIR}" "${abs_file}")
      if(in_build MATCHES "^\\.\\./")
        set(out_file "${CMAKE_CURRENT_BINARY_DIR}/${basename}.F90")
      else()
        get_filename_component(file_dir "${abs_file}" DIRECTORY)
        set(out_file "${file_dir}/${basename}.F90")
      endif()
    else()
      file(RELATIVE_PATH rel_file "${CMAKE_CURRENT_SOURCE_DIR}" "${abs_file}")
      get_filename_component(rel_dir "${rel_file}" DIRECTORY)
      if(rel_dir)
        set(out_file "${CMAKE_CURRENT_BINARY_DIR}/${rel_dir}/${basename}.F90")
      else()
        set(out_file "${CMAKE_CURRENT_BINARY_DIR}/${basename}.F90")
      endif()
    endif()
    add_custom_command(OUTPUT "${out_file}"
      COMMAND "${Python3_EXECUTABLE}" "${PFUNIT_FALLBACK_PREPROCESSOR}" ${flags}
              "${abs_file}" "${out_file}"
      DEPENDS "${abs_file}" "${PFUNIT_FALLBACK_PREPROCESSOR}"
      WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}"
      COMMENT "Preprocessing pFUnit test suite ${basename}.pf (fallback)"
      VERBATIM)
    list(APPEND out_files "${out_file}")
    list(APPEND modules "${basename}")
  endforeach()
  set(${out_var} "${out_files}" PARENT_SCOPE)
  set(${modules_var} "${modules}" PARENT_SCOPE)
endfunction()

function(pfunit_fallback_add_executable test_package_name)
  cmake_parse_arguments(PF_TEST "" "" "TEST_SOURCES;OTHER_SOURCES;LINK_LIBRARIES" ${ARGN})
  if(PF_TEST_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR
      "pfunit_fallback_add_executable(${test_package_name}): unknown arguments "
      "${PF_TEST_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT PF_TEST_TEST_SOURCES)
    message(FATAL_ERROR "add_pfunit_ctest(${test_package_name}): TEST_SOURCES is empty")
  endif()

  _pfunit_fallback_sources(test_sources_f90 suite_modules ${PF_TEST_TEST_SOURCES})

  # The driver: what pFUnit's driver.F90 does with its list of suites.
  set(uses "")
  set(calls "")
  foreach(module IN LISTS suite_modules)
    string(APPEND uses "   use Wrap${module}, only: ${module}_suite\n")
    string(APPEND calls "   call ${module}_suite()\n")
  endforeach()
  set(driver "${CMAKE_CURRENT_BINARY_DIR}/${test_package_name}_driver.F90")
  file(CONFIGURE OUTPUT "${driver}" CONTENT
"! Generated by PFUnitFallback.cmake for the test executable ${test_package_name}; do not edit.
program pfunit_fallback_driver
   use funit, only: pff_initialize, pff_finalize
${uses}   implicit none
   call pff_initialize()
${calls}   call pff_finalize()
end program pfunit_fallback_driver
" @ONLY)

  add_executable(${test_package_name}
    ${test_sources_f90}
    ${PF_TEST_OTHER_SOURCES}
    "${driver}")
  set(mod_dir "${CMAKE_CURRENT_BINARY_DIR}/mod/${test_package_name}")
  set_target_properties(${test_package_name} PROPERTIES Fortran_MODULE_DIRECTORY "${mod_dir}")
  target_include_directories(${test_package_name} PRIVATE "${mod_dir}")
  target_include_directories(${test_package_name} PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}")
  target_link_libraries(${test_package_name} pfunit_fallback ${PF_TEST_LINK_LIBRARIES})
endfunction()

function(add_pfunit_ctest test_package_name)
  set(oneValueArgs REGISTRY MAX_PES EXTRA_USE EXTRA_INITIALIZE EXTRA_FINALIZE WORKING_DIRECTORY)
  set(multiValueArgs TEST_SOURCES OTHER_SOURCES LINK_LIBRARIES LABELS)
  cmake_parse_arguments(PF_TEST "" "${oneValueArgs}" "${multiValueArgs}" ${ARGN})
  if(PF_TEST_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR
      "add_pfunit_ctest(${test_package_name}): unknown arguments ${PF_TEST_UNPARSED_ARGUMENTS}")
  endif()
  foreach(option IN ITEMS REGISTRY EXTRA_USE EXTRA_INITIALIZE EXTRA_FINALIZE)
    if(DEFINED PF_TEST_${option})
      message(FATAL_ERROR "add_pfunit_ctest(${test_package_name}): ${option} is not supported "
        "by the pFUnit fallback; install pFUnit (see docs/DEVELOPERS.md)")
    endif()
  endforeach()
  if(PF_TEST_MAX_PES)
    message(WARNING "add_pfunit_ctest(${test_package_name}): MAX_PES ignored, the pFUnit "
      "fallback runs tests serially")
  endif()

  pfunit_fallback_add_executable(${test_package_name}
    TEST_SOURCES ${PF_TEST_TEST_SOURCES}
    OTHER_SOURCES ${PF_TEST_OTHER_SOURCES}
    LINK_LIBRARIES ${PF_TEST_LINK_LIBRARIES})

  if(PF_TEST_WORKING_DIRECTORY)
    set(workdir "${PF_TEST_WORKING_DIRECTORY}")
  else()
    set(workdir "${CMAKE_CURRENT_BINARY_DIR}")
  endif()
  add_test(NAME ${test_package_name}
    WORKING_DIRECTORY "${workdir}"
    COMMAND ${test_package_name} --verbose)
  set_property(TEST ${test_package_name}
    PROPERTY FAIL_REGULAR_EXPRESSION "Encountered 1 or more failures/errors during testing")
  if(PF_TEST_LABELS)
    set_property(TEST ${test_package_name} PROPERTY LABELS ${PF_TEST_LABELS})
  endif()
endfunction()
