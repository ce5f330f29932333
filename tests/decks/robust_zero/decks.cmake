# Decks of a body held only by a rough interface with friction, its load taken off to exactly
# zero (robust_zero/<deck>.check beside each deck): exit code 0, status completed, every check
# holding.  Included from tests/decks/CMakeLists.txt.  One BLAS thread: these runs end at a zero-force
# rest that threaded BLAS reaches by a different round-off (zero_singular_slip_*: its failure before).
file(GLOB robust_zero_checks CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/robust_zero/*.check)
foreach(check IN LISTS robust_zero_checks)
  get_filename_component(name ${check} NAME_WE)
  add_test(NAME robust_zero_${name}
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:kontakt2d> -DDECK=${CMAKE_CURRENT_SOURCE_DIR}/robust_zero/${name}.dat
            -DWORK=${K2D_DECK_WORK} -DARGS=-q -DH5DUMP=${H5DUMP_EXECUTABLE} ${K2D_CHECK_ARGS}
            -P ${CMAKE_CURRENT_SOURCE_DIR}/run_good_deck.cmake)
  set_tests_properties(robust_zero_${name} PROPERTIES LABELS regression ENVIRONMENT "${K2D_PYTHONPATH};OPENBLAS_NUM_THREADS=1")
endforeach()
