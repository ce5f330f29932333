# Run kontakt2d on a malformed deck and check that it is rejected properly:
# exit code 2, the expected message (regular expression in EXPECT_FILE) on
# stderr, no result file left behind, and no message that echoes a whole huge
# card (stderr of at most 64 kB: cards are echoed cut, never twice).  ctest's
# TIMEOUT of these tests (60 s) makes a reader that takes quadratic time fail.
#   cmake -DEXE=... -DDECK=... -DEXPECT_FILE=... -DWORK=... -P run_bad_deck.cmake
file(READ "${EXPECT_FILE}" expect)
string(STRIP "${expect}" expect)
get_filename_component(name "${DECK}" NAME_WE)
set(out "${WORK}/${name}.h5")
file(REMOVE "${out}")
execute_process(COMMAND "${EXE}" "${DECK}" -q -o "${out}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT rc STREQUAL "2")
  message(FATAL_ERROR "expected exit code 2, got '${rc}'\nstdout:\n${stdout}\nstderr:\n${stderr}")
endif()
if(NOT stderr MATCHES "${expect}")
  message(FATAL_ERROR "message not found.\nexpected (regex): ${expect}\nstderr:\n${stderr}")
endif()
if(stderr MATCHES "Fortran runtime|Backtrace|SIGSEGV")
  message(FATAL_ERROR "a Fortran runtime error escaped:\n${stderr}")
endif()
string(LENGTH "${stderr}" nerr)
if(nerr GREATER 65536)
  message(FATAL_ERROR "the messages are ${nerr} bytes long: a card was echoed whole")
endif()
if(EXISTS "${out}")
  message(FATAL_ERROR "a result file was written for a rejected deck: ${out}")
endif()
message(STATUS "rejected as expected:\n${stderr}")
