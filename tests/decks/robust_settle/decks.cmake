# Decks of the round-off floor of the Newton correction and of pairs frozen by the guard against
# chatter in the mode their solution gives (robust_settle/<deck>.check beside each deck; from the
# generated scenes 177 and 98, docs/robustness.md): exit code 0, status completed, every check
# holding.  Included from tests/decks/CMakeLists.txt.  One BLAS thread, as the campaign runs them.
file(GLOB robust_settle_checks CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/robust_settle/*.check)
foreach(check IN LISTS robust_settle_checks)
  get_filename_component(name ${check} NAME_WE)
  add_test(NAME robust_settle_${name}
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:kontakt2d> -DDECK=${CMAKE_CURRENT_SOURCE_DIR}/robust_settle/${name}.dat
            -DWORK=${K2D_DECK_WORK} -DARGS=-q -DH5DUMP=${H5DUMP_EXECUTABLE} ${K2D_CHECK_ARGS}
            -P ${CMAKE_CURRENT_SOURCE_DIR}/run_good_deck.cmake)
  set_tests_properties(robust_settle_${name} PROPERTIES LABELS regression ENVIRONMENT "${K2D_PYTHONPATH};OPENBLAS_NUM_THREADS=1")
endforeach()
